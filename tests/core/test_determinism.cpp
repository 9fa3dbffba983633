// Results must not depend on the number of threads: forces are gathered per particle in a fixed
// order, so 1 and 2 threads give bit-identical states (Box2D-style determinism check).
#include <gtest/gtest.h>
#include <omp.h>

#include <cstring>
#include <optional>
#include <random>
#include <set>

#include "core/random_insertion.hpp"
#include "core/team_limit.hpp"
#include "support/scenes.hpp"

using namespace grainlab;
using namespace grainlab::test;

namespace {
// Beads with random velocities in a 20 x 20 x 30 mm box of plane walls (open at the top unless
// `closed`), gravity, friction and rolling resistance (arf; 0: none, so that the vectorised pair
// kernel runs where the CPU has it). list_skin_fraction: the active pair list's skin; gravity in
// m/s^2, downwards.
Simulation random_box(long count, uint64_t seed, bool closed, double arf = 0.05,
                      double list_skin_fraction = default_list_skin_fraction,
                      double gravity = 9.81) {
  std::vector<Sphere> spheres;
  std::mt19937_64 rng(seed);
  InsertionRegion box;
  box.box_min = {0, 0, 0};
  box.box_max = {0.02, 0.02, 0.03};
  insert_random_spheres(spheres, box, count, 1.8e-3, 2.2e-3, rng);
  ParticleStore p;
  for (size_t i = 0; i < spheres.size(); ++i)
    p.add(static_cast<uint32_t>(i), 0, spheres[i].radius, glass_density, spheres[i].centre,
          {uniform01(rng) - 0.5, uniform01(rng) - 0.5, uniform01(rng) - 0.5}, {}, false);
  std::vector<Wall> walls{plane_wall({0, 0, 0}, {0, 0, 1}), plane_wall({0, 0, 0}, {1, 0, 0}),
                          plane_wall({0.02, 0, 0}, {-1, 0, 0}), plane_wall({0, 0, 0}, {0, 1, 0}),
                          plane_wall({0, 0.02, 0}, {0, -1, 0})};
  if (closed) walls.push_back(plane_wall({0, 0, 0.03}, {0, 0, -1}));
  SimulationSettings settings = settings_for(0.9e-3, 0.5, 0.1, {0, 0, -gravity});
  settings.list_skin_fraction = list_skin_fraction;
  return Simulation(std::move(p), walls, two_material_table(0.5, 0.3, arf), settings);
}

// Positions, velocities and spins bit for bit equal.
void expect_same_bits(const ParticleStore& x, const ParticleStore& y) {
  ASSERT_EQ(x.size(), y.size());
  EXPECT_EQ(x.id, y.id);
  EXPECT_EQ(0, std::memcmp(x.position.data(), y.position.data(), x.size() * sizeof(Vec3)));
  EXPECT_EQ(0, std::memcmp(x.velocity.data(), y.velocity.data(), x.size() * sizeof(Vec3)));
  EXPECT_EQ(0, std::memcmp(x.angular_velocity.data(), y.angular_velocity.data(),
                           x.size() * sizeof(Vec3)));
}

// `change_team_every` > 0: the steps' team goes 1, 2, 3, 1, ... every that many steps
// (step_team_limit, core/team_limit.hpp), as when a run follows the free CPUs.
ParticleStore run_pile(int threads, int change_team_every = 0) {
  omp_set_num_threads(threads);
  Simulation sim = random_box(1000, 11, true);  // above parallel_threshold
  long contacts = 0;
  std::set<int> teams;
  for (int s = 0; s < 20000; ++s) {
    if (change_team_every > 0 && s % change_team_every == 0)
      step_team_limit = 1 + (s / change_team_every) % 3;
    sim.step();
    teams.insert(omp_get_max_threads());
    contacts += sim.touching_pair_count();
  }
  step_team_limit = 0;
  EXPECT_GT(contacts, 3000) << "the run must exercise many contacts";
  EXPECT_GT(sim.rebuild_count(), 2);
  EXPECT_EQ(teams.size(), change_team_every > 0 ? 3u : 1u) << "the teams the steps ran with";
  return sim.particles();
}
}  // namespace

