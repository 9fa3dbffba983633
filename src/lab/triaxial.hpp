// The triaxial test (DESIGN.md sec. 5, issue 5): a cuboid specimen between four lateral walls
// held at the confining stress by servo control and two platens moving toward each other at a
// constant speed, no gravity, to a final axial strain. Loading rate: the paper's platen speed,
// or the fastest rate whose inertial number I = strain_rate d sqrt(rho / p) stays below a bound.
#pragma once

#include <toml++/toml.h>

#include <optional>
#include <string>

#include "io/scene_run.hpp"
#include "lab/specimen.hpp"

namespace grainlab {

struct TriaxialSettings {
  SpecimenSettings specimen;
  std::optional<std::string> specimen_file;  // a prepared specimen to reuse
  std::optional<double> platen_speed;        // m/s each platen; empty: from the inertial number
  double max_inertial_number = 1e-3;
  double max_axial_strain = 0.15;
  double output_strain_interval = 0.001;
  bool vtk = false;
  double vtk_strain_interval = 0.01;
  double checkpoint_interval = 300.0;  // s of wall time between checkpoints
};

void run_triaxial(const std::string& config_path, const toml::table& root,
                  const RunOptions& options);

// `grainlab run --resume DIR`: continues an interrupted triaxial run from DIR/checkpoint.bin and
// produces the same files as an uninterrupted run.
void resume_triaxial(const RunOptions& options);

// `grainlab prepare CONFIG --out DIR`: the preparation of a triaxial config alone.
void run_prepare(const std::string& config_path, const RunOptions& options);

}  // namespace grainlab
