// Placeholder: the `calibrate` subcommand is being built (src/calibrate/).
#include <fmt/format.h>

#include "command.hpp"

namespace grainlab::app {

Command add_calibrate_command(CLI::App& app) {
  CLI::App* sub = app.add_subcommand("calibrate", "analyse laboratory measurements (restitution, friction)");
  return {sub, [] {
            fmt::print(stderr, "grainlab calibrate: not available in this build yet\n");
            return exit_failed;
          }};
}

}  // namespace grainlab::app
