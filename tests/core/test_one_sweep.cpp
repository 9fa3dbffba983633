// A step as one sweep over the particles (core/one_sweep.cpp) against the same step in stages,
// its reference: the same packing run with every possible step as a sweep and with none must end
// in bit-identical states, on 1, 2 and 3 threads. The packing: 12 x 12 x 12 beads of two sizes
// with random velocities and spins, under gravity, in a box whose lid has mass and is pushed down
// by a force, compacted affinely for a while (Simulation::scale_positions, as the plane strain
// preparation does) and lifted by a skin halfway, so that the list is selected again and rebuilt
// during the run (the steps around those run in stages: a sweep next to a list update would throw
// std::logic_error), beads touch the walls, and contacts begin inside steps (handed to the scalar
// law).
#include <gtest/gtest.h>
#include <omp.h>

#include <cstring>
#include <random>
#include <vector>

#include "core/pair_kernel_simd.hpp"
#include "core/random_insertion.hpp"
#include "core/simulation.hpp"
#include "support/same_bits.hpp"
#include "support/scenes.hpp"

using namespace grainlab;
using namespace grainlab::test;

namespace {

struct SweepRun {
  ParticleStore particles;
  std::vector<Wall> walls;
  std::vector<Vec3> springs;
  std::vector<double> largest_overlap;  // per step
  long steps = 0, sweeps = 0, refreshes = 0, rebuilds = 0, handed_back = 0, touching = 0;
  long flat_gathers = 0;  // steps whose gather walked flat
  std::string kernel;
  StepPhaseTimes times;  // when the run was timed
};

Simulation make_packing() {
  std::mt19937_64 rng(41);
  auto jitter = [&](double half_width) { return half_width * (2.0 * uniform01(rng) - 1.0); };
  ParticleStore p;
  constexpr int side = 12;
  constexpr double spacing = 2.0e-3;
  for (int k = 0; k < side * side * side; ++k) {
    const Vec3 centre = cubic_lattice_site(k, side, spacing, [&] { return jitter(5e-6); });
    const double radius = (k * 7919) % 3 == 0 ? 0.995e-3 : 1.0e-3;
    p.add(static_cast<uint32_t>(k), 0, radius + jitter(5e-6), glass_density, centre,
          {jitter(0.2), jitter(0.2), jitter(0.2)}, {jitter(300.0), jitter(300.0), jitter(300.0)},
          false);
  }
  const double l = side * spacing;
  std::vector<Wall> walls = cube_walls(l);
  Wall& lid = walls.back();
  lid.mass = 0.01;                   // kg
  lid.external_force = {0, 0, -20};  // N: about 50 kPa on the top layer
  SimulationSettings settings = settings_for(0.98e-3, 0.6, 0.1, {0, 0, -9.81});
  // The steps and moves below are sized for an active list skin of a tenth of the skin (about
  // 20 um; the default is thinner since docs/performance.md sec. 30)
  settings.list_skin_fraction = 0.1;
  return Simulation(std::move(p), walls, two_material_table(0.6, 0.3), settings);
}

SweepRun run(Simulation::OneSweep choice, int threads, long steps, bool timed = false,
             Simulation::GatherWalk walk = Simulation::GatherWalk::automatic) {
  omp_set_num_threads(threads);
  Simulation sim = make_packing();
  sim.set_one_sweep(choice);
  sim.set_gather_walk(walk);
  sim.time_step_phases(timed);
  SweepRun r;
  r.kernel = sim.pair_kernel_name();
  const long refreshes = sim.list_refresh_count(), rebuilds = sim.rebuild_count();
  for (long s = 0; s < steps; ++s) {
    // for 40 steps, an affine compaction of 5e-5 per step (moves of up to 1 um a step, more
    // than the beads' own, widen the sweep's bound); halfway, the lid lifted by a skin: the
    // walls force a rebuild
    if (s >= steps / 4 && s < steps / 4 + 40)
      sim.scale_positions({12e-3, 12e-3, 12e-3}, 1.0 - 5e-5);
    if (s == steps / 2) {
      const Wall& lid = sim.walls().back();
      sim.set_wall_point(sim.walls().size() - 1, lid.point - sim.settings().skin * lid.normal);
    }
    sim.step();
    r.touching += sim.touching_pair_count();
    r.handed_back += sim.pairs_handed_to_scalar_law() + sim.walls_handed_to_scalar_law();
    r.largest_overlap.push_back(sim.max_overlap_fraction());
  }
  r.steps = steps;
  r.sweeps = sim.one_sweep_steps();
  r.flat_gathers = sim.flat_gather_steps();
  r.refreshes = sim.list_refresh_count() - refreshes;
  r.rebuilds = sim.rebuild_count() - rebuilds;
  r.particles = sim.particles();
  r.walls = sim.walls();
  r.springs.assign(sim.pair_contacts().sliding_spring.begin(),
                   sim.pair_contacts().sliding_spring.end());
  r.times = sim.step_phase_times();
  omp_set_num_threads(omp_get_num_procs());
  return r;
}

void expect_identical(const SweepRun& a, const SweepRun& b) {
  expect_same_particle_bits(a.particles, b.particles);
  ASSERT_EQ(a.springs.size(), b.springs.size());
  EXPECT_EQ(0, std::memcmp(a.springs.data(), b.springs.data(), a.springs.size() * sizeof(Vec3)));
  EXPECT_EQ(a.largest_overlap, b.largest_overlap);
  ASSERT_EQ(a.walls.size(), b.walls.size());
  for (size_t k = 0; k < a.walls.size(); ++k) {
    EXPECT_EQ(0, std::memcmp(&a.walls[k].point, &b.walls[k].point, sizeof(Vec3))) << "wall " << k;
    EXPECT_EQ(0, std::memcmp(&a.walls[k].force, &b.walls[k].force, sizeof(Vec3))) << "wall " << k;
  }
  EXPECT_EQ(a.handed_back, b.handed_back);
}

constexpr long steps = 3000;

}  // namespace

