// Runs one of grainlab's Python helper scripts (plots with Debian's matplotlib):
//   $GRAINLAB_PYTHON (default /usr/bin/python3) $GRAINLAB_SCRIPTS_DIR/NAME ARGS...
// GRAINLAB_SCRIPTS_DIR defaults to the source tree's scripts/ directory (fixed at compile time).
#pragma once

#include <string>
#include <vector>

namespace grainlab {

std::string script_path(const std::string& name);

// Throws std::runtime_error when the script is missing, cannot start, or fails.
void run_python_script(const std::string& name, const std::vector<std::string>& arguments);

}  // namespace grainlab
