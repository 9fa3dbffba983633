// The full contact law for one contact: the pieces of DESIGN.md sec. 2 put together. The
// optional pieces are template switches, chosen once outside the force loop, so the loop has
// no per-contact branching on the model and no virtual calls.
#pragma once

#include <cmath>

#include "contact/kinematics.hpp"
#include "contact/normal.hpp"
#include "contact/pair_table.hpp"
#include "contact/rolling.hpp"
#include "contact/rolling_force.hpp"
#include "contact/sliding.hpp"
#include "contact/twisting.hpp"

namespace grainlab {

// History of one contact, as pointers into the contact store's arrays (null when a piece is off).
struct ContactHistoryRef {
  Vec3* sliding_spring;
  Vec3* rolling_angle;
  double* twisting_angle;
  Vec3* rolling_force_displacement;
};

struct ContactResponse {
  Vec3 force_on_a;          // N (B receives the opposite)
  Vec3 torque_on_a;         // N m, about A's centre
  Vec3 torque_on_b;         // N m, about B's centre
  double normal_stiffness;  // k_n, N/m
  double normal_force;      // F_n, N
};

// k_n = pi E r* (Eq. 4) and c_n = 2 zeta sqrt(k_n m*) (Eq. 7 corrected) of one contact. They
// depend only on the two bodies, so the particle-pair loop takes them from the contact store
// (computed when the neighbour list is built) instead of evaluating them every step.
inline NormalParams normal_params(const PairParams& pair, double effective_radius,
                                  double effective_mass) {
  const double k_n = pair.stiffness_per_radius * effective_radius;
  return {k_n, 2.0 * pair.damping_ratio * std::sqrt(k_n * effective_mass)};
}

// normal: k_n and c_n of this contact (normal_params); lever_a, lever_b: distance from each
// centre to the contact point; effective_inertia I* in kg m^2; contact_radius a (Eq. 10, m), used
// only by the rolling and twisting pieces. k.effective_radius is read only by those pieces and the
// rolling-force piece; k.effective_mass is not read.
template <bool Rolling, bool Twisting, bool RollingForce>
inline ContactResponse contact_response(const PairParams& pair, const NormalParams& normal,
                                        const ContactKinematics& k, double lever_a, double lever_b,
                                        double effective_inertia, double contact_radius, double dt,
                                        ContactHistoryRef h) {
  const Vec3& n = k.normal;
  const double c_n = normal.damping;
  const double f_n = normal_force(normal, k.overlap, k.overlap_rate);

  const SlidingParams sliding{pair.rns * normal.stiffness, pair.rzs * c_n, pair.friction};
  keep_in_tangent_plane(*h.sliding_spring, n);
  SlidingHistory sliding_history{*h.sliding_spring};
  Vec3 tangential = sliding_force(sliding, k.tangential_velocity, f_n, dt, sliding_history);
  *h.sliding_spring = sliding_history.spring;

  if constexpr (RollingForce) {
    const RollingForceParams rf{pair.rolling_force_stiffness_ratio * normal.stiffness,
                                pair.rolling_force_friction};
    keep_in_tangent_plane(*h.rolling_force_displacement, n);
    RollingForceHistory rh{*h.rolling_force_displacement};
    tangential +=
        rolling_force(rf, n, k.relative_angular_velocity, k.effective_radius, f_n, dt, rh);
    *h.rolling_force_displacement = rh.displacement;
  }

  ContactResponse r;
  r.force_on_a = tangential - f_n * n;
  const Vec3 arm = cross(n, tangential);  // (n x F_t): torque per unit lever
  r.torque_on_a = lever_a * arm;
  r.torque_on_b = lever_b * arm;
  r.normal_stiffness = normal.stiffness;
  r.normal_force = f_n;

  if constexpr (Rolling || Twisting) {
    const double d = 2.0 * k.effective_radius;
    const double k_theta = d * d * sliding.stiffness;  // Eq. 6
    const double c_theta =
        pair.rolling_damping_ratio * 2.0 * std::sqrt(effective_inertia * k_theta);
    if constexpr (Rolling) {
      const RollingParams rolling{k_theta, c_theta, pair.arf * contact_radius};
      keep_in_tangent_plane(*h.rolling_angle, n);
      RollingHistory rh{*h.rolling_angle};
      const Vec3 m =
          rolling_moment(rolling, rolling_rate(k.relative_angular_velocity, n), f_n, dt, rh);
      *h.rolling_angle = rh.angle;
      r.torque_on_a += m;
      r.torque_on_b -= m;
    }
    if constexpr (Twisting) {
      const TwistingParams twisting{k_theta, c_theta, pair.twisting_friction * contact_radius};
      TwistingHistory th{*h.twisting_angle};
      const Vec3 m = twisting_moment(twisting, n, k.relative_angular_velocity, f_n, dt, th);
      *h.twisting_angle = th.angle;
      r.torque_on_a += m;
      r.torque_on_b -= m;
    }
  }
  return r;
}

}  // namespace grainlab
