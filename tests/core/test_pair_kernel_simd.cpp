// The vectorised pair kernel (core/pair_kernel_simd.hpp) against the scalar contact law, its
// reference: the same pile of beads run through the scalar loop and through the kernel of every
// instruction set this CPU has must end in bit-identical states. The pile mixes two bead
// materials (different friction, restitution and tangential damping), sticking and sliding
// contacts, contacts beginning inside a step (handed back to the scalar law), separations and
// neighbour rebuilds; the test checks that contacts were handed back. In a build that lets the
// compiler fuse multiply-adds (-march=native with FMA) the scalar loop may round differently from
// the kernel, which never fuses; there only the instruction sets are compared with each other.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>

#include "core/pair_kernel_simd.hpp"
#include "core/random_insertion.hpp"
#include "support/same_bits.hpp"
#include "support/scenes.hpp"

using namespace grainlab;
using namespace grainlab::test;

namespace {

// Materials: 0 and 1 two kinds of glass, 2 the walls.
PairTable mixed_table() {
  PairTable t({Material{"glass_a", glass_E, 0.245, glass_density},
               Material{"glass_b", 0.5 * glass_E, 0.245, 1.5 * glass_density},
               Material{"wall", {}, {}, {}}});
  auto pair = [&](int a, int b, double e, double mu, double rzs) {
    PairProperties p;
    p.restitution = e;
    p.friction = mu;
    p.rzs = rzs;
    t.set(a, b, p);
  };
  pair(0, 0, 0.9, 0.3, 0.0);
  pair(0, 1, 0.6, 0.1, 0.2);
  pair(1, 1, 0.4, 0.5, 0.5);
  pair(0, 2, 0.8, 0.2, 0.0);
  pair(1, 2, 0.7, 0.0, 0.0);
  return t;
}

struct KernelChoice {
  explicit KernelChoice(const char* value) { setenv("GRAINLAB_SIMD", value, 1); }
  ~KernelChoice() { unsetenv("GRAINLAB_SIMD"); }
};

struct PileResult {
  ParticleStore particles;
  std::string kernel;
  std::vector<Vec3> springs;        // per pair entry
  std::vector<PairResult> results;  // per pair entry: force, torque arm, overlap, F_n
  long touching = 0;
  long rebuilds = 0;
  long handed_back = 0;  // entries the kernel handed to the scalar law (first touch in a step)
  std::vector<double> largest_overlap;  // per step: the largest overlap / min(r_i, r_j)
  bool prefetched = false;              // the kernel's rows prefetched (at the end)
};

// The state a run ends in: the particles, and the pair entries' springs and results.
void keep_final_state(const Simulation& sim, PileResult& r) {
  r.particles = sim.particles();
  r.springs.assign(sim.pair_contacts().sliding_spring.begin(),
                   sim.pair_contacts().sliding_spring.end());
  r.results.assign(sim.pair_contacts().result.begin(), sim.pair_contacts().result.end());
}

// one_material: every bead of glass_a (the kernel then broadcasts the one pair's constants instead
// of looking them up per lane); otherwise a third of them glass_b.
PileResult run_pile(
    const char* kernel, int threads, long steps, bool one_material = false,
    SimulationSettings::Prefetch prefetch = SimulationSettings::Prefetch::automatic) {
  KernelChoice choice(kernel);
  omp_set_num_threads(threads);
  // 10 x 10 x 10 beads of radius 0.995-1.005 mm on a 2 mm lattice, jittered by up to 5 um:
  // neighbours overlap by up to 2 % of a radius or just miss, and the walls hold them in.
  std::mt19937_64 rng(23);
  auto jitter = [&](double half_width) { return half_width * (2.0 * uniform01(rng) - 1.0); };
  ParticleStore p;
  constexpr int side = 10;
  constexpr double spacing = 2.0e-3;
  for (int k = 0; k < side * side * side; ++k) {
    const Vec3 centre = cubic_lattice_site(k, side, spacing, [&] { return jitter(5e-6); });
    const bool b = !one_material && (k * 7919) % 3 == 0;
    p.add(static_cast<uint32_t>(k), b ? 1 : 0, 1.0e-3 + jitter(5e-6),
          b ? 1.5 * glass_density : glass_density, centre, {jitter(0.2), jitter(0.2), jitter(0.2)},
          {jitter(300.0), jitter(300.0), jitter(300.0)}, false);
  }
  const double l = side * spacing;
  std::vector<Wall> walls = cube_walls(l);
  for (Wall& w : walls) w.material = 2;
  SimulationSettings settings = settings_for(0.995e-3, 0.4, 0.1, {0, 0, -9.81});
  settings.prefetch = prefetch;
  Simulation sim(std::move(p), walls, mixed_table(), settings);
  PileResult r;
  r.kernel = sim.pair_kernel_name();
  for (long s = 0; s < steps; ++s) {
    sim.step();
    r.touching += sim.touching_pair_count();
    r.handed_back += sim.pairs_handed_to_scalar_law();
    r.largest_overlap.push_back(sim.max_overlap_fraction());
  }
  r.rebuilds = sim.rebuild_count();
  r.prefetched = sim.rows_prefetch();
  keep_final_state(sim, r);
  omp_set_num_threads(omp_get_num_procs());
  return r;
}

void expect_identical(const PileResult& a, const PileResult& b) {
  SCOPED_TRACE(a.kernel + " against " + b.kernel);
  expect_same_particle_bits(a.particles, b.particles);
  // the health check's largest overlap, step by step (the kernel takes it as a masked maximum
  // across the lanes; the scalar loop one contact at a time)
  EXPECT_EQ(a.largest_overlap, b.largest_overlap);
  // the contact histories and results of the last step, entry by entry
  ASSERT_EQ(a.springs.size(), b.springs.size());
  EXPECT_EQ(0, std::memcmp(a.springs.data(), b.springs.data(), a.springs.size() * sizeof(Vec3)));
  ASSERT_EQ(a.results.size(), b.results.size());
  EXPECT_EQ(0,
            std::memcmp(a.results.data(), b.results.data(), a.results.size() * sizeof(PairResult)));
}

bool cpu_has(const char* isa) {
  __builtin_cpu_init();
  if (std::string(isa) == "avx2") return __builtin_cpu_supports("avx2");
  if (std::string(isa) == "avx512") return __builtin_cpu_supports("avx512f");
  return true;
}

// Runs `run(isa)` for AVX2 and AVX-512 where this CPU has them and expects each to end in the
// state, and to hand back the contacts, of the SSE2 kernel's run.
template <class Result, class Run>
void expect_wider_instruction_sets_match(const Result& sse2, Run run) {
  for (const char* isa : {"avx2", "avx512"}) {
    if (!cpu_has(isa)) continue;
    const Result r = run(isa);
    EXPECT_EQ(r.kernel, isa);
    EXPECT_EQ(r.handed_back, sse2.handed_back);
    expect_identical(sse2, r);
  }
}

constexpr long pile_steps = 8000;

}  // namespace

