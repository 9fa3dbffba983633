// JSON reports for programs (and for scripts/plot_calibration.py). NaN becomes null.
#include <cmath>

#include "calibrate/report.hpp"

namespace grainlab::calibrate {
namespace {

using nlohmann::json;

json number(double x) {
  return std::isfinite(x) ? json(x) : json(nullptr);
}

json interval(const ConfidenceInterval& ci) {
  return {{"level", ci.level}, {"low", number(ci.low)}, {"high", number(ci.high)}};
}

json estimate(const Estimate& e) {
  return {{"value", number(e.value)},
          {"standard_error", number(e.standard_error)},
          {"ci", interval(e.ci)}};
}

}  // namespace

json restitution_json(const RestitutionAnalysis& a) {
  json materials = json::array();
  for (const auto& m : a.materials) {
    json throws = json::array();
    for (const auto& t : m.throws)
      throws.push_back({{"line", t.line},
                        {"H_m", t.launch_height_m},
                        {"h_m", t.rebound_height_m},
                        {"e", t.restitution}});
    materials.push_back({{"material", m.material},
                         {"n", m.n},
                         {"mean", number(m.mean)},
                         {"sd", number(m.sd)},
                         {"standard_error", number(m.standard_error)},
                         {"ci", interval(m.ci)},
                         {"throws", throws}});
  }
  return {{"analysis", "restitution"},
          {"method", "flat throw, e = sqrt(h/H)"},
          {"source", a.source},
          {"materials", materials}};
}

json trajectory_json(const TrajectoryResult& r) {
  json points = json::array();
  for (std::size_t i = 0; i < r.points.size(); ++i)
    points.push_back({{"line", r.points[i].line},
                      {"t_s", r.points[i].t_s},
                      {"x_m", r.points[i].x_m},
                      {"z_m", r.points[i].z_m},
                      {"side", r.side[i] < 0 ? "before" : (r.side[i] > 0 ? "after" : "unused")},
                      {"residual_m", r.residual_m[i]}});
  const double g = r.gravity.value;
  return {{"analysis", "trajectory"},
          {"source", r.source},
          {"n_before", r.n_before},
          {"n_after", r.n_after},
          {"dof", r.dof},
          {"gravity_fitted", r.gravity_fitted},
          {"gravity_m_s2", estimate(r.gravity)},
          // z(t) = a + b (t - t_ref) - g (t - t_ref)^2 / 2 on each side
          {"parabola_before",
           {{"t_ref_s", r.t_ref_s},
            {"a_m", r.coefficients[0]},
            {"b_m_s", r.coefficients[1]},
            {"g_m_s2", g}}},
          {"parabola_after",
           {{"t_ref_s", r.t_ref_s},
            {"a_m", r.coefficients[2]},
            {"b_m_s", r.coefficients[3]},
            {"g_m_s2", g}}},
          {"impact_time_s", estimate(r.impact_time_s)},
          {"impact_height_m", estimate(r.impact_height_m)},
          {"H_m", estimate(r.launch_height_m)},
          {"h_m", estimate(r.rebound_height_m)},
          {"vertical_velocity_before_m_s", estimate(r.velocity_before)},
          {"vertical_velocity_after_m_s", estimate(r.velocity_after)},
          {"horizontal_velocity_before_m_s", r.horizontal_velocity_before},
          {"horizontal_velocity_after_m_s", r.horizontal_velocity_after},
          {"e_heights", estimate(r.e_heights)},
          {"e_velocity", estimate(r.e_velocity)},
          {"rms_residual_before_m", r.rms_residual_before_m},
          {"rms_residual_after_m", r.rms_residual_after_m},
          {"max_abs_residual_m", r.max_abs_residual_m},
          {"warnings", r.warnings},
          {"points", points}};
}

json friction_json(const FrictionAnalysis& a) {
  json materials = json::array();
  for (const auto& m : a.materials) {
    json speeds = json::array();
    for (const auto& s : m.speeds) {
      json points = json::array();
      for (const auto& p : s.points)
        points.push_back({{"line", p.line},
                          {"normal_load_N", p.normal_load_n},
                          {"friction_force_N", p.friction_force_n}});
      speeds.push_back({{"speed_mm_per_min", s.speed_mm_per_min},
                        {"points", points},
                        {"through_origin",
                         {{"n", s.origin.n},
                          {"mu", s.origin.slope},
                          {"standard_error", number(s.origin.standard_error)},
                          {"ci", interval(s.origin.ci)},
                          {"r_squared", number(s.origin.r_squared)},
                          {"residual_sd_N", number(s.origin.residual_sd_n)},
                          {"residuals_N", s.origin.residuals_n}}},
                        {"free_intercept",
                         {{"slope", s.free.slope},
                          {"slope_standard_error", number(s.free.slope_standard_error)},
                          {"intercept_N", s.free.intercept_n},
                          {"intercept_standard_error_N", number(s.free.intercept_standard_error_n)},
                          {"intercept_p_value", number(s.free.intercept_p_value)},
                          {"intercept_significant", s.free.intercept_significant},
                          {"r_squared", number(s.free.r_squared)}}}});
    }
    json fit = nullptr;
    if (m.speed_fit) {
      const SpeedFit& f = *m.speed_fit;
      fit = {{"model", "mu = c0 + c1 u + c2 u^2 + c3 w, u = min(V, V_b), w = max(V - V_b, 0)"},
             {"breakpoint_mm_per_min", f.breakpoint_mm_per_min},
             {"has_linear_part", f.has_linear_part},
             {"coefficients", f.coefficients},
             {"covariance", f.covariance},
             {"n", f.n},
             {"dof", f.dof},
             {"residual_sd_N", number(f.residual_sd_n)},
             {"low_speed", {{"q2", f.low_q2()}, {"q1", f.low_q1()}, {"q0", f.low_q0()}}},
             {"high_speed", {{"slope", f.high_slope()}, {"intercept", f.high_intercept()}}},
             {"quasi_static", estimate(f.quasi_static)}};
    }
    materials.push_back({{"material", m.material},
                         {"speeds", speeds},
                         {"speed_fit", fit},
                         {"speed_fit_note", m.speed_fit_note}});
  }
  return {{"analysis", "friction"},
          {"method", "mu = slope of F-P through the origin per speed; speed fit of Eq. 2 shape"},
          {"source", a.source},
          {"level", a.options.level},
          {"breakpoint_mm_per_min", a.options.breakpoint_mm_per_min},
          {"materials", materials},
          {"warnings", a.warnings}};
}

}  // namespace grainlab::calibrate
