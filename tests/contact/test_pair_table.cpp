// Material-pair constants and the time step, against the reference case (docs/contact-model.md).
#include <gtest/gtest.h>

#include <numbers>

#include "contact/pair_table.hpp"
#include "contact/time_step.hpp"
#include "support/scenes.hpp"

using namespace grainlab;

TEST(PairTable, ReferenceGlassStiffnessAndCollisionDuration) {
  PairTable t({Material{"glass", 46.2e9, 0.245, 2500.0}});
  t.set(0, 0, test::pair_properties(0.926, 0.16));
  // k_n = pi E r*, r* = 0.5 mm for two 2 mm beads: 7.257e7 N/m
  EXPECT_NEAR(t(0, 0).stiffness_per_radius * 0.5e-3, 7.2571e7, 0.0001e7);
  // Eq. 11 for the reference beads: 8.44e-7 s
  EXPECT_NEAR(collision_duration(1e-3, 2500.0, 46.2e9, 0.926), 8.441e-7, 0.001e-7);
}

TEST(PairTable, CollisionDurationEqualsHalfDampedPeriod) {
  // t_c = pi / omega_d with omega_0^2 = k_n/m*: identical to Eq. 11 for two equal spheres.
  const double r = 1e-3, rho = 2500.0, E = 46.2e9, e = 0.5;
  const double m = rho * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  const double k = std::numbers::pi * E * r / 2.0, mstar = m / 2.0;
  const double l = std::log(e);
  const double zeta = -l / std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
  const double wd = std::sqrt(k / mstar) * std::sqrt(1 - zeta * zeta);
  EXPECT_NEAR(collision_duration(r, rho, E, e), std::numbers::pi / wd, 1e-18);
}

TEST(PairTable, WallMaterialUsesParticleModulusAndSeriesCombination) {
  PairTable t({Material{"a", 40e9, {}, 2500.0}, Material{"b", 10e9, {}, 2500.0},
               Material{"wall", {}, {}, {}}});
  t.set(0, 1, test::pair_properties(0.9, 0.2));
  t.set(0, 2, test::pair_properties(0.9, 0.2));
  EXPECT_DOUBLE_EQ(t(0, 1).youngs_modulus, 2 * 40e9 * 10e9 / 50e9);  // springs in series
  EXPECT_DOUBLE_EQ(t(1, 0).youngs_modulus, t(0, 1).youngs_modulus);  // symmetric
  EXPECT_DOUBLE_EQ(t(0, 2).youngs_modulus, 40e9);
  PairProperties own = test::pair_properties(0.9, 0.2);
  own.youngs_modulus = 70e9;
  t.set(1, 2, own);
  EXPECT_DOUBLE_EQ(t(1, 2).youngs_modulus, 70e9);
}

TEST(PairTable, RejectsNonPhysicalValues) {
  PairTable t({Material{"a", 40e9, {}, 2500.0}, Material{"wall", {}, {}, {}}});
  EXPECT_THROW(t.set(0, 0, test::pair_properties(0.0, 0.2)), std::invalid_argument);
  EXPECT_THROW(t.set(0, 0, test::pair_properties(1.01, 0.2)), std::invalid_argument);
  EXPECT_THROW(t.set(0, 0, test::pair_properties(0.5, -0.1)), std::invalid_argument);
  EXPECT_THROW(t.set(1, 1, test::pair_properties(0.5, 0.1)),
               std::invalid_argument);  // no E at all
}

TEST(PairTable, OptionalPiecesSwitchOnlyWhenUsed) {
  PairTable t({Material{"a", 40e9, {}, 2500.0}});
  t.set(0, 0, test::pair_properties(0.9, 0.2));
  EXPECT_FALSE(t.pieces().rolling);
  PairProperties p = test::pair_properties(0.9, 0.2);
  p.arf = 0.1;
  t.set(0, 0, p);
  EXPECT_TRUE(t.pieces().rolling);
  EXPECT_FALSE(t.pieces().twisting);
}
