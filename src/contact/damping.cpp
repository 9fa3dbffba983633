#include "contact/damping.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace grainlab {
namespace {

// Motion of the overlap for unit approach speed and omega_0 = 1:
//   U'' + 2 zeta U' + U = 0, U(0) = 0, U'(0) = 1; the force is U + 2 zeta U'.
struct ForceZero {
  double time;     // first t > 0 with U + 2 zeta U' = 0
  double speed;    // -U'(time): separation speed
  double overlap;  // U(time)
};

ForceZero force_zero(double z) {
  using std::exp;
  if (z < 1.0 - 1e-9) {  // under-damped
    const double wd = std::sqrt(1.0 - z * z);
    // U + 2 zeta U' = exp(-zeta t)[(1 - 2 zeta^2)/wd sin(wd t) + 2 zeta cos(wd t)]
    const double phase = std::numbers::pi - std::atan2(2.0 * z * wd, 1.0 - 2.0 * z * z);
    const double t = phase / wd;
    const double decay = exp(-z * t);
    const double velocity = decay * (std::cos(phase) - z / wd * std::sin(phase));
    return {t, -velocity, decay * std::sin(phase) / wd};
  }
  if (z <= 1.0 + 1e-9) {  // critically damped: U = t e^-t, force = e^-t (t + 2 - 2t)
    const double t = 2.0;
    return {t, -(1.0 - t) * exp(-t), t * exp(-t)};
  }
  // over-damped: roots s1,2 = -zeta +- q
  const double q = std::sqrt(z * z - 1.0);
  const double s1 = -z + q, s2 = -z - q;
  const double t = std::log(2.0 * z * z - 1.0 + 2.0 * z * q) / q;
  const double velocity = (s1 * exp(s1 * t) - s2 * exp(s2 * t)) / (2.0 * q);
  const double overlap = (exp(s1 * t) - exp(s2 * t)) / (2.0 * q);
  return {t, -velocity, overlap};
}

}  // namespace

double textbook_damping_ratio(double e) {
  if (!(e > 0.0 && e <= 1.0)) throw std::invalid_argument("restitution must lie in (0, 1]");
  const double l = std::log(e);
  return -l / std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
}

double clamped_restitution(double z) {
  if (z <= 0.0) return 1.0;
  return force_zero(z).speed;
}

double clamped_force_duration(double z) {
  if (z <= 0.0) return std::numbers::pi;
  return force_zero(z).time;
}

double clamped_overlap_duration(double z) {
  if (z <= 0.0) return std::numbers::pi;
  const ForceZero f = force_zero(z);
  return f.time + f.overlap / f.speed;
}

double damping_ratio_for_restitution(double e) {
  if (!(e > 0.0 && e <= 1.0)) throw std::invalid_argument("restitution must lie in (0, 1]");
  if (e == 1.0) return 0.0;
  // clamped_restitution falls monotonically from 1 (zeta = 0) towards 0 (zeta -> infinity).
  double lo = 0.0, hi = 1.0;
  while (clamped_restitution(hi) > e) hi *= 2.0;
  for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (clamped_restitution(mid) > e ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace grainlab
