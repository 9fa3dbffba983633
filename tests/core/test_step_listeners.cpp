// The step loop's extension points: step listeners and their order, the per-particle
// external force source, the rebuild check on walls that grow or turn, and the pair-table command.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "support/scenes.hpp"

using namespace grainlab;
using namespace grainlab::test;

namespace {

struct Log : StepListener {
  std::string calls;
  void before_step(Simulation&) override { calls += 'b'; }
  void after_rebuild(Simulation&) override { calls += 'r'; }
  void after_step(const Simulation&) override { calls += 'a'; }
};

}  // namespace

TEST(StepListeners, CalledInOrderAndRebuildOnlyWhenTheListIsRebuilt) {
  ParticleStore p;  // a sphere flying through empty space at 1 m/s
  p.add(0, 0, 1e-3, glass_density, {0, 0, 0}, {1.0, 0, 0}, {}, false);
  SimulationSettings s = settings_for(1e-3, 0.9, 0.1);
  Simulation sim(std::move(p), {}, two_material_table(0.9, 0.1), s);
  Log log;
  {
    const ScopedListener attached(sim, log);
    // It moves 1 m/s * dt per step; the list is rebuilt once it has moved half the skin.
    const long steps_to_rebuild = static_cast<long>(std::ceil(0.5 * s.skin / s.time_step)) + 1;
    sim.advance(steps_to_rebuild);
  }
  const long rebuilds = std::count(log.calls.begin(), log.calls.end(), 'r');
  EXPECT_EQ(rebuilds, sim.rebuild_count() - 1);  // minus the rebuild at construction
  EXPECT_GE(rebuilds, 1);
  EXPECT_EQ(log.calls.substr(0, 2), "ba");
  EXPECT_NE(log.calls.find("bra"), std::string::npos) << log.calls;
  sim.step();  // detached: no more calls
  EXPECT_EQ(std::count(log.calls.begin(), log.calls.end(), 'b'), sim.step_count() - 1);
}

// A constant external force on free spheres, set after the first force evaluation (it acts from
// the next one): velocity Verlet then moves each sphere exactly as a constant acceleration
// a = F/m started with v = a dt/2 at t = dt, x(t) = x0 + a t (t - dt) / 2. The spheres are far
// apart, and are re-sorted by a rebuild part-way, so each force must follow its particle through
// the permutation.
TEST(ExternalForce, ConstantForceGivesUniformAccelerationAndFollowsTheParticle) {
  // Spheres in separate lanes along x (3 mm apart: they never touch), pushed along y in
  // alternate directions, so that the spatial re-sort at the rebuilds changes their storage order.
  ParticleStore p;
  const int n = 8;
  auto start = [](uint32_t id) { return Vec3{0.003 * id, 0.0, 0.0}; };
  for (int i = 0; i < n; ++i) p.add(i, 0, 1e-3, glass_density, start(i), {}, {}, false);
  Simulation sim(std::move(p), {}, two_material_table(0.9, 0.1), settings_for(1e-3, 0.9, 0.1));
  const double m = sphere_mass(1e-3);
  std::vector<Vec3> force(n);
  const std::vector<uint32_t> ids_at_start = sim.particles().id;
  for (size_t k = 0; k < sim.particles().size(); ++k) {
    const uint32_t id = sim.particles().id[k];
    force[id] = {0.01 * id, id % 2 ? -0.3 : 0.3, -0.02};  // N: ~3.6 mm in 6000 steps
    sim.set_external_force(k, force[id]);
  }
  sim.advance(6000);
  ASSERT_NE(sim.particles().id, ids_at_start) << "the test needs a re-sort part-way";
  const double t = sim.time(), dt = sim.settings().time_step;
  const ParticleStore& q = sim.particles();
  for (size_t k = 0; k < q.size(); ++k) {
    const uint32_t id = q.id[k];
    const Vec3 moved = (0.5 * t * (t - dt) / m) * force[id];
    EXPECT_LT(norm(q.position[k] - start(id) - moved), 1e-9 * norm(moved)) << "particle " << id;
  }
  sim.clear_external_forces();
  sim.advance(2);  // the force of the last evaluation acts for half a step more
  const Vec3 v = q.velocity[0];
  sim.advance(10);
  EXPECT_EQ(sim.particles().velocity[0].x, v.x);  // no force any more
}

// A rectangle that grows towards a sphere: its edge reaches the sphere without its centre point
// moving. The list must be rebuilt (the sphere was not a candidate: it was farther than the skin
// from the rectangle) and the sphere must be pushed.
TEST(RebuildCheck, RectangleThatGrowsTriggersARebuild) {
  ParticleStore p;
  const double r = 1e-3;
  p.add(0, 0, r, glass_density, {0.01 + 3 * r, 0, 0.99 * r}, {}, {}, false);
  Wall w;
  w.shape = WallShape::rectangle;
  w.material = 1;
  w.normal = {0, 0, 1};
  w.axis_u = {1, 0, 0};
  w.half_u = w.half_v = 0.01;
  finish_wall_geometry(w);
  Simulation sim(std::move(p), {w}, two_material_table(0.9, 0.1), settings_for(r, 0.9, 0.1));
  ASSERT_EQ(sim.wall_contacts().size(), 0u) << "the sphere starts out of reach of the rectangle";
  // Grow the rectangle in 20 steps of 0.25 r: the edge passes under the sphere's centre.
  for (int k = 0; k < 20; ++k) {
    Wall bigger = sim.walls()[0];
    bigger.half_u += 0.25 * r;
    sim.set_wall_geometry(0, bigger);
    sim.step();
  }
  EXPECT_GT(sim.rebuild_count(), 1);
  EXPECT_GT(sim.particles().velocity[0].z, 0.0) << "the grown rectangle must push the sphere up";
}

TEST(PairTableCommand, RefusesATableWithOtherPieces) {
  ParticleStore p;
  p.add(0, 0, 1e-3, glass_density, {0, 0, 0}, {}, {}, false);
  Simulation sim(std::move(p), {}, two_material_table(0.9, 0.1), settings_for(1e-3, 0.9, 0.1));
  EXPECT_NO_THROW(sim.set_pair_table(two_material_table(0.5, 0.3)));
  EXPECT_EQ(sim.pair_table()(0, 0).friction, 0.3);
  EXPECT_THROW(sim.set_pair_table(two_material_table(0.5, 0.3, 5.0)), std::invalid_argument)
      << "a rolling-resistance piece cannot appear after construction";
}

// A blow-up names the config key of the time step of the kind of run it is in.
TEST(BlowUpAdvice, NamesTheTimeStepKeyOfLabTests) {
  for (const auto key :
       {SimulationSettings::StepKey::scene, SimulationSettings::StepKey::lab_test}) {
    ParticleStore p;
    p.add(0, 0, 1e-3, glass_density, {0, 0, 0.01}, {}, {}, false);
    SimulationSettings s = settings_for(1e-3, 0.9, 0.1);
    s.step_key = key;
    Simulation sim(std::move(p), {}, two_material_table(0.9, 0.1), s);
    sim.set_particle_velocity(0, {1e3, 0, 0});  // above max_speed
    try {
      sim.step();
      FAIL() << "a particle above max_speed must stop the run";
    } catch (const BlowUpError& e) {
      const std::string message = e.what();
      const bool lab = key == SimulationSettings::StepKey::lab_test;
      EXPECT_EQ(message.find("test.dt_fraction") != std::string::npos, lab) << message;
      EXPECT_EQ(message.find("simulation.dt_fraction") != std::string::npos, !lab) << message;
    }
  }
}
