// The triaxial test (docs/lab-tests.md): a cuboid specimen between four lateral walls
// held at the confining stress by servo control and two platens moving toward each other at a
// constant speed, no gravity, to a final axial strain. Loading rate: the paper's platen speed,
// or the fastest rate whose inertial number I = strain_rate d sqrt(rho / p) stays below a bound.
#pragma once

#include <toml++/toml.h>

#include <string>

#include "io/scene_run.hpp"
#include "lab/element_test.hpp"

namespace grainlab {

struct TriaxialConfig : ElementTestConfig {
  double max_axial_strain = 0.15;
};

TriaxialConfig read_triaxial_config(const std::string& path, const toml::table& root);

void run_triaxial(const std::string& config_path, const toml::table& root,
                  const RunOptions& options);

// Continues an interrupted run from its checkpoint (grainlab run --resume DIR).
void resume_triaxial(ElementRun run, const toml::table& root, const RunOptions& options);

}  // namespace grainlab
