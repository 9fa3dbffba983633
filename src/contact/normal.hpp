// Normal piece of the contact law (published Eq. 3, normal part):
//   F_n = k_n U_n + c_n dU_n/dt,  clamped to F_n >= 0 (contacts never pull).
//   k_n [N/m] = pi E r* (Eq. 4);  c_n [N s/m] = 2 zeta sqrt(k_n m*) (Eq. 7, corrected: see
//   contact/damping.hpp for how zeta is chosen so that the clamped contact returns e exactly).
#pragma once

namespace grainlab {

struct NormalParams {
  double stiffness = 0.0;  // k_n, N/m
  double damping = 0.0;    // c_n, N s/m
};

// Magnitude of the repulsive normal force on each body, N.
inline double normal_force(const NormalParams& p, double overlap, double overlap_rate) {
  const double f = p.stiffness * overlap + p.damping * overlap_rate;
  return f > 0.0 ? f : 0.0;
}

}  // namespace grainlab