TEST(OneSweep, GivesTheBitsOfTheStagesOnOneTwoAndThreeThreads) {
  const SweepRun stages = run(Simulation::OneSweep::never, 1, steps);
  if (stages.kernel == std::string("scalar")) GTEST_SKIP() << "the sweep needs the pair kernel";
  EXPECT_EQ(stages.sweeps, 0);
  // the run selects the list again and rebuilds it, touches the walls and hands contacts back
  EXPECT_GE(stages.refreshes, 3);
  EXPECT_GE(stages.rebuilds, 1);
  EXPECT_GT(stages.touching, 200L * steps);
  EXPECT_GT(stages.handed_back, 0);
  for (int threads : {1, 2, 3}) {
    SCOPED_TRACE(testing::Message() << threads << " threads");
    const SweepRun swept = run(Simulation::OneSweep::always, threads, steps);
    // all but the steps next to a list update, and the first (no bound yet)
    EXPECT_GT(swept.sweeps, steps * 8 / 10);
    EXPECT_LT(swept.sweeps, steps);
    EXPECT_EQ(swept.refreshes, stages.refreshes);
    EXPECT_EQ(swept.rebuilds, stages.rebuilds);
    expect_identical(stages, swept);
  }
}

// The gather's flat walk (core/particle_passes_simd.hpp, GatherInput::row_owner) against the
// particles one by one: the same bits in stages and in sweeps, on 1 and 2 threads (1,728 beads,
// more than a block of the walk, with walls, a lid with an external force and selections of the
// list; on a machine without AVX-512 both take the particles one by one).
TEST(GatherWalk, FlatGivesTheBitsOfOneByOneInStagesAndSweepsOnOneAndTwoThreads) {
  using Walk = Simulation::GatherWalk;
  const SweepRun one_by_one = run(Simulation::OneSweep::never, 1, steps, false, Walk::one_by_one);
  if (one_by_one.kernel == std::string("scalar")) GTEST_SKIP() << "the owners are the kernel's";
  for (const auto sweep : {Simulation::OneSweep::never, Simulation::OneSweep::always})
    for (int threads : {1, 2}) {
      SCOPED_TRACE(testing::Message() << threads << " threads"
                                      << (sweep == Simulation::OneSweep::always ? ", swept" : ""));
      expect_identical(one_by_one, run(sweep, threads, steps, false, Walk::flat));
    }
}