TEST(PairKernelSimd, EveryInstructionSetMatchesTheScalarLaw) {
  const PileResult scalar = run_pile("off", 1, pile_steps);
  EXPECT_EQ(scalar.kernel, "scalar");
  // The run must exercise what the kernel has to get right.
  EXPECT_GT(scalar.touching, 1000L * pile_steps) << "too few contacts";
  EXPECT_GE(scalar.rebuilds, 1);
  EXPECT_EQ(scalar.handed_back, 0);
  const PileResult sse2 = run_pile("sse2", 1, pile_steps);
  EXPECT_EQ(sse2.kernel, "sse2");
  // Contacts that may have begun inside a step were handed to the scalar law (which applies the
  // first-touch correction where it finds one), and they are the exception: the kernel computed
  // the rest.
  EXPECT_GT(sse2.handed_back, 100) << "the kernel never handed a contact to the scalar law";
  EXPECT_LT(sse2.handed_back, sse2.touching / 100);
#ifndef __FMA__
  expect_identical(scalar, sse2);
#endif
  expect_wider_instruction_sets_match(sse2,
                                      [](const char* isa) { return run_pile(isa, 1, pile_steps); });
}

TEST(PairKernelSimd, OneMaterialMatchesTheScalarLawOnEveryInstructionSet) {
  const PileResult scalar = run_pile("off", 1, pile_steps / 2, true);
  EXPECT_GT(scalar.touching, 1000L * pile_steps / 2) << "too few contacts";
  const PileResult sse2 = run_pile("sse2", 1, pile_steps / 2, true);
  EXPECT_GT(sse2.handed_back, 0);
#ifndef __FMA__
  expect_identical(scalar, sse2);
#endif
  expect_wider_instruction_sets_match(
      sse2, [](const char* isa) { return run_pile(isa, 1, pile_steps / 2, true); });
  // and the mixed pile differs from it (the materials reach the law)
  const PileResult mixed = run_pile("sse2", 1, pile_steps / 2);
  EXPECT_NE(0, std::memcmp(mixed.particles.position.data(), sse2.particles.position.data(),
                           sse2.particles.size() * sizeof(Vec3)));
}

