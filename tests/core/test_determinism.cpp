// Results must not depend on the number of threads: forces are gathered per particle in a fixed
// order, so 1 and 2 threads give bit-identical states (Box2D-style determinism check).
#include <gtest/gtest.h>
#include <omp.h>

#include <cstring>
#include <random>

#include "core/random_insertion.hpp"
#include "support/scenes.hpp"

using namespace grainlab;
using namespace grainlab::test;

namespace {
// Beads with random velocities in a 20 x 20 x 30 mm box of plane walls (open at the top unless
// `closed`), gravity, friction and rolling resistance.
Simulation random_box(long count, uint64_t seed, bool closed) {
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
  return Simulation(std::move(p), walls, two_material_table(0.5, 0.3, 0.05),
                    settings_for(0.9e-3, 0.5, 0.1, {0, 0, -9.81}));
}

ParticleStore run_pile(int threads) {
  omp_set_num_threads(threads);
  Simulation sim = random_box(1000, 11, true);  // above parallel_threshold
  long contacts = 0;
  for (int s = 0; s < 20000; ++s) {
    sim.step();
    contacts += sim.touching_pair_count();
  }
  EXPECT_GT(contacts, 3000) << "the run must exercise many contacts";
  EXPECT_GT(sim.rebuild_count(), 2);
  return sim.particles();
}
}  // namespace

TEST(Determinism, OneAndTwoThreadsGiveBitIdenticalStates) {
  const ParticleStore a = run_pile(1);
  const ParticleStore b = run_pile(2);
  omp_set_num_threads(omp_get_num_procs());
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(a.id, b.id);
  EXPECT_EQ(0, std::memcmp(a.position.data(), b.position.data(), a.size() * sizeof(Vec3)));
  EXPECT_EQ(0, std::memcmp(a.velocity.data(), b.velocity.data(), a.size() * sizeof(Vec3)));
  EXPECT_EQ(0, std::memcmp(a.angular_velocity.data(), b.angular_velocity.data(),
                           a.size() * sizeof(Vec3)));
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
  // another version (format 3 stored two torques per entry, format 2 also k_n and c_n) is refused
  // with both versions named.
  std::string bytes = one_bead_state();
  bytes[0] = '3';  // little-endian: the version is the lowest byte
  StateReader old(bytes);
  try {
    Simulation b(old, one_bead_table);
    ADD_FAILURE() << "a state of format 3 was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("format 3"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("format 4"), std::string::npos) << e.what();
  }
  bytes[7] = 'x';  // not a grainlab state at all
  StateReader foreign(bytes);
  EXPECT_THROW(Simulation(foreign, one_bead_table), std::runtime_error);
}