// Automatic times the steps with each walk and keeps the faster (core/gather_walk_trial.hpp;
// its choice from given times: test_gather_walk_trial.cpp): a run that walks both, in stages and
// in sweeps, gives the bits of one by one. (On one thread, whose team cannot change and start
// the trial again; the kernel's AVX2 or AVX-512 passes, which have both walks.)
TEST(GatherWalk, AutomaticWalksBothAndGivesTheBitsOfOneByOne) {
  using Walk = Simulation::GatherWalk;
  const SweepRun one_by_one = run(Simulation::OneSweep::never, 1, steps, false, Walk::one_by_one);
  if (one_by_one.kernel == std::string("scalar") || one_by_one.kernel == std::string("sse2"))
    GTEST_SKIP() << "one walk only";
  EXPECT_EQ(one_by_one.flat_gathers, 0);
  for (const auto sweep : {Simulation::OneSweep::never, Simulation::OneSweep::always}) {
    SCOPED_TRACE(sweep == Simulation::OneSweep::always ? "swept" : "stages");
    const SweepRun automatic = run(sweep, 1, steps, false, Walk::automatic);
    expect_identical(one_by_one, automatic);
    // 1,728 beads: one by one by the rule, flat in half the trial's steps, then the faster
    using Trial = GatherWalkTrial;
    EXPECT_GE(automatic.flat_gathers, Trial::trial_steps / 2);
    EXPECT_LE(automatic.flat_gathers, steps - Trial::warm_up_steps - Trial::trial_steps / 2);
  }
}

// Automatic, before its first trial ends: flat where each thread of the team has
// flat_gather_share particles or more.
TEST(GatherWalk, AutomaticIsFlatFromTenThousandParticlesAThread) {
  EXPECT_EQ(Simulation::flat_gather_share, 10000);
  EXPECT_TRUE(Simulation::walks_gather_flat_automatically(11636, 1));   // dense-11k, 1 thread
  EXPECT_FALSE(Simulation::walks_gather_flat_automatically(11636, 2));  // 5,818 a thread
  EXPECT_TRUE(Simulation::walks_gather_flat_automatically(88400, 2));   // the plane strain test
  EXPECT_FALSE(Simulation::walks_gather_flat_automatically(88400, 16));
  EXPECT_TRUE(Simulation::walks_gather_flat_automatically(160000, 16));
  EXPECT_FALSE(Simulation::walks_gather_flat_automatically(1728, 1));
}

TEST(OneSweep, AutomaticWhereTheDriftsLeadFitsTheL3OnTwoThreadsWherePartnersLieBeyondTheL2) {
  // at about 1.5 KiB a bead: the farthest partner's distance in the particle order within half
  // the L3; the mean reach beyond the L2 for 2 threads, within it for 1 (docs/performance.md
  // sec. 45 for the tiles of dense-11k)
  EXPECT_EQ(one_sweep_team(600.0, 1200, 1L << 20, 32L << 20), 1);    // the reach inside the L2
  EXPECT_EQ(one_sweep_team(1475.0, 2952, 1L << 20, 32L << 20), 2);   // dense-88k on the VM
  EXPECT_EQ(one_sweep_team(3994.2, 7933, 1L << 20, 32L << 20), 2);   // 744,704 beads, 4x4x4
  EXPECT_EQ(one_sweep_team(8856.3, 17853, 1L << 20, 32L << 20), 0);  // 838k beads, 6x6x2
  EXPECT_EQ(one_sweep_team(8856.3, 17853, 1L << 20, 64L << 20), 2);  // a larger L3
  EXPECT_EQ(one_sweep_team(1475.0, 2952, 4L << 20, 32L << 20), 1);   // a larger L2
  EXPECT_EQ(one_sweep_team(600.0, 1200, 1L << 20, 3L << 20), 0);     // a small L3
  EXPECT_GT(l3_cache_bytes(), 0);
  // 1,728 beads: a row's farthest partner lies about 125 beads ahead on average, some 190 KB,
  // inside an L2 of 256 KB or more, and 284 at most (about 440 KB), inside half an L3 of 4 MB or
  // more. Automatic sweeps the steps the sweep can take on 1 thread, and none on 2.
  if (l2_cache_bytes() < (256L << 10) || l3_cache_bytes() < (4L << 20))
    GTEST_SKIP() << "an L2 under 256 KB or an L3 under 4 MB";
  const SweepRun always = run(Simulation::OneSweep::always, 1, 200);
  if (always.kernel == std::string("scalar")) GTEST_SKIP() << "the sweep needs the pair kernel";
  EXPECT_GT(always.sweeps, 0);
  EXPECT_EQ(run(Simulation::OneSweep::automatic, 1, 200).sweeps, always.sweeps);
  EXPECT_EQ(run(Simulation::OneSweep::automatic, 2, 200).sweeps, 0);
}

