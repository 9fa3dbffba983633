// A sphere under gravity on a plane: static overlap m g / k_n, and motion down an incline:
// rolling without slip (a = 5/7 g sin theta) when tan theta < 3.5 mu, sliding
// (a = g (sin theta - mu cos theta)) otherwise. Analytical rigid-body results.
#include <gtest/gtest.h>

#include <numbers>

#include "support/scenes.hpp"

using namespace grainlab;
using namespace grainlab::test;

namespace {
constexpr double g = 9.81, radius = 1e-3, mu = 0.16;
double bead_mass() {
  return glass_density * 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
}
double wall_stiffness() {
  return std::numbers::pi * glass_E * radius;
}  // k_n = pi E r* with r* = r

// Sphere resting on the plane z = 0, gravity tilted by theta about y (equivalent to an incline).
Simulation sphere_on_incline(double theta) {
  ParticleStore p;
  const double overlap = bead_mass() * g * std::cos(theta) / wall_stiffness();
  p.add(0, 0, radius, glass_density, {0, 0, radius - overlap}, {}, {}, false);
  return Simulation(std::move(p), {plane_wall({}, {0, 0, 1})}, two_material_table(0.5, mu),
                    settings_for(radius, 0.5, 0.1, {g * std::sin(theta), 0, -g * std::cos(theta)}));
}
}  // namespace

TEST(Gravity, SphereSettlesToStaticOverlap) {
  ParticleStore p;
  p.add(0, 0, radius, glass_density, {0, 0, radius}, {}, {}, false);  // just touching, at rest
  Simulation sim(std::move(p), {plane_wall({}, {0, 0, 1})}, two_material_table(0.5, mu),
                 settings_for(radius, 0.5, 0.1, {0, 0, -g}));
  while (sim.time() < 2e-4) sim.step();
  const double overlap = radius - sim.particles().position[0].z;
  const double expected = bead_mass() * g / wall_stiffness();  // 7.08e-13 m
  EXPECT_NEAR(overlap, expected, 1e-6 * expected);
  EXPECT_LT(std::abs(sim.particles().velocity[0].z), 1e-12);
}

TEST(Gravity, SphereRollsWithoutSlipOnGentleIncline) {
  for (double tan_theta : {0.1, 0.3, 0.5}) {  // all below 3.5 mu = 0.56
    const double theta = std::atan(tan_theta);
    Simulation sim = sphere_on_incline(theta);
    const double duration = 5e-3;
    while (sim.time() < duration) sim.step();
    const double a = 2.0 * sim.particles().position[0].x / (sim.time() * sim.time());
    EXPECT_NEAR(a, 5.0 / 7.0 * g * std::sin(theta), 0.005 * a) << "tan theta = " << tan_theta;
    // rolling: surface speed equals centre speed (v = w r, w about +y for motion along +x)
    const auto& q = sim.particles();
    EXPECT_NEAR(q.angular_velocity[0].y * radius, q.velocity[0].x, 1e-3 * q.velocity[0].x);
  }
}

TEST(Gravity, SphereSlidesOnSteepIncline) {
  for (double tan_theta : {0.6, 0.84, 1.5}) {  // above 3.5 mu = 0.56
    const double theta = std::atan(tan_theta);
    Simulation sim = sphere_on_incline(theta);
    while (sim.time() < 5e-3) sim.step();
    const double a = 2.0 * sim.particles().position[0].x / (sim.time() * sim.time());
    EXPECT_NEAR(a, g * (std::sin(theta) - mu * std::cos(theta)), 0.005 * a)
        << "tan theta = " << tan_theta;
    // slipping: the surface moves slower than the centre
    const auto& q = sim.particles();
    EXPECT_LT(q.angular_velocity[0].y * radius, 0.99 * q.velocity[0].x);
  }
}