namespace {

// (handed_back: in the step where the pairs close; largest_overlap: per step, as in run_pile)
struct SidewaysResult : PileResult {
  double curvature_term = 0;  // |s|^2 / (2 D) of the pairs, m
};

// 64 pairs of beads far apart from each other. In each the second bead slides past the first,
// sideways (along y), at 1 m/s: at step `closing` the pair's centres line up along x at a distance
// of r_i + r_j - delta, with s = dt v perpendicular to the line. The overlap grew only by the
// curvature term of pair_entry's test, |s|^2 / (2 D), about 2.4e-12 m: delta from 0.1 to 3.2
// times it, so that the test finds about the first half begun in the step (first touch) and the
// rest older. The kernel must hand the first half back to the scalar law: a bound of the
// curvature term that fell short would let its lanes take them.
SidewaysResult run_sideways_pairs(const char* kernel, long closing) {
  KernelChoice choice(kernel);
  omp_set_num_threads(1);
  constexpr double radius = 1.0e-3, speed = 1.0;
  const SimulationSettings settings = settings_for(radius, 0.5, 0.1, {0.0, 0.0, 0.0});
  const double dt = settings.time_step, reach = 2.0 * radius;
  const double curvature_term = (dt * speed) * (dt * speed) / (2.0 * reach);
  ParticleStore p;
  for (int k = 0; k < 64; ++k) {
    const Vec3 first{0.0, 0.0, 10.0 * reach * k};
    const double delta = (0.1 + 0.05 * k) * curvature_term;
    const Vec3 second =
        first + Vec3{reach - delta, -speed * dt * static_cast<double>(closing), 0.0};
    p.add(static_cast<uint32_t>(2 * k), 0, radius, glass_density, first, {}, {}, false);
    p.add(static_cast<uint32_t>(2 * k + 1), 0, radius, glass_density, second, {0.0, speed, 0.0}, {},
          false);
  }
  Simulation sim(std::move(p), {}, mixed_table(), settings);
  SidewaysResult r;
  r.kernel = sim.pair_kernel_name();
  r.curvature_term = curvature_term;
  for (long s = 0; s < closing; ++s) {
    sim.step();
    r.largest_overlap.push_back(sim.max_overlap_fraction());
  }
  r.handed_back = sim.pairs_handed_to_scalar_law();
  keep_final_state(sim, r);
  omp_set_num_threads(omp_get_num_procs());
  return r;
}

}  // namespace

// The kernel's bound of the curvature term (begun_curvature_bound, from the speed bound that the
// half kick forms) lets a batch skip pair_entry's test for contacts begun in the step; here the
// curvature term alone decides that test, and the kernel must make the scalar law's decisions.
TEST(PairKernelSimd, PairsClosedBySidewaysMotionAreHandedBackAsTheScalarLawDecides) {
  constexpr long closing = 20;  // steps: the half kicks have formed a bound of the speeds by then
  const SidewaysResult scalar = run_sideways_pairs("off", closing);
  EXPECT_GT(scalar.curvature_term, 1e-12);
  for (const char* isa : {"sse2", "avx2", "avx512"}) {
    if (!cpu_has(isa)) continue;
    const SidewaysResult r = run_sideways_pairs(isa, closing);
    SCOPED_TRACE(r.kernel);
    EXPECT_EQ(r.kernel, isa);
    // about half of the 64 pairs began in the step, and only those were handed back
    EXPECT_GT(r.handed_back, 16);
    EXPECT_LT(r.handed_back, 48);
    expect_identical(scalar, r);
  }
}

