#include "io/python_script.hpp"

#include <fmt/format.h>
#include <spawn.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>

extern char** environ;

namespace grainlab {

std::string script_path(const std::string& name) {
  const char* dir = std::getenv("GRAINLAB_SCRIPTS_DIR");
  const std::string base = (dir && *dir) ? dir : GRAINLAB_DEFAULT_SCRIPTS_DIR;
  return (std::filesystem::path(base) / name).string();
}

void run_python_script(const std::string& name, const std::vector<std::string>& arguments) {
  const std::string script = script_path(name);
  if (!std::filesystem::exists(script))
    throw std::runtime_error(
        fmt::format("script {} not found (set GRAINLAB_SCRIPTS_DIR to the directory holding {})",
                    script, name));
  const char* py = std::getenv("GRAINLAB_PYTHON");
  const std::string python = (py && *py) ? py : "/usr/bin/python3";
  std::vector<std::string> args{python, script};
  args.insert(args.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int spawn_error = posix_spawn(&pid, python.c_str(), nullptr, nullptr, argv.data(), environ);
  int status = 0;
  if (spawn_error == 0) waitpid(pid, &status, 0);
  if (spawn_error != 0)
    throw std::runtime_error(fmt::format("cannot run {} (set GRAINLAB_PYTHON)", python));
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error(fmt::format("{} {} failed: no plot written", python, script));
}

}  // namespace grainlab
