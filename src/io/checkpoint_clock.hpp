// When a long run saves itself: every `interval_s` of wall time, and at once when Ctrl-C or
// SIGTERM asks it to stop (then it throws Interrupted after saving). One clock serves every
// resumable loop: scene runs, the preparation, the loading of an element test and the
// sliding-friction test.
#pragma once

#include <chrono>

#include "io/interrupt.hpp"

namespace grainlab {

// The default wall time between checkpoints of every resumable run, s (cost:
// bench/checkpoint_cost.py: 0.5 % of a full-scale run at this interval).
inline constexpr double default_checkpoint_interval_s = 60.0;

class CheckpointClock {
 public:
  // `read_clock_every`: the wall clock is read at every that many polls (the interrupt flag at
  // every poll), so that a loop of cheap steps can poll at each step.
  explicit CheckpointClock(double interval_s, long read_clock_every = 1)
      : interval_s_(interval_s), read_clock_every_(read_clock_every > 0 ? read_clock_every : 1) {}

  // Wall time since this session (this process's share of the run) began, s: what a save adds
  // to the wall time of the sessions before it.
  double session_time() const { return seconds_since(session_start_); }

  // At a point where the run can be saved: on Ctrl-C / SIGTERM, `save()` and then
  // Interrupted(`stop_message()`); otherwise `save()` when `interval_s` has passed since the last
  // save (or since the session began).
  template <class Save, class StopMessage>
  void poll(Save&& save, StopMessage&& stop_message) {
    if (interrupt_requested()) {
      save();
      throw Interrupted(stop_message());
    }
    if (++polls_ % read_clock_every_ == 0 && seconds_since(last_save_) >= interval_s_) {
      save();
      last_save_ = Clock::now();
    }
  }

 private:
  using Clock = std::chrono::steady_clock;
  static double seconds_since(Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
  }
  double interval_s_;
  long read_clock_every_;
  long polls_ = 0;
  Clock::time_point session_start_ = Clock::now(), last_save_ = session_start_;
};

}  // namespace grainlab
