// Rolling resistance against its analytical solution: a sphere rolling on a flat under gravity
// with its rolling moment on the cap mu_theta F_n = ARF a m g decelerates uniformly and stops
// after a distance fixed by the moment alone.
//   rolling without slip at the contact point (v = l w, l = r - U_n the lever):
//     m dv/dt = F,   I dw/dt = -l F - M   =>   dv/dt = -M l / (I + m l^2),
//     stopping distance s = v0^2 (I + m l^2) / (2 M l),  M = ARF a m g,  a = sqrt(r^2 - l^2).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "support/scenes.hpp"

using namespace grainlab;
using namespace grainlab::test;

namespace {

struct Stop {
  double distance;  // m, where the centre's velocity first reaches zero
  double expected;  // m, analytical
};

Stop roll_until_stopped(double dt_fraction) {
  const double r = 1e-3, g = 9.81, arf = 40.0, v0 = 1e-3;
  const PairTable table = two_material_table(0.5, 0.5, arf);
  const double m = sphere_mass(r);
  const double inertia = 0.4 * m * r * r;
  const double k_n = table(0, 1).stiffness_per_radius * r;
  const double overlap = m * g / k_n;  // resting overlap
  const double lever = r - overlap;
  ParticleStore p;
  p.add(0, 0, r, glass_density, {0, 0, lever}, {v0, 0, 0}, {0, v0 / lever, 0}, false);
  Simulation sim(std::move(p), {plane_wall({0, 0, 0}, {0, 0, 1})}, table,
                 settings_for(r, 0.5, dt_fraction, {0, 0, -g}));
  const double a = std::sqrt(r * r - lever * lever);
  const double moment = arf * a * m * g;
  Stop s{0.0, v0 * v0 * (inertia + m * lever * lever) / (2.0 * moment * lever)};
  double previous_x = 0.0, previous_v = v0;
  while (sim.time() < 10.0) {
    sim.step();
    const double v = sim.particles().velocity[0].x, x = sim.particles().position[0].x;
    if (v <= 0.0) {  // interpolate the zero crossing of v
      s.distance = previous_x + (x - previous_x) * previous_v / (previous_v - v);
      break;
    }
    previous_x = x, previous_v = v;
  }
  return s;
}

}  // namespace

TEST(RollingResistance, SphereStopsAfterTheAnalyticDistance) {
  for (double dt_fraction : {0.1, 0.05}) {
    SCOPED_TRACE(dt_fraction);
    const Stop s = roll_until_stopped(dt_fraction);
    ASSERT_GT(s.distance, 0.0) << "the sphere never stopped";
    fmt::print("dt = {} t_c: stopped after {:.6e} m, analytical {:.6e} m (ratio {:.6f})\n",
               dt_fraction, s.distance, s.expected, s.distance / s.expected);
    EXPECT_NEAR(s.distance / s.expected, 1.0, 1e-4)
        << "distance " << s.distance << " m, analytical " << s.expected << " m";
  }
}
