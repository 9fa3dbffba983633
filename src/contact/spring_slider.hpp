// The spring-slider shared by the sliding, rolling and rolling-force pieces: an elastic history
// vector kept in the current tangent plane, a parallel dashpot, and a Coulomb-type cap. On slip
// the spring is shortened so that the elastic part alone sits on the cap (Cundall & Strack 1979).
#pragma once

#include "core/vec3.hpp"

namespace grainlab {

// Turns a history vector into the current tangent plane (normal n) without changing its length,
// so that a contact that rolls or tilts keeps its stored elastic energy.
inline void keep_in_tangent_plane(Vec3& history, const Vec3& n) {
  const double length2 = norm2(history);
  if (length2 == 0.0) return;
  Vec3 in_plane = history - dot(history, n) * n;
  const double in_plane2 = norm2(in_plane);
  if (in_plane2 > 0.0) in_plane *= std::sqrt(length2 / in_plane2);
  history = in_plane;
}

// Advances the history by `increment` (what the step actually moved: in velocity Verlet the
// half-step relative velocity times dt, which makes the spring second order) and returns
// stiffness*history + damping*rate, capped in length at `cap`. `rate` is the end-of-step estimate
// of the relative velocity, used by the dashpot only. Units follow the caller:
// displacement/force for sliding, angle/moment for rolling.
inline Vec3 spring_slider(double stiffness, double damping, double cap, const Vec3& increment,
                          const Vec3& rate, Vec3& history) {
  history += increment;
  Vec3 response = stiffness * history + damping * rate;
  const double magnitude2 = norm2(response);
  if (magnitude2 > cap * cap) {
    // Slip: the response sits on the cap, and the spring keeps only what the cap allows.
    response *= cap / std::sqrt(magnitude2);
    history = stiffness > 0.0 ? (1.0 / stiffness) * (response - damping * rate) : Vec3{};
  }
  return response;
}

}  // namespace grainlab
