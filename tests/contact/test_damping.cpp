// Damping ratio from restitution: the textbook Eq. 7 (ln form) and the clamped-contact inversion.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "contact/damping.hpp"

using namespace grainlab;

TEST(Damping, TextbookRatioMatchesFormula) {
  // zeta = -ln e / sqrt(pi^2 + ln^2 e), by hand for e = 0.926: ln e = -0.0768806
  EXPECT_NEAR(textbook_damping_ratio(0.926), 0.0768806 / std::sqrt(9.8696044 + 0.0059106), 1e-6);
  EXPECT_EQ(textbook_damping_ratio(1.0), 0.0);
}

TEST(Damping, UnclampedAnalyticRestitutionWouldBeExact) {
  // Without the clamp the bodies separate when U returns to 0 at t = pi/omega_d and
  // e = exp(-zeta pi / sqrt(1 - zeta^2)): the textbook ratio inverts that exactly.
  for (double e : {0.1, 0.5, 0.926}) {
    const double z = textbook_damping_ratio(e);
    EXPECT_NEAR(std::exp(-z * std::numbers::pi / std::sqrt(1 - z * z)), e, 1e-12);
  }
}

TEST(Damping, ClampMakesTextbookRatioReboundTooHigh) {
  // The observation: with the clamp, the textbook zeta for e = 0.5 rebounds near 0.55.
  EXPECT_NEAR(clamped_restitution(textbook_damping_ratio(0.5)), 0.55, 0.005);
}

TEST(Damping, InversionReturnsInputRestitution) {
  for (double e : {0.05, 0.1, 0.3, 0.5, 0.58, 0.73, 0.926, 0.94, 0.999, 1.0}) {
    const double z = damping_ratio_for_restitution(e);
    EXPECT_NEAR(clamped_restitution(z), e, 1e-12) << "e = " << e;
    if (e < 1.0) {
      EXPECT_GT(z, textbook_damping_ratio(e)) << "clamp needs more damping";
    }
  }
}

TEST(Damping, ClampedRestitutionIsContinuousAcrossCriticalDamping) {
  // under-, critically and over-damped branches must join
  EXPECT_NEAR(clamped_restitution(1.0 - 2e-9), clamped_restitution(1.0), 1e-6);
  EXPECT_NEAR(clamped_restitution(1.0 + 2e-9), clamped_restitution(1.0), 1e-6);
}

TEST(Damping, UndampedContactLastsHalfAPeriod) {
  EXPECT_NEAR(clamped_force_duration(1e-12), std::numbers::pi, 1e-9);
  EXPECT_NEAR(clamped_overlap_duration(1e-12), std::numbers::pi, 1e-9);
}

TEST(Damping, RejectsNonPhysicalRestitution) {
  EXPECT_THROW(damping_ratio_for_restitution(0.0), std::invalid_argument);
  EXPECT_THROW(damping_ratio_for_restitution(1.1), std::invalid_argument);
}
