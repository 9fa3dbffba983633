#include "calibrate/plot.hpp"

#include <fmt/format.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <vector>

extern char** environ;

namespace grainlab::calibrate {

std::string plot_script_path() {
  const char* dir = std::getenv("GRAINLAB_SCRIPTS_DIR");
  const std::string base = (dir && *dir) ? dir : GRAINLAB_DEFAULT_SCRIPTS_DIR;
  return (std::filesystem::path(base) / "plot_calibration.py").string();
}

void plot_analysis(const nlohmann::json& analysis, const std::string& png_path) {
  namespace fs = std::filesystem;
  const std::string script = plot_script_path();
  if (!fs::exists(script))
    throw std::runtime_error(
        fmt::format("plot script {} not found (set GRAINLAB_SCRIPTS_DIR to "
                    "the directory holding plot_calibration.py)",
                    script));
  const char* py = std::getenv("GRAINLAB_PYTHON");
  const std::string python = (py && *py) ? py : "/usr/bin/python3";
  const fs::path json_path =
      fs::temp_directory_path() / fmt::format("grainlab_plot_{}.json", ::getpid());
  {
    std::ofstream out(json_path);
    out << analysis.dump(1);
    if (!out) throw std::runtime_error(fmt::format("cannot write {}", json_path.string()));
  }
  std::vector<std::string> args{python, script, json_path.string(), png_path};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int spawn_error = posix_spawn(&pid, python.c_str(), nullptr, nullptr, argv.data(), environ);
  int status = 0;
  if (spawn_error == 0) waitpid(pid, &status, 0);
  std::error_code ec;
  fs::remove(json_path, ec);
  if (spawn_error != 0)
    throw std::runtime_error(
        fmt::format("cannot run {} for the plot (set GRAINLAB_PYTHON)", python));
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error(
        fmt::format("the plot script failed ({} {}): no plot written", python, script));
}

}  // namespace grainlab::calibrate
