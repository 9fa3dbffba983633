// grainlab: a virtual granular laboratory (DEM). See README.md and docs/.
#include <fmt/format.h>
#include <unistd.h>

#include <cstdlib>
#include <exception>
#include <vector>

#include "command.hpp"
#include "grainlab/version.hpp"

namespace {

// How long an OpenMP thread that waits at a barrier spins before it sleeps. GCC's runtime spins
// 300,000 rounds by default: on an idle machine the fastest, but when another process holds one
// of the cores, the spinning thread keeps its core while the thread it waits for shares the
// other, and a run takes 2.4 times as long (docs/performance.md sec. 15). Sleeping at once
// (OMP_WAIT_POLICY=passive) is safe but pays a wake-up at every barrier (up to 1.2x slower on
// an idle machine). 1,000 rounds keep the idle speed within the noise and a busy machine at
// less than twice the idle time. libgomp reads its settings when it is loaded, before main, so
// the setting takes a restart of the program with it in the environment; a user's own
// OMP_WAIT_POLICY or GOMP_SPINCOUNT is kept.
constexpr const char* barrier_spin_rounds = "1000";

void bounded_spin_waiting(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT")) return;
  if (setenv("GOMP_SPINCOUNT", barrier_spin_rounds, 0) != 0) return;
  execv("/proc/self/exe", argv);  // returns only on failure: then go on with the default
}

}  // namespace

int main(int argc, char** argv) {
  using namespace grainlab::app;
  bounded_spin_waiting(argv);
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
