// Virtual laboratory tests. A config with a `[test]` table is run by the test named in
// `test.type`; each test is one file in src/lab/ plus one row in the registry (registry.cpp).
// A test reads the sections of the config it needs, builds its specimen, walls and controllers,
// runs the core, measures like the laboratory does and writes its results (always summary.json)
// into the output directory. Element tests on a prepared specimen (triaxial, oedometer,
// plane_strain) share lab/element_test.hpp: preparation, the time step, checkpoints and resume,
// progress.
#pragma once

#include <toml++/toml.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "io/scene_run.hpp"
#include "lab/element_test.hpp"

namespace grainlab {

// Thrown (after the results are written, with the warning in summary.json) when the number a
// test exists to measure came out meaningless, e.g. a friction fit with R^2 near zero: the run
// exits with code 1 and the message says what to change.
class UnreliableResult : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct LabTestEntry {
  const char* type;         // value of test.type
  const char* description;  // one line for --help and errors
  void (*run)(const std::string& config_path, const toml::table& root, const RunOptions& options);
  // Element tests only (nullptr otherwise): the shared settings of a config (for `prepare`), and
  // the continuation of a run from its checkpoint (for `run --resume`).
  ElementTestConfig (*element_config)(const std::string& config_path,
                                      const toml::table& root) = nullptr;
  void (*resume)(ElementRun run, const toml::table& root, const RunOptions& options) = nullptr;
};

const std::vector<LabTestEntry>& lab_tests();

// Runs the test named by root["test"]["type"]; ConfigError when it is missing or unknown.
void run_lab_test(const std::string& config_path, const toml::table& root,
                  const RunOptions& options);

// `grainlab run --resume DIR`: continues the interrupted element test in DIR/checkpoint.bin and
// produces the same files as an uninterrupted run.
void resume_lab_test(const RunOptions& options);

// What `grainlab params` shows for an element-test config: the config's materials and pairs as
// a scene of the test's smallest beads (two, so their own pair counts) and its box of walls, so
// the derived constants and the time step are those the test runs with. ConfigError for a test
// without a specimen.
struct ElementTestScene {
  SceneConfig scene;
  ParticleStore particles;
};
ElementTestScene element_test_scene(const std::string& config_path, const toml::table& root);

// `grainlab prepare CONFIG --out DIR`: the preparation of an element test's specimen alone.
void run_prepare(const std::string& config_path, const RunOptions& options);

}  // namespace grainlab
