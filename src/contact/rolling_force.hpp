// Optional "rolling force" term of the published Eq. 3 (k_r, mu_r), off by default because the
// reference case gives it no values. grainlab reads it as a tangential force at the contact that
// resists the rolling displacement U_r [m] = accumulated r* (w_rel x n):
//   F_r = k_r U_r on body A (B gets -F_r), |F_r| <= mu_r F_n,  k_r [N/m], mu_r [-].
#pragma once

#include "contact/spring_slider.hpp"

namespace grainlab {

struct RollingForceParams {
  double stiffness = 0.0;  // k_r, N/m
  double friction = 0.0;   // mu_r, -
};

struct RollingForceHistory {
  Vec3 displacement;  // U_r, m
};

// relative_rotation: the step's relative rotation (rad); the spring has no dashpot.
inline Vec3 rolling_force(const RollingForceParams& p, const Vec3& n, const Vec3& relative_rotation,
                          double effective_radius, double normal_force, RollingForceHistory& h) {
  const Vec3 increment = effective_radius * cross(relative_rotation, n);
  return spring_slider(p.stiffness, 0.0, p.friction * normal_force, increment, Vec3{},
                       h.displacement);
}

}  // namespace grainlab
