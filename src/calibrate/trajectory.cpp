#include "calibrate/trajectory.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>

#include "calibrate/input_error.hpp"
#include "calibrate/least_squares.hpp"

namespace grainlab::calibrate {
namespace {

constexpr double standard_gravity = 9.80665;  // m/s^2, only for a plausibility warning

// Index of the first impact: the lowest point of the first run of points in the lowest tenth
// of the height range (the bead moves fast there, so camera noise cannot fake a minimum), and
// the end of the free flight after it (the next such run, i.e. a second impact, or the end).
struct Segmentation {
  std::size_t impact = 0;
  std::size_t end = 0;  // one past the last point of the after-impact flight
};

std::optional<Segmentation> find_impact(const std::vector<TrackPoint>& p) {
  double z_min = p.front().z_m, z_max = p.front().z_m;
  for (const auto& q : p) {
    z_min = std::min(z_min, q.z_m);
    z_max = std::max(z_max, q.z_m);
  }
  if (!(z_max > z_min)) return std::nullopt;
  const double band = z_min + 0.1 * (z_max - z_min);
  std::vector<std::pair<std::size_t, std::size_t>> runs;  // [begin, end) of low points
  for (std::size_t i = 0; i < p.size();) {
    if (p[i].z_m >= band) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < p.size() && p[j].z_m < band) ++j;
    runs.push_back({i, j});
    i = j;
  }
  for (std::size_t r = 0; r < runs.size(); ++r) {
    auto [b, e] = runs[r];
    std::size_t k = b;
    for (std::size_t i = b; i < e; ++i)
      if (p[i].z_m < p[k].z_m) k = i;
    if (k == 0 || k + 1 == p.size()) continue;  // at an end of the track: not seen to bounce
    std::size_t end = p.size();
    if (r + 1 < runs.size()) {  // a second impact: stop at its lowest point
      auto [b2, e2] = runs[r + 1];
      end = b2;
      for (std::size_t i = b2; i < e2; ++i)
        if (p[i].z_m < p[end].z_m) end = i;
    }
    return Segmentation{k, end};
  }
  return std::nullopt;
}

struct Derived {
  double tau_i, z_i, v1, v2, launch, rebound, e_heights, e_velocity, g;
};

// Quantities derived from the parameters (a1, b1, a2, b2, g), see the header.
Derived derive(const std::array<double, 5>& q, double plate_z) {
  const auto [a1, b1, a2, b2, g] = q;
  Derived d{};
  d.g = g;
  d.tau_i = (a2 - a1) / (b1 - b2);
  d.z_i = a1 + b1 * d.tau_i - 0.5 * g * d.tau_i * d.tau_i - plate_z;
  d.v1 = b1 - g * d.tau_i;
  d.v2 = b2 - g * d.tau_i;
  d.launch = a1 + b1 * b1 / (2.0 * g) - plate_z;   // apex of the parabola before impact
  d.rebound = a2 + b2 * b2 / (2.0 * g) - plate_z;  // apex after impact
  d.e_heights = std::sqrt(d.rebound / d.launch);
  d.e_velocity = -d.v2 / d.v1;
  return d;
}

struct SideFit {
  LinearFit fit;
  std::size_t split = 0;  // first index of the after-impact side
};

LinearFit fit_parabolas(const std::vector<TrackPoint>& p, std::size_t begin_after, std::size_t end,
                        double t_ref, const std::optional<double>& gravity) {
  std::vector<std::vector<double>> rows;
  std::vector<double> y;
  for (std::size_t i = 0; i < end; ++i) {
    const double tau = p[i].t_s - t_ref;
    const bool after = i >= begin_after;
    std::vector<double> row{after ? 0.0 : 1.0, after ? 0.0 : tau, after ? 1.0 : 0.0,
                            after ? tau : 0.0};
    if (gravity) {
      y.push_back(p[i].z_m + 0.5 * *gravity * tau * tau);
    } else {
      row.push_back(-0.5 * tau * tau);
      y.push_back(p[i].z_m);
    }
    rows.push_back(std::move(row));
  }
  return least_squares(rows, y);
}

double slope_of_line(const std::vector<TrackPoint>& p, std::size_t begin, std::size_t end) {
  std::vector<std::vector<double>> rows;
  std::vector<double> y;
  for (std::size_t i = begin; i < end; ++i) {
    rows.push_back({1.0, p[i].t_s - p[begin].t_s});
    y.push_back(p[i].x_m);
  }
  return least_squares(rows, y).coefficients[1];
}

}  // namespace

