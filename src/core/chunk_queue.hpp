// Work sharing for the stages of a step that run inside one parallel region
// (Simulation::compute_forces). [0, n) is cut into the team's blocks (the partition
// schedule(static) makes, core/thread_block.hpp) and each block into chunks. Every thread first
// takes the chunks of its own block, in order, so that in a balanced step it works on the same
// particles, and the same cache lines, as in the stage before and the step before; then it
// takes what is left of the other threads' blocks. A thread on a slower core (another process
// on it, a lower clock with many cores busy) thus hands its last chunks to the others instead of
// making them wait at the next barrier: on a 16-core server the threads had waited 14 % of the
// step at the barriers with fixed blocks (docs/performance.md sec. 16).
//
// Which thread computes a chunk never changes the arithmetic of a particle or a contact (each
// is computed whole, by one thread, from data no other thread writes in that stage), so the
// results stay bit-identical for any thread count and any order in which chunks are taken.
#pragma once

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <memory>

#include "core/thread_block.hpp"

namespace grainlab {

class ChunkQueue {
 public:
  ChunkQueue() = default;
  // Plans are made afresh before each use; a copy starts without one.
  ChunkQueue(const ChunkQueue&) {}
  ChunkQueue& operator=(const ChunkQueue&) { return *this; }

  // Serial, before the parallel region: `team` blocks of [0, n), taken `chunk` indices at a
  // time. `team` must be the size of the team that will call drain (otherwise each thread falls
  // back to its own block of [0, n), without sharing).
  void plan(long n, int team, long chunk) {
    if (team > capacity_) {
      cursors_ = std::make_unique<Cursor[]>(team);
      capacity_ = team;
    }
    n_ = n, team_ = team, chunk_ = std::max(1L, chunk);
    for (int t = 0; t < team; ++t) {
      const IndexBlock b = block_of(n, team, t);
      cursors_[t].next.store(b.first, std::memory_order_relaxed);
      cursors_[t].end = b.end;
    }
  }

  // Inside the region, by every thread of the team: calls chunk(first, end) until no index of
  // [0, n) is left. What the chunks write is visible to the other threads after the next
  // barrier.
  template <class F>
  void drain(F&& chunk) {
    const int team = omp_get_num_threads(), me = omp_get_thread_num();
    if (team != team_) {  // not the planned team: no sharing, each thread its own block
      const IndexBlock b = thread_block(n_);
      if (b.first < b.end) chunk(b.first, b.end);
      return;
    }
    for (int k = 0; k < team; ++k) {  // own block first, then the next threads' blocks
      Cursor& c = cursors_[(me + k) % team];
      for (;;) {
        const long first = c.next.fetch_add(chunk_, std::memory_order_relaxed);
        if (first >= c.end) break;
        chunk(first, std::min(first + chunk_, c.end));
      }
    }
  }

 private:
  struct alignas(64) Cursor {  // one cache line each: threads take chunks without false sharing
    std::atomic<long> next{0};
    long end = 0;
  };
  std::unique_ptr<Cursor[]> cursors_;
  int capacity_ = 0, team_ = 0;
  long n_ = 0, chunk_ = 1;
};

// The chunk size for n indices on a team: about 8 chunks per thread, so that the last ones can
// even out a slower core, and between 64 and 1,024 particles (a chunk's rows end with one
// partly filled batch of the vectorised kernel, and each chunk costs one atomic increment).
inline long stage_chunk(long n, int team) {
  if (team <= 1) return std::max(1L, n);
  return std::clamp(n / (8L * team), 64L, 1024L);
}

}  // namespace grainlab
