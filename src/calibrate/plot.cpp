#include "calibrate/plot.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "io/python_script.hpp"

namespace grainlab::calibrate {

std::string plot_script_path() {
  return script_path("plot_calibration.py");
}

void plot_analysis(const nlohmann::json& analysis, const std::string& png_path) {
  namespace fs = std::filesystem;
  const fs::path json_path =
      fs::temp_directory_path() / fmt::format("grainlab_plot_{}.json", ::getpid());
  {
    std::ofstream out(json_path);
    out << analysis.dump(1);
    if (!out) throw std::runtime_error(fmt::format("cannot write {}", json_path.string()));
  }
  std::error_code ec;
  try {
    run_python_script("plot_calibration.py", {json_path.string(), png_path});
  } catch (...) {
    fs::remove(json_path, ec);
    throw;
  }
  fs::remove(json_path, ec);
}

}  // namespace grainlab::calibrate