std::vector<TrackPoint> read_track(const CsvTable& table) {
  const std::size_t c_t = table.column("t_s");
  const std::size_t c_x = table.column("x_m");
  const std::size_t c_z = table.column("z_m");
  std::vector<TrackPoint> points;
  for (const CsvRecord& rec : table.records()) {
    TrackPoint q{rec.line, table.number(rec, c_t), table.number(rec, c_x), table.number(rec, c_z)};
    if (!points.empty() && !(q.t_s > points.back().t_s))
      throw InputError(
          fmt::format("{}: t_s = {} is not after the previous point's t_s = {} "
                      "(times must increase)",
                      table.where(rec), q.t_s, points.back().t_s));
    points.push_back(q);
  }
  return points;
}

TrajectoryResult analyse_trajectory(std::vector<TrackPoint> points, const std::string& source,
                                    const TrajectoryOptions& options) {
  const std::size_t need = options.min_points_per_side;
  if (points.size() < 2 * need + 1)
    throw InputError(
        fmt::format("{}: {} track points; at least {} are needed ({} before and {} "
                    "after the impact, plus one more for the residuals)",
                    source, points.size(), 2 * need + 1, need, need));
  const auto seg = find_impact(points);
  if (!seg)
    throw InputError(
        fmt::format("{}: no impact found: the bead is never seen to come down and "
                    "go up again",
                    source));
  const std::size_t k = seg->impact;
  const double t_ref = points[k].t_s;

  // The lowest point may be just before or just after the impact: keep the better fit.
  std::optional<SideFit> best;
  for (std::size_t split : {k, k + 1}) {
    const std::size_t n_before = split, n_after = seg->end - split;
    if (n_before < need || n_after < need) continue;
    try {
      LinearFit f = fit_parabolas(points, split, seg->end, t_ref, options.gravity);
      if (!best || f.ssr < best->fit.ssr) best = SideFit{std::move(f), split};
    } catch (const RankDeficient&) {
    }
  }
  if (!best) {
    const std::size_t before = k + 1, after = seg->end - k;
    throw InputError(fmt::format(
        "{} line {}: impact found here (t_s = {}), but there are too few points to fit a "
        "parabola on each side ({} up to and including it, {} from it to the {}; need {} on each "
        "side)",
        source, points[k].line, points[k].t_s, before, after,
        seg->end < points.size() ? "second impact" : "end", need));
  }
  const LinearFit& fit = best->fit;
  const std::size_t split = best->split;

  TrajectoryResult r;
  r.source = source;
  r.n_before = split;
  r.n_after = seg->end - split;
  r.dof = fit.dof;
  r.gravity_fitted = !options.gravity;
  r.t_ref_s = t_ref;
  r.coefficients = fit.coefficients;

  std::array<double, 5> q{fit.coefficients[0], fit.coefficients[1], fit.coefficients[2],
                          fit.coefficients[3],
                          options.gravity ? *options.gravity : fit.coefficients[4]};
  const std::size_t n_par = fit.coefficients.size();
  if (!(q[4] > 0.0))
    throw InputError(
        fmt::format("{}: the fitted gravity is {:.4g} m/s^2, not positive: is z "
                    "measured upwards, and is the track a free flight?",
                    source, q[4]));
  const Derived d = derive(q, options.plate_z_m);
  if (!(d.v1 < 0.0 && d.v2 > 0.0) || !std::isfinite(d.tau_i))
    throw InputError(
        fmt::format("{} line {}: no impact: the fitted vertical velocity does not "
                    "reverse from downwards to upwards here (before {:.4g} m/s, "
                    "after {:.4g} m/s)",
                    source, points[k].line, d.v1, d.v2));
  if (!(d.launch > 0.0 && d.rebound > 0.0))
    throw InputError(
        fmt::format("{}: the fitted apex heights above the plate (z = {}) are H = "
                    "{:.4g} m and h = {:.4g} m; both must be positive (check "
                    "--plate-z)",
                    source, options.plate_z_m, d.launch, d.rebound));

  // Delta method: Var f = J C J^T, J by central differences scaled to each standard error.
  auto delta = [&](const std::function<double(const Derived&)>& f) {
    std::vector<double> jac(n_par);
    for (std::size_t j = 0; j < n_par; ++j) {
      const double se = std::sqrt(std::max(fit.cov(j, j), 0.0));
      const double h = se > 0.0 ? 1e-3 * se : 1e-8 * std::max(1.0, std::abs(q[j]));
      auto qp = q, qm = q;
      qp[j] += h;
      qm[j] -= h;
      jac[j] = (f(derive(qp, options.plate_z_m)) - f(derive(qm, options.plate_z_m))) / (2.0 * h);
    }
    double var = 0.0;
    for (std::size_t i = 0; i < n_par; ++i)
      for (std::size_t j = 0; j < n_par; ++j) var += jac[i] * fit.cov(i, j) * jac[j];
    Estimate e;
    e.value = f(d);
    e.standard_error = std::sqrt(std::max(var, 0.0));
    if (fit.dof > 0)
      e.ci = t_interval(e.value, e.standard_error, static_cast<double>(fit.dof), options.level);
    else
      e.ci = {options.level, e.value, e.value};
    return e;
  };
  r.gravity = delta([](const Derived& x) { return x.g; });
  if (options.gravity) r.gravity = {*options.gravity, 0.0, {options.level, q[4], q[4]}};
  r.impact_time_s = delta([&](const Derived& x) { return x.tau_i + t_ref; });
  r.impact_height_m = delta([](const Derived& x) { return x.z_i; });
  r.launch_height_m = delta([](const Derived& x) { return x.launch; });
  r.rebound_height_m = delta([](const Derived& x) { return x.rebound; });
  r.velocity_before = delta([](const Derived& x) { return x.v1; });
  r.velocity_after = delta([](const Derived& x) { return x.v2; });
  r.e_heights = delta([](const Derived& x) { return x.e_heights; });
  r.e_velocity = delta([](const Derived& x) { return x.e_velocity; });
  r.horizontal_velocity_before = slope_of_line(points, 0, split);
  r.horizontal_velocity_after = slope_of_line(points, split, seg->end);

  // Residuals per point (the fit's residuals are in point order over [0, end)).
  r.side.assign(points.size(), 0);
  r.residual_m.assign(points.size(), 0.0);
  double ss_before = 0.0, ss_after = 0.0;
  for (std::size_t i = 0; i < seg->end; ++i) {
    const double res = fit.residuals[i];
    r.side[i] = i < split ? -1 : 1;
    r.residual_m[i] = res;
    (i < split ? ss_before : ss_after) += res * res;
    r.max_abs_residual_m = std::max(r.max_abs_residual_m, std::abs(res));
  }
  r.rms_residual_before_m = std::sqrt(ss_before / static_cast<double>(r.n_before));
  r.rms_residual_after_m = std::sqrt(ss_after / static_cast<double>(r.n_after));

  if (seg->end < points.size())
    r.warnings.push_back(
        fmt::format("a second impact near t_s = {}: the {} points from there on "
                    "are not used",
                    points[seg->end].t_s, points.size() - seg->end));
  if (d.z_i < -3.0 * r.impact_height_m.standard_error - 1e-9)
    r.warnings.push_back(
        fmt::format("the bead centre at impact is {:.4g} m BELOW the plate "
                    "(z = {}); check --plate-z",
                    d.z_i, options.plate_z_m));
  else if (d.z_i > 0.05 * d.launch)
    r.warnings.push_back(
        fmt::format("the bead centre at impact is {:.4g} m above the plate "
                    "(z = {}), more than 5 % of H; check --plate-z",
                    d.z_i, options.plate_z_m));
  if (r.gravity_fitted && std::abs(q[4] - standard_gravity) >
                              std::max(0.05 * standard_gravity, 3.0 * r.gravity.standard_error))
    r.warnings.push_back(
        fmt::format("fitted g = {:.4g} m/s^2 differs from 9.81 by more than "
                    "5 %: check the camera's length and time scales",
                    q[4]));
  if (d.rebound > d.launch)
    r.warnings.push_back("the rebound apex is higher than the launch apex (e > 1)");
  r.points = std::move(points);
  return r;
}

}  // namespace grainlab::calibrate
