// The scale study's results (lab/scale_study.hpp): the table of runs (scale.csv), the fits with
// their uncertainty (the shared least squares of calibrate/least_squares.hpp), the extrapolation
// to the reference beads' 2 mm with its confidence interval, and the statement of what makes the
// peak grow, with the numbers that show it (summary.json).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/vec3.hpp"

namespace grainlab {

// One (d, gravity) run, read from its summary.json.
struct ScaleRun {
  std::string name;       // its subdirectory
  double diameter = 0.0;  // m
  double gravity = 0.0;   // m/s^2 (0: off)
  std::string status;     // "ok", or what went wrong
  long particles = 0;
  Vec3 size;                       // m: width, thickness, height at the start of the loading
  double peak_axial_stress = NAN;  // Pa
  double axial_strain_at_peak = NAN;
  double self_weight_ratio = NAN;  // rho_bulk g H / sigma_3 at the start of the loading
  double max_inertial_number = NAN;
  double wall_time = NAN;  // s, the run's own (preparation of the scaled specimen excluded)
};

struct ScaleStudyFacts {
  double confining_stress = 0.0;  // Pa
  std::string loading;            // how the platens were driven, in words
};

// Writes DIR/scale.csv and DIR/summary.json; returns the one-paragraph explanation.
std::string write_scale_study_report(const std::vector<ScaleRun>& runs, const ScaleStudyFacts& f,
                                     const std::string& dir, nlohmann::json header);

}  // namespace grainlab
