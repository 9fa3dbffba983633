// The derived constants of one material pair (a row of the pair table, contact/pair_table.hpp).
// A plain struct with no includes, so that the per-instruction-set objects of the vectorised
// pair kernel (core/pair_kernel_simd.cpp) can read it without pulling in library code.
#pragma once

namespace grainlab {

struct PairParams {
  double stiffness_per_radius = 0.0;    // pi E, Pa (k_n = pi E r*, Eq. 4)
  double damping_ratio = 0.0;           // zeta used (returns e exactly with the clamp)
  double textbook_damping_ratio = 0.0;  // zeta of Eq. 7, reported only
  double rns = 0.5, rzs = 0.0;
  double friction = 0.0;
  double arf = 0.0;
  double rolling_damping_ratio = 0.0;  // eta_theta
  double twisting_friction = 0.0;
  double rolling_force_stiffness_ratio = 0.0;
  double rolling_force_friction = 0.0;
  double youngs_modulus = 0.0;  // E used for this pair, Pa
  double restitution = 1.0;
  bool defined = false;
};

}  // namespace grainlab
