// The per-particle passes of velocity Verlet (core/particle_passes_simd.hpp) on every instruction
// set this CPU runs, against a reference integration written here with core/vec3.hpp's
// arithmetic, particle by particle: every value must be the reference's bit for bit, for any
// range of particles (the AVX-512 object takes 8 at a time and the rest one by one).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "core/particle_passes_simd.hpp"
#include "core/vec3.hpp"
#include "support/random_values.hpp"

namespace grainlab {
namespace {

using test::Random;

// Particles with random velocities, forces and masses (some fixed), positions since the
// selection and the build some of which lie beyond the thresholds, and one NaN velocity.
struct Pile {
  std::vector<Vec3> position, velocity, angular_velocity, rotation, force, torque, at_refresh,
      at_build;
  std::vector<double> inverse_mass, inverse_inertia;
  double half_list_skin2 = 4e-10, half_skin2 = 4e-8, time_step = 8.4e-8;

  explicit Pile(int n, unsigned seed) {
    Random random(seed);
    const auto u = [&] { return random.uniform(); };
    const auto vec = [&](double scale) { return random.vec3(scale); };
    for (int i = 0; i < n; ++i) {
      position.push_back(vec(0.04));
      velocity.push_back(vec(0.3));
      angular_velocity.push_back(vec(300.0));
      rotation.push_back(vec(1.0));
      force.push_back(vec(0.05));
      torque.push_back(vec(1e-5));
      // displacements since the selection about half the list skin, since the build about a
      // tenth of the skin's half, a few beyond it
      at_refresh.push_back(position.back() + vec(2.2e-5));
      at_build.push_back(position.back() + vec(i % 37 == 5 ? 3e-4 : 2e-5));
      const bool fixed = i % 29 == 3;
      inverse_mass.push_back(fixed ? 0.0 : 1.0 / (1.05e-5 * (1.0 + 0.02 * u())));
      inverse_inertia.push_back(fixed ? 0.0 : 1.0 / (4.2e-12 * (1.0 + 0.02 * u())));
    }
    if (n > 20) velocity[19].y = std::nan("");
  }
  ParticlePassInput input(bool list_test, bool rebuild_test) {
    return {components(position),
            components(velocity),
            components(angular_velocity),
            components(rotation),
            components(force),
            components(torque),
            inverse_mass.data(),
            inverse_inertia.data(),
            list_test ? components(at_refresh) : nullptr,
            rebuild_test ? components(at_build) : nullptr,
            half_list_skin2,
            half_skin2,
            time_step};
  }
};

bool same_bits(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3)) == 0;
}
bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// The reference: velocity Verlet's first half kick and drift, particle by particle.
void reference_kick_and_drift(Pile& p, long first, long end, bool list_test, bool rebuild_test,
                              bool bound, DriftTally& tally) {
  const double dt = p.time_step, half = 0.5 * dt;
  for (long i = first; i < end; ++i) {
    p.velocity[i] += (half * p.inverse_mass[i]) * p.force[i];
    p.angular_velocity[i] += (half * p.inverse_inertia[i]) * p.torque[i];
    p.position[i] += dt * p.velocity[i];
    p.rotation[i] += dt * p.angular_velocity[i];
    if (!list_test) continue;
    const double d2 = norm2(p.position[i] - p.at_refresh[i]);
    if (d2 > p.half_list_skin2) tally.stale = 1;
    if (bound) {
      tally.displacement2 = std::max(tally.displacement2, d2);
      tally.scale2 = std::max(tally.scale2, norm2(p.position[i]));
    }
    if (rebuild_test && norm2(p.position[i] - p.at_build[i]) > p.half_skin2) tally.moved = 1;
  }
}

// The reference closing half kick.
void reference_half_kick(Pile& p, long first, long end, double& max_speed2, double* next_speed2) {
  const double half = 0.5 * p.time_step;
  for (long i = first; i < end; ++i) {
    const Vec3 kick = (half * p.inverse_mass[i]) * p.force[i];
    p.velocity[i] += kick;
    p.angular_velocity[i] += (half * p.inverse_inertia[i]) * p.torque[i];
    const double v2 = norm2(p.velocity[i]);
    max_speed2 = std::max(max_speed2, std::isnan(v2) ? INFINITY : v2);
    if (next_speed2) {
      const double next2 = norm2(p.velocity[i] + kick);
      *next_speed2 = std::max(*next_speed2, std::isnan(next2) ? INFINITY : next2);
    }
  }
}

