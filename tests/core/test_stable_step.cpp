// The stable step of every spring-dashpot (contact/stability.hpp):
//  - the closed-form critical step matches the integrator: a sphere resting on a wall, nudged,
//    rings down just below it and grows just above it (undamped and strongly damped springs);
//  - a sphere resting on a slope with a strongly damped tangential or rolling spring creeps
//    (or blows up) at the plain dt_fraction * t_c step, and stays put at the step the rule
//    chooses.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "contact/damping.hpp"
#include "contact/stability.hpp"
#include "support/scenes.hpp"

using namespace grainlab;
using namespace grainlab::test;

namespace {

constexpr double radius = 1e-3;

// Ratio of the normal oscillation's amplitude late in the run to its first amplitude, for a
// sphere pressed on a wall by a strong body force and nudged, at dt = factor * dt_crit.
double ring_down(double restitution, double factor) {
  const PairTable table = two_material_table(restitution, 0.0);
  const double m = sphere_mass(radius);
  const double k_n = table(0, 1).stiffness_per_radius * radius;
  const double c_n = 2.0 * table(0, 1).damping_ratio * std::sqrt(k_n * m);
  const double g = 1e4;  // a deep resting overlap, so the nudge never opens the contact
  const double rest = m * g / k_n;
  ParticleStore p;
  p.add(0, 0, radius, glass_density, {0, 0, radius - rest}, {0, 0, 1e-5}, {}, false);
  SimulationSettings s = settings_for(radius, restitution, 0.1, {0, 0, -g});
  s.time_step = factor * critical_time_step(k_n, c_n, m);
  s.max_overlap_fraction = 1.0;
  Simulation sim(std::move(p), {plane_wall({0, 0, 0}, {0, 0, 1})}, table, s);
  auto amplitude = [&](int steps) {
    double worst = 0.0;
    for (int k = 0; k < steps; ++k) {
      sim.step();
      worst = std::max(worst, std::abs(radius - sim.particles().position[0].z - rest));
    }
    return worst;
  };
  const double first = amplitude(20);
  sim.advance(300);
  return amplitude(20) / first;
}

}  // namespace

TEST(StableStep, CriticalStepMatchesTheIntegrator) {
  for (double e : {1.0, 0.5, 0.05}) {
    SCOPED_TRACE(e);
    // undamped (e = 1) the amplitude below the limit neither grows nor decays: it stays near 1
    if (e < 1.0)
      EXPECT_LT(ring_down(e, 0.97), 1.0) << "below the critical step the contact must ring down";
    else
      EXPECT_LT(ring_down(e, 0.97), 1.1) << "below the critical step it must not grow";
    EXPECT_GT(ring_down(e, 1.03), 10.0) << "above it the oscillation must grow";
  }
}

namespace {

struct SlopeRun {
  double creep;  // m, movement of the centre along the slope
  bool blew_up;
  double time_step;
};

// A soft sphere (so that the contact circle, and with it the rolling resistance, is large
// enough to hold it) resting on a 10-degree slope: rolling resistance stops it rolling, friction
// stops it sliding. Only an unstable spring-dashpot can move it.
SlopeRun rest_on_slope(double rzs, double rolling_damping_ratio, bool use_rule) {
  const double soft_E = 1e6, theta = 10.0 * std::numbers::pi / 180.0, g = 9.81;
  PairTable t({Material{"soft", soft_E, 0.3, glass_density}, Material{"wall", {}, {}, {}}});
  PairProperties q;
  q.restitution = 0.5;
  q.friction = 0.5;
  q.rzs = rzs;
  q.arf = 100.0;
  q.rolling_damping_ratio = rolling_damping_ratio;
  t.set(0, 0, q);
  t.set(0, 1, q);
  const double m = sphere_mass(radius);
  const double rest = m * g * std::cos(theta) / (t(0, 1).stiffness_per_radius * radius);
  const double plain = 0.1 * collision_duration(radius, glass_density, soft_E, 0.5);
  SimulationSettings s;
  s.time_step = use_rule ? stable_time_step(plain, t, 0, radius).time_step : plain;
  s.gravity = {g * std::sin(theta), 0.0, -g * std::cos(theta)};
  s.skin = 0.2 * radius;
  ParticleStore p;
  p.add(0, 0, radius, glass_density, {0, 0, radius - rest}, {}, {0, 1e-9, 0}, false);
  Simulation sim(std::move(p), {plane_wall({0, 0, 0}, {0, 0, 1})}, t, s);
  SlopeRun out{0.0, false, s.time_step};
  try {
    while (sim.time() < 0.05) sim.step();
  } catch (const BlowUpError&) {
    out.blew_up = true;
  }
  out.creep = sim.particles().position[0].x;
  return out;
}

}  // namespace

TEST(StableStep, StronglyDampedSpringsDoNotCreepDownASlope) {
  // elastic deflection under the slope's pull: m g sin(theta) / k_s, about 1e-8 m here
  const double allowed = 1e-3 * radius;
  for (auto [rzs, eta] : {std::pair{50.0, -1.0}, std::pair{0.0, 5.0}}) {
    SCOPED_TRACE(testing::Message() << "rzs " << rzs << ", rolling damping ratio " << eta);
    const SlopeRun plain = rest_on_slope(rzs, eta, false);
    EXPECT_TRUE(plain.blew_up || std::abs(plain.creep) > allowed)
        << "control: at 0.1 t_c the damped spring must be unstable (creep " << plain.creep << ")";
    const SlopeRun ruled = rest_on_slope(rzs, eta, true);
    fmt::print("rzs {} eta {}: dt {:.3e} s: {}creep {:.3e} m; rule's dt {:.3e} s: creep {:.3e} m\n",
               rzs, eta, plain.time_step, plain.blew_up ? "blew up, " : "", plain.creep,
               ruled.time_step, ruled.creep);
    EXPECT_LT(ruled.time_step, plain.time_step);
    EXPECT_FALSE(ruled.blew_up);
    EXPECT_LT(std::abs(ruled.creep), allowed) << "time step " << ruled.time_step;
  }
}

TEST(StableStep, ReferenceGlassBeadsKeepTheirStep) {
  // The reference pairs (glass-glass e 0.926 mu 0.16, glass-membrane e 0.58 mu 0.21,
  // glass-paper e 0.73 mu 0.18; RZS = 0, ARF = 0) leave dt = 0.1 t_c untouched.
  PairTable t({Material{"glass", glass_E, 0.245, glass_density}, Material{"rubber", {}, {}, {}},
               Material{"paper", {}, {}, {}}});
  auto set = [&](int b, double e, double mu) {
    PairProperties q;
    q.restitution = e;
    q.friction = mu;
    t.set(0, b, q);
  };
  set(0, 0.926, 0.16), set(1, 0.58, 0.21), set(2, 0.73, 0.18);
  const double r = 0.99e-3;
  const double plain = 0.1 * collision_duration(r, glass_density, glass_E, 0.926);
  const TimeStepChoiceForMaterial chosen = stable_time_step(plain, t, 0, r);
  EXPECT_EQ(chosen.time_step, plain);
  EXPECT_TRUE(chosen.limited_by.empty());
  // with a margin: the most restrictive piece (glass-rubber, zeta 0.19) allows 1.5 times that step
  EXPECT_GT(material_step_limit(t, 0, r).time_step, 1.5 * plain);
}
