// The fits of the sliding-friction test (docs/calibration.md; Tang et al. 2019, Eq. 2, Table 4).
//
// A slider faced with the boundary material is pulled over a bead bed at constant speed V;
// the rope force F is measured for several normal loads P. Coulomb friction F = mu P, so at
// one speed mu is the slope of the F-P line through the origin. The free-intercept line
// F = mu' P + F0 is fitted as a check: a significant F0 means an adhesion, a rope/pulley loss or
// a load offset that the through-origin slope would hide.
//
// Speed effect: mu(V) quadratic below a breakpoint V_b and linear above it, continuous at V_b
// (the shape of the published Eq. 2):
//   mu(V) = c0 + c1 u + c2 u^2 + c3 w,   u = min(V, V_b),  w = max(V - V_b, 0).
// It is fitted to every (V, P, F) point of a material at once, F = P mu(V) (linear in c), so
// the uncertainty of the quasi-static coefficient mu(V -> 0) = c0 comes from all the data.
//
// Units: P and F in N, V in mm/min, mu dimensionless.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "calibrate/statistics.hpp"

namespace grainlab::calibrate {

struct LoadPoint {
  std::size_t line = 0;  // line in the input file
  double speed_mm_per_min = 0.0;
  double normal_load_n = 0.0;     // P
  double friction_force_n = 0.0;  // F
};

// F = mu P (through the origin), least squares: mu = sum(P F) / sum(P^2), dof = n - 1.
// R^2 here is the centred one, 1 - SSR / sum (F - mean F)^2 (comparable with the free line's;
// the uncentred R^2 that spreadsheets report for a line through the origin is always higher).
struct OriginFit {
  std::size_t n = 0;
  double slope = 0.0;  // mu
  double standard_error = 0.0;
  ConfidenceInterval ci;
  double r_squared = 0.0;
  double residual_sd_n = 0.0;
  std::vector<double> residuals_n;
};

// F = slope P + intercept, dof = n - 2; the intercept is significant when its two-sided
// p-value is below 1 - level.
struct FreeFit {
  std::size_t n = 0;
  double slope = 0.0;
  double slope_standard_error = 0.0;  // NaN when n == 2
  double intercept_n = 0.0;
  double intercept_standard_error_n = 0.0;  // NaN when n == 2
  double intercept_p_value = 1.0;           // NaN when n == 2
  bool intercept_significant = false;
  double r_squared = 0.0;
};

OriginFit fit_through_origin(const std::vector<LoadPoint>& points, double level = 0.95);
FreeFit fit_free_intercept(const std::vector<LoadPoint>& points, double level = 0.95);

struct SpeedFit {
  double breakpoint_mm_per_min = 5.0;
  bool has_linear_part = true;       // false when no speed lies above the breakpoint
  std::vector<double> coefficients;  // c0, c1 (per mm/min), c2 (per (mm/min)^2)[, c3 per mm/min]
  std::vector<double> covariance;    // row-major, coefficients.size()^2
  std::size_t n = 0;                 // points used
  std::size_t dof = 0;               // n - number of coefficients
  double residual_sd_n = 0.0;
  Estimate quasi_static;  // mu(V -> 0) = c0

  double friction_at(double speed_mm_per_min) const;  // mu(V)
  // Standard error of mu(V) from the coefficients' covariance.
  double friction_standard_error_at(double speed_mm_per_min) const;
  // The same curve written like the published Eq. 2: below the breakpoint
  // mu = q2 V^2 + q1 V + q0, above it mu = s V + m.
  double low_q0() const { return coefficients[0]; }
  double low_q1() const { return coefficients[1]; }
  double low_q2() const { return coefficients[2]; }
  double high_slope() const { return has_linear_part ? coefficients[3] : 0.0; }
  double high_intercept() const;
};

// Fits mu(V) to all points of one material (the linear part only when some speed lies above
// the breakpoint). Throws RankDeficient when the speeds do not determine the curve (e.g. only
// two distinct speeds at or below the breakpoint, one of them at it).
SpeedFit fit_speed_curve(const std::vector<LoadPoint>& points, double breakpoint_mm_per_min,
                         double level = 0.95);

}  // namespace grainlab::calibrate
