#include <fmt/format.h>
#include <omp.h>

#include <memory>

#include "command.hpp"
#include "io/config_error.hpp"
#include "io/interrupt.hpp"
#include "io/team_follower.hpp"
#include "lab/lab_test.hpp"

namespace grainlab::app {

Command add_prepare_command(CLI::App& app) {
  auto options = std::make_shared<RunOptions>();
  auto config = std::make_shared<std::string>();
  CLI::App* sub = app.add_subcommand("prepare",
                                     "prepare (compress) the specimen of an element-test config "
                                     "(triaxial, oedometer, plane_strain) and save it");
  sub->add_option("config", *config, "element-test configuration (TOML)")->required();
  sub->add_option("--out", options->out_dir, "output directory (specimen.csv, specimen.json)")
      ->required();
  sub->add_flag("--overwrite", options->overwrite,
                "replace results in an existing output directory");
  sub->add_option("--threads", options->threads, "OpenMP threads (results do not depend on it)")
      ->check(CLI::Range(1, 1024));
  sub->add_flag("--quiet", options->quiet, "no progress output");
  return {sub, [options, config] {
            try {
              if (options->threads > 0) omp_set_num_threads(options->threads);
              // (without --threads, the steps' team follows the CPUs other processes leave free)
              const auto follower = follow_free_cpus(options->threads > 0, options->quiet);
              run_prepare(*config, *options);
            } catch (const ConfigError& e) {
              fmt::print(stderr, "grainlab: error: {}\n", e.what());
              return exit_bad_input;
            } catch (const Interrupted& e) {
              fmt::print(stderr, "\ngrainlab: {}\n", e.what());
              return exit_interrupted;
            }
            fmt::print("specimen written to {}/specimen.csv\n", options->out_dir);
            return exit_ok;
          }};
}

}  // namespace grainlab::app
