#include "command.hpp"
namespace grainlab::app {
Command add_run_command(CLI::App& app) {
  CLI::App* sub = app.add_subcommand("run", "run");
  return {sub, [] { return exit_failed; }};
}
}  // namespace grainlab::app
