// grainlab: a virtual granular laboratory (DEM). See README.md and docs/.
#include <fmt/format.h>

#include <cstdlib>
#include <exception>
#include <vector>

#include "command.hpp"
#include "grainlab/version.hpp"

int main(int argc, char** argv) {
  using namespace grainlab::app;
  // OpenMP threads that busy-wait at barriers collapse when the cores are shared (another job, a
  // parallel ctest): let idle threads sleep unless the user chose otherwise. Must precede the
  // first parallel region.
  setenv("OMP_WAIT_POLICY", "passive", /*overwrite=*/0);
  CLI::App app{"grainlab: discrete element virtual granular laboratory"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("grainlab ") + grainlab::version_string);
  std::vector<Command> commands{add_run_command(app), add_params_command(app),
                                add_prepare_command(app), add_calibrate_command(app)};
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? exit_ok : exit_bad_input;
  }
  try {
    for (const Command& c : commands)
      if (c.subcommand->parsed()) return c.run();
  } catch (const std::exception& e) {
    fmt::print(stderr, "grainlab: error: {}\n", e.what());
    return exit_failed;
  }
  return exit_bad_input;
}
