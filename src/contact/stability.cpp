#include "contact/stability.hpp"

#include <fmt/format.h>

#include <numbers>

#include "contact/contact_law.hpp"

namespace grainlab {
namespace {

struct Inertias {
  double mass, moment;  // kg, kg m^2 (infinite for a wall)
};

Inertias inertias(const ContactBody& body) {
  if (body.is_wall()) return {INFINITY, INFINITY};
  const double r = body.radius;
  const double m = body.density * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  return {m, 0.4 * m * r * r};
}

SpringDashpot make(std::string piece, std::string key, double k, double c, double m) {
  const double zeta = c / (2.0 * std::sqrt(k * m));
  return {std::move(piece), std::move(key), k, c, m, zeta, critical_time_step(k, c, m)};
}

}  // namespace

std::vector<SpringDashpot> spring_dashpots(const PairParams& pair, const ContactBody& a,
                                           const ContactBody& b) {
  const Inertias ia = inertias(a), ib = inertias(b);
  const double r_star = b.is_wall() ? a.radius : a.radius * b.radius / (a.radius + b.radius);
  const double m_star = 1.0 / (1.0 / ia.mass + 1.0 / ib.mass);
  // Contact-point inertia for a tangential force: translation plus the spin the force's moment
  // about each centre causes (lever = radius).
  auto tangential_compliance = [](const ContactBody& body, const Inertias& in) {
    return body.is_wall() ? 0.0 : 1.0 / in.mass + body.radius * body.radius / in.moment;
  };
  const double m_t = 1.0 / (tangential_compliance(a, ia) + tangential_compliance(b, ib));
  const double i_star = 1.0 / (1.0 / ia.moment + 1.0 / ib.moment);

  const NormalParams normal = normal_params(pair, r_star, m_star);  // k_n, c_n as the force loop
  const double k_n = normal.stiffness, c_n = normal.damping;
  std::vector<SpringDashpot> out;
  out.push_back(make("normal", "restitution", k_n, c_n, m_star));
  const double k_s = pair.rns * k_n;
  if (pair.friction > 0.0) out.push_back(make("sliding", "rzs", k_s, pair.rzs * c_n, m_t));
  const double k_theta = 4.0 * r_star * r_star * k_s;  // Eq. 6
  const double c_theta = pair.rolling_damping_ratio * 2.0 * std::sqrt(i_star * k_theta);
  if (pair.arf > 0.0)
    out.push_back(make("rolling", "rolling_damping_ratio", k_theta, c_theta, i_star));
  if (pair.twisting_friction > 0.0)
    out.push_back(make("twisting", "rolling_damping_ratio", k_theta, c_theta, i_star));
  if (pair.rolling_force_stiffness_ratio > 0.0)
    out.push_back(make("rolling force", "rolling_force_stiffness_ratio",
                       pair.rolling_force_stiffness_ratio * k_n, 0.0, m_t));
  return out;
}

StepLimit step_limit(const std::vector<SpringDashpot>& pieces) {
  StepLimit limit;
  for (const SpringDashpot& p : pieces) {
    const double allowed = critical_time_step(contacts_in_parallel * p.stiffness,
                                              contacts_in_parallel * p.damping, p.mass);
    if (allowed < limit.time_step) {
      limit.time_step = allowed;
      limit.limiting = p;
    }
  }
  return limit;
}

std::string describe(const SpringDashpot& piece, const std::string& pair_name) {
  return fmt::format("the {} spring-dashpot of {} (damping ratio {:.3g}{})", piece.piece, pair_name,
                     piece.damping_ratio,
                     piece.key.empty() ? "" : fmt::format(", set by [[pair]] {}", piece.key));
}

MaterialStepLimit material_step_limit(const PairTable& table, int particle_material,
                                      double radius) {
  MaterialStepLimit out;
  const Material& a = table.material(particle_material);
  if (!a.density) return out;
  for (int b = 0; b < table.material_count(); ++b) {
    const PairParams& pair = table(particle_material, b);
    if (!pair.defined) continue;
    const Material& other = table.material(b);
    const ContactBody body_b = other.density ? ContactBody{radius, *other.density} : ContactBody{};
    const StepLimit limit = step_limit(spring_dashpots(pair, {radius, *a.density}, body_b));
    if (limit.time_step < out.time_step) {
      out.time_step = limit.time_step;
      out.description = describe(limit.limiting, a.name + "-" + other.name);
    }
  }
  return out;
}

}  // namespace grainlab