TEST(Determinism, OneAndTwoThreadsGiveBitIdenticalStates) {
  const ParticleStore a = run_pile(1);
  const ParticleStore b = run_pile(2);
  omp_set_num_threads(omp_get_num_procs());
  expect_same_bits(a, b);
}

// A run without --threads changes its team between steps as other processes take and leave CPUs
// (io/team_follower.hpp): with teams of 1, 2 and 3 threads in turn, every 97 steps (rebuilds and
// refreshes fall on steps of each team), it ends in the bits of one thread.
TEST(Determinism, ATeamThatChangesBetweenStepsGivesTheBitsOfOneThread) {
  const ParticleStore a = run_pile(1);
  const ParticleStore b = run_pile(1, 97);
  omp_set_num_threads(omp_get_num_procs());
  expect_same_bits(a, b);
}

// The drift's particles through a chunk queue (Simulation::set_drift_sharing; automatic on 4
// threads or more), and the chunks of every stage shared as on many threads, the owner's last one
// given up too (Simulation::set_chunk_sharing; automatic on 8 threads or more): on 2 and 3
// threads, whose stages hand chunks to one another, the run ends in the bits of one thread that
// drifts its particles in order; with rolling resistance (the scalar law) and without (the
// vectorised kernel, whose velocity records the drift writes). At 1,000 beads a chunk is 64 beads
// whatever the chunks per thread; 2 per thread makes them longer. And the automatic choices on 4
// and 8 threads (more threads than this machine may have: their turns still interleave), over a
// shorter run. Reference: the same run on one thread, drift not shared. Every step in stages (the
// sweep, core/one_sweep.cpp, may be automatic on 2 threads and has its own queues).
TEST(Determinism, SharedChunksGiveTheBitsOfOneThread) {
  for (double arf : {0.05, 0.0}) {
    SCOPED_TRACE(testing::Message() << "rolling resistance " << arf);
    const auto run = [&](int threads, int steps, Simulation::DriftSharing sharing,
                         std::optional<Simulation::ChunkSharing> chunks) {
      omp_set_num_threads(threads);
      Simulation sim = random_box(1000, 13, true, arf);
      sim.set_one_sweep(Simulation::OneSweep::never);
      sim.set_drift_sharing(sharing);
      sim.set_chunk_sharing(chunks);
      for (int s = 0; s < steps; ++s) sim.step();
      if (steps > 1000) {
        EXPECT_GT(sim.rebuild_count(), 1);
      }
      const bool shared = sharing == Simulation::DriftSharing::always ||
                          (sharing == Simulation::DriftSharing::automatic &&
                           threads >= Simulation::shared_drift_team);
      EXPECT_EQ(sim.shared_drift_steps(), shared ? steps : 0);
      return sim.particles();
    };
    using Sharing = Simulation::ChunkSharing;
    constexpr auto always = Simulation::DriftSharing::always;
    const ParticleStore one = run(1, 6000, Simulation::DriftSharing::never, std::nullopt);
    for (int threads : {2, 3}) {
      SCOPED_TRACE(testing::Message() << threads << " threads");
      expect_same_bits(one, run(threads, 6000, always, std::nullopt));
      expect_same_bits(one, run(threads, 6000, always, Sharing{16, false}));
      expect_same_bits(one, run(threads, 6000, always, Sharing{2, false}));
    }
    const ParticleStore short_one = run(1, 300, Simulation::DriftSharing::never, std::nullopt);
    for (int threads : {4, 8}) {
      SCOPED_TRACE(testing::Message() << threads << " threads, automatic");
      expect_same_bits(short_one,
                       run(threads, 300, Simulation::DriftSharing::automatic, std::nullopt));
    }
  }
  omp_set_num_threads(omp_get_num_procs());
}

// The automatic chunk sharing: as measured on 2 threads below 8 threads, finer chunks that the
// owner need not keep from 8 (docs/performance.md sec. 34).
TEST(ChunkSharing, FollowsTheTeam) {
  Simulation sim = random_box(600, 3, true);
  for (int team : {1, 2, 7}) {
    EXPECT_EQ(sim.chunk_sharing(team).chunks_per_thread, 8) << team;
    EXPECT_TRUE(sim.chunk_sharing(team).owner_keeps_last) << team;
  }
  for (int team : {8, 16, 64}) {
    EXPECT_EQ(sim.chunk_sharing(team).chunks_per_thread, 16) << team;
    EXPECT_FALSE(sim.chunk_sharing(team).owner_keeps_last) << team;
  }
  sim.set_chunk_sharing(Simulation::ChunkSharing{4, true});
  EXPECT_EQ(sim.chunk_sharing(16).chunks_per_thread, 4);
  EXPECT_TRUE(sim.chunk_sharing(16).owner_keeps_last);
  sim.set_chunk_sharing(std::nullopt);
  EXPECT_EQ(sim.chunk_sharing(16).chunks_per_thread, 16);
}

