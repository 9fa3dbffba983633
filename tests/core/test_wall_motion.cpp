// Walls that move: prescribed velocity, and walls with mass integrated under the particles'
// force plus an external load (the slider of the sliding-friction test).
#include <gtest/gtest.h>

#include <cmath>

#include "support/scenes.hpp"

using namespace grainlab;
using namespace grainlab::test;

TEST(WallMotion, PrescribedVelocityMovesWall) {
  ParticleStore p;
  p.add(0, 0, 1e-3, glass_density, {0, 0, 0.01}, {}, {}, false);
  Wall w = plane_wall({0, 0, 0}, {0, 0, 1});
  w.velocity = {0, 0, 0.01};
  Simulation sim(std::move(p), {w}, two_material_table(0.9, 0.1), settings_for(1e-3, 0.9, 0.1));
  sim.advance(1000);
  EXPECT_NEAR(sim.walls()[0].point.z, 0.01 * sim.time(), 1e-15);
}

TEST(WallMotion, MassiveWallAcceleratesUnderExternalForce) {
  ParticleStore p;
  p.add(0, 0, 1e-3, glass_density, {0, 0, 0.01}, {}, {}, false);
  Wall w = plane_wall({0, 0, 0}, {0, 0, 1});
  w.mass = 0.5;
  w.external_force = {2.0, 0, 0};  // a = 4 m/s^2 along x, in its own plane
  Simulation sim(std::move(p), {w}, two_material_table(0.9, 0.1), settings_for(1e-3, 0.9, 0.1));
  sim.advance(2000);
  const double t = sim.time();
  EXPECT_NEAR(sim.walls()[0].point.x, 0.5 * 4.0 * t * t,
              1e-12 * t * t);  // exact for constant force
}

TEST(WallMotion, ImpactOnFreeWallConservesMomentum) {
  // A bead hits a free 1 g plate head on: momentum of bead + plate is conserved, and the
  // rebound follows e with the two-body reduced mass (wall treated as a body of mass 1 g).
  ParticleStore p;
  const double v0 = 0.5;
  p.add(0, 0, 1e-3, glass_density, {0, 0, 1.01e-3}, {0, 0, -v0}, {}, false);
  Wall w = plane_wall({0, 0, 0}, {0, 0, 1});
  w.mass = 1e-3;
  Simulation sim(std::move(p), {w}, two_material_table(1.0, 0.0), settings_for(1e-3, 1.0, 0.01));
  const double m = 1.0 / sim.particles().inverse_mass[0];
  sim.advance(20000);
  const double momentum = m * sim.particles().velocity[0].z + w.mass * sim.walls()[0].velocity.z;
  EXPECT_NEAR(momentum, -m * v0, 1e-9 * m * v0);
  // elastic two-body collision: v_wall = 2 m v0 / (m + M) downwards
  EXPECT_NEAR(sim.walls()[0].velocity.z, -2 * m * v0 / (m + w.mass), 2e-3 * v0);
}

TEST(BlowUp, NanVelocityStopsTheRunWithAdvice) {
  ParticleStore p;
  p.add(0, 0, 1e-3, glass_density, {0, 0, 0.01}, {}, {}, false);
  Simulation sim(std::move(p), {plane_wall({}, {0, 0, 1})}, two_material_table(0.9, 0.1),
                 settings_for(1e-3, 0.9, 0.1));
  sim.set_particle_velocity(0, {std::nan(""), 0.0, 0.0});
  try {
    sim.step();
    FAIL() << "a NaN velocity must stop the run";
  } catch (const BlowUpError& e) {
    EXPECT_NE(std::string(e.what()).find("NaN"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("dt_fraction"), std::string::npos) << e.what();
  }
}