TEST(PairKernelSimd, RowsThatPrefetchGiveTheSameBits) {
  // The pile is small, so the rows prefetch only when told to; the results must not change.
  using Prefetch = SimulationSettings::Prefetch;
  const PileResult automatic = run_pile("auto", 2, pile_steps / 2);
  const PileResult always = run_pile("auto", 2, pile_steps / 2, false, Prefetch::always);
  const PileResult never = run_pile("auto", 2, pile_steps / 2, false, Prefetch::never);
  EXPECT_NE(always.kernel, "scalar");
  // 1,000 beads: a row's partners lie about 110 beads ahead, some 170 KB, inside any L2 of 256 KB
  if (l2_cache_bytes() >= 256L << 10) {
    EXPECT_FALSE(automatic.prefetched);
  }
  EXPECT_TRUE(always.prefetched);
  EXPECT_FALSE(never.prefetched);
  EXPECT_GE(always.rebuilds, 1);  // the choice was made again at a rebuild, and held
  expect_identical(never, always);
  expect_identical(never, automatic);
}

TEST(PairKernelSimd, PrefetchWhereThePartnersLieBeyondTheL2) {
  // rows 0: partners 3 and 5 (farthest 5 ahead); 1: none (left out); 2: partner 4 (2 ahead)
  const std::vector<uint32_t> row_start{0, 2, 2, 3}, partner{3, 5, 4};
  const PartnerReach reach = partner_reach(row_start.data(), partner.data(), 3);
  EXPECT_DOUBLE_EQ(reach.mean, 3.5);
  EXPECT_EQ(reach.farthest, 5);
  const std::vector<uint32_t> empty_rows{0, 0, 0};
  EXPECT_EQ(partner_reach(empty_rows.data(), nullptr, 2).mean, 0.0);
  EXPECT_EQ(partner_reach(empty_rows.data(), nullptr, 2).farthest, 0);
  // about 1.5 KiB a bead: on a 1 MiB L2 the switch lies at 683 beads, on 2 MiB at 1,365
  EXPECT_FALSE(prefetch_pays(600.0, 1L << 20));
  EXPECT_TRUE(prefetch_pays(800.0, 1L << 20));
  EXPECT_FALSE(prefetch_pays(800.0, 2L << 20));
  EXPECT_TRUE(prefetch_pays(1500.0, 2L << 20));
  EXPECT_GT(l2_cache_bytes(), 0);
}

TEST(PairKernelSimd, OneTwoAndThreeThreadsGiveBitIdenticalStates) {
  // Each chunk of rows fills its own lane vectors: the packing of contacts into vectors differs
  // with the thread count and with which thread takes which chunk (three threads on CI's two
  // cores take chunks from each other's blocks whenever one is descheduled), the results must
  // not.
  const PileResult one = run_pile("auto", 1, pile_steps);
  const PileResult two = run_pile("auto", 2, pile_steps);
  const PileResult three = run_pile("auto", 3, pile_steps);
  EXPECT_NE(one.kernel, "scalar");
  EXPECT_EQ(one.handed_back, two.handed_back);
  EXPECT_EQ(one.handed_back, three.handed_back);
  expect_identical(one, two);
  expect_identical(one, three);
}

// The wall contacts through the kernel's lanes against the scalar wall law. Beads of two
// materials in a cylinder, on a floor and a small shelf (a rectangle whose edges beads touch),
// pressed by a lid with mass that an external force drives down (its velocity is integrated, so
// the lanes' wall velocities, wall mass and end-of-step estimate all count); beads are thrown in
// with random velocities, so contacts with the walls begin inside steps and are handed back.
struct WallPileResult {
  std::string kernel;
  ParticleStore particles;
  WallContacts contacts;
  std::vector<Wall> walls;
  long touching = 0;         // wall contacts with F_n > 0, summed over the steps
  long handed_back = 0;      // wall contacts handed to the scalar law, summed over the steps
  long by_wall[6] = {};      // touching contacts per wall, summed over the steps
  bool plane_lanes = false;  // the kernel found the touching candidates (at the end)
};

