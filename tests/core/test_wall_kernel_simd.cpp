// The kernel's plane wall rows (core/pair_kernel_simd.hpp, plane_wall_rows) on every instruction
// set this CPU runs, over ranges of wall entries that start and end anywhere in a group of 8:
// which candidates touch is checked against geometry/wall.hpp's wall_gap, computed here, and every
// output (results, springs, entries handed back, the largest overlap) must be the SSE2 object's
// bit for bit. That the lanes' law is the scalar wall law's is checked on whole runs in
// test_pair_kernel_simd.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "contact/pair_params.hpp"
#include "core/pair_kernel_simd.hpp"
#include "core/vec3.hpp"
#include "geometry/wall.hpp"
#include "support/random_values.hpp"

namespace grainlab {
namespace {

using test::Random;

using PlaneWallRows = double (*)(const SimdPairInput&, const SimdWallInput&,
                                 const SimdWallCandidates&, uint32_t, uint32_t, uint32_t*, long&);
using Records = void (*)(const SimdPairInput&, long, long);

// Beads of 1 mm radius in a 10 mm box with 7 plane walls (the box's six, three of them tilted,
// and one through the middle); each bead a candidate of the walls within 1 mm of it and of a few
// more, about half of them touching. Some beads are fixed, as are all walls but one (with mass);
// one bead's position is NaN.
struct Scene {
  static constexpr int wall_count = 7;
  std::vector<Vec3> position, velocity, angular_velocity, force, torque;
  std::vector<double> radius, inverse_mass, inverse_inertia, record;
  std::vector<int32_t> material;
  std::vector<Wall> walls;
  std::vector<SimdWallState> wall_state;
  SimdPlanes planes{};  // (the lanes beyond the walls read zeros)
  std::vector<uint32_t> row_start{0}, owner;
  std::vector<uint16_t> wall;
  PairParams pair_params[4];