struct Isa {
  const char* name;
  SimdParticlePasses passes;
  bool supported;
};

// A contact store for the gather: random rows of pair entries (partners after the particle),
// their transpose, results with touching and apart entries, wall entries, external forces and
// gravity; some particles fixed.
struct Contacts {
  struct Result {  // as core/contact_store.hpp's PairResult
    Vec3 force_on_first, torque_arm;
    double overlap = 0.0, normal_force = 0.0;
  };
  std::vector<uint32_t> row_start{0}, partner, col_start, col_pair, wall_row_start{0};
  std::vector<uint32_t> row_owner, wall_owner;  // (for the flat walk)
  std::vector<Result> result;
  std::vector<Vec3> wall_force, wall_torque, external_force;
  std::vector<double> radius, inverse_mass;
  Vec3 gravity{-0.0, -0.2, -9.81};  // (a negative zero: a zero's sign in a sum counts)

  explicit Contacts(int n, unsigned seed, bool with_walls = true) {
    Random random(seed);
    const auto u = [&] { return random.uniform(); };
    const auto vec = [&](double scale) { return random.vec3(scale); };
    for (int i = 0; i < n; ++i) {
      // (every 29th row longer than a row of the packings: 9 entries)
      const int entries = i + 1 < n ? (i % 29 == 5 ? 9 : static_cast<int>(random() % 6)) : 0;
      for (int k = 0; k < entries; ++k) {
        const auto any_partner = static_cast<uint32_t>(i + 1 + random() % std::min(40, n - 1 - i));
        // (and particle 70 second in more entries than that, where n > 70)
        partner.push_back(i >= 60 && i < 70 && k == 0 && n > 70 ? 70u : any_partner);
        row_owner.push_back(static_cast<uint32_t>(i));
        const bool touching = random() % 3 != 0;
        result.push_back(touching ? Result{vec(0.1), vec(0.05), 2e-6 * (1.0 + u()), 0.1}
                                  : Result{});
      }
      row_start.push_back(static_cast<uint32_t>(partner.size()));
      const bool walled = random() % 5 == 0 && with_walls;
      for (int k = 0, walls = walled ? 1 + static_cast<int>(random() % 2) : 0; k < walls; ++k) {
        wall_force.push_back(vec(0.2));
        wall_owner.push_back(static_cast<uint32_t>(i));
        wall_torque.push_back(vec(1e-4));
      }
      wall_row_start.push_back(static_cast<uint32_t>(wall_force.size()));
      external_force.push_back(vec(0.01));
      radius.push_back(1e-3 * (1.0 + 0.01 * u()));
      inverse_mass.push_back(i % 23 == 4 ? 0.0 : 1.0 / (1.05e-5 * (1.0 + 0.02 * u())));
    }
    // the transpose, in entry order per particle
    col_start.assign(n + 1, 0);
    for (uint32_t j : partner) ++col_start[j + 1];
    for (int i = 0; i < n; ++i) col_start[i + 1] += col_start[i];
    col_pair.resize(partner.size());
    std::vector<uint32_t> next(col_start.begin(), col_start.end() - 1);
    for (uint32_t e = 0; e < partner.size(); ++e) col_pair[next[partner[e]]++] = e;
  }
  GatherInput input(bool external, std::vector<Vec3>& force, std::vector<Vec3>& torque,
                    bool flat = false) const {
    GatherInput in{row_start.data(),
                   col_start.data(),
                   col_pair.data(),
                   &result[0].force_on_first.x,
                   wall_row_start.data(),
                   components(wall_force),
                   components(wall_torque),
                   radius.data(),
                   inverse_mass.data(),
                   external ? components(external_force) : nullptr,
                   {gravity.x, gravity.y, gravity.z},
                   components(force),
                   components(torque)};
    if (flat) {
      in.row_owner = row_owner.data();
      in.partner = partner.data();
      in.wall_owner = wall_owner.data();
    }
    return in;
  }
};
static_assert(sizeof(Contacts::Result) == 8 * sizeof(double));

