// Restitution from a camera-tracked trajectory of one flat throw (docs/calibration.md).
//
// The bead centre is in free flight before and after the impact, so its height follows two
// parabolas with the same gravity:
//   before: z(t) = a1 + b1 (t - t0) - g (t - t0)^2 / 2,   after: z(t) = a2 + b2 (t - t0) - ...
// Both are fitted together by linear least squares (g shared and fitted, or fixed by the user).
// With a shared g the parabolas cross where a1 + b1 tau = a2 + b2 tau, which is the impact:
//   tau_i = (a2 - a1) / (b1 - b2), vertical velocities v1 = b1 - g tau_i, v2 = b2 - g tau_i.
// Reported: e_velocity = -v2 / v1 (the definition of restitution, normal impact velocities),
// and, as the throw-table method does, H and h = apex heights above the plate and
// e_heights = sqrt(h / H). The two differ because the bead centre hits at one radius above the
// plate; e_heights is what a height-measuring laboratory gets, e_velocity is the exact one.
// Uncertainties of derived quantities by the delta method from the fit's covariance.
//
// Units: t in s, x and z in m, g in m/s^2, velocities in m/s.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "calibrate/csv_table.hpp"
#include "calibrate/statistics.hpp"

namespace grainlab::calibrate {

struct TrackPoint {
  std::size_t line = 0;
  double t_s = 0.0;
  double x_m = 0.0;
  double z_m = 0.0;
};

struct TrajectoryOptions {
  double plate_z_m = 0.0;
  std::optional<double> gravity;  // fixed g (m/s^2); fitted when empty
  double level = 0.95;
  std::size_t min_points_per_side = 3;
};

struct TrajectoryResult {
  std::string source;
  std::vector<TrackPoint> points;
  std::vector<int> side;           // per point: -1 before impact, +1 after, 0 not used
  std::vector<double> residual_m;  // per point: z - fitted z (0 when not used)
  std::size_t n_before = 0;
  std::size_t n_after = 0;
  std::size_t dof = 0;
  bool gravity_fitted = true;
  Estimate gravity;                  // m/s^2
  double t_ref_s = 0.0;              // t0 of the parameterisation
  std::vector<double> coefficients;  // a1, b1, a2, b2 (and g when fitted)
  Estimate impact_time_s;
  Estimate impact_height_m;                 // bead centre at impact, above the plate
  Estimate launch_height_m;                 // H: apex before impact above the plate
  Estimate rebound_height_m;                // h: apex after impact above the plate
  Estimate velocity_before;                 // vertical, m/s (negative)
  Estimate velocity_after;                  // vertical, m/s (positive)
  Estimate e_heights;                       // sqrt(h / H)
  Estimate e_velocity;                      // -v_after / v_before
  double horizontal_velocity_before = 0.0;  // m/s, straight-line fit of x(t)
  double horizontal_velocity_after = 0.0;
  double rms_residual_before_m = 0.0;
  double rms_residual_after_m = 0.0;
  double max_abs_residual_m = 0.0;
  std::vector<std::string> warnings;
};

// Reads columns t_s, x_m, z_m. Throws InputError (file and line where there is one).
std::vector<TrackPoint> read_track(const CsvTable& table);

// Finds the impact and fits the parabolas. Throws InputError for no impact, too few points on
// a side, or a track that is not a free flight (e.g. fitted g not positive).
TrajectoryResult analyse_trajectory(std::vector<TrackPoint> points, const std::string& source,
                                    const TrajectoryOptions& options = {});

}  // namespace grainlab::calibrate