  explicit Scene(int n, unsigned seed) {
    Random random(seed);
    const auto plane = [&](Vec3 point, Vec3 normal) {
      Wall w;
      w.shape = WallShape::plane;
      w.point = point;
      w.normal = normal;
      w.material = 1;
      finish_wall_geometry(w);
      walls.push_back(w);
    };
    plane({0, 0, 0}, Vec3{0, 0, 1} + random.vec3(0.05));
    plane({10e-3, 0, 0}, Vec3{-1, 0, 0} + random.vec3(0.05));
    plane({0, 0, 0}, {1, 0, 0});
    plane({0, 10e-3, 0}, Vec3{0, -1, 0} + random.vec3(0.05));
    plane({0, 0, 0}, {0, 1, 0});
    plane({0, 0, 10e-3}, {0, 0, -1});
    plane({5e-3, 5e-3, 5e-3}, {1, 1, 1});
    for (int k = 0; k < wall_count; ++k) {
      const Wall& w = walls[k];
      planes.point_x[k] = w.point.x, planes.point_y[k] = w.point.y, planes.point_z[k] = w.point.z;
      planes.normal_x[k] = w.normal.x, planes.normal_y[k] = w.normal.y;
      planes.normal_z[k] = w.normal.z;
      SimdWallState s{};
      const Vec3 v = random.vec3(0.01), v_end = v + random.vec3(0.001);
      s.velocity[0] = v.x, s.velocity[1] = v.y, s.velocity[2] = v.z;
      s.velocity_at_end[0] = v_end.x, s.velocity_at_end[1] = v_end.y;
      s.velocity_at_end[2] = v_end.z;
      s.inverse_mass = k == 5 ? 1.0 / 0.01 : 0.0;
      s.material = 1;
      wall_state.push_back(s);
    }
    planes.count = wall_count;
    for (int i = 0; i < n; ++i) {
      const double r = 1e-3 * (1.0 + 0.01 * random.uniform());
      // a centre anywhere in the box, or up to 0.2 mm beyond its planes
      const Vec3 x = Vec3{5e-3, 5e-3, 5e-3} + random.vec3(5.2e-3);
      position.push_back(x);
      radius.push_back(r);
      velocity.push_back(random.vec3(0.2));
      angular_velocity.push_back(random.vec3(200.0));
      force.push_back(random.vec3(0.05));
      torque.push_back(random.vec3(1e-5));
      const bool fixed = i % 13 == 4;
      inverse_mass.push_back(fixed ? 0.0 : 1.0 / (1.05e-5 * (1.0 + 0.02 * random.uniform())));
      inverse_inertia.push_back(fixed ? 0.0 : 1.0 / (4.2e-12 * (1.0 + 0.02 * random.uniform())));
      material.push_back(0);
      // the candidates: as a list with a 1 mm skin would have them, and a few more
      for (int k = 0; k < wall_count; ++k)
        if (wall_gap(walls[k], x).gap < r + 1e-3 || random.uniform() < -0.9) {
          owner.push_back(static_cast<uint32_t>(i));
          wall.push_back(static_cast<uint16_t>(k));
        }
      row_start.push_back(static_cast<uint32_t>(owner.size()));
    }
    position[n / 2].y = std::nan("");
    record.resize(size_t(n) * particle_record_size);
    for (PairParams& p : pair_params) {
      p.stiffness_per_radius = M_PI * 46.2e9;
      p.damping_ratio = 0.2;
      p.rns = 0.5;
      p.rzs = 0.1;
      p.friction = 0.3;
    }
  }
  SimdPairInput input() {
    SimdPairInput in{};
    in.position = components(position);
    in.velocity = components(velocity);
    in.angular_velocity = components(angular_velocity);
    in.force = components(force);
    in.torque = components(torque);
    in.radius = radius.data();
    in.inverse_mass = inverse_mass.data();
    in.inverse_inertia = inverse_inertia.data();
    in.material = material.data();
    in.particle_record = record.data();
    in.pair_params = pair_params;
    in.material_count = 2;
    in.time_step = 8.4e-8;
    in.drift = 2e-4;  // s: long enough that some contacts may have begun in it
    return in;
  }
};

// What one run writes: the entry arrays (force, torque, spring as Vec3s; stiffness and normal
// force), each range's handed-back entries in order, and each range's largest overlap.
struct Outputs {
  std::vector<Vec3> force, torque, spring;
  std::vector<double> stiffness, normal_force;
  std::vector<uint32_t> deferred;
  std::vector<double> largest;
};

Outputs run(const char* isa, PlaneWallRows rows, Records records, Scene& scene,
            const std::vector<uint32_t>& cuts) {
  SCOPED_TRACE(isa);
  const size_t m = scene.owner.size();
  Outputs out;
  // what was there before: springs to be kept or cleared, results to be overwritten
  Random random(99);
  for (size_t e = 0; e < m; ++e) {
    out.spring.push_back(random.vec3(1e-6));
    out.force.push_back({1.5, 2.5, 3.5});
    out.torque.push_back({4.5, 5.5, 6.5});
    out.stiffness.push_back(7.5);
    out.normal_force.push_back(8.5);
  }
  SimdPairInput in = scene.input();
  records(in, 0, static_cast<long>(scene.radius.size()));
  const SimdWallInput walls{scene.wall_state.data(), components(out.spring),
                            components(out.force),   components(out.torque),
                            out.stiffness.data(),    out.normal_force.data()};
  const SimdWallCandidates candidates{scene.owner.data(), scene.wall.data(), &scene.planes};
  std::vector<uint32_t> deferred(m);
  for (size_t c = 0; c + 1 < cuts.size(); ++c) {
    long count = -1;
    out.largest.push_back(
        rows(in, walls, candidates, cuts[c], cuts[c + 1], deferred.data() + cuts[c], count));
    EXPECT_GE(count, 0);
    out.deferred.insert(out.deferred.end(), deferred.begin() + cuts[c],
                        deferred.begin() + cuts[c] + count);
  }
  return out;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

bool cpu_has(const char* isa) {
  __builtin_cpu_init();
  if (std::string(isa) == "avx2") return __builtin_cpu_supports("avx2");
  if (std::string(isa) == "avx512") return __builtin_cpu_supports("avx512f");
  return true;
}

TEST(WallKernelSimd, PlaneWallRowsFindTheTouchingCandidatesOfWallGapOnEveryInstructionSet) {
  Scene scene(1000, 7);
  const auto m = static_cast<uint32_t>(scene.owner.size());
  // ranges of every length from 0 to 20 entries, then longer ones, cut anywhere
  std::vector<uint32_t> cuts{0};
  for (uint32_t length = 0; cuts.back() + length < m && length <= 20; ++length)
    cuts.push_back(cuts.back() + length);
  for (uint32_t step = 37; cuts.back() + step < m; step += 11) cuts.push_back(cuts.back() + step);
  cuts.push_back(m);
  const Outputs sse2 =
      run("sse2", &simd_sse2::plane_wall_rows, &simd_sse2::particle_records, scene, cuts);

  // The reference: touching where the radius exceeds wall_gap's gap (or either is NaN) and not
  // both bodies fixed; the largest overlap / r of each range over the touching ones.
  long touching = 0, apart = 0;
  std::vector<double> largest;
  for (size_t c = 0; c + 1 < cuts.size(); ++c) {
    double range_largest = 0.0;
    for (uint32_t e = cuts[c]; e < cuts[c + 1]; ++e) {
      const uint32_t i = scene.owner[e];
      const WallGap g = wall_gap(scene.walls[scene.wall[e]], scene.position[i]);
      const double overlap = scene.radius[i] - g.gap;
      const bool both_fixed =
          scene.inverse_mass[i] + scene.wall_state[scene.wall[e]].inverse_mass == 0.0;
      if (overlap <= 0.0 || both_fixed) {
        ++apart;
        EXPECT_TRUE(sse2.force[e] == Vec3{} && sse2.torque[e] == Vec3{} &&
                    sse2.spring[e] == Vec3{} && sse2.stiffness[e] == 0.0 &&
                    sse2.normal_force[e] == 0.0)
            << "entry " << e << " is apart but not cleared";
        continue;
      }
      ++touching;
      range_largest = std::max(range_largest, overlap / scene.radius[i]);
      const bool handed_back =
          std::find(sse2.deferred.begin(), sse2.deferred.end(), e) != sse2.deferred.end();
      // a touching contact the lanes ran has its stiffness k_n = pi E r (NaN with a NaN
      // position); one handed back is left as it was
      EXPECT_TRUE(handed_back ? sse2.stiffness[e] == 7.5 : sse2.stiffness[e] != 7.5)
          << "entry " << e;
    }
    largest.push_back(range_largest);
  }
  EXPECT_GT(touching, m / 4);
  EXPECT_GT(apart, m / 4);
  EXPECT_FALSE(sse2.deferred.empty()) << "no contact may have begun in the step";
  EXPECT_TRUE(same_bits(largest, sse2.largest));

  for (const char* isa : {"avx2", "avx512"}) {
    if (!cpu_has(isa)) continue;
    const bool avx2 = std::string(isa) == "avx2";
    const Outputs wide =
        run(isa, avx2 ? &simd_avx2::plane_wall_rows : &simd_avx512::plane_wall_rows,
            avx2 ? &simd_avx2::particle_records : &simd_avx512::particle_records, scene, cuts);
    SCOPED_TRACE(isa);
    EXPECT_TRUE(same_bits(sse2.force, wide.force));
    EXPECT_TRUE(same_bits(sse2.torque, wide.torque));
    EXPECT_TRUE(same_bits(sse2.spring, wide.spring));
    EXPECT_TRUE(same_bits(sse2.stiffness, wide.stiffness));
    EXPECT_TRUE(same_bits(sse2.normal_force, wide.normal_force));
    EXPECT_EQ(sse2.deferred, wide.deferred);
    EXPECT_TRUE(same_bits(sse2.largest, wide.largest));
  }
}

}  // namespace
}  // namespace grainlab
