// The gather's walk chosen by measurement (Simulation::GatherWalk::automatic). The gather can
// walk a block's entries flat or take the particles one by one (core/particle_passes_simd.hpp);
// both give the same sums, bit for bit, but which is faster depends on the core: on the
// development VM's Zen 5 one by one was 1.4x faster with 5,818 particles a thread and flat 1.4x
// faster with 11,636 (its branch predictor remembers where each particle's entries end for the
// first and not for the second), on its Intel Xeon flat was 1.36x faster with 5,818 as well
// (docs/performance.md sec. 40, 53). No particle count fits both, so the step loop times its own
// steps with each walk and keeps the faster.
//
// The trial: after warm_up_steps steps with the rule's walk (Simulation::
// walks_gather_flat_automatically), blocks of block_steps steps alternate flat, one by one, one
// by one, flat, and again (ABBA ABBA: a drift of the machine's speed that is linear over the
// trial falls on both walks alike); the walk whose median step took less wins, and is kept for
// settled_steps steps before the next trial (a VM's host may change). A median is not moved by
// the few steps that rebuild or refresh the neighbour list or write output. A change of the
// particle count or of the step's team starts again from the warm-up. The choice changes no result,
// only the time; it is not saved with the state.
#pragma once

#include <array>

namespace grainlab {

class GatherWalkTrial {
 public:
  static constexpr int block_steps = 16;
  static constexpr int trial_blocks = 8;
  static constexpr int trial_steps = block_steps * trial_blocks;
  static constexpr long warm_up_steps = 32;
  static constexpr long settled_steps = 16384;

  // The walk of the coming step for n particles on a team of `team` (flat: true). `rule` is the
  // walk before any trial has ended. The same answer for every call within one step.
  bool flat(long n, int team, bool rule);
  // The wall time of the step just taken (once per step, after flat()).
  void step_took(double seconds);

  long trials_done() const { return trials_done_; }
  // the medians of the last trial's steps, s (0 before the first trial ends)
  double last_flat_median() const { return last_flat_median_; }
  double last_one_by_one_median() const { return last_one_by_one_median_; }

 private:
  bool in_trial() const { return trial_step_ >= 0; }
  bool trial_walk() const;  // the walk of trial step trial_step_

  long particles_ = -1;
  int team_ = 0;
  bool chosen_flat_ = false;  // the walk outside trials
  long countdown_ = 0;        // steps before the next trial begins
  int trial_step_ = -1;       // -1: no trial under way
  int flat_count_ = 0, one_by_one_count_ = 0;
  std::array<double, trial_steps / 2> flat_seconds_{}, one_by_one_seconds_{};
  long trials_done_ = 0;
  double last_flat_median_ = 0.0, last_one_by_one_median_ = 0.0;
};

}  // namespace grainlab
