// What the two force loops (core/contact_forces.cpp for the pair entries, core/wall_forces.cpp
// for the wall candidates) share: the end-of-step velocity estimates for the dashpots and the
// switch from the contact law's runtime pieces to the template that has them. Internal to
// src/core.
#pragma once

#include "core/particles.hpp"
#include "core/simulation.hpp"

namespace grainlab::force_loop {

// Velocities for the dashpots. Velocity Verlet evaluates forces at the end of the step, when
// only the half-step velocity v(t + dt/2) is known; a dashpot fed with it lags by half a step,
// which is a first-order error in the dissipation (at dt = 0.1 t_c a single collision with
// e = 0.5 rebounds with 0.46). Completing the kick with the last force,
// v(t + dt) ~ v(t + dt/2) + dt/2 F(t)/m, makes it second order (docs/contact-model.md).
// The springs instead advance by dt v(t + dt/2), the displacement the drift actually made
// (contact/kinematics.hpp).
inline Vec3 velocity_at_step_end(const ParticleStore& p, size_t i, double dt) {
  return p.velocity[i] + (0.5 * dt * p.inverse_mass[i]) * p.force[i];
}
inline Vec3 spin_at_step_end(const ParticleStore& p, size_t i, double dt) {
  return p.angular_velocity[i] + (0.5 * dt * p.inverse_inertia[i]) * p.torque[i];
}

// Calls F<R, T, RF>() for the runtime combination of optional pieces.
template <template <bool, bool, bool> class F, class... Args>
double dispatch(ContactPieces pieces, Args&&... args) {
  const int code =
      (pieces.rolling ? 4 : 0) | (pieces.twisting ? 2 : 0) | (pieces.rolling_force ? 1 : 0);
  switch (code) {
    case 0:
      return F<false, false, false>::run(args...);
    case 1:
      return F<false, false, true>::run(args...);
    case 2:
      return F<false, true, false>::run(args...);
    case 3:
      return F<false, true, true>::run(args...);
    case 4:
      return F<true, false, false>::run(args...);
    case 5:
      return F<true, false, true>::run(args...);
    case 6:
      return F<true, true, false>::run(args...);
    default:
      return F<true, true, true>::run(args...);
  }
}

}  // namespace grainlab::force_loop
