#include <fmt/format.h>

#include <memory>

#include "command.hpp"
#include "io/config_error.hpp"
#include "io/derived_report.hpp"
#include "io/scene_builder.hpp"
#include "io/toml_reader.hpp"
#include "lab/lab_test.hpp"

namespace grainlab::app {

Command add_params_command(CLI::App& app) {
  auto config = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  CLI::App* sub = app.add_subcommand(
      "params", "show the contact constants derived for each material pair of a config");
  sub->add_option("config", *config, "scene or element-test configuration (TOML)")->required();
  sub->add_flag("--json", *json, "print JSON instead of a table");
  return {sub, [config, json] {
            try {
              // A scene, or an element test seen as the scene it runs (its beads and box).
              const toml::table root = parse_toml_file(*config);
              ElementTestScene test;
              if (root.contains("test")) test = element_test_scene(*config, root);
              const SceneConfig c = root.contains("test") ? test.scene : load_scene(*config);
              const PairTable table = build_pair_table(c);
              const ParticleStore particles =
                  root.contains("test") ? test.particles : build_particles(c);
              const auto pairs = derive_pairs(c, table, particles);
              const TimeStepChoice dt = choose_time_step(c, pairs);
              if (*json)
                fmt::print("{}\n", derived_pairs_json(pairs, dt).dump(2));
              else
                fmt::print("{}", derived_pairs_text(pairs, dt));
            } catch (const ConfigError& e) {
              fmt::print(stderr, "grainlab: error: {}\n", e.what());
              return exit_bad_input;
            }
            return exit_ok;
          }};
}

}  // namespace grainlab::app
