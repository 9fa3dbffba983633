// Plots of the analyses (--plot out.png) by scripts/plot_calibration.py with Debian's
// matplotlib. The C++ side writes the analysis JSON (report.hpp) to a temporary file and runs
//   $GRAINLAB_PYTHON (default /usr/bin/python3) $GRAINLAB_SCRIPTS_DIR/plot_calibration.py in out
// GRAINLAB_SCRIPTS_DIR defaults to the source tree's scripts/ directory (compile time).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace grainlab::calibrate {

std::string plot_script_path();

// Writes the plot to `png_path` (the script writes a temporary file and renames it). Throws
// std::runtime_error with the script's exit status when it fails.
void plot_analysis(const nlohmann::json& analysis, const std::string& png_path);

}  // namespace grainlab::calibrate
