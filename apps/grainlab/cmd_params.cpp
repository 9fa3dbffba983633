#include "command.hpp"
namespace grainlab::app {
Command add_params_command(CLI::App& app) {
  CLI::App* sub = app.add_subcommand("params", "params");
  return {sub, [] { return exit_failed; }};
}
}  // namespace grainlab::app