// The reference gather: per particle its weight, its row's forces, its column's opposite forces,
// each entry's torque as the particle's lever (r - overlap / 2) times the arm, its walls, its
// external force.
void reference_gather(const Contacts& c, bool external, long first, long end,
                      std::vector<Vec3>& force, std::vector<Vec3>& torque) {
  for (long i = first; i < end; ++i) {
    const double r = c.radius[i];
    Vec3 f = c.inverse_mass[i] > 0.0 ? (1.0 / c.inverse_mass[i]) * c.gravity : Vec3{};
    Vec3 t;
    for (uint32_t e = c.row_start[i]; e < c.row_start[i + 1]; ++e) {
      f += c.result[e].force_on_first;
      t += (r - 0.5 * c.result[e].overlap) * c.result[e].torque_arm;
    }
    for (uint32_t k = c.col_start[i]; k < c.col_start[i + 1]; ++k) {
      const Contacts::Result& x = c.result[c.col_pair[k]];
      f -= x.force_on_first;
      t += (r - 0.5 * x.overlap) * x.torque_arm;
    }
    for (uint32_t e = c.wall_row_start[i]; e < c.wall_row_start[i + 1]; ++e) {
      f += c.wall_force[e];
      t += c.wall_torque[e];
    }
    if (external) f += c.external_force[i];
    force[i] = f;
    torque[i] = t;
  }
}
std::vector<Isa> instruction_sets() {
  __builtin_cpu_init();
  return {{"sse2",
           {&simd_sse2::kick_and_drift, &simd_sse2::half_kick, &simd_sse2::gather, "sse2"},
           true},
          {"avx2",
           {&simd_avx2::kick_and_drift, &simd_avx2::half_kick, &simd_avx2::gather, "avx2"},
           __builtin_cpu_supports("avx2") != 0},
          {"avx512",
           {&simd_avx512::kick_and_drift, &simd_avx512::half_kick, &simd_avx512::gather, "avx512"},
           __builtin_cpu_supports("avx512f") != 0}};
}

// Ranges that start and end anywhere within a group of 8, are shorter than 8, or empty.
std::vector<std::pair<long, long>> ranges(long n) {
  return {{0, n}, {3, n - 5}, {1, 9}, {8, 16}, {5, 12}, {7, 7}, {40, 41}, {17, 40}, {n - 8, n}};
}

TEST(ParticlePasses, KickAndDriftGiveTheReferenceBitsOnEveryInstructionSet) {
  constexpr int n = 203;
  for (const Isa& isa : instruction_sets()) {
    if (!isa.supported) continue;
    for (const auto& [first, end] : ranges(n))
      for (int tests = 0; tests < 5; ++tests) {
        // no test; the list's; the list's and the bound; the list's and the build's; all
        const bool list_test = tests > 0, bound = tests == 2 || tests == 4,
                   rebuild_test = tests >= 3;
        SCOPED_TRACE(std::string(isa.name) + " particles " + std::to_string(first) + ".." +
                     std::to_string(end) + " tests " + std::to_string(tests));
        Pile expected(n, 7), got(n, 7);
        DriftTally want, have;
        reference_kick_and_drift(expected, first, end, list_test, rebuild_test, bound, want);
        isa.passes.kick_and_drift(got.input(list_test, rebuild_test), first, end, bound, have);
        EXPECT_TRUE(same_bits(got.velocity, expected.velocity));
        EXPECT_TRUE(same_bits(got.angular_velocity, expected.angular_velocity));
        EXPECT_TRUE(same_bits(got.position, expected.position));
        EXPECT_TRUE(same_bits(got.rotation, expected.rotation));
        EXPECT_EQ(have.stale, want.stale);
        EXPECT_EQ(have.moved, want.moved);
        EXPECT_TRUE(same_bits(have.displacement2, want.displacement2))
            << have.displacement2 << " against " << want.displacement2;
        EXPECT_TRUE(same_bits(have.scale2, want.scale2));
      }
  }
}

TEST(ParticlePasses, TheTestsFindWhatMovedFarInEveryRange) {
  // (that the comparison above is not between two tallies that never change)
  constexpr int n = 203;
  Pile pile(n, 7);
  DriftTally all, first_five;
  reference_kick_and_drift(pile, 0, n, true, true, true, all);
  EXPECT_EQ(all.stale, 1);
  EXPECT_EQ(all.moved, 1);  // particle 5, 42, ... moved 3e-4 m from the build
  EXPECT_GT(all.displacement2, 0.0);
  Pile again(n, 7);
  reference_kick_and_drift(again, 0, 5, true, true, true, first_five);
  EXPECT_EQ(first_five.moved, 0);
}

