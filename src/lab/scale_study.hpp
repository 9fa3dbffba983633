// The scale study: the plane strain test (lab/plane_strain.hpp) repeated with the bead diameter d
// and the model scaled together (same particle count, same size spread, same specimen shape),
// with gravity off and on, to show what makes the peak axial stress depend on d.
//
// Dimensional analysis: with the contact stiffness scaling with d (k_n = pi E r* at a fixed E,
// Hertz alike), a fixed confining stress and a fixed inertial number I = eps_dot d sqrt(rho / p),
// the test has no length scale left, so the peak cannot depend on d, except through the
// self-weight ratio rho g H / sigma_3 when gravity acts. A fixed platen speed keeps I fixed too
// (eps_dot = 2 v / H with H proportional to d); only a fixed strain rate makes I grow with d.
//
// The specimen is prepared once, at the config's own diameter and without gravity (a preparation
// without gravity is scale-free), and scaled to every d: positions, radii and box multiplied by
// d / d_base. Each (d, gravity) pair is then an ordinary, resumable plane strain run in its own
// subdirectory, with every length of the config multiplied by d / d_base and every time (the
// re-equilibration's limit) and rate (the servo's cap) scaled with it, so that the runs differ
// only by the scale. An interrupted study continues where it stopped (grainlab run --resume DIR).
#pragma once

#include <toml++/toml.h>

#include <string>
#include <vector>

#include "io/scene_run.hpp"
#include "lab/plane_strain.hpp"

namespace grainlab {

enum class ScaleLoading { inertial, platen_speed, strain_rate };

struct ScaleStudyConfig {
  std::vector<double> diameters;       // m
  std::vector<bool> gravity_settings;  // false: off, true: on
  double gravity = 9.81;               // m/s^2 along -z, when on
  ScaleLoading loading = ScaleLoading::inertial;
  double strain_rate = 0.0;  // 1/s, the loading = "strain_rate" case (2 v / H at every d)
  toml::table base_root;     // the plane strain config at the base diameter (study keys removed)
  PlaneStrainConfig base;    // ... read
};

// The published diameters (1, 2, 4, 8, 10, 12, 14, 16, 18 m) and the reference beads' 2 mm.
std::vector<double> default_scale_study_diameters();

ScaleStudyConfig read_scale_study_config(const std::string& path, const toml::table& root);
void run_scale_study(const std::string& path, const toml::table& root, const RunOptions& options);

// Whether DIR holds a scale study (its stored config), and its continuation.
bool is_scale_study_dir(const std::string& dir);
void resume_scale_study(const RunOptions& options);

}  // namespace grainlab
