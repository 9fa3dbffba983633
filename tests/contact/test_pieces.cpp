// Each piece of the contact law in isolation, against values computed by hand.
#include <gtest/gtest.h>

#include "contact/contact_law.hpp"

using namespace grainlab;

TEST(NormalPiece, SpringPlusDashpotNeverTensile) {
  const NormalParams p{1000.0, 2.0};
  EXPECT_DOUBLE_EQ(normal_force(p, 0.01, 0.5), 1000.0 * 0.01 + 2.0 * 0.5);  // 11 N
  EXPECT_DOUBLE_EQ(normal_force(p, 0.001, -1.0), 0.0);  // 1 - 2 < 0: clamped, not -1 N
}

TEST(SlidingPiece, ElasticThenCoulombSlip) {
  const SlidingParams p{1000.0, 0.0, 0.5};
  SlidingHistory h;
  // stick: U_s = 0.001 m, F = k_s U_s = 1 N < mu F_n = 5 N
  Vec3 f = sliding_force(p, {0.001, 0.0, 0.0}, {0.001, 0.0, 0.0}, 10.0, h);
  EXPECT_DOUBLE_EQ(f.x, 1.0);
  EXPECT_DOUBLE_EQ(h.spring.x, 0.001);
  // slip: trial 1000 * 0.011 = 11 N > 5 N: force on the cap, spring shortened to 5/1000 m
  f = sliding_force(p, {0.01, 0.0, 0.0}, {0.01, 0.0, 0.0}, 10.0, h);
  EXPECT_DOUBLE_EQ(f.x, 5.0);
  EXPECT_DOUBLE_EQ(h.spring.x, 0.005);
  // no normal force: no friction, and the spring is emptied
  f = sliding_force(p, {}, {}, 0.0, h);
  EXPECT_DOUBLE_EQ(norm(f), 0.0);
  EXPECT_DOUBLE_EQ(norm(h.spring), 0.0);
}

TEST(SlidingPiece, DashpotCountsTowardsTheCap) {
  const SlidingParams p{1000.0, 100.0, 0.5};
  SlidingHistory h;
  // trial: k_s * 0.001 + c_s * 0.01 = 1 + 1 = 2 N (below 5 N cap)
  const Vec3 f = sliding_force(p, {0.001, 0.0, 0.0}, {0.01, 0.0, 0.0}, 10.0, h);
  EXPECT_DOUBLE_EQ(f.x, 2.0);
  // at slip the spring keeps (F - c v)/k
  SlidingHistory g;
  const Vec3 s =
      sliding_force(p, {0.004, 0.0, 0.0}, {0.04, 0.0, 0.0}, 10.0, g);  // trial 4 + 4 = 8 N
  EXPECT_DOUBLE_EQ(s.x, 5.0);
  EXPECT_DOUBLE_EQ(g.spring.x, (5.0 - 4.0) / 1000.0);
}

TEST(SpringSlider, SpringTakesTheIncrementAndDashpotTheRate) {
  // The history advances by the step's displacement only; the dashpot reads the rate only.
  Vec3 h;
  const Vec3 f = spring_slider(10.0, 2.0, 100.0, {0.1, 0.0, 0.0}, {0.0, 3.0, 0.0}, h);
  EXPECT_DOUBLE_EQ(h.x, 0.1);
  EXPECT_DOUBLE_EQ(h.y, 0.0);
  EXPECT_DOUBLE_EQ(f.x, 1.0);  // k * 0.1
  EXPECT_DOUBLE_EQ(f.y, 6.0);  // c * 3
}

TEST(SpringSlider, HistoryTurnsIntoNewTangentPlaneKeepingLength) {
  Vec3 h{3.0, 0.0, 4.0};  // length 5, not in the plane of n = z
  keep_in_tangent_plane(h, {0.0, 0.0, 1.0});
  EXPECT_DOUBLE_EQ(h.x, 5.0);
  EXPECT_DOUBLE_EQ(h.z, 0.0);
}

