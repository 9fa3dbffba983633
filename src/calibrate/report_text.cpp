// Text reports for a person: tables laid out like the published Tables 3 and 4.
#include <fmt/format.h>

#include <cmath>

#include "calibrate/report.hpp"
#include "calibrate/text_table.hpp"

namespace grainlab::calibrate {
namespace {

std::string num(double x, int digits = 4) {
  return std::isfinite(x) ? fmt::format("{:.{}f}", x, digits) : "n/a";
}

std::string gnum(double x, int digits = 4) {
  return std::isfinite(x) ? fmt::format("{:.{}g}", x, digits) : "n/a";
}

std::string interval(const ConfidenceInterval& ci, int digits = 4) {
  if (!std::isfinite(ci.low) || !std::isfinite(ci.high) || ci.low == ci.high) return "n/a";
  return fmt::format("[{}, {}]", num(ci.low, digits), num(ci.high, digits));
}

// " + 0.00317 V" / " - 0.00317 V": a polynomial term with its sign spaced out.
std::string term(double c, const char* power) {
  return fmt::format(" {} {:.4g}{}", c < 0 ? '-' : '+', std::abs(c), power);
}

std::string percent(double level) {
  return fmt::format("{:g} %", 100.0 * level);
}

std::string estimate_line(const char* name, const Estimate& e, const char* unit, int digits) {
  return fmt::format("  {:<34} {} ± {} {}  ({} CI {})\n", name, num(e.value, digits),
                     num(e.standard_error, digits), unit, percent(e.ci.level),
                     interval(e.ci, digits));
}

}  // namespace

std::string restitution_text(const RestitutionAnalysis& a) {
  const double level = a.materials.empty() ? 0.95 : a.materials.front().ci.level;
  std::string out = fmt::format(
      "Restitution coefficients from {}\n(flat-throw test, e = sqrt(h/H) per throw; "
      "{} confidence interval of the mean,\nStudent t with n - 1 degrees of freedom)\n\n",
      a.source, percent(level));
  TextTable t({"material", "n", "e mean", "sd", "s.e.", fmt::format("{} CI", percent(level)),
               "e min", "e max"});
  for (const auto& m : a.materials) {
    double lo = 1.0, hi = 0.0;
    for (const auto& th : m.throws) {
      lo = std::min(lo, th.restitution);
      hi = std::max(hi, th.restitution);
    }
    t.add_row({m.material, fmt::format("{}", m.n), num(m.mean), num(m.sd), num(m.standard_error),
               interval(m.ci), num(lo), num(hi)});
  }
  out += t.str();
  for (const auto& m : a.materials)
    if (m.n < 2) out += fmt::format("\n  note: {} has one throw: no sd or CI\n", m.material);
  return out;
}

std::string trajectory_text(const TrajectoryResult& r) {
  std::string out = fmt::format(
      "Restitution from the tracked trajectory {}\n(free-flight parabolas before and after the "
      "impact, least squares with {} g;\n{} confidence intervals, Student t with {} degrees of "
      "freedom)\n\n",
      r.source, r.gravity_fitted ? "a shared fitted" : "a fixed", percent(r.e_velocity.ci.level),
      r.dof);
  out += fmt::format("  points used: {} before the impact, {} after (of {})\n", r.n_before,
                     r.n_after, r.points.size());
  out += estimate_line(r.gravity_fitted ? "g (fitted)" : "g (fixed)", r.gravity, "m/s^2", 4);
  out += estimate_line("impact time", r.impact_time_s, "s", 6);
  out += estimate_line("bead centre at impact above plate", r.impact_height_m, "m", 5);
  out += estimate_line("H (launch apex above plate)", r.launch_height_m, "m", 5);
  out += estimate_line("h (rebound apex above plate)", r.rebound_height_m, "m", 5);
  out += estimate_line("vertical velocity before impact", r.velocity_before, "m/s", 4);
  out += estimate_line("vertical velocity after impact", r.velocity_after, "m/s", 4);
  out += fmt::format("  {:<34} {} m/s before, {} m/s after\n", "horizontal velocity",
                     num(r.horizontal_velocity_before), num(r.horizontal_velocity_after));
  out += "\n";
  out += estimate_line("e = sqrt(h/H)", r.e_heights, "", 4);
  out += estimate_line("e = -v_after/v_before", r.e_velocity, "", 4);
  out += fmt::format("\n  residuals of z: rms {} mm before, {} mm after, largest {} mm\n",
                     num(1e3 * r.rms_residual_before_m, 3), num(1e3 * r.rms_residual_after_m, 3),
                     num(1e3 * r.max_abs_residual_m, 3));
  for (const auto& w : r.warnings) out += fmt::format("  warning: {}\n", w);
  return out;
}

std::string friction_text(const FrictionAnalysis& a) {
  const double level = a.options.level;
  const double v_b = a.options.breakpoint_mm_per_min;
  std::string out = fmt::format(
      "Friction coefficients from {}\n(sliding-friction test; mu = slope of the F-P line "
      "through the origin at each speed;\n{} confidence intervals, Student t; R^2 centred; "
      "the free-intercept\nline F = slope P + F0 is a check, '*' = F0 significant)\n\n",
      a.source, percent(level));
  TextTable t({"material", "V (mm/min)", "n", "mu", "s.e.", fmt::format("{} CI", percent(level)),
               "R^2", "free slope", "F0 (N)", "F0 s.e.", "p(F0)", ""});
  for (const auto& m : a.materials)
    for (const auto& s : m.speeds)
      t.add_row({m.material, gnum(s.speed_mm_per_min, 6), fmt::format("{}", s.origin.n),
                 num(s.origin.slope), num(s.origin.standard_error), interval(s.origin.ci),
                 num(s.origin.r_squared), num(s.free.slope), num(s.free.intercept_n, 5),
                 num(s.free.intercept_standard_error_n, 5), num(s.free.intercept_p_value, 3),
                 s.free.intercept_significant ? "*" : ""});
  out += t.str();

  out += fmt::format(
      "\nSpeed fit per material (quadratic for V <= {0:g} mm/min, linear above, continuous at\n"
      "{0:g} mm/min; fitted to all points at once as F = P mu(V); the quasi-static coefficient is "
      "mu(V -> 0)):\n",
      v_b);
  for (const auto& m : a.materials) {
    if (!m.speed_fit) {
      out += fmt::format("  {}: {}\n", m.material, m.speed_fit_note);
      continue;
    }
    const SpeedFit& f = *m.speed_fit;
    // Written like the published Eq. 2 (coefficients of V in mm/min).
    out += fmt::format("  {}: mu = {:.4f}{}{}   (V <= {:g} mm/min)\n", m.material, f.low_q0(),
                       term(f.low_q1(), " V"), term(f.low_q2(), " V^2"), v_b);
    if (f.has_linear_part)
      out += fmt::format("  {:{}}  mu = {:.4f}{}   (V > {:g} mm/min)\n", "", m.material.size(),
                         f.high_intercept(), term(f.high_slope(), " V"), v_b);
    out += fmt::format("  {:{}}  {} points, {} dof, residual sd {} N\n", "", m.material.size(), f.n,
                       f.dof, gnum(f.residual_sd_n, 3));
    if (f.dof == 0)
      out += fmt::format("  {:{}}  (no degrees of freedom left: no uncertainty)\n", "",
                         m.material.size());
  }

  out += fmt::format(
      "\nFriction coefficients (as the published Table 4: at the highest speed tested, and "
      "quasi-static)\n\n");
  TextTable s({"material", "V max (mm/min)", "mu at V max", fmt::format("{} CI", percent(level)),
               "quasi-static mu", fmt::format("{} CI", percent(level))});
  for (const auto& m : a.materials) {
    const auto& top = m.speeds.back();
    s.add_row({m.material, gnum(top.speed_mm_per_min, 6), num(top.origin.slope),
               interval(top.origin.ci), m.speed_fit ? num(m.speed_fit->quasi_static.value) : "n/a",
               m.speed_fit ? interval(m.speed_fit->quasi_static.ci) : "n/a"});
  }
  out += s.str();
  for (const auto& w : a.warnings) out += fmt::format("  warning: {}\n", w);
  return out;
}

}  // namespace grainlab::calibrate
