// Per-contact kinematics, computed once per contact per step and handed to every piece of the
// contact law (normal, sliding, rolling, twisting). Body A is a particle; body B is a particle
// or a wall. Symbols (docs/contact-model.md):
//   n        unit normal from A towards B                          [-]
//   U_n      overlap r_A + r_B - D (or r_A - distance to wall)     [m]
//   dU_n/dt  overlap rate, positive while approaching              [m/s]
//   v_t      tangential velocity of B's surface relative to A's at the contact point  [m/s]
//   w_rel    angular velocity of B minus that of A                 [rad/s]
//   r*, m*   effective radius and mass (r_A, m_A against a wall)   [m], [kg]
//
// Two estimates of the relative motion, for two different jobs (docs/contact-model.md,
// "Integration order"). Velocity Verlet evaluates forces at the end of a step, when the particles
// have moved by dt v(t + dt/2):
//   - the springs (sliding, rolling, twisting, rolling force) advance by what the step actually
//     moved: dt times the half-step relative velocity (the midpoint rule, second order);
//   - the dashpots need the velocity at the end of the step, v(t + dt/2) + dt/2 F(t)/m (second
//     order too). Advancing the springs with this end-of-step velocity would put them half a
//     step ahead: a first-order error (the tangential restitution of a sticking impact was 0.04
//     off at 50 steps per contact).
#pragma once

#include "core/vec3.hpp"

namespace grainlab {

struct ContactKinematics {
  Vec3 normal;
  double overlap = 0.0;
  double overlap_rate = 0.0;
  Vec3 tangential_velocity;        // end of step, for the dashpots
  Vec3 relative_angular_velocity;  // end of step, for the dashpots
  // What this step moved (half-step relative velocity times dt): the springs' increments.
  Vec3 tangential_displacement;    // m
  Vec3 relative_rotation;          // rad
  double overlap_increment = 0.0;  // m, growth of U_n over the step
  double effective_radius = 0.0;
  double effective_mass = 0.0;
};

// Relative velocity of B's surface point with respect to A's, split into its normal rate and
// tangential part. lever_a/lever_b: distance from each centre to the contact point.
inline void set_relative_velocity(ContactKinematics& k, const Vec3& velocity_a,
                                  const Vec3& angular_velocity_a, double lever_a,
                                  const Vec3& velocity_b, const Vec3& angular_velocity_b,
                                  double lever_b) {
  const Vec3& n = k.normal;
  // surface velocities v_a + lever_a (w_a x n) and v_b - lever_b (w_b x n): one cross product
  const Vec3 relative = velocity_b - velocity_a -
                        cross(lever_b * angular_velocity_b + lever_a * angular_velocity_a, n);
  const double normal_speed = dot(relative, n);
  k.overlap_rate = -normal_speed;
  k.tangential_velocity = relative - normal_speed * n;
  k.relative_angular_velocity = angular_velocity_b - angular_velocity_a;
}

// The step's relative displacement at the contact point from the half-step velocities (the ones
// the drift used): the increments of the spring histories. For the midpoint rule the levers are
// those at mid-step: lever + lever_shrink * (U_n(end) - U_n(mid)), where lever_shrink is how much
// a lever shortens per unit of overlap: 1/2 for each sphere of a pair (lever r - U_n/2), 1 for a
// sphere on a wall (lever r - U_n). With the end-of-step levers the increment is off by
// dt w dU_n/2 each step, a drift of the spring. The normal is the end-of-step one (the history
// lives in its tangent plane); its turn over half a step is left out.
inline void set_step_displacement(ContactKinematics& k, double dt, const Vec3& velocity_a,
                                  const Vec3& angular_velocity_a, double lever_a,
                                  const Vec3& velocity_b, const Vec3& angular_velocity_b,
                                  double lever_b, double lever_shrink) {
  const Vec3& n = k.normal;
  // the spin terms (w x n) have no normal component
  const double normal_speed = dot(velocity_b - velocity_a, n);
  k.overlap_increment = -dt * normal_speed;
  const double shift = lever_shrink * 0.5 * k.overlap_increment;
  const Vec3 relative =
      velocity_b - velocity_a -
      cross((lever_b + shift) * angular_velocity_b + (lever_a + shift) * angular_velocity_a, n);
  k.tangential_displacement = dt * (relative - dot(relative, n) * n);
  k.relative_rotation = dt * (angular_velocity_b - angular_velocity_a);
}

}  // namespace grainlab
