// A subcommand of the grainlab program: its CLI11 subcommand and what runs when it was chosen.
// Exit codes: 0 success, 1 run failed (e.g. blew up), 2 bad input (config, data file, options),
// 130 interrupted (a checkpoint was written where the run can resume).
#pragma once

#include <CLI/CLI.hpp>
#include <functional>

namespace grainlab::app {

inline constexpr int exit_ok = 0;
inline constexpr int exit_failed = 1;
inline constexpr int exit_bad_input = 2;
inline constexpr int exit_interrupted = 130;  // Ctrl-C / SIGTERM: checkpoint written

struct Command {
  CLI::App* subcommand;
  std::function<int()> run;
};

Command add_run_command(CLI::App& app);
Command add_params_command(CLI::App& app);
Command add_prepare_command(CLI::App& app);
Command add_calibrate_command(CLI::App& app);

}  // namespace grainlab::app
