// Affine compaction (control/affine_compaction.hpp): the box and every bead strained by the same
// homogeneous increment each step. Checked against the exact kinematics of the scheme on beads
// that touch nothing (each bead keeps its place relative to the box, the box shrinks by the
// product of the increments), and on a simple-cubic stack with gaps: the mean wall stress rises
// to the target without overshoot and the stack ends isotropically compressed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "control/affine_compaction.hpp"
#include "control/box_controller.hpp"
#include "geometry/cuboid_box.hpp"
#include "measure/boundary.hpp"
#include "support/scenes.hpp"

using namespace grainlab;
using namespace grainlab::test;

namespace {

constexpr double r = 1e-3;
constexpr int n = 4;  // spheres per edge

// n^3 spheres on a simple-cubic lattice `spacing` apart, in a box touching none of them.
Simulation spaced_stack(double spacing) {
  ParticleStore p;
  uint32_t id = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k)
        p.add(id++, 0, r, glass_density,
              {(i + 0.5) * spacing, (j + 0.5) * spacing, (k + 0.5) * spacing}, {}, {}, false);
  const double side = n * spacing;
  return Simulation(std::move(p), cuboid_walls({0, 0, 0}, {side, side, side}, 1, 1),
                    two_material_table(0.5, 0.0), settings_for(r, 0.5, 0.1));
}

}  // namespace

// No contact anywhere (spacing 3 r): the rate stays at its cap, every bead keeps its coordinate
// relative to the box (to round-off), and the box side after N steps is side0 (1 - rate dt)^N.
TEST(AffineCompaction, StrainsBeadsAndWallsByTheSameIncrement) {
  Simulation sim = spaced_stack(3 * r);
  const double rate = 50.0;  // 1/s
  AffineCompaction compaction(100e3, rate);
  const ScopedListener attached(sim, compaction);
  const Vec3 low0 = box_low(sim.walls()), size0 = box_size(sim.walls());
  const ParticleStore& p = sim.particles();
  std::vector<Vec3> relative0(p.size());  // by particle id
  for (size_t i = 0; i < p.size(); ++i) {
    const Vec3& x = p.position[i];
    relative0[p.id[i]] = {(x.x - low0.x) / size0.x, (x.y - low0.y) / size0.y,
                          (x.z - low0.z) / size0.z};
  }
  const int steps = 10000;
  sim.advance(steps);
  EXPECT_EQ(compaction.strain_rate(), rate);
  const double expected = size0.x * std::pow(1.0 - rate * sim.settings().time_step, steps);
  const Vec3 low = box_low(sim.walls()), size = box_size(sim.walls());
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(size[a] / expected, 1.0, 1e-12);
  EXPECT_LT(size.x, 0.99 * size0.x);  // it did compact
  for (size_t i = 0; i < p.size(); ++i) {
    const Vec3 rel{(p.position[i].x - low.x) / size.x, (p.position[i].y - low.y) / size.y,
                   (p.position[i].z - low.z) / size.z};
    const Vec3& rel0 = relative0[p.id[i]];
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(rel[a], rel0[a], 1e-12);
  }
}

// Gaps of 2 % of the diameter, every contact closing at the same strain (the stiffest jamming a
// packing can have): the averaged mean wall stress rises to the target and ends within 2 % of it,
// and the three axes end equally compressed. Its overshoot on the way is less than half of what
// the walls' servos give when they compact the same stack at the same strain-rate cap (box
// controller, compaction regime).
TEST(AffineCompaction, ReachesTheTargetStressWithLessOvershootThanTheWalls) {
  const double target = 100e3, rate = 20.0;
  const int steps = 60000;
  Simulation affine = spaced_stack(2.04 * r);
  AffineCompaction compaction(target, rate);
  double affine_highest = 0.0;
  {
    const ScopedListener attached(affine, compaction);
    for (int s = 0; s < steps; ++s) {
      affine.step();
      affine_highest = std::max(affine_highest, compaction.stress_error());
    }
  }
  EXPECT_NEAR(compaction.stress_error(), 0.0, 0.02);
  const Vec3 size = box_size(affine.walls());
  EXPECT_LT(size.x, n * 2 * r);  // the gaps closed and the stack is compressed
  EXPECT_NEAR(size.y / size.x, 1.0, 1e-12);
  EXPECT_NEAR(size.z / size.x, 1.0, 1e-12);

  Simulation walls = spaced_stack(2.04 * r);
  const AxisControl held{AxisMode::stress, target};
  BoxController servo(BoxControlSettings{{held, held, held}, ServoRegime::compaction, 0.0, rate});
  double walls_highest = 0.0;
  {
    const ScopedListener attached(walls, servo);
    for (int s = 0; s < steps; ++s) {
      walls.step();
      double sum = 0.0;
      for (int k = 0; k < 6; ++k) sum += wall_stress(walls.walls(), k);
      walls_highest = std::max(walls_highest, sum / (6 * target) - 1.0);
    }
  }
  std::printf("highest mean wall stress / target - 1: affine %.3f, walls %.3f\n", affine_highest,
              walls_highest);
  EXPECT_LT(affine_highest, 0.5 * walls_highest);
}
