// The simulated flat-throw test must return the input restitution: |e_sim - e| <= 0.005 for e
// from 0.3 to 0.95, on a wall and on a fixed bead (the round trip of docs/lab-tests.md).
#include <gtest/gtest.h>

#include "contact/pair_table.hpp"
#include "lab/flat_throw.hpp"
#include "support/scenes.hpp"

using namespace grainlab;

namespace {
FlatThrowResult throw_bead(double e, bool onto_bead, double friction = 0.2) {
  PairTable table({Material{"glass", 46.2e9, 0.245, 2500.0}, Material{"target", {}, {}, {}}});
  PairProperties p = test::pair_properties(e, friction);
  table.set(0, 0, p);
  table.set(0, 1, p);
  FlatThrowSettings s;
  s.bead_material = "glass";
  s.target_material = onto_bead ? "glass" : "target";
  s.target_is_bead = onto_bead;
  s.launch_height = 0.3;
  s.launch_speed = 0.2;
  s.spin = s.launch_speed / 1e-3;  // rolling off the launch table
  return simulate_flat_throw(s, table, 2500.0);
}
}  // namespace

class FlatThrow : public ::testing::TestWithParam<double> {};

TEST_P(FlatThrow, OnWallReturnsInputRestitution) {
  const FlatThrowResult r = throw_bead(GetParam(), false);
  EXPECT_NEAR(r.restitution_simulated, GetParam(), 0.005);
  EXPECT_NEAR(r.restitution_velocity_ratio, GetParam(), 0.005);
  EXPECT_GT(r.contact_steps, 100) << "the contact must be resolved by many steps";
}

TEST_P(FlatThrow, OnFixedBeadReturnsInputRestitution) {
  const FlatThrowResult r = throw_bead(GetParam(), true);
  EXPECT_NEAR(r.restitution_simulated, GetParam(), 0.005);
}

INSTANTIATE_TEST_SUITE_P(RestitutionRange, FlatThrow,
                         ::testing::Values(0.3, 0.5, 0.58, 0.73, 0.926, 0.95));

TEST(FlatThrowTrajectory, FramesFollowTheMeasuredHeights) {
  const FlatThrowResult r = throw_bead(0.58, false);
  ASSERT_GT(r.trajectory.size(), 100u);
  // first frame: centre one radius above the launch height of the bead's lowest point
  EXPECT_NEAR(r.trajectory.front().z, 0.3 + 1e-3, 1e-12);
  double apex_after = 0.0;
  for (const auto& f : r.trajectory)
    if (f.t > 0.3) apex_after = std::max(apex_after, f.z);
  EXPECT_NEAR(apex_after - 1e-3, r.rebound_height, 1e-4);  // 1 ms frames: apex within 0.1 mm
}
