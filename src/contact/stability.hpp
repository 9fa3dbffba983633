// A stable time step for every spring-dashpot of the contact law (docs/contact-model.md,
// "Time step").
//
// Each piece of a contact is an oscillator: a spring k and a dashpot c acting on an effective
// inertia m (symbols below). grainlab integrates it with velocity Verlet, the dashpot reading the
// end-of-step velocity estimate v(t + dt/2) + dt/2 F(t)/m. For one such oscillator the scheme is
// stable only while
//     omega dt <= 2 (sqrt(1 + 4 zeta^2) - 2 zeta),   omega = sqrt(k/m), zeta = c / (2 sqrt(k m)),
// (the spectral radius of the step's amplification matrix reaches 1 there; for zeta = 0 it is the
// familiar omega dt = 2, for a strong dashpot it tends to dt = m/c). Above it the oscillation
// grows: a heavily damped tangential or rolling spring then creeps, e.g. a sphere slides down a
// slope it should rest on.
//
// A bead in a packing is held by several contacts at once, and its fastest modes are faster and
// more damped than one contact's. grainlab therefore requires every piece in use to be stable as
// the oscillator of a bead held by `contacts_in_parallel` = 4 such contacts (4k, 4c, m: twice the
// frequency and twice the damping ratio). The factor is measured, not guessed: with the
// compaction restitution 0.3 (zeta_n 0.50) at dt = 0.1 t_c the reference specimen (11,636
// beads) never came to rest (unbalanced force stuck near 1e-3), which this rule predicts (it
// allows 0.075 t_c there), while the undamped or lightly damped reference pairs keep 0.1 t_c.
//
//   piece         k                 c                 m (effective inertia)
//   normal        k_n               c_n               m* = m_a m_b / (m_a + m_b)
//   sliding       k_s = RNS k_n     c_s = RZS c_n     m_t: 1/m_t = sum over bodies of 1/m + r^2/I
//                                                     (= 2/7 m* for solid spheres)
//   rolling       k_theta           c_theta           I* = I_a I_b / (I_a + I_b)
//   twisting      k_theta           c_theta           I*
//   rolling force k_r = ratio k_n   none              m_t
// (a wall is a body of infinite mass and inertia; radii and masses are those of the smallest
// particles of each material).
#pragma once

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <string>
#include <vector>

#include "contact/pair_table.hpp"
#include "contact/time_step.hpp"

namespace grainlab {

inline constexpr double contacts_in_parallel = 4.0;

// Critical step of one spring-dashpot under grainlab's integrator, s.
inline double critical_time_step(double stiffness, double damping, double mass) {
  const double omega = std::sqrt(stiffness / mass);
  const double zeta = damping / (2.0 * std::sqrt(stiffness * mass));
  return 2.0 * (std::sqrt(1.0 + 4.0 * zeta * zeta) - 2.0 * zeta) / omega;
}

struct SpringDashpot {
  std::string piece;  // "normal", "sliding", "rolling", "twisting", "rolling force"
  std::string key;    // the [[pair]] key to change: the one that sets its damping, or (for
                      // the undamped rolling force) its stiffness
  double stiffness;   // N/m or N m/rad
  double damping;     // N s/m or N m s/rad
  double mass;        // kg or kg m^2
  double damping_ratio;
  double critical_step;  // s
};

// The body on each side of a contact: a sphere (radius, density) or a wall (radius 0).
struct ContactBody {
  double radius = 0.0;   // m; 0 for a wall
  double density = 0.0;  // kg/m^3
  bool is_wall() const { return radius == 0.0; }
};

// The spring-dashpots a pair switches on, each with its critical step.
std::vector<SpringDashpot> spring_dashpots(const PairParams& pair, const ContactBody& a,
                                           const ContactBody& b);

// The most restrictive of them: the largest step allowed (the critical step of the piece held
// by contacts_in_parallel contacts) and which piece sets it.
struct StepLimit {
  double time_step = INFINITY;  // s
  SpringDashpot limiting{};     // the piece with the smallest critical step
};
StepLimit step_limit(const std::vector<SpringDashpot>& pieces);

// The step limit over every defined pair of one particle material (radius, density) with every
// material of the table (wall materials have no density; another particle material is taken
// with the same radius, which is exact for the lab tests, whose beads are one material).
// `description` names the pair and the piece that set it, e.g. "the sliding dashpot of glass-rubber
// (zeta 3.1, [[pair]] rzs)".
struct MaterialStepLimit {
  double time_step = INFINITY;
  std::string description;
};
MaterialStepLimit material_step_limit(const PairTable& table, int particle_material, double radius);

std::string describe(const SpringDashpot& piece, const std::string& pair_name);

}  // namespace grainlab

namespace grainlab {

// The one time-step rule: the step wanted (dt_fraction * t_c), lowered where a spring-dashpot of
// the particle material's pairs needs a smaller one to stay stable.
struct TimeStepChoiceForMaterial {
  double time_step = 0.0;  // s
  std::string limited_by;  // empty when dt_fraction * t_c was kept
};
inline TimeStepChoiceForMaterial stable_time_step(double wanted, const PairTable& table,
                                                  int particle_material, double min_radius) {
  const MaterialStepLimit limit = material_step_limit(table, particle_material, min_radius);
  if (wanted <= limit.time_step) return {wanted, {}};
  return {limit.time_step, limit.description};
}

// The time step of a run whose particles are all of one material (every laboratory test), by
// the one rule: dt = dt_fraction x the shortest collision duration t_c (Eq. 11, at the smallest
// radius) over the pairs in use, material with each of `partners` (itself, the walls' materials),
// then lowered where a spring-dashpot of the material's pairs needs it (stable_time_step).
// Scenes apply the same rule over their derived pairs (io/scene_builder.cpp, choose_time_step).
struct MaterialTimeStep {
  double time_step = 0.0;           // s
  double collision_duration = 0.0;  // s, the shortest over the pairs in use
  double dt_fraction = 0.0;         // time_step / collision_duration
  std::string limited_by;           // empty when dt_fraction * t_c was kept
};
inline MaterialTimeStep material_time_step(double dt_fraction, const PairTable& table,
                                           int particle_material,
                                           std::initializer_list<int> partners, double min_radius,
                                           double density) {
  MaterialTimeStep out;
  out.collision_duration = INFINITY;
  for (int other : partners) {
    const PairParams& p = table(particle_material, other);
    if (p.defined)
      out.collision_duration =
          std::min(out.collision_duration,
                   collision_duration(min_radius, density, p.youngs_modulus, p.restitution));
  }
  const TimeStepChoiceForMaterial step =
      stable_time_step(dt_fraction * out.collision_duration, table, particle_material, min_radius);
  out.time_step = step.time_step;
  out.limited_by = step.limited_by;
  out.dt_fraction = out.time_step / out.collision_duration;
  return out;
}

}  // namespace grainlab