TEST(RollingPiece, SpringSliderOnRelativeRotation) {
  const RollingParams p{2.0, 0.0, 1e-4};  // k_theta 2 N m/rad, mu_theta 0.1 mm
  RollingHistory h;
  const Vec3 rate = rolling_rate({0.0, 0.01, 0.3}, {0.0, 0.0, 1.0});  // spin about n is not rolling
  EXPECT_DOUBLE_EQ(rate.z, 0.0);
  Vec3 m = rolling_moment(p, 0.1 * rate, rate, 100.0, h);  // theta = 1e-3 rad: M = 2e-3 < 1e-2 N m
  EXPECT_DOUBLE_EQ(m.y, 2e-3);
  m = rolling_moment(p, {0.0, 0.1, 0.0}, {0.0, 1.0, 0.0}, 100.0, h);  // trial 0.202 > 0.01: capped
  EXPECT_DOUBLE_EQ(m.y, 1e-2);
  EXPECT_DOUBLE_EQ(h.angle.y, 5e-3);
}

TEST(RollingPiece, ContactCircleRadius) {
  // Two unit spheres at distance 1.6: circle radius sqrt(1 - 0.8^2) = 0.6
  EXPECT_NEAR(contact_circle_radius(1.0, 1.0, 1.6), 0.6, 1e-15);
  // Sphere r = 1 pressed 0.2 into a wall: sqrt(1 - 0.8^2) = 0.6
  EXPECT_NEAR(contact_circle_radius_on_wall(1.0, 0.2), 0.6, 1e-15);
}

TEST(TwistingPiece, CapsAboutTheNormal) {
  const TwistingParams p{1.0, 0.0, 1e-3};
  TwistingHistory h;
  Vec3 m =
      twisting_moment(p, {0, 0, 1}, {0.0, 0.0, 5e-3}, {0.0, 0.0, 0.5}, 10.0, h);  // 5e-3 < 1e-2
  EXPECT_DOUBLE_EQ(m.z, 5e-3);
  m = twisting_moment(p, {0, 0, 1}, {0.0, 0.0, -5e-2}, {0.0, 0.0, -5.0}, 10.0,
                      h);  // -4.5e-2 capped
  EXPECT_DOUBLE_EQ(m.z, -1e-2);
  EXPECT_DOUBLE_EQ(h.angle, -1e-2);
}

TEST(RollingForcePiece, ResistsRollingDisplacement) {
  const RollingForceParams p{100.0, 0.1};
  RollingForceHistory h;
  // w_rel = (0, 1, 0), n = z: rate = r* (w x n) = 0.5 * (1, 0, 0)
  const Vec3 f = rolling_force(p, {0, 0, 1}, {0.0, 0.01, 0.0}, 0.5, 100.0, h);
  EXPECT_DOUBLE_EQ(f.x, 100.0 * 0.005);
}

TEST(Kinematics, StepDisplacementUsesMidStepLevers) {
  // Sphere A spinning about y above a wall (n = -z from A to the wall), approaching it: over the
  // step the overlap grows by dU = 1e-8 m, so the lever r - U_n is dU/2 longer at mid-step than
  // at the end; the tangential displacement of the contact point is dt (v_x - lever_mid w_y).
  ContactKinematics k;
  k.normal = {0, 0, -1};
  const double dt = 1e-7, lever_end = 1e-3 - 2e-8, w = 100.0, v_n = 0.1;
  set_step_displacement(k, dt, {0.01, 0, -v_n}, {0, w, 0}, lever_end, {}, {}, 0.0, 1.0);
  const double d_u = v_n * dt;
  EXPECT_DOUBLE_EQ(k.overlap_increment, d_u);
  const double lever_mid = lever_end + 0.5 * d_u;
  // B's surface relative to A's: -(v_a + lever w_a x n); w x n = (0, w, 0) x (0, 0, -1) = (-w, 0,
  // 0)
  EXPECT_NEAR(k.tangential_displacement.x, -dt * (0.01 - lever_mid * w), 1e-22);
  EXPECT_DOUBLE_EQ(k.tangential_displacement.z, 0.0);
  // a pair: each lever r - U_n/2 grows by dU/4 at mid-step
  ContactKinematics q;
  q.normal = {1, 0, 0};
  set_step_displacement(q, dt, {v_n, 0, 0}, {0, 0, w}, lever_end, {}, {0, 0, w}, lever_end, 0.5);
  EXPECT_NEAR(q.tangential_displacement.y, -dt * 2.0 * (lever_end + 0.25 * d_u) * w, 1e-22);
}