TEST(OneSweep, ACommandBetweenStepsForgetsTheBound) {
  omp_set_num_threads(2);
  Simulation sim = make_packing();
  if (sim.pair_kernel_name() == std::string("scalar")) GTEST_SKIP() << "needs the pair kernel";
  sim.set_one_sweep(Simulation::OneSweep::always);
  sim.advance(20);
  const long before = sim.one_sweep_steps();
  EXPECT_GE(before, 15);
  // the same velocity again: nothing moves differently, but the bound is no longer known
  sim.set_particle_velocity(7, sim.particles().velocity[7]);
  sim.step();
  EXPECT_EQ(sim.one_sweep_steps(), before) << "the step after a velocity command runs in stages";
  sim.step();
  EXPECT_EQ(sim.one_sweep_steps(), before + 1) << "and the next one as a sweep again";
  // A homogeneous strain of the positions (the affine compaction) widens the bound by the
  // largest move: a small one (under 1e-9 m) keeps the sweep, one of 0.1 % (up to 21 um, more
  // than half the list skin, 10 um) makes the next step run in stages, and it selects the list
  // again.
  const Vec3 centre{12e-3, 12e-3, 12e-3};
  sim.scale_positions(centre, 1.0 - 1e-8);
  sim.step();
  EXPECT_EQ(sim.one_sweep_steps(), before + 2) << "a small move keeps the sweep";
  const long refreshes = sim.list_refresh_count();
  sim.scale_positions(centre, 0.999);
  sim.step();
  EXPECT_EQ(sim.one_sweep_steps(), before + 2) << "a move beyond the bound: in stages";
  EXPECT_GT(sim.list_refresh_count(), refreshes);
  sim.set_one_sweep(Simulation::OneSweep::never);
  sim.advance(3);
  EXPECT_EQ(sim.one_sweep_steps(), before + 2);
  omp_set_num_threads(omp_get_num_procs());
}

// The step phase timers (core/step_phase_times.hpp, grainlab_bench --phase-times) leave the
// results as they are, and account for every step: each thread's parts of a region add up to the
// region's time, and the parts' means to the steps' wall time. Reference: the same run untimed.
TEST(StepPhaseTimes, LeaveTheBitsAndAccountForTheSteps) {
  for (Simulation::OneSweep choice : {Simulation::OneSweep::always, Simulation::OneSweep::never}) {
    const bool sweeps = choice == Simulation::OneSweep::always;
    SCOPED_TRACE(sweeps ? "every possible step as one sweep" : "in stages");
    const SweepRun untimed = run(choice, 2, 600);
    const SweepRun timed = run(choice, 2, 600, true);
    expect_identical(untimed, timed);
    ASSERT_GT(timed.refreshes + timed.rebuilds, 0);
    const StepPhaseTimes& t = timed.times;
    EXPECT_EQ(t.steps(), 600);
    EXPECT_EQ(t.threads(), 2);
    EXPECT_EQ(untimed.times.steps(), 0);
    double sum = 0.0;
    for (int k = 0; k < StepPhaseTimes::part_count; ++k) {
      const auto part = static_cast<StepPhaseTimes::Part>(k);
      EXPECT_GE(t.largest(part), t.mean(part)) << StepPhaseTimes::names[k];
      sum += t.mean(part);
    }
    EXPECT_GT(t.step_seconds(), 0.0);
    EXPECT_NEAR(sum, t.step_seconds(), 1e-9 * t.step_seconds());
    // the stages that ran were timed: the sweeps' where steps were swept, the others' (the steps
    // next to a list update run in stages either way) and the list updates
    for (auto part : {StepPhaseTimes::drift, StepPhaseTimes::contacts, StepPhaseTimes::gather,
                      StepPhaseTimes::list_update, StepPhaseTimes::start})
      EXPECT_GT(t.mean(part), 0.0) << StepPhaseTimes::names[part];
    EXPECT_EQ(t.mean(StepPhaseTimes::sweep_block) > 0.0, sweeps);
    EXPECT_EQ(timed.sweeps > 0, sweeps);
  }
}
