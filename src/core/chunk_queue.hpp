// Work sharing for the stages of a step that run inside one parallel region
// (Simulation::compute_forces; the drift's region on 4 threads or more, Simulation::kick_and_drift;
// the tails of a swept step, core/one_sweep.cpp). [0, n) is cut into the team's blocks (the
// partition schedule(static) makes, core/thread_block.hpp, or the one the threads' speeds make,
// core/thread_partition.hpp) and each block into chunks. Every thread first
// takes the chunks of its own block from its front, in order, so that in a balanced step it works
// on the same particles, and the same cache lines, as in the stage before and the step before.
// Then it takes chunks of the other threads' blocks from their backs, as long as the owner has
// at least two chunks left (on 8 threads or more, one: the plan's owner_keeps_last): a thread on a
// slower core (another process on it, a lower clock with many cores busy) thus hands its last
// chunks to the others instead of making them wait at the next barrier (on a 16-core server the
// threads had waited 14 % of the step at the barriers with fixed blocks, docs/performance.md sec.
// 16), but a chunk changes hands only where the owner is really behind. A taken-over chunk is dear:
// its particles' data lies in the owner's caches (written by its drift, read again by its gather),
// and on the 2-core development VM such a chunk took about 1.5 times as long. Taking the next
// chunks from the owner's front, as this queue first did, took them whenever the owner was a
// fraction of a chunk behind; and for the thread whose block follows, the back of a block is the
// part whose rows reach into its own particles (docs/performance.md sec. 20).
//
// A block's chunks are of one length (Tail::even, the default), or they shrink towards its back
// (Tail::shrinking, chunk_bounds): then the last chunk a thread works on, its own or one it takes
// from another block, is short, and the threads could reach the next barrier within a short
// chunk of each other. With equal chunks a thread waited 78 µs of 1.7 ms per step at the
// contacts' barrier on 16 threads of 139,632 beads, where a chunk takes about 100 µs
// (docs/performance.md sec. 31). On the 2 threads of the development VM the shrinking tails
// gained nothing (0.99 of the even ones over 30 interleaved rounds, waits of 4 to 9 µs either
// way, sec. 33), nor on 16 Xeon threads (0.975 on 139,632 beads and 0.996 on 88,400, medians of
// 5 and 4 interleaved rounds, sec. 34: the waits there come from threads held up anywhere in the
// step, not only in their last chunk); they stay a choice (`grainlab_bench --chunk-tail`).
//
// Which thread computes a chunk never changes the arithmetic of a particle or a contact (each
// is computed whole, by one thread, from data no other thread writes in that stage), so the
// results stay bit-identical for any thread count and any order in which chunks are taken.
#pragma once

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/thread_block.hpp"
#include "core/thread_partition.hpp"

namespace grainlab {

class ChunkQueue {
 public:
  ChunkQueue() = default;
  // Plans are made afresh before each use; a copy starts without one.
  ChunkQueue(const ChunkQueue&) {}
  ChunkQueue& operator=(const ChunkQueue&) { return *this; }

  enum class Tail { even, shrinking };  // the chunks at a block's back (chunk_bounds)

  // Serial, before the parallel region: `team` equal blocks of [0, n), taken `chunk` indices at
  // a time. `team` must be the size of the team that will call drain (otherwise each thread
  // falls back to its own block of [0, n), without sharing).
  // owner_keeps_last: whether a block's last untaken chunk stays with its owner (the rule
  // measured on 2 threads, sec. 20), or may go to another thread too (Simulation::chunk_sharing:
  // on 8 threads or more, sec. 34).
  void plan(long n, int team, long chunk, Tail tail = Tail::even, bool owner_keeps_last = true) {
    plan_blocks(n, team, chunk, tail, owner_keeps_last,
                [&](int t) { return block_of(n, team, t); });
  }
  // The same with the blocks of a partition (core/thread_partition.hpp).
  void plan(const ThreadPartition& partition, long chunk, Tail tail = Tail::even,
            bool owner_keeps_last = true) {
    plan_blocks(partition.size(), partition.team(), chunk, tail, owner_keeps_last,
                [&](int t) { return partition.block(t); });
  }

  // The same with ranges of [0, n) of any length, one per thread of `team`, in order (the tails
  // of the blocks of a step run as one sweep, core/one_sweep.cpp). Drained by a team other than
  // the planned one, its first thread takes every range whole.
  template <class RangeOf>
  void plan_ranges(long n, int team, long chunk, Tail tail, RangeOf&& range_of) {
    plan_blocks(n, team, chunk, tail, true, range_of);
    ranges_ = true;
  }

  // The chunks of block [first, end) for chunks of `chunk` indices, as `bounds` (chunk k is
  // [bounds[k], bounds[k + 1])): `chunk` indices each, the first chunk what is left (at most
  // `chunk`); with a shrinking tail, from the back two of the shortest length, then each twice
  // the one behind it up to `chunk`. The shortest is an eighth of `chunk`, at least 32
  // indices (a chunk's rows end in a part-filled batch of the vectorised kernel) and at most
  // `chunk`.
  static void chunk_bounds(long first, long end, long chunk, Tail tail, std::vector<long>& bounds) {
    bounds.clear();
    bounds.push_back(end);
    const long shortest =
        tail == Tail::shrinking ? std::min(chunk, std::max(smallest_chunk, chunk / 8)) : chunk;
    long length = shortest, same_length = 0;
    for (long at = end; at > first;) {
      const long next = std::max(first, at - length);
      bounds.push_back(next);
      at = next;
      // (two of the shortest, then doubling up to `chunk`)
      if (length < chunk && (length > shortest || ++same_length == 2))
        length = std::min(chunk, 2 * length);
    }
    std::reverse(bounds.begin(), bounds.end());
  }

