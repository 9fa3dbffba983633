#include "lab/triaxial_plot.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "io/output_manifest.hpp"
#include "io/python_script.hpp"

namespace grainlab {

void plot_triaxial_curve(const std::string& dir) {
  try {
    record_output(dir + "/curve.png");
    record_output(dir + "/curve.png.tmp.png");
    run_python_script("plot_triaxial.py", {dir});
  } catch (const std::runtime_error& e) {
    fmt::print(stderr, "grainlab: warning: no curve.png: {}\n", e.what());
  }
}

}  // namespace grainlab
