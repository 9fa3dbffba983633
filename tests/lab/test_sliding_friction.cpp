// Simulated sliding-friction test. Coulomb check: a slider on fixed beads that never meet its
// edges must give F = mu_s P exactly, so the F-P slope is the input friction.
#include <gtest/gtest.h>

#include "lab/sliding_friction.hpp"
#include "support/scenes.hpp"

using namespace grainlab;

TEST(SlidingFriction, SliderOnFixedBeadsGivesInputFriction) {
  PairTable table({Material{"glass", 46.2e9, 0.245, 2500.0}, Material{"rubber", {}, {}, {}}});
  table.set(0, 0, test::pair_properties(0.926, 0.16));
  table.set(0, 1, test::pair_properties(0.58, 0.21));
  SlidingFrictionSettings s;
  s.slider_material = "rubber";
  s.bed_length = 0.024;
  s.bed_width = 0.01;
  s.slider_length = 0.014;
  s.slide_distance = 0.004;  // the second half (20 ms) is past the rope's start-up transient
  s.speed = 0.1;
  s.fixed_bed = true;
  const SlidingFrictionResult r = simulate_sliding_friction(s, table, 2500.0);
  ASSERT_EQ(r.runs.size(), 4u);
  EXPECT_GT(r.bead_count, 6);
  EXPECT_NEAR(r.friction_apparent, 0.21, 1e-4);
  EXPECT_GT(r.r_squared, 0.9999);
  for (const LoadRun& run : r.runs) EXPECT_NEAR(run.mean_force / run.load, 0.21, 1e-4);
}