// planes: the cylinder and the shelf replaced by four planes around the pile, one of them
// tilted (the kernel then finds the touching candidates itself: plane_wall_rows).
WallPileResult run_wall_pile(const char* kernel, int threads, long steps, bool planes = false) {
  KernelChoice choice(kernel);
  omp_set_num_threads(threads);
  std::mt19937_64 rng(5);
  auto jitter = [&](double half_width) { return half_width * (2.0 * uniform01(rng) - 1.0); };
  constexpr double spacing = 1.9996e-3, cylinder_radius = spacing * 2.2360680 + 0.9996e-3,
                   axis = 7.0e-3;
  ParticleStore p;
  uint32_t id = 0;
  for (int layer = 0; layer < 8; ++layer)
    for (int a = -3; a <= 3; ++a)
      for (int b = -3; b <= 3; ++b) {
        const Vec3 centre{axis + spacing * a + jitter(2e-7), axis + spacing * b + jitter(2e-7),
                          0.9996e-3 + spacing * layer};
        if (std::hypot(centre.x - axis, centre.y - axis) > cylinder_radius - 0.99e-3) continue;
        const bool second = id % 3 == 1;
        p.add(id++, second ? 1 : 0, 1.0e-3 + jitter(2e-7),
              second ? 1.5 * glass_density : glass_density, centre,
              {jitter(0.2), jitter(0.2), jitter(0.2)},
              {jitter(300.0), jitter(300.0), jitter(300.0)}, false);
      }
  Wall cylinder;
  cylinder.shape = WallShape::cylinder;
  cylinder.point = {axis, axis, 0.0};
  cylinder.radius = cylinder_radius;
  finish_wall_geometry(cylinder);
  Wall shelf;
  shelf.shape = WallShape::rectangle;
  shelf.point = {axis, axis, 0.9996e-3 + 1.5 * spacing};  // between the second and third layers
  shelf.normal = {0, 0, 1};
  shelf.half_u = shelf.half_v = 1.6e-3;
  finish_wall_geometry(shelf);
  Wall lid = plane_wall({0, 0, 1.9996e-3 + 7 * spacing}, {0, 0, -1});
  lid.mass = 0.01;  // kg
  lid.velocity = {0, 0, -0.05};
  lid.external_force = {0, 0, -20.0};  // N
  std::vector<Wall> walls{plane_wall({0, 0, 0}, {0, 0, 1}), cylinder, shelf, lid};
  if (planes) {
    const double half = 2 * spacing + 0.9996e-3;  // the outermost beads touch
    walls = {walls[0],
             plane_wall({axis - half, 0, 0}, {1, 0, 0}),
             plane_wall({axis + half, 0, 0}, {-1, 0.02, 0.01}),
             lid,
             plane_wall({0, axis - half, 0}, {0, 1, 0}),
             plane_wall({0, axis + half, 0}, {0, -1, 0})};
  }
  for (Wall& w : walls) w.material = 2;
  Simulation sim(std::move(p), walls, mixed_table(),
                 settings_for(0.995e-3, 0.4, 0.1, {0, 0, -9.81}));
  WallPileResult r;
  r.kernel = sim.pair_kernel_name();
  for (long s = 0; s < steps; ++s) {
    sim.step();
    r.plane_lanes = sim.walls_in_plane_lanes();
    const WallContacts& c = sim.wall_contacts();
    r.touching += std::count_if(c.normal_force.begin(), c.normal_force.end(),
                                [](double f) { return f > 0.0; });
    r.handed_back += sim.walls_handed_to_scalar_law();
    for (size_t e = 0; e < c.size(); ++e) r.by_wall[c.wall[e]] += c.normal_force[e] > 0.0;
  }
  r.particles = sim.particles();
  r.contacts = sim.wall_contacts();
  r.walls = sim.walls();
  omp_set_num_threads(omp_get_num_procs());
  return r;
}

