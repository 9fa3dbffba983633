// Collision duration and time step (docs/contact-model.md).
//   t_c = 2 r_min sqrt(rho (pi^2 + ln^2 e) / (3 E))   (published Eq. 11) [s]
// is exactly the duration of a binary collision of two spheres of radius r_min under this
// model with the textbook damping (omega_0^2 = k_n/m* = 3E/(4 r^2 rho) for equal spheres and for
// a sphere on a wall alike). Integrating with dt = t_c is unstable; grainlab uses
// dt = dt_fraction * t_c (default 0.1).
#pragma once

#include <cmath>
#include <numbers>

namespace grainlab {

inline double collision_duration(double min_radius, double density, double youngs_modulus,
                                 double restitution) {
  const double l = std::log(restitution);
  return 2.0 * min_radius *
         std::sqrt(density * (std::numbers::pi * std::numbers::pi + l * l) /
                   (3.0 * youngs_modulus));
}

inline constexpr double default_dt_fraction = 0.1;

// The most steps grainlab takes in one run (or one stage of a test). A run that would need more
// (a duration, a speed or a material constant off by orders of magnitude) is refused up front
// with the number and the key to change; 1e9 steps of the reference specimen are a month on two
// cores.
inline constexpr double max_steps_per_run = 1e9;

}  // namespace grainlab
