// Rolling-resistance piece (published Eqs. 3, 6, 9, 10, with Eq. 9 replaced):
//   M_r = k_theta theta_r + c_theta dtheta_r/dt on body A (B gets -M_r), |M_r| <= mu_theta F_n,
//   theta_r [rad]: accumulated relative rolling rotation (tangential part of w_B - w_A),
//   k_theta = (2 r*)^2 k_s [N m/rad] (Eq. 6),
//   c_theta = eta_theta 2 sqrt(I* k_theta) [N m s/rad] (replaces the dimensionally
//             inconsistent printed Eq. 9; eta_theta is a damping ratio),
//   mu_theta = ARF a [m], a = radius of the contact circle (Eq. 10).
#pragma once

#include "contact/spring_slider.hpp"

namespace grainlab {

struct RollingParams {
  double stiffness = 0.0;         // k_theta, N m/rad
  double damping = 0.0;           // c_theta, N m s/rad
  double moment_per_force = 0.0;  // mu_theta, m
};

struct RollingHistory {
  Vec3 angle;  // theta_r, rad
};

// Rolling part of the relative angular velocity: its component in the tangent plane.
inline Vec3 rolling_rate(const Vec3& relative_angular_velocity, const Vec3& n) {
  return relative_angular_velocity - dot(relative_angular_velocity, n) * n;
}

// Moment on body A, N m. increment: the step's rolling rotation (rad); rate: end-of-step rolling
// rate (rad/s, for the dashpot); both from rolling_rate().
inline Vec3 rolling_moment(const RollingParams& p, const Vec3& increment, const Vec3& rate,
                           double normal_force, RollingHistory& h) {
  return spring_slider(p.stiffness, p.damping, p.moment_per_force * normal_force, increment, rate,
                       h.angle);
}

// Radius of the circle in which two spheres' surfaces intersect (Eq. 10), m; for a sphere on a
// wall (radius_b = 0 passed as "flat") it is sqrt(r_A^2 - (r_A - U_n)^2).
inline double contact_circle_radius(double radius_a, double radius_b, double distance) {
  const double x =
      (distance * distance + radius_b * radius_b - radius_a * radius_a) / (2.0 * distance);
  const double a2 = radius_b * radius_b - x * x;
  return a2 > 0.0 ? std::sqrt(a2) : 0.0;
}
inline double contact_circle_radius_on_wall(double radius, double overlap) {
  const double a2 = radius * radius - (radius - overlap) * (radius - overlap);
  return a2 > 0.0 ? std::sqrt(a2) : 0.0;
}

}  // namespace grainlab
