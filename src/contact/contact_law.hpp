// The full contact law for one contact: the pieces of docs/contact-model.md put together. The
// optional pieces are template switches, chosen once outside the force loop, so the loop has
// no per-contact branching on the model and no virtual calls.
#pragma once

#include <algorithm>
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

// The torques follow from two vectors: the tangential force turns each body about its centre
// with torque lever × (n × F_t), and the rolling and twisting moments act on A as `moment` and
// on B as -moment. So the torque on A is lever_a torque_arm + moment, on B lever_b torque_arm -
// moment (torque_on_a / torque_on_b below). The pair store keeps the arm and the overlap, from
// which each body's lever follows, instead of two torques (core/contact_store.hpp).
struct ContactResponse {
  Vec3 force_on_a;          // N (B receives the opposite)
  Vec3 torque_arm;          // n x F_t, N: torque per metre of lever, on either body
  Vec3 moment;              // N m, rolling + twisting moment on A (zero without those pieces)
  double normal_stiffness;  // k_n, N/m
  double normal_force;      // F_n, N

  Vec3 torque_on_a(double lever_a) const { return lever_a * torque_arm + moment; }
  Vec3 torque_on_b(double lever_b) const { return lever_b * torque_arm - moment; }
};

// k_n = pi E r* (Eq. 4) and c_n = 2 zeta sqrt(k_n m*) (Eq. 7 corrected) of one contact,
// evaluated per contact per step (storing them per entry cost 16 B each; docs/performance.md
// sec. 13).
inline NormalParams normal_params(const PairParams& pair, double effective_radius,
                                  double effective_mass) {
  const double k_n = pair.stiffness_per_radius * effective_radius;
  return {k_n, 2.0 * pair.damping_ratio * std::sqrt(k_n * effective_mass)};
}

// normal: k_n and c_n of this contact (normal_params); effective_inertia I* in kg m^2;
// contact_radius a (Eq. 10, m), used
// only by the rolling and twisting pieces. k.effective_radius is read only by those pieces and the
// rolling-force piece; k.effective_mass is not read.
template <bool Rolling, bool Twisting, bool RollingForce>
inline ContactResponse contact_response(const PairParams& pair, const NormalParams& normal,
                                        const ContactKinematics& k, double effective_inertia,
                                        double contact_radius, ContactHistoryRef h) {
  const Vec3& n = k.normal;
  const double c_n = normal.damping;
  const double f_n = normal_force(normal, k.overlap, k.overlap_rate);

  const SlidingParams sliding{pair.rns * normal.stiffness, pair.rzs * c_n, pair.friction};
  keep_in_tangent_plane(*h.sliding_spring, n);
  SlidingHistory sliding_history{*h.sliding_spring};
  Vec3 tangential = sliding_force(sliding, k.tangential_displacement, k.tangential_velocity, f_n,
                                  sliding_history);
  *h.sliding_spring = sliding_history.spring;

  if constexpr (RollingForce) {
    const RollingForceParams rf{pair.rolling_force_stiffness_ratio * normal.stiffness,
                                pair.rolling_force_friction};
    keep_in_tangent_plane(*h.rolling_force_displacement, n);
    RollingForceHistory rh{*h.rolling_force_displacement};
    tangential += rolling_force(rf, n, k.relative_rotation, k.effective_radius, f_n, rh);
    *h.rolling_force_displacement = rh.displacement;
  }

  ContactResponse r;
  r.force_on_a = tangential - f_n * n;
  r.torque_arm = cross(n, tangential);
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
      const Vec3 m = rolling_moment(rolling, rolling_rate(k.relative_rotation, n),
                                    rolling_rate(k.relative_angular_velocity, n), f_n, rh);
      *h.rolling_angle = rh.angle;
      r.moment += m;
    }
    if constexpr (Twisting) {
      const TwistingParams twisting{k_theta, c_theta, pair.twisting_friction * contact_radius};
      TwistingHistory th{*h.twisting_angle};
      const Vec3 m =
          twisting_moment(twisting, n, k.relative_rotation, k.relative_angular_velocity, f_n, th);
      *h.twisting_angle = th.angle;
      r.moment += m;
    }
  }
  return r;
}

// First touch inside a step. A contact that begins a fraction 1 - f into a step (in contact for
// the last f dt of it) needs two corrections to stay second order:
//  - its springs may only take the displacement made while in contact: the step's increments
//    are scaled by f (the whole step's increment would pre-load the tangential spring by
//    (1 - f) dt v_t, a first-order error);
//  - velocity Verlet spreads each force over the two half-steps around the time it is
//    evaluated, so the step is charged dt/2 (0 + F_end). With a dashpot the force jumps at first
//    touch to F_touch (c_n dU_n/dt, and its tangential share), the response at zero overlap
//    with empty springs; the exact charge is f dt/2 (F_touch + F_end), and since F_end =
//    F_touch + O(dt) the charge misses dt/2 (2f - 1) F_touch, an impulse error of order c_n v dt
//    (1 % in e for e = 0.5 at 50 steps per contact). That jump term is added to the stored force
//    at half weight, because the stored force acts for dt/2 in this step's closing kick and again
//    for dt/2 in the next step's opening kick: the missing impulse arrives in full, at most half
//    a step late. The O(dt^2) remainder, the springs' share, is left as velocity Verlet has it:
//    its error at first touch and at separation cancel, which keeps an elastic collision
//    energy-conserving (correcting it at first touch alone made a gas of elastic spheres gain
//    4e-4 of its energy over a few hundred collisions).

// f in (0, 1] when the contact began during this step, 0 when it touched before (or does not
// touch now). overlap_before: U_n at the start of the step (exact for the caller's geometry).
// Round-off of up to 1e-7 of the step's growth counts as touching at the step boundary, so that
// a contact beginning exactly there is not missed (one ending a step inside that sliver, with a
// chance of about 1e-7, is charged in both steps: -1/2 then +1/2 of F_touch, O(dt^2)).
inline double first_touch_fraction(double overlap_before, double overlap) {
  const double growth = overlap - overlap_before;
  if (!(overlap > 0.0 && overlap_before <= 1e-7 * growth)) return 0.0;
  return std::min(1.0, overlap / growth);
}

inline void scale_step_increments(ContactKinematics& k, double fraction) {
  k.tangential_displacement *= fraction;
  k.relative_rotation *= fraction;
}

template <bool Rolling, bool Twisting, bool RollingForce>
inline void charge_first_touch(const PairParams& pair, const NormalParams& normal,
                               const ContactKinematics& k, double fraction,
                               double effective_inertia, ContactResponse& r) {
  ContactKinematics touch = k;
  touch.overlap = 0.0;
  touch.tangential_displacement = touch.relative_rotation = Vec3{};
  Vec3 sliding{}, rolling{}, rolling_force{};
  double twisting = 0.0;
  const ContactResponse t = contact_response<Rolling, Twisting, RollingForce>(
      pair, normal, touch, effective_inertia, 0.0, {&sliding, &rolling, &twisting, &rolling_force});
  const double weight = 0.5 * (2.0 * fraction - 1.0);
  r.force_on_a += weight * t.force_on_a;
  r.torque_arm += weight * t.torque_arm;
  if constexpr (Rolling || Twisting) r.moment += weight * t.moment;
}

}  // namespace grainlab