template <class T, class A>
bool same_bytes(const std::vector<T, A>& a, const std::vector<T, A>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

void expect_identical(const WallPileResult& a, const WallPileResult& b) {
  SCOPED_TRACE(a.kernel + " against " + b.kernel);
  EXPECT_EQ(a.particles.id, b.particles.id);
  EXPECT_TRUE(same_bytes(a.particles.position, b.particles.position));
  EXPECT_TRUE(same_bytes(a.particles.velocity, b.particles.velocity));
  EXPECT_TRUE(same_bytes(a.particles.angular_velocity, b.particles.angular_velocity));
  EXPECT_TRUE(same_bytes(a.particles.force, b.particles.force));
  EXPECT_TRUE(same_bytes(a.particles.torque, b.particles.torque));
  EXPECT_TRUE(same_bytes(a.contacts.wall, b.contacts.wall));
  EXPECT_TRUE(same_bytes(a.contacts.sliding_spring, b.contacts.sliding_spring));
  EXPECT_TRUE(same_bytes(a.contacts.force_on_particle, b.contacts.force_on_particle));
  EXPECT_TRUE(same_bytes(a.contacts.torque_on_particle, b.contacts.torque_on_particle));
  EXPECT_TRUE(same_bytes(a.contacts.normal_stiffness, b.contacts.normal_stiffness));
  EXPECT_TRUE(same_bytes(a.contacts.normal_force, b.contacts.normal_force));
  ASSERT_FALSE(a.walls.empty());
  ASSERT_EQ(a.walls.size(), b.walls.size());
  for (size_t k = 0; k < a.walls.size(); ++k) {
    EXPECT_EQ(0, std::memcmp(&a.walls[k].point, &b.walls[k].point, sizeof(Vec3))) << k;
    EXPECT_EQ(0, std::memcmp(&a.walls[k].velocity, &b.walls[k].velocity, sizeof(Vec3))) << k;
    EXPECT_EQ(0, std::memcmp(&a.walls[k].force, &b.walls[k].force, sizeof(Vec3))) << k;
    EXPECT_TRUE(same_bytes(std::vector<double>{a.walls[k].contact_stiffness},
                           std::vector<double>{b.walls[k].contact_stiffness}))
        << k;
    EXPECT_EQ(a.walls[k].contact_count, b.walls[k].contact_count) << k;
  }
}

constexpr long wall_pile_steps = 6000;

// The scalar law's run of the wall pile (planes: see run_wall_pile), the SSE2 kernel's against
// it, and the wider instruction sets' and two threads' against the SSE2 kernel's. The pile must
// hold beads on every wall, at least min_touching wall contacts per step on average, and hand
// back some contacts, at most one in handed_back_share of the touching ones.
void expect_wall_piles_match(bool planes, int wall_count, long min_touching,
                             long handed_back_share) {
  const WallPileResult scalar = run_wall_pile("off", 1, wall_pile_steps, planes);
  EXPECT_FALSE(scalar.plane_lanes);
  for (int k = 0; k < wall_count; ++k)
    EXPECT_GT(scalar.by_wall[k], 0) << "no bead touches wall " << k;
  EXPECT_GT(scalar.touching, min_touching * wall_pile_steps) << "too few wall contacts";
  const WallPileResult sse2 = run_wall_pile("sse2", 1, wall_pile_steps, planes);
  EXPECT_EQ(sse2.plane_lanes, planes);
  EXPECT_GT(sse2.handed_back, 20) << "no wall contact was handed to the scalar law";
  EXPECT_LT(sse2.handed_back, sse2.touching / handed_back_share);
#ifndef __FMA__
  expect_identical(scalar, sse2);
#endif
  expect_wider_instruction_sets_match(
      sse2, [&](const char* isa) { return run_wall_pile(isa, 1, wall_pile_steps, planes); });
  const WallPileResult two = run_wall_pile("auto", 2, wall_pile_steps, planes);
  EXPECT_EQ(two.plane_lanes, planes);
  expect_identical(sse2, two);
}

TEST(PairKernelSimd, WallContactsMatchTheScalarWallLawOnEveryInstructionSet) {
  // Every wall holds beads at the end (the shelf by its face or its edges), and the lid with
  // mass has moved under its load.
  expect_wall_piles_match(false, 4, 50, 100);
}

TEST(PairKernelSimd, PlaneWallsFoundByTheLanesMatchTheScalarWallLawOnEveryInstructionSet) {
  // (fewer contacts than in the cylinder, whose wall the outer beads lie against)
  expect_wall_piles_match(true, 6, 10, 20);
}

TEST(PairKernelSimd, UnknownOrUnsupportedChoiceIsRefusedByName) {
  {
    KernelChoice choice("avx1024");
    try {
      select_simd_pair_kernel();
      FAIL() << "an unknown GRAINLAB_SIMD value was accepted";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("GRAINLAB_SIMD=avx1024"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("expected off, sse2, avx2, avx512"), std::string::npos);
    }
  }
  if (!cpu_has("avx512")) {
    KernelChoice choice("avx512");
    EXPECT_THROW(select_simd_pair_kernel(), std::runtime_error);
  }
  KernelChoice automatic("");
  EXPECT_STREQ(select_simd_pair_kernel().name,
               cpu_has("avx512") ? "avx512" : (cpu_has("avx2") ? "avx2" : "sse2"));
}