TEST(Determinism, RestoredStateContinuesBitIdentically) {
  // A checkpoint taken mid-run and restored must continue exactly as the uninterrupted run.
  Simulation a = random_box(700, 5, false);
  const PairTable table = a.pair_table();
  a.advance(3000);
  StateWriter saved;
  a.save_state(saved);
  StateReader reader(saved.bytes());
  Simulation b(reader, table);
  EXPECT_TRUE(reader.at_end());
  a.advance(5000);
  b.advance(5000);
  EXPECT_GT(a.rebuild_count(), 3);
  EXPECT_EQ(a.rebuild_count(), b.rebuild_count());
  EXPECT_GT(a.list_refresh_count(), a.rebuild_count());
  EXPECT_EQ(a.list_refresh_count(), b.list_refresh_count());
  EXPECT_EQ(a.time(), b.time());
  const ParticleStore &x = a.particles(), &y = b.particles();
  EXPECT_EQ(0, std::memcmp(x.position.data(), y.position.data(), x.size() * sizeof(Vec3)));
  EXPECT_EQ(0, std::memcmp(x.angular_velocity.data(), y.angular_velocity.data(),
                           x.size() * sizeof(Vec3)));
}

namespace {
// The saved state of one bead above a floor, and the table it was made with.
const PairTable one_bead_table = two_material_table(0.5, 0.3);
std::string one_bead_state() {
  ParticleStore p;
  p.add(0, 0, 1e-3, glass_density, {0, 0, 0.01}, {}, {}, false);
  Simulation a(std::move(p), {plane_wall({}, {0, 0, 1})}, one_bead_table,
               settings_for(1e-3, 0.5, 0.1));
  StateWriter saved;
  a.save_state(saved);
  return saved.bytes();
}
}  // namespace

TEST(Determinism, TruncatedStateIsRefused) {
  const std::string bytes = one_bead_state();
  StateReader cut(bytes.substr(0, bytes.size() / 2));
  EXPECT_THROW(Simulation(cut, one_bead_table), std::runtime_error);
}

TEST(Determinism, StateOfAnotherFormatIsRefusedByVersion) {
  // The first 8 bytes are the format's magic, "grnlab0" and a version digit: a state written by
  // another version (format 4 kept no candidate list, format 3 stored two torques per entry,
  // format 2 also k_n and c_n) is refused
  // with both versions named.
  std::string bytes = one_bead_state();
  bytes[0] = '3';  // little-endian: the version is the lowest byte
  StateReader old(bytes);
  try {
    Simulation b(old, one_bead_table);
    ADD_FAILURE() << "a state of format 3 was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("format 3"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("format 5"), std::string::npos) << e.what();
  }
  bytes[7] = 'x';  // not a grainlab state at all
  StateReader foreign(bytes);
  EXPECT_THROW(Simulation(foreign, one_bead_table), std::runtime_error);
}

namespace {
// The pile of OneAndTwoThreadsGiveBitIdenticalStates, 1 thread, with the given active-list skin.
Simulation pile_with_list_skin(double arf, double list_skin_fraction, long steps) {
  omp_set_num_threads(1);
  Simulation sim = random_box(1000, 11, true, arf, list_skin_fraction);
  sim.advance(steps);
  omp_set_num_threads(omp_get_num_procs());
  return sim;
}

}  // namespace

