// The work sharing of the step's stages (core/chunk_queue.hpp): every index of [0, n) is handed
// out exactly once, in chunks that never cross a thread's block and shrink towards its back; a
// thread that is late finds its block done by the others, from its back, all but the one chunk
// left to it (or all of it, where the plan lets the owner's last chunk go too); a team other than
// the planned one still covers [0, n) once.
#include <gtest/gtest.h>
#include <omp.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "core/chunk_queue.hpp"

using namespace grainlab;

namespace {

struct Coverage {
  std::vector<int> times_taken;        // per index
  std::vector<int> taken_by;           // per index: the thread that took it
  std::vector<long> chunks_of_thread;  // per thread
  bool chunk_crossed_a_block = false, chunk_too_long = false;
};

// Drains a queue planned for `planned` threads on a team of `team`; `late` (>= 0) is a thread
// that starts `delay` after the others.
Coverage drain(long n, int planned, int team, long chunk, int late = -1,
               std::chrono::milliseconds delay = {}, ChunkQueue::Tail tail = ChunkQueue::Tail::even,
               bool owner_keeps_last = true) {
  ChunkQueue q;
  q.plan(n, planned, chunk, tail, owner_keeps_last);
  Coverage c;
  c.times_taken.assign(n, 0);
  c.taken_by.assign(n, -1);
  c.chunks_of_thread.assign(team, 0);
  const long block = planned > 0 ? (n + planned - 1) / planned : n;
  std::atomic<bool> crossed{false}, too_long{false};
#pragma omp parallel num_threads(team)
  {
    const int me = omp_get_thread_num();
    if (me == late) std::this_thread::sleep_for(delay);
    q.drain([&](long first, long end) {
      ++c.chunks_of_thread[me];
      if (team == planned) {
        if (end - first > chunk) too_long = true;
        if (first / block != (end - 1) / block) crossed = true;
      }
      for (long i = first; i < end; ++i) {
#pragma omp atomic
        ++c.times_taken[i];
        c.taken_by[i] = me;
      }
    });
  }
  c.chunk_crossed_a_block = crossed;
  c.chunk_too_long = too_long;
  return c;
}

}  // namespace

TEST(ChunkQueue, EveryIndexIsTakenExactlyOnce) {
  for (long n : {0L, 1L, 7L, 1000L, 12345L})
    for (int team : {1, 2, 3, 4, 8})
      for (long chunk : {1L, 64L, stage_chunk(n, team)})
        for (ChunkQueue::Tail tail : {ChunkQueue::Tail::even, ChunkQueue::Tail::shrinking})
          for (bool owner_keeps_last : {true, false}) {
            SCOPED_TRACE(testing::Message()
                         << "n " << n << " team " << team << " chunk " << chunk << " shrinking "
                         << (tail == ChunkQueue::Tail::shrinking) << " owner keeps its last "
                         << owner_keeps_last);
            const Coverage c = drain(n, team, team, chunk, -1, {}, tail, owner_keeps_last);
            for (long i = 0; i < n; ++i) ASSERT_EQ(c.times_taken[i], 1) << "index " << i;
            EXPECT_FALSE(c.chunk_crossed_a_block);
            EXPECT_FALSE(c.chunk_too_long);
          }
}

TEST(ChunkQueue, ChunksShrinkTowardsTheBackOfABlock) {
  std::vector<long> b;
  // 1,000 indices in chunks of 64: from the back 32, 32, then 64 up to the front, whose chunk
  // takes the 40 left.
  ChunkQueue::chunk_bounds(3000, 4000, 64, ChunkQueue::Tail::shrinking, b);
  std::vector<long> length;
  for (size_t k = 0; k + 1 < b.size(); ++k) length.push_back(b[k + 1] - b[k]);
  ASSERT_EQ(b.front(), 3000);
  ASSERT_EQ(b.back(), 4000);
  ASSERT_EQ(length.size(), 17u);
  EXPECT_EQ(length[0], 40);
  for (size_t k = 1; k < 15; ++k) EXPECT_EQ(length[k], 64) << "chunk " << k;
  EXPECT_EQ(length[15], 32);
  EXPECT_EQ(length[16], 32);
  // Chunks of 727 (2 threads on 11,636 beads): from the back 90, 90, 180, 360, 720, then 727.
  ChunkQueue::chunk_bounds(0, 5818, 727, ChunkQueue::Tail::shrinking, b);
  const std::vector<long> back(b.end() - 6, b.end());
  EXPECT_EQ(back,
            (std::vector<long>{5818 - 1440, 5818 - 720, 5818 - 360, 5818 - 180, 5818 - 90, 5818}));
  for (size_t k = 1; k + 6 < b.size(); ++k) EXPECT_EQ(b[k + 1] - b[k], 727) << "chunk " << k;
  EXPECT_GT(b[1] - b[0], 0);
  EXPECT_LE(b[1] - b[0], 727);
  // Never shorter than 32 unless the block is; an empty block has no chunk.
  ChunkQueue::chunk_bounds(0, 20, 64, ChunkQueue::Tail::shrinking, b);
  EXPECT_EQ(b, (std::vector<long>{0, 20}));
  ChunkQueue::chunk_bounds(5, 5, 64, ChunkQueue::Tail::shrinking, b);
  EXPECT_EQ(b, (std::vector<long>{5}));
}

TEST(ChunkQueue, EvenChunksLeaveWhatIsLeftToTheFront) {
  std::vector<long> b;
  ChunkQueue::chunk_bounds(3000, 4000, 64, ChunkQueue::Tail::even, b);
  ASSERT_EQ(b.size(), 17u);
  EXPECT_EQ(b[1] - b[0], 40);
  for (size_t k = 1; k + 1 < b.size(); ++k) EXPECT_EQ(b[k + 1] - b[k], 64) << "chunk " << k;
}

