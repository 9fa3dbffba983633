// Sliding piece (published Eq. 3, tangential part; Eqs. 5 and 8):
//   F_s = k_s U_s + c_s dU_s/dt on body A (B gets -F_s), |F_s| <= mu_s F_n,
//   U_s: tangential spring [m] = accumulated displacement of B's surface relative to A's,
//   kept in the current tangent plane; k_s = RNS k_n [N/m], c_s = RZS c_n [N s/m].
#pragma once

#include "contact/spring_slider.hpp"

namespace grainlab {

struct SlidingParams {
  double stiffness = 0.0;  // k_s, N/m
  double damping = 0.0;    // c_s, N s/m
  double friction = 0.0;   // mu_s, -
};

struct SlidingHistory {
  Vec3 spring;  // U_s, m
};

// Tangential force on body A, N. The history must already lie in the tangent plane of n
// (see keep_in_tangent_plane); tangential_displacement is the step's increment of U_s (m) and
// tangential_velocity the end-of-step dU_s/dt (m/s, for the dashpot).
inline Vec3 sliding_force(const SlidingParams& p, const Vec3& tangential_displacement,
                          const Vec3& tangential_velocity, double normal_force, SlidingHistory& h) {
  return spring_slider(p.stiffness, p.damping, p.friction * normal_force, tangential_displacement,
                       tangential_velocity, h.spring);
}

}  // namespace grainlab