namespace {
// k_n / r* = 1e8 Pa, k_s/k_n = 0.5, mu 0.3
PairParams pair_with_damping_ratio(double zeta) {
  PairParams pair;
  pair.stiffness_per_radius = 1e8;
  pair.damping_ratio = zeta;
  pair.rns = 0.5;
  pair.friction = 0.3;
  return pair;
}
}  // namespace

TEST(FirstTouch, FractionOfTheStepInContact) {
  EXPECT_DOUBLE_EQ(first_touch_fraction(-3e-9, 1e-9), 0.25);    // touched 3/4 into the step
  EXPECT_DOUBLE_EQ(first_touch_fraction(0.0, 1e-9), 1.0);       // at the step's start
  EXPECT_DOUBLE_EQ(first_touch_fraction(2e-9, 3e-9), 0.0);      // touching before the step
  EXPECT_DOUBLE_EQ(first_touch_fraction(-1e-9, -0.5e-9), 0.0);  // separating, not touching
}

TEST(FirstTouch, ChargesTheDashpotJumpOverThePartInContact) {
  // A pair touching half-way through the step (f = 1/2) is charged exactly what velocity Verlet
  // charges (the correction 0.5 (2f - 1) F_touch vanishes); touching at the start (f = 1) it gets
  // F_touch / 2 more, touching at the very end (f -> 0) F_touch / 2 less.
  const PairParams pair = pair_with_damping_ratio(0.2);
  ContactKinematics k;
  k.normal = {1, 0, 0};
  k.overlap = 1e-9;
  k.overlap_rate = 0.5;
  const NormalParams normal{5e4, 0.1};
  const double f_touch = normal.damping * k.overlap_rate;  // c_n dU/dt at zero overlap
  for (auto [fraction, extra] :
       {std::pair{0.5, 0.0}, std::pair{1.0, 0.5 * f_touch}, std::pair{0.0, -0.5 * f_touch}}) {
    ContactResponse r{};
    charge_first_touch<false, false, false>(pair, normal, k, fraction, 0.0, r);
    EXPECT_NEAR(r.force_on_a.x, -extra, 1e-15) << fraction;  // A is pushed along -n
  }
}

TEST(ContactLaw, HeadOnPairForceAndTorques) {
  // Two spheres touching along x with overlap 1e-5 m, B sliding in +y relative to A.
  const PairParams pair = pair_with_damping_ratio(0.1);
  ContactKinematics k;
  k.normal = {1.0, 0.0, 0.0};
  k.overlap = 1e-5;
  k.effective_radius = 5e-4;
  k.effective_mass = 1e-5;
  set_relative_velocity(k, {0, 0, 0}, {0, 0, 0}, 1e-3, {-0.01, 1e-3, 0}, {0, 0, 0}, 1e-3);
  EXPECT_DOUBLE_EQ(k.overlap_rate, 0.01);
  Vec3 spring;
  const double dt = 1e-7;
  set_step_displacement(k, dt, {0, 0, 0}, {0, 0, 0}, 1e-3, {-0.01, 1e-3, 0}, {0, 0, 0}, 1e-3, 0.25);
  EXPECT_DOUBLE_EQ(k.tangential_displacement.y, 1e-3 * dt);
  EXPECT_DOUBLE_EQ(k.overlap_increment, 0.01 * dt);
  const ContactResponse r = contact_response<false, false, false>(
      pair, normal_params(pair, k.effective_radius, k.effective_mass), k, 0.0, 0.0,
      {&spring, nullptr, nullptr, nullptr});
  const double kn = 1e8 * 5e-4, cn = 2 * 0.1 * std::sqrt(kn * 1e-5);
  const double fn = kn * 1e-5 + cn * 0.01;
  EXPECT_DOUBLE_EQ(r.normal_force, fn);
  EXPECT_DOUBLE_EQ(r.force_on_a.x, -fn);   // A is pushed away from B
  const double ft = 0.5 * kn * 1e-3 * dt;  // stick: k_s * v_t * dt, along +y (B drags A)
  EXPECT_NEAR(r.force_on_a.y, ft, 1e-15);
  // torque on A = lever n x F_t = 1e-3 * (x cross y) * ft = +z
  EXPECT_NEAR(r.torque_on_a(1e-3).z, 1e-3 * ft, 1e-18);
  EXPECT_NEAR(r.torque_on_b(1e-3).z, 1e-3 * ft, 1e-18);
}
