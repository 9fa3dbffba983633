#include <fmt/format.h>
#include <omp.h>

#include <memory>

#include "command.hpp"
#include "core/simulation.hpp"
#include "io/config_error.hpp"
#include "io/interrupt.hpp"
#include "io/scene_run.hpp"
#include "io/team_follower.hpp"
#include "io/toml_reader.hpp"
#include "lab/lab_test.hpp"

namespace grainlab::app {

Command add_run_command(CLI::App& app) {
  auto options = std::make_shared<RunOptions>();
  auto config = std::make_shared<std::string>();
  CLI::App* sub = app.add_subcommand("run", "run a scene or virtual test from a TOML config");
  auto resume = std::make_shared<std::string>();
  CLI::Option* config_option = sub->add_option(
      "config", *config,
      "scene or test configuration (TOML; docs/scene-schema.md, docs/lab-tests.md)");
  CLI::Option* out_option =
      sub->add_option("--out", options->out_dir, "output directory (created; must be empty)");
  sub->add_option("--resume", *resume,
                  "continue an interrupted element test (triaxial, oedometer, plane_strain) from "
                  "DIR/checkpoint.bin")
      ->excludes(config_option)
      ->excludes(out_option);
  sub->add_flag("--overwrite", options->overwrite,
                "replace results in an existing output directory");
  sub->add_option("--threads", options->threads, "OpenMP threads (results do not depend on it)")
      ->check(CLI::Range(1, 1024));
  sub->add_flag("--quiet", options->quiet, "no progress output");
  return {sub, [options, config, resume] {
            if (resume->empty() && (config->empty() || options->out_dir.empty())) {
              fmt::print(stderr,
                         "grainlab: error: run needs CONFIG and --out DIR (or --resume DIR)\n");
              return exit_bad_input;
            }
            try {
              if (options->threads > 0) omp_set_num_threads(options->threads);
              // (without --threads, the steps' team follows the CPUs other processes leave free)
              const auto follower = follow_free_cpus(options->threads > 0, options->quiet);
              if (!resume->empty()) {
                options->out_dir = *resume;
                if (is_scene_checkpoint(options->out_dir + "/checkpoint.bin"))
                  resume_scene(*options);
                else
                  resume_lab_test(*options);
              } else {
                // A config with a [test] table is a virtual laboratory test (src/lab/).
                const toml::table root = parse_toml_file(*config);
                if (root.contains("test"))
                  run_lab_test(*config, root, *options);
                else
                  run_scene(*config, *options);
              }
            } catch (const ConfigError& e) {
              fmt::print(stderr, "grainlab: error: {}\n", e.what());
              return exit_bad_input;
            } catch (const UnreliableResult& e) {
              fmt::print(stderr, "grainlab: error: {}\n", e.what());
              return exit_failed;
            } catch (const BlowUpError& e) {
              fmt::print(stderr, "grainlab: error: {}\n", e.what());
              return exit_failed;
            } catch (const Interrupted& e) {
              fmt::print(stderr, "\ngrainlab: {}\n", e.what());
              return exit_interrupted;
            }
            fmt::print("results written to {}/\n", options->out_dir);
            return exit_ok;
          }};
}

}  // namespace grainlab::app