// The active pair list (core/neighbor_search.hpp) leaves out candidates beyond a thinner skin and
// selects again when a bead has moved half of it. The forces of the entries left out are zero
// and the order of the others is kept, so the run must be bit for bit the run over every
// candidate (fraction 1), for the scalar law (rolling resistance) and for the pair kernel alike;
// a contact the refreshes missed would change the bits.
TEST(Determinism, ActivePairListGivesTheBitsOfTheFullList) {
  for (const double arf : {0.05, 0.0}) {
    const long steps = 20000;
    const Simulation full = pile_with_list_skin(arf, 1.0, steps);
    const Simulation thin = pile_with_list_skin(arf, default_list_skin_fraction, steps);
    SCOPED_TRACE(arf > 0.0 ? "scalar law (rolling resistance)" : full.pair_kernel_name());
    EXPECT_EQ(full.rebuild_count(), thin.rebuild_count()) << "the skin alone decides rebuilds";
    EXPECT_EQ(full.list_refresh_count(), full.rebuild_count()) << "fraction 1: one per rebuild";
    EXPECT_GT(thin.list_refresh_count(), 3 * thin.rebuild_count())
        << "the run must exercise refreshes between rebuilds";
    EXPECT_LT(thin.pair_contacts().size(), full.pair_contacts().size());
    expect_same_bits(full.particles(), thin.particles());
  }
}

namespace {
// 8 x 8 x 10 beads of radius 0.94-0.96 mm on a 1.90 mm lattice, shifted by up to 0.01 mm, in a
// closed box of plane walls that fits the lattice: about half of the neighbours start
// overlapping (by up to about 4 % of a radius), and the beads push each other about and stay in
// contact.
Simulation confined_lattice(uint64_t seed) {
  std::mt19937_64 rng(seed);
  const double spacing = 1.90e-3;
  const int nx = 8, ny = 8, nz = 10;
  ParticleStore p;
  uint32_t id = 0;
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x) {
        const Vec3 jitter{uniform01(rng) - 0.5, uniform01(rng) - 0.5, uniform01(rng) - 0.5};
        const Vec3 centre =
            Vec3{(x + 0.5) * spacing, (y + 0.5) * spacing, (z + 0.5) * spacing} + 0.02e-3 * jitter;
        p.add(id++, 0, 0.94e-3 + 0.02e-3 * uniform01(rng), glass_density, centre, {}, {}, false);
      }
  const Vec3 top{nx * spacing, ny * spacing, nz * spacing};
  std::vector<Wall> walls{plane_wall({0, 0, 0}, {0, 0, 1}), plane_wall(top, {0, 0, -1}),
                          plane_wall({0, 0, 0}, {1, 0, 0}), plane_wall(top, {-1, 0, 0}),
                          plane_wall({0, 0, 0}, {0, 1, 0}), plane_wall(top, {0, -1, 0})};
  return Simulation(std::move(p), walls, two_material_table(0.5, 0.3),
                    settings_for(0.94e-3, 0.5, 0.1, {0, 0, -9.81}));
}
}  // namespace

// Every pair of beads that overlaps, found by brute force, is in the active list at every step
// checked, while the beads of a tight lattice push each other about (refreshes between the
// checks; ActivePairListGivesTheBitsOfTheFullList covers rebuilds).
TEST(Determinism, ActivePairListHoldsEveryTouchingPair) {
  omp_set_num_threads(1);
  Simulation sim = confined_lattice(7);
  long touching_checked = 0;
  for (int check = 0; check < 200; ++check) {
    sim.advance(100);
    const ParticleStore& p = sim.particles();
    const PairContacts& c = sim.pair_contacts();
    std::set<std::pair<uint32_t, uint32_t>> listed;
    for (size_t i = 0; i < p.size(); ++i)
      for (uint32_t e = c.row_start[i]; e < c.row_start[i + 1]; ++e)
        listed.insert({static_cast<uint32_t>(i), c.partner[e]});
    for (size_t i = 0; i < p.size(); ++i)
      for (size_t j = i + 1; j < p.size(); ++j) {
        const double reach = p.radius[i] + p.radius[j];
        if (norm2(p.position[j] - p.position[i]) >= reach * reach) continue;
        ++touching_checked;
        ASSERT_TRUE(listed.count({static_cast<uint32_t>(i), static_cast<uint32_t>(j)}))
            << "beads " << p.id[i] << " and " << p.id[j] << " overlap at step " << sim.step_count()
            << " but are not in the active list";
      }
  }
  omp_set_num_threads(omp_get_num_procs());
  EXPECT_GT(touching_checked, 50000) << "the run must check many contacts";
  EXPECT_GT(sim.list_refresh_count(), 10) << "the run must refresh the active list";
}
