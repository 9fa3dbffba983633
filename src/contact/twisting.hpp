// Optional twisting piece (off unless a pair sets `twisting_friction`):
//   M_t = (k_t theta_t + c_t dtheta_t/dt) n on body A (B gets -M_t), |M_t| <= mu_t F_n,
//   theta_t [rad]: accumulated relative spin about the normal ((w_B - w_A) . n),
//   k_t = k_theta, c_t = c_theta (the rolling constants), mu_t = twisting_friction * a [m].
#pragma once

#include <cmath>

#include "core/vec3.hpp"

namespace grainlab {

struct TwistingParams {
  double stiffness = 0.0;         // N m/rad
  double damping = 0.0;           // N m s/rad
  double moment_per_force = 0.0;  // m
};

struct TwistingHistory {
  double angle = 0.0;  // rad
};

// relative_rotation: the step's relative rotation (rad) that advances the spring;
// relative_angular_velocity: end-of-step estimate (rad/s) for the dashpot.
inline Vec3 twisting_moment(const TwistingParams& p, const Vec3& n, const Vec3& relative_rotation,
                            const Vec3& relative_angular_velocity, double normal_force,
                            TwistingHistory& h) {
  const double rate = dot(relative_angular_velocity, n);
  h.angle += dot(relative_rotation, n);
  double moment = p.stiffness * h.angle + p.damping * rate;
  const double cap = p.moment_per_force * normal_force;
  if (std::abs(moment) > cap) {
    moment = std::copysign(cap, moment);
    h.angle = p.stiffness > 0.0 ? (moment - p.damping * rate) / p.stiffness : 0.0;
  }
  return moment * n;
}

}  // namespace grainlab
