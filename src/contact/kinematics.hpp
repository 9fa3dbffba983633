// Per-contact kinematics, computed once per contact per step and handed to every piece of the
// contact law (normal, sliding, rolling, twisting). Body A is a particle; body B is a particle
// or a wall. Symbols (DESIGN.md sec. 2):
//   n        unit normal from A towards B                          [-]
//   U_n      overlap r_A + r_B - D (or r_A - distance to wall)     [m]
//   dU_n/dt  overlap rate, positive while approaching              [m/s]
//   v_t      tangential velocity of B's surface relative to A's at the contact point  [m/s]
//   w_rel    angular velocity of B minus that of A                 [rad/s]
//   r*, m*   effective radius and mass (r_A, m_A against a wall)   [m], [kg]
#pragma once

#include "core/vec3.hpp"

namespace grainlab {

struct ContactKinematics {
  Vec3 normal;
  double overlap = 0.0;
  double overlap_rate = 0.0;
  Vec3 tangential_velocity;
  Vec3 relative_angular_velocity;
  double effective_radius = 0.0;
  double effective_mass = 0.0;
};

// Relative velocity of B's surface point with respect to A's, split into its normal rate and
// tangential part. lever_a/lever_b: distance from each centre to the contact point.
inline void set_relative_velocity(ContactKinematics& k, const Vec3& velocity_a,
                                  const Vec3& angular_velocity_a, double lever_a,
                                  const Vec3& velocity_b, const Vec3& angular_velocity_b,
                                  double lever_b) {
  const Vec3& n = k.normal;
  const Vec3 surface_a = velocity_a + lever_a * cross(angular_velocity_a, n);
  const Vec3 surface_b = velocity_b - lever_b * cross(angular_velocity_b, n);
  const Vec3 relative = surface_b - surface_a;
  const double normal_speed = dot(relative, n);
  k.overlap_rate = -normal_speed;
  k.tangential_velocity = relative - normal_speed * n;
  k.relative_angular_velocity = angular_velocity_b - angular_velocity_a;
}

}  // namespace grainlab