TEST(ChunkQueue, ALateThreadFindsItsBlockTakenByTheOthersFromTheBack) {
  // Thread 1 starts 200 ms late; thread 0 has long since done its own block and taken thread 1's
  // chunks from the back, all but the last one left: the front chunk, which thread 1 takes.
  for (ChunkQueue::Tail tail : {ChunkQueue::Tail::even, ChunkQueue::Tail::shrinking}) {
    const long n = 4000, chunk = 64;
    std::vector<long> bounds;
    ChunkQueue::chunk_bounds(n / 2, n, chunk, tail, bounds);
    const long front_end = bounds[1];
    const Coverage c = drain(n, 2, 2, chunk, 1, std::chrono::milliseconds(200), tail);
    for (long i = 0; i < n; ++i) ASSERT_EQ(c.times_taken[i], 1) << "index " << i;
    for (long i = 0; i < n / 2; ++i) ASSERT_EQ(c.taken_by[i], 0) << "index " << i;
    for (long i = n / 2; i < front_end; ++i) ASSERT_EQ(c.taken_by[i], 1) << "index " << i;
    for (long i = front_end; i < n; ++i) ASSERT_EQ(c.taken_by[i], 0) << "index " << i;
    EXPECT_EQ(c.chunks_of_thread[1], 1);
  }
}

TEST(ChunkQueue, AThreadTakesAnotherBlockOnlyWhileItsOwnerHasTwoChunksLeft) {
  // One chunk per block: a thread that is late still finds its only chunk, however late.
  const Coverage one = drain(64, 2, 2, 32, 1, std::chrono::milliseconds(100));
  for (long i = 0; i < 64; ++i) ASSERT_EQ(one.times_taken[i], 1) << "index " << i;
  for (long i = 32; i < 64; ++i) ASSERT_EQ(one.taken_by[i], 1) << "index " << i;
  // Two chunks: the other thread takes the back one.
  const Coverage two = drain(256, 2, 2, 64, 1, std::chrono::milliseconds(100));
  for (long i = 128; i < 192; ++i) ASSERT_EQ(two.taken_by[i], 1) << "index " << i;
  for (long i = 192; i < 256; ++i) ASSERT_EQ(two.taken_by[i], 0) << "index " << i;
  // A shrinking tail cuts a block of 64 into two of the shortest (32 each): the same.
  const Coverage shrunk =
      drain(128, 2, 2, 64, 1, std::chrono::milliseconds(100), ChunkQueue::Tail::shrinking);
  for (long i = 64; i < 96; ++i) ASSERT_EQ(shrunk.taken_by[i], 1) << "index " << i;
  for (long i = 96; i < 128; ++i) ASSERT_EQ(shrunk.taken_by[i], 0) << "index " << i;
}

TEST(ChunkQueue, WhereTheOwnerNeedNotKeepItsLastChunkALateOwnerFindsItsBlockDone) {
  // Thread 1 starts 100 ms late: thread 0 takes all four of its chunks, the last one too.
  const Coverage c =
      drain(512, 2, 2, 64, 1, std::chrono::milliseconds(100), ChunkQueue::Tail::even, false);
  for (long i = 0; i < 512; ++i) ASSERT_EQ(c.times_taken[i], 1) << "index " << i;
  for (long i = 0; i < 512; ++i) ASSERT_EQ(c.taken_by[i], 0) << "index " << i;
  EXPECT_EQ(c.chunks_of_thread[1], 0);
}

TEST(ChunkQueue, ATeamOtherThanPlannedStillCoversEveryIndexOnce) {
  for (int team : {1, 2, 3}) {
    const Coverage c = drain(1000, 4, team, 64);
    for (long i = 0; i < 1000; ++i)
      ASSERT_EQ(c.times_taken[i], 1) << "team " << team << " index " << i;
  }
}

TEST(ChunkQueue, ChunkSizeGivesEachThreadSeveralChunks) {
  EXPECT_EQ(stage_chunk(11636, 1), 11636);      // one thread: its block in one piece
  EXPECT_EQ(stage_chunk(11636, 2), 727);        // 8 per thread
  EXPECT_EQ(stage_chunk(1000, 16), 64);         // never below 64
  EXPECT_EQ(stage_chunk(1000000, 16), 1024);    // never above 1,024
  EXPECT_EQ(stage_chunk(139632, 16, 16), 545);  // 16 per thread where asked
}

// Ranges of any length, one per thread (the tails of a swept step's blocks): every index of the
// ranges is taken exactly once and no other, by the planned team and, whole by its first thread,
// by another team.
TEST(ChunkQueue, PlannedRangesAreTakenExactlyOnce) {
  const long n = 10000;
  const std::vector<IndexBlock> ranges{{1000, 1700}, {2500, 2500}, {6000, 9000}};
  for (int team : {3, 2, 1})
    for (ChunkQueue::Tail tail : {ChunkQueue::Tail::even, ChunkQueue::Tail::shrinking}) {
      SCOPED_TRACE(testing::Message() << "team " << team);
      ChunkQueue q;
      q.plan_ranges(n, 3, 64, tail, [&](int t) { return ranges[t]; });
      std::vector<int> times(n, 0);
#pragma omp parallel num_threads(team)
      q.drain([&](long first, long end) {
        for (long i = first; i < end; ++i) {
#pragma omp atomic
          ++times[i];
        }
      });
      for (long i = 0; i < n; ++i) {
        const bool in_a_range = (i >= 1000 && i < 1700) || (i >= 6000 && i < 9000);
        ASSERT_EQ(times[i], in_a_range ? 1 : 0) << "index " << i;
      }
    }
}
