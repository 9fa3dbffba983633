#include "io/derived_report.hpp"

#include <fmt/format.h>

namespace grainlab {
namespace {

nlohmann::json spring_dashpots_json(const std::vector<SpringDashpot>& pieces) {
  nlohmann::json list = nlohmann::json::array();
  for (const SpringDashpot& s : pieces)
    list.push_back({{"piece", s.piece},
                    {"stiffness", s.stiffness},
                    {"damping", s.damping},
                    {"effective_inertia", s.mass},
                    {"damping_ratio", s.damping_ratio},
                    {"critical_step_s", s.critical_step}});
  return list;
}

}  // namespace

nlohmann::json derived_pairs_json(const std::vector<DerivedPair>& pairs, const TimeStepChoice& dt) {
  nlohmann::json list = nlohmann::json::array();
  for (const DerivedPair& p : pairs) {
    list.push_back({
        {"materials", {p.material_a, p.material_b}},
        {"contact", p.wall_pair ? "particle-wall" : "particle-particle"},
        {"radius_a_m", p.radius_a},
        {"radius_b_m", p.radius_b},
        {"effective_radius_m", p.effective_radius},
        {"effective_mass_kg", p.effective_mass},
        {"restitution", p.restitution},
        {"friction", p.friction},
        {"arf", p.arf},
        {"k_n_N_per_m", p.normal_stiffness},
        {"k_s_N_per_m", p.sliding_stiffness},
        {"k_theta_N_m_per_rad", p.rolling_stiffness},
        {"c_n_N_s_per_m", p.normal_damping},
        {"c_s_N_s_per_m", p.sliding_damping},
        {"damping_ratio_textbook", p.damping_ratio_textbook},
        {"damping_ratio_used", p.damping_ratio},
        {"mu_theta_m_at_half_percent_overlap", p.rolling_moment_per_force_at_half_percent},
        {"collision_duration_s", p.collision_duration},
        {"stable_step_s", p.step_limit.time_step},
        {"spring_dashpots", spring_dashpots_json(p.spring_dashpots)},
    });
  }
  return {{"pairs", list},
          {"collision_duration_s", dt.collision_duration},
          {"time_step_s", dt.time_step},
          {"dt_fraction", dt.dt_fraction},
          {"time_step_explicit", dt.explicit_dt},
          {"stable_step_s", dt.stable_limit},
          {"stable_step_set_by", dt.stable_limit_set_by},
          {"time_step_limited_by_stability", dt.limited_by_stability}};
}

std::string derived_pairs_text(const std::vector<DerivedPair>& pairs, const TimeStepChoice& dt) {
  std::string out = fmt::format(
      "{:<28} {:>9} {:>6} {:>5} {:>11} {:>11} {:>11} {:>11} {:>11} {:>8} {:>8} {:>11}\n", "pair",
      "r* [m]", "e", "mu_s", "k_n [N/m]", "k_s [N/m]", "k_th [Nm]", "c_n [Ns/m]", "c_s [Ns/m]",
      "zeta_Eq7", "zeta", "t_c [s]");
  for (const DerivedPair& p : pairs) {
    const std::string name =
        fmt::format("{}-{}{}", p.material_a, p.material_b, p.wall_pair ? " (wall)" : "");
    out += fmt::format(
        "{:<28} {:>9.4g} {:>6.3f} {:>5.3f} {:>11.4e} {:>11.4e} {:>11.4e} {:>11.4e} {:>11.4e} "
        "{:>8.5f} "
        "{:>8.5f} {:>11.4e}\n",
        name, p.effective_radius, p.restitution, p.friction, p.normal_stiffness,
        p.sliding_stiffness, p.rolling_stiffness, p.normal_damping, p.sliding_damping,
        p.damping_ratio_textbook, p.damping_ratio, p.collision_duration);
    if (p.arf > 0.0)
      out += fmt::format(
          "{:<28} rolling: ARF = {:.4g}, mu_theta = ARF a = {:.4e} m at U_n = 0.5 % r*\n", "",
          p.arf, p.rolling_moment_per_force_at_half_percent);
    std::string pieces;
    for (const SpringDashpot& s : p.spring_dashpots)
      pieces += fmt::format("{}{} {:.3e} s (zeta {:.3g})", pieces.empty() ? "" : ", ", s.piece,
                            s.critical_step, s.damping_ratio);
    out += fmt::format("{:<28} critical steps: {}\n", "", pieces);
  }
  out += fmt::format(
      "\ncollision duration t_c (Eq. 11, smallest over the pairs) = {:.4e} s\n"
      "stable step ({}, held by four such contacts) = {:.4e} s\n"
      "time step dt = {:.4e} s = {:.3g} t_c{}\n"
      "zeta_Eq7: textbook damping ratio -ln e / sqrt(pi^2 + ln^2 e); zeta: the ratio grainlab "
      "uses,\n"
      "which returns e exactly with the no-tension clamp (docs/contact-model.md).\n",
      dt.collision_duration, dt.stable_limit_set_by, dt.stable_limit, dt.time_step, dt.dt_fraction,
      dt.explicit_dt            ? " (set explicitly)"
      : dt.limited_by_stability ? " (lowered below dt_fraction * t_c for stability)"
                                : " (dt_fraction; integrating at t_c itself is unstable)");
  return out;
}

}  // namespace grainlab