TEST(ParticlePasses, HalfKickGivesTheReferenceBitsAndSpeedsOnEveryInstructionSet) {
  constexpr int n = 203;
  for (const Isa& isa : instruction_sets()) {
    if (!isa.supported) continue;
    for (const auto& [first, end] : ranges(n))
      for (const bool next : {false, true}) {
        SCOPED_TRACE(std::string(isa.name) + " particles " + std::to_string(first) + ".." +
                     std::to_string(end) + (next ? " with" : " without") + " the next speed");
        Pile expected(n, 11), got(n, 11);
        double want_speed2 = 0.0, want_next2 = 0.5, have_speed2 = 0.0, have_next2 = 0.5;
        reference_half_kick(expected, first, end, want_speed2, next ? &want_next2 : nullptr);
        isa.passes.half_kick(got.input(false, false), first, end, have_speed2,
                             next ? &have_next2 : nullptr);
        EXPECT_TRUE(same_bits(got.velocity, expected.velocity));
        EXPECT_TRUE(same_bits(got.angular_velocity, expected.angular_velocity));
        EXPECT_TRUE(same_bits(have_speed2, want_speed2))
            << have_speed2 << " against " << want_speed2;
        EXPECT_TRUE(same_bits(have_next2, want_next2));
        // the NaN velocity of particle 19 counts as infinite wherever the range holds it
        if (first <= 19 && 19 < end) {
          EXPECT_EQ(have_speed2, INFINITY);
        }
      }
  }
}

// One by one and walked flat (GatherInput::row_owner), over ranges that span more than one of
// the flat walk's blocks (gather_flat_block) and start and end within them.
TEST(ParticlePasses, GatherGivesTheReferenceSumsOnEveryInstructionSetOneByOneOrFlat) {
  constexpr int n = 157;
  static_assert(n > gather_flat_block);
  const Contacts contacts(n, 5);
  for (const Isa& isa : instruction_sets()) {
    if (!isa.supported) continue;
    for (const auto& [first, end] : ranges(n))
      for (const bool external : {false, true})
        for (const bool flat : {false, true}) {
          SCOPED_TRACE(std::string(isa.name) + " particles " + std::to_string(first) + ".." +
                       std::to_string(end) + (external ? " with" : " without") +
                       " external forces" + (flat ? ", flat" : ", one by one"));
          // (what lies outside the range must stay as it was: start from a pattern)
          std::vector<Vec3> want_force(n, Vec3{1.0, 2.0, 3.0}), want_torque(n, Vec3{4.0, 5.0, 6.0});
          std::vector<Vec3> have_force = want_force, have_torque = want_torque;
          reference_gather(contacts, external, first, end, want_force, want_torque);
          isa.passes.gather(contacts.input(external, have_force, have_torque, flat), first, end);
          EXPECT_TRUE(same_bits(have_force, want_force));
          EXPECT_TRUE(same_bits(have_torque, want_torque));
        }
  }
  // Without wall entries the walk needs no wall owners (null), on every instruction set.
  const Contacts no_walls(n, 7, false);
  ASSERT_EQ(no_walls.wall_row_start.back(), 0u);
  for (const Isa& isa : instruction_sets()) {
    if (!isa.supported) continue;
    SCOPED_TRACE(std::string(isa.name) + ", no walls, flat");
    std::vector<Vec3> want_force(n), want_torque(n);
    std::vector<Vec3> have_force = want_force, have_torque = want_torque;
    reference_gather(no_walls, true, 0, n, want_force, want_torque);
    GatherInput in = no_walls.input(true, have_force, have_torque, true);
    in.wall_owner = nullptr;
    isa.passes.gather(in, 0, n);
    EXPECT_TRUE(same_bits(have_force, want_force));
    EXPECT_TRUE(same_bits(have_torque, want_torque));
  }
  // (rows and columns of many lengths, the longest past 8)
  long long_rows = 0, long_columns = 0;
  for (int i = 0; i < n; ++i) {
    long_rows += contacts.row_start[i + 1] - contacts.row_start[i] > 8;
    long_columns += contacts.col_start[i + 1] - contacts.col_start[i] > 8;
  }
  EXPECT_GT(long_rows, 2);
  EXPECT_GT(long_columns, 0);
  // (the sums are not trivial: some particle has entries on both sides and a wall)
  long both = 0;
  for (int i = 0; i < n; ++i)
    both += contacts.row_start[i + 1] > contacts.row_start[i] &&
            contacts.col_start[i + 1] > contacts.col_start[i] &&
            contacts.wall_row_start[i + 1] > contacts.wall_row_start[i];
  EXPECT_GT(both, 3);
}

}  // namespace
}  // namespace grainlab
