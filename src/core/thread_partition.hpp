// The blocks of [0, n) that the threads of a step start from, sized by how fast each thread has
// been going. Every stage of a step starts each thread on the same block (the drift in full on 2
// and 3 threads, every other stage from its front, core/chunk_queue.hpp), so that a particle's data
// stays in one core's caches from stage to stage and from step to step. With equal blocks, a thread
// on a slower core (another process or another virtual machine on it, a lower clock) makes the
// others wait at every barrier: on 2 threads the drift has no chunks to hand over, and in the
// force stages the owner keeps its last chunk (docs/performance.md sec. 34 for 4 and more). On the
// 2-core development VM, whose two CPUs drift apart by up to 1.9x for minutes at a time, the first
// thread to finish waited 80 to 120 microseconds per step at the force stage's barrier alone
// (docs/performance.md sec. 24). So each thread times the work it does on its own block, and the
// blocks follow the threads' speeds, smoothed over steps.
//
// Which thread computes a particle never changes its arithmetic, so the results stay
// bit-identical whatever the blocks.
#pragma once

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/thread_block.hpp"

namespace grainlab {

class ThreadPartition {
 public:
  // Serial, before a step's parallel regions: the blocks of [0, n) for a team of `team`. The
  // speeds are forgotten when the team changes.
  void plan(long n, int team) {
    team = std::max(team, 1);
    if (team != team_) {
      slots_.assign(static_cast<size_t>(team), Slot{});
      shares_.assign(static_cast<size_t>(team), 1.0 / team);
      team_ = team;
    }
    n_ = n;
    bounds_.resize(static_cast<size_t>(team) + 1);
    bounds_[0] = 0;
    double reached = 0.0;
    for (int t = 0; t < team; ++t) {
      reached += shares_[t];
      bounds_[t + 1] = std::clamp(std::lround(reached * n), bounds_[t], n);
    }
    bounds_[team] = n;  // (rounding)
  }

  int team() const { return team_; }
  long size() const { return n_; }
  // Block t of the plan.
  IndexBlock block(int t) const { return {bounds_[t], bounds_[t + 1]}; }
  // The calling thread's block when the region's team is the planned one (n indices); otherwise
  // the equal block schedule(static) would give (core/thread_block.hpp).
  IndexBlock thread_block_of(long n) const {
    const int team = omp_get_num_threads();
    return team == team_ && n == n_ ? block(omp_get_thread_num()) : thread_block(n);
  }

  // Inside a region, by thread t of the planned team: it spent `seconds` on `count` indices of
  // its own block.
  void record(int t, long count, double seconds) {
    if (t >= team_) return;
    slots_[t].count += count;
    slots_[t].seconds += seconds;
  }

  // Serial, after a step. Every `window` steps each thread's speed (indices per second on its
  // own block, over the window) is folded into its running speed, smoothed over about
  // 1 / smoothing windows, and the shares follow the speeds where one of them moved by more
  // than `dead_band`: between such moves each particle stays with its thread.
  void update() {
    if (++steps_ < window) return;
    steps_ = 0;
    double total = 0.0;
    bool measured = true;
    for (Slot& s : slots_) {
      if (s.count > 0 && s.seconds > 0.0) {
        const double speed = s.count / s.seconds;
        s.speed = s.speed > 0.0 ? s.speed + smoothing * (speed - s.speed) : speed;
      }
      s.count = 0, s.seconds = 0.0;
      total += s.speed, measured = measured && s.speed > 0.0;
    }
    if (!measured) return;
    // Shares in proportion to the speeds, but none below half of an equal one (a stalled window
    // must not starve a thread): those get that floor, the others the rest in proportion.
    const double floor = 0.5 / team_;
    double floored = 0.0, rest = 0.0;
    for (const Slot& s : slots_)
      if (s.speed / total < floor)
        floored += floor;
      else
        rest += s.speed / total;
    std::vector<double> shares(slots_.size());
    double moved = 0.0;
    for (size_t t = 0; t < slots_.size(); ++t) {
      const double share = slots_[t].speed / total;
      shares[t] = share < floor ? floor : share * (1.0 - floored) / rest;
    }
    double uneven = 0.0;
    for (size_t t = 0; t < slots_.size(); ++t)
      uneven = std::max(uneven, std::abs(shares[t] * team_ - 1.0));
    // Threads within `equal_band` of one speed keep equal blocks: small differences the chunks
    // they hand each other even out, and a block's speed measures its particles (walls, the
    // contact count) as much as its core; equal blocks are the layout every figure before
    // docs/performance.md sec. 24 was measured with.
    if (uneven <= equal_band) std::fill(shares.begin(), shares.end(), 1.0 / team_);
    for (size_t t = 0; t < slots_.size(); ++t)
      moved = std::max(moved, std::abs(shares[t] - shares_[t]));
    if (moved > dead_band) shares_ = std::move(shares);
  }

 private:
  static constexpr int window = 32;
  static constexpr double smoothing = 0.3;
  static constexpr double dead_band = 0.005;
  static constexpr double equal_band = 0.08;
  int steps_ = 0;
  struct alignas(64) Slot {  // one cache line each: the threads record without false sharing
    long count = 0;
    double seconds = 0.0;
    double speed = 0.0;  // indices per second; 0 until measured
  };
  std::vector<Slot> slots_;
  std::vector<double> shares_{1.0};  // of [0, n), per thread; they add up to 1
  std::vector<long> bounds_{0, 0};
  int team_ = 0;
  long n_ = 0;
};

}  // namespace grainlab