  // What a thread did on its own block in one drain: indices, and the seconds it took.
  struct OwnWork {
    long count = 0;
    double seconds = 0.0;
  };

  // Inside the region, by every thread of the team: calls chunk(first, end) for every chunk of
  // its own block not taken by others, then for others' chunks while their owners lag; the team
  // together takes every index of [0, n) (of the ranges, after plan_ranges) exactly once. What the
  // chunks write is visible to the other threads after the next barrier. Returns what the thread
  // did on its own block (the time it took to do it: a thread's speed, core/thread_partition.hpp).
  template <class F>
  OwnWork drain(F&& chunk) {
    const int team = omp_get_num_threads(), me = omp_get_thread_num();
    OwnWork own_work;
    if (team != team_) {  // not the planned team: no sharing, each thread its own block
      if (ranges_) {      // (the ranges, by the first thread)
        if (me == 0)
          for (int t = 0; t < team_; ++t)
            if (cursors_[t].bounds.front() < cursors_[t].bounds.back())
              chunk(cursors_[t].bounds.front(), cursors_[t].bounds.back());
        return own_work;
      }
      const IndexBlock b = thread_block(n_);
      if (b.first < b.end) chunk(b.first, b.end);
      return own_work;
    }
    Cursor& own = cursors_[me];
    const double start = omp_get_wtime();
    for (long k = 0; take(own, 0, k, true);)  // own block, from the front
      own_work.count += run(own, k, chunk);
    own_work.seconds = omp_get_wtime() - start;
    for (int t = 1; t < team; ++t) {  // the others', from the back, while their owners lag
      Cursor& other = cursors_[(me + t) % team];
      for (long k = 0; take(other, left_to_owner_, k, false);) run(other, k, chunk);
    }
    return own_work;
  }

 private:
  // Chunks of a block go to other threads only while more than this many are untaken: the
  // owner's last chunk stays its own (measured on 2 threads: docs/performance.md sec. 20), unless
  // the plan says otherwise (owner_keeps_last, false on 8 threads or more: sec. 34).
  static constexpr long chunks_left_to_owner = 1;
  static constexpr long smallest_chunk = 32;

  // The chunks of block [first, end) not yet taken are numbers [front, back), both halves of one
  // atomic word, so that the owner (front) and the others (back) never take the same chunk.
  struct alignas(64) Cursor {  // one cache line each: threads take chunks without false sharing
    std::atomic<uint64_t> untaken{0};
    std::vector<long> bounds;  // of the chunks (chunk_bounds); its storage kept from plan to plan
  };
  static uint64_t pack(long front, long back) {
    return static_cast<uint64_t>(front) << 32 | static_cast<uint64_t>(back);
  }
  // Takes chunk number k of c: its front one (from_front) or its back one, if more than `leave`
  // chunks are untaken. False when there is none to take.
  static bool take(Cursor& c, long leave, long& k, bool from_front) {
    uint64_t u = c.untaken.load(std::memory_order_relaxed);
    for (;;) {
      const long front = static_cast<long>(u >> 32), back = static_cast<long>(u & 0xffffffffu);
      if (back - front <= leave) return false;
      const uint64_t taken = from_front ? pack(front + 1, back) : pack(front, back - 1);
      if (c.untaken.compare_exchange_weak(u, taken, std::memory_order_relaxed)) {
        k = from_front ? front : back - 1;
        return true;
      }
    }
  }
  template <class F>
  long run(const Cursor& c, long k, F& chunk) const {  // returns the chunk's length
    const long first = c.bounds[k], end = c.bounds[k + 1];
    chunk(first, end);
    return end - first;
  }
  template <class BlockOf>
  void plan_blocks(long n, int team, long chunk, Tail tail, bool owner_keeps_last,
                   BlockOf&& block) {
    if (team > capacity_) {
      cursors_ = std::make_unique<Cursor[]>(team);
      capacity_ = team;
    }
    n_ = n, team_ = team, ranges_ = false;
    left_to_owner_ = owner_keeps_last ? chunks_left_to_owner : 0;
    long length = std::max(1L, chunk);
    // (chunk numbers are 32-bit halves of one atomic word: a block of more than 2^32 - 100
    // chunks is taken in longer chunks)
    constexpr long max_chunks = 0xffffffffL - 100;
    for (int t = 0; t < team; ++t) {
      const IndexBlock b = block(t);
      length = std::max(length, (b.end - b.first + max_chunks - 1) / max_chunks);
    }
    for (int t = 0; t < team; ++t) {
      const IndexBlock b = block(t);
      Cursor& c = cursors_[t];
      chunk_bounds(b.first, b.end, length, tail, c.bounds);
      c.untaken.store(pack(0, static_cast<long>(c.bounds.size()) - 1), std::memory_order_relaxed);
    }
  }
  std::unique_ptr<Cursor[]> cursors_;
  int capacity_ = 0, team_ = 0;
  long n_ = 0;
  bool ranges_ = false;                        // planned by plan_ranges
  long left_to_owner_ = chunks_left_to_owner;  // (the plan's owner_keeps_last)
};

// The chunk size for n indices on a team: about `chunks_per_thread` chunks per thread (8, or 16
// on 8 threads or more: Simulation::chunk_sharing), so that the last ones can even out a slower
// core, and between 64 and 1,024 particles (a chunk's rows end with one partly filled batch of
// the vectorised kernel, and each chunk costs one atomic increment).
inline long stage_chunk(long n, int team, long chunks_per_thread = 8) {
  if (team <= 1) return std::max(1L, n);
  return std::clamp(n / (chunks_per_thread * team), 64L, 1024L);
}

}  // namespace grainlab
