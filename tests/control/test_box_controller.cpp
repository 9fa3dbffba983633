// The box controller (control/box_controller.hpp): per axis a fixed pair of walls, walls driven at
// a speed, or walls held at a stress by the servo. Checked on a simple-cubic stack of touching
// spheres in a box: exact wall kinematics for the fixed and driven axes, and the servo's
// steady state against the target stress.
#include <gtest/gtest.h>

#include <cmath>

#include "control/box_controller.hpp"
#include "geometry/cuboid_box.hpp"
#include "measure/boundary.hpp"
#include "support/scenes.hpp"

using namespace grainlab;
using namespace grainlab::test;

namespace {

constexpr double r = 1e-3;
constexpr int n = 4;  // spheres per edge

Simulation cubic_stack() {
  ParticleStore p;
  uint32_t id = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k)
        p.add(id++, 0, r, glass_density, {(2 * i + 1) * r, (2 * j + 1) * r, (2 * k + 1) * r}, {},
              {}, false);
  const double side = 2 * n * r;
  return Simulation(std::move(p), cuboid_walls({0, 0, 0}, {side, side, side}, 1, 1),
                    two_material_table(0.5, 0.0), settings_for(r, 0.5, 0.1));
}

}  // namespace

TEST(BoxController, FixedAxesStayAndDrivenPlatensMoveAtTheirSpeed) {
  Simulation sim = cubic_stack();
  const double v = -0.05;  // m/s: the platens move apart (nothing is compressed)
  BoxController control(
      BoxControlSettings{{AxisControl{}, AxisControl{}, AxisControl{AxisMode::speed, 0.0, v}}});
  const ScopedListener attached(sim, control);
  const Vec3 size0 = box_size(sim.walls());
  sim.advance(1000);
  const Vec3 size = box_size(sim.walls());
  EXPECT_EQ(size.x, size0.x);
  EXPECT_EQ(size.y, size0.y);
  EXPECT_NEAR(size.z - size0.z, -2.0 * v * sim.time(), 1e-15);
}

// x walls held at 100 kPa, y and z fixed: the stack is compressed along x until each x wall
// carries sigma A, A = (2 n r)^2; interval-averaged over the last 2000 steps, within 0.5 %.
TEST(BoxController, ServoHoldsTheTargetStress) {
  Simulation sim = cubic_stack();
  const double target = 100e3;
  BoxController control(
      BoxControlSettings{{AxisControl{AxisMode::stress, target}, AxisControl{}, AxisControl{}},
                         ServoRegime::holding,
                         0.01});
  const ScopedListener attached(sim, control);
  sim.advance(20000);
  double sum_low = 0.0, sum_high = 0.0;
  const int samples = 2000;
  for (int s = 0; s < samples; ++s) {
    sim.step();
    sum_low += wall_stress(sim.walls(), x_low);
    sum_high += wall_stress(sim.walls(), x_high);
  }
  EXPECT_NEAR(sum_low / samples / target, 1.0, 0.005);
  EXPECT_NEAR(sum_high / samples / target, 1.0, 0.005);
  EXPECT_EQ(box_size(sim.walls()).y, 2 * n * r);  // fixed axes untouched
  EXPECT_LT(box_size(sim.walls()).x, 2 * n * r);  // compressed
}
