#include "calibrate/friction_fits.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "calibrate/least_squares.hpp"

namespace grainlab::calibrate {
namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

double centred_r_squared(const std::vector<LoadPoint>& points, double ssr) {
  double mean_f = 0.0;
  for (const auto& p : points) mean_f += p.friction_force_n;
  mean_f /= static_cast<double>(points.size());
  double sst = 0.0;
  for (const auto& p : points) sst += (p.friction_force_n - mean_f) * (p.friction_force_n - mean_f);
  return sst > 0.0 ? 1.0 - ssr / sst : nan;
}

// Regressors of mu(V): 1, u, u^2 [, w], u = min(V, V_b), w = max(V - V_b, 0).
std::vector<double> speed_basis(double v, double v_b, bool linear_part) {
  const double u = std::min(v, v_b);
  std::vector<double> b{1.0, u, u * u};
  if (linear_part) b.push_back(std::max(v - v_b, 0.0));
  return b;
}

}  // namespace

OriginFit fit_through_origin(const std::vector<LoadPoint>& points, double level) {
  if (points.empty()) throw std::invalid_argument("fit_through_origin: no points");
  OriginFit f;
  f.n = points.size();
  double spp = 0.0, spf = 0.0;
  for (const auto& p : points) {
    spp += p.normal_load_n * p.normal_load_n;
    spf += p.normal_load_n * p.friction_force_n;
  }
  if (!(spp > 0.0)) throw RankDeficient("all normal loads are zero");
  f.slope = spf / spp;
  double ssr = 0.0;
  for (const auto& p : points) {
    const double r = p.friction_force_n - f.slope * p.normal_load_n;
    f.residuals_n.push_back(r);
    ssr += r * r;
  }
  f.r_squared = centred_r_squared(points, ssr);
  if (f.n >= 2) {
    const double dof = static_cast<double>(f.n - 1);
    f.residual_sd_n = std::sqrt(ssr / dof);
    f.standard_error = f.residual_sd_n / std::sqrt(spp);  // Var(mu) = s^2 / sum P^2
    f.ci = t_interval(f.slope, f.standard_error, dof, level);
  } else {
    f.residual_sd_n = f.standard_error = nan;
    f.ci = {level, f.slope, f.slope};
  }
  return f;
}

FreeFit fit_free_intercept(const std::vector<LoadPoint>& points, double level) {
  std::vector<std::vector<double>> rows;
  std::vector<double> y;
  for (const auto& p : points) {
    rows.push_back({p.normal_load_n, 1.0});
    y.push_back(p.friction_force_n);
  }
  const LinearFit lf = least_squares(rows, y);  // throws RankDeficient for one distinct load
  FreeFit f;
  f.n = points.size();
  f.slope = lf.coefficients[0];
  f.intercept_n = lf.coefficients[1];
  f.r_squared = centred_r_squared(points, lf.ssr);
  if (lf.dof > 0) {
    f.slope_standard_error = lf.standard_error(0);
    f.intercept_standard_error_n = lf.standard_error(1);
    const double t = f.intercept_n / f.intercept_standard_error_n;
    f.intercept_p_value = f.intercept_standard_error_n > 0.0
                              ? student_t_two_sided_p(t, static_cast<double>(lf.dof))
                              : (f.intercept_n == 0.0 ? 1.0 : 0.0);
    f.intercept_significant = f.intercept_p_value < 1.0 - level;
  } else {
    f.slope_standard_error = f.intercept_standard_error_n = f.intercept_p_value = nan;
  }
  return f;
}

double SpeedFit::friction_at(double v) const {
  const auto b = speed_basis(v, breakpoint_mm_per_min, has_linear_part);
  double mu = 0.0;
  for (std::size_t i = 0; i < b.size(); ++i) mu += b[i] * coefficients[i];
  return mu;
}

double SpeedFit::friction_standard_error_at(double v) const {
  if (dof == 0) return nan;
  const auto b = speed_basis(v, breakpoint_mm_per_min, has_linear_part);
  const std::size_t p = b.size();
  double var = 0.0;
  for (std::size_t i = 0; i < p; ++i)
    for (std::size_t j = 0; j < p; ++j) var += b[i] * covariance[i * p + j] * b[j];
  return std::sqrt(std::max(var, 0.0));
}

double SpeedFit::high_intercept() const {
  // Above V_b: mu = mu(V_b) + c3 (V - V_b) = c3 V + (mu(V_b) - c3 V_b).
  return friction_at(breakpoint_mm_per_min) - high_slope() * breakpoint_mm_per_min;
}

SpeedFit fit_speed_curve(const std::vector<LoadPoint>& points, double breakpoint_mm_per_min,
                         double level) {
  SpeedFit f;
  f.breakpoint_mm_per_min = breakpoint_mm_per_min;
  f.has_linear_part = false;
  for (const auto& p : points)
    if (p.speed_mm_per_min > breakpoint_mm_per_min) f.has_linear_part = true;
  // F = P mu(V): the regressors of mu(V), each multiplied by the load.
  std::vector<std::vector<double>> rows;
  std::vector<double> y;
  for (const auto& p : points) {
    auto b = speed_basis(p.speed_mm_per_min, breakpoint_mm_per_min, f.has_linear_part);
    for (double& x : b) x *= p.normal_load_n;
    rows.push_back(std::move(b));
    y.push_back(p.friction_force_n);
  }
  const LinearFit lf = least_squares(rows, y);
  f.coefficients = lf.coefficients;
  f.covariance = lf.covariance;
  f.n = points.size();
  f.dof = lf.dof;
  f.residual_sd_n = lf.residual_sd();
  f.quasi_static.value = f.coefficients[0];
  if (f.dof > 0) {
    f.quasi_static.standard_error = lf.standard_error(0);
    f.quasi_static.ci = t_interval(f.quasi_static.value, f.quasi_static.standard_error,
                                   static_cast<double>(f.dof), level);
  } else {
    f.quasi_static.standard_error = nan;
    f.quasi_static.ci = {level, f.quasi_static.value, f.quasi_static.value};
  }
  return f;
}

}  // namespace grainlab::calibrate
