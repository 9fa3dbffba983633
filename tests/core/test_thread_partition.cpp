// The blocks the threads of a step start from (core/thread_partition.hpp): equal until the
// threads' speeds are measured; then each block in proportion to its thread's speed where the
// speeds differ by more than the equal band, and equal again where they do not; blocks change
// only at the end of a window of steps; every plan covers [0, n) once, in order; a chunk queue
// planned on the partition takes its blocks. The speeds are given to record() directly, so the
// expected blocks follow from the shares by hand.
#include <gtest/gtest.h>
#include <omp.h>

#include <vector>

#include "core/chunk_queue.hpp"
#include "core/thread_partition.hpp"

using namespace grainlab;

namespace {

// One step in which thread t worked on `count` indices of its own block at speeds[t] per second.
void record_step(ThreadPartition& p, const std::vector<double>& speeds, long count = 1000) {
  for (size_t t = 0; t < speeds.size(); ++t)
    p.record(static_cast<int>(t), count, count / speeds[t]);
  p.update();
}

// Runs `steps` steps with the given speeds, planning each as Simulation::step does.
void run_steps(ThreadPartition& p, long n, const std::vector<double>& speeds, int steps) {
  for (int k = 0; k < steps; ++k) {
    p.plan(n, static_cast<int>(speeds.size()));
    record_step(p, speeds);
  }
  p.plan(n, static_cast<int>(speeds.size()));
}

long length(IndexBlock b) {
  return b.end - b.first;
}

void expect_covers(const ThreadPartition& p, long n) {
  long next = 0;
  for (int t = 0; t < p.team(); ++t) {
    EXPECT_EQ(p.block(t).first, next) << "block " << t;
    EXPECT_LE(p.block(t).first, p.block(t).end) << "block " << t;
    next = p.block(t).end;
  }
  EXPECT_EQ(next, n);
}

}  // namespace

TEST(ThreadPartition, EqualBlocksUntilMeasured) {
  ThreadPartition p;
  p.plan(11636, 2);
  EXPECT_EQ(length(p.block(0)), 5818);
  EXPECT_EQ(length(p.block(1)), 5818);
  p.plan(1001, 4);
  expect_covers(p, 1001);
  for (int t = 0; t < 4; ++t) EXPECT_NEAR(length(p.block(t)), 250.25, 1.0);
}

TEST(ThreadPartition, BlocksFollowTheSpeedsWhereTheyDiffer) {
  ThreadPartition p;
  // thread 1 at 2/3 of thread 0's speed (a core shared a third of the time): after enough
  // windows its block is 2/5 of the particles
  run_steps(p, 10000, {3e6, 2e6}, 32 * 40);
  expect_covers(p, 10000);
  // (within the dead band of 0.005 of a share the blocks stay as they are)
  EXPECT_NEAR(length(p.block(0)), 6000, 50);
  EXPECT_NEAR(length(p.block(1)), 4000, 50);
  // the speeds even out again: equal blocks
  run_steps(p, 10000, {3e6, 3e6}, 32 * 40);
  EXPECT_EQ(length(p.block(0)), 5000);
}

TEST(ThreadPartition, SpeedsWithinTheEqualBandKeepEqualBlocks) {
  ThreadPartition p;
  // 10 % apart: shares 0.524 and 0.476, within 8 % of an equal share
  run_steps(p, 10000, {1.1e6, 1.0e6}, 32 * 40);
  EXPECT_EQ(length(p.block(0)), 5000);
  // 25 % apart: 0.556 and 0.444
  run_steps(p, 10000, {1.25e6, 1.0e6}, 32 * 40);
  EXPECT_NEAR(length(p.block(0)), 5556, 50);
}

TEST(ThreadPartition, BlocksChangeOnlyAtTheEndOfAWindow) {
  ThreadPartition p;
  run_steps(p, 10000, {3e6, 1e6}, 31);  // one step short of the first window
  EXPECT_EQ(length(p.block(0)), 5000);
  run_steps(p, 10000, {3e6, 1e6}, 1);
  EXPECT_NE(length(p.block(0)), 5000);
  const IndexBlock after_window = p.block(0);
  run_steps(p, 10000, {3e6, 1e6}, 31);
  EXPECT_EQ(p.block(0).end, after_window.end);
}

TEST(ThreadPartition, AStalledThreadKeepsHalfAnEqualShare) {
  ThreadPartition p;
  run_steps(p, 10000, {1e6, 1e3, 1e6, 1e6}, 32 * 40);  // thread 1 nearly stopped
  expect_covers(p, 10000);
  EXPECT_EQ(length(p.block(1)), 1250);  // half of an equal quarter ...
  // ... the rest shared by the others in proportion to their speeds
  EXPECT_NEAR(length(p.block(0)), 2917, 1);
  EXPECT_NEAR(length(p.block(2)), 2917, 1);
}

TEST(ThreadPartition, ANewTeamStartsEqual) {
  ThreadPartition p;
  run_steps(p, 10000, {3e6, 1e6}, 32 * 10);
  ASSERT_NE(length(p.block(0)), 5000);
  p.plan(10000, 3);
  expect_covers(p, 10000);
  EXPECT_NEAR(length(p.block(0)), 3333, 1);
  EXPECT_NEAR(length(p.block(2)), 3333, 1);
}

TEST(ThreadPartition, AChunkQueueOnThePartitionTakesItsBlocks) {
  ThreadPartition p;
  run_steps(p, 10000, {3e6, 1e6}, 32 * 40);  // blocks of about 7,500 and 2,500
  const IndexBlock own[2] = {p.block(0), p.block(1)};
  ChunkQueue q;
  q.plan(p, 100);
  std::vector<int> times(10000, 0);
  std::vector<long> own_count(2, 0);
  bool crossed = false;
#pragma omp parallel num_threads(2)
  {
    const ChunkQueue::OwnWork w = q.drain([&](long first, long end) {
      for (int t = 0; t < 2; ++t)
        if (first < own[t].end && end > own[t].end) crossed = true;
      for (long i = first; i < end; ++i) {
#pragma omp atomic
        ++times[i];
      }
    });
    own_count[omp_get_thread_num()] = w.count;
  }
  for (long i = 0; i < 10000; ++i) ASSERT_EQ(times[i], 1) << "index " << i;
  EXPECT_FALSE(crossed);
  // what each thread did of its own block is at most that block, and the two blocks' own work
  // plus what was handed over covers everything
  EXPECT_LE(own_count[0], length(own[0]));
  EXPECT_LE(own_count[1], length(own[1]));
  EXPECT_GT(own_count[0] + own_count[1], 0);
}
