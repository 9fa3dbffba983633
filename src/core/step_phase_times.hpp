// Where the threads of a step spend their time: for each thread, the work of each stage of the
// step and its wait after it (at the barrier that follows, or at the end of the region), and for
// the thread that runs the step, the time outside the parallel regions. Measured with
// omp_get_wtime at the stage boundaries, only while switched on (Simulation::time_step_phases;
// `grainlab_bench --phase-times`, docs/performance.md sec. 1); off, each mark is one test of a
// flag. What is timed does not change: the results are the same bits either way.
//
// A wait is what a thread loses to the others: the slowest thread's lead at a barrier and the
// barrier itself. Summed over the steps, the mean wait exceeds the spread of the threads' summed
// work when the slowest thread changes from step to step.
#pragma once

#include <omp.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

namespace grainlab {

class StepPhaseTimes {
 public:
  enum Part : int {
    // each thread's, inside the regions
    start,          // from the region's start to the thread's first instruction in it
    drift,          // the stages' first region: half kick, drift, velocity records
    drift_wait,     //   its end
    records,        // the force region's records (after a list update or on a fresh state)
    records_wait,   //   the barrier after them
    contacts,       // pair rows and wall contacts
    contacts_wait,  //   the barrier after them
    gather,         // the particles' sums and closing half kick (thread 0: the walls' totals)
    gather_wait,    //   the region's end
    sweep_head,     // one sweep (core/one_sweep.cpp): 1. the head, and chunks of the tails' drift
    sweep_head_wait,
    sweep_block,  // 2. the block's rows, sums and half kicks (its tail left)
    sweep_block_wait,
    sweep_tails,  // 3. the blocks' tails: rows and wall contacts, shared
    sweep_tails_wait,
    sweep_late,  // 4. the late particles, and the tails' sums and half kicks, shared
    sweep_late_wait,
    thread_parts,
    // the stepping thread's, outside the regions
    list_update = thread_parts,  // refreshes and rebuilds (their own regions included)
    serial,                      // the rest: listeners, walls, planning, the health check
    part_count
  };
  static constexpr std::array<const char*, part_count> names{
      "region start", "drift",        "  wait",       "records",      "  wait",
      "contacts",     "  wait",       "gather",       "  wait",       "sweep: head",
      "  wait",       "sweep: block", "  wait",       "sweep: tails", "  wait",
      "sweep: late",  "  wait",       "list updates", "serial, other"};

  bool on() const { return on_; }
  // Switches the timers on (zeroed, room for `most_threads`) or off.
  void switch_on(bool on, int most_threads) {
    on_ = on;
    slots_.assign(on ? static_cast<size_t>(std::max(1, most_threads)) : 0, Slot{});
    team_seen_ = 1, steps_ = 0, step_seconds_ = 0.0;
  }
  static double now() { return omp_get_wtime(); }

  // The stepping thread, before a region.
  void region_begins() { region_start_ = now(); }
  // A thread, first inside a region: returns its start time.
  double thread_begins() {
    const double t = now();
    add(start, t - region_start_);
    return t;
  }
  // A thread of a region: ends `stage`, begun at `since`, waits at a barrier for the team
  // (`stage` + 1 is its wait) and sets `since` to the barrier's end. (Out of line, in
  // core/step_phase_times.cpp: an inline copy in a file compiled without OpenMP would lose its
  // barrier, and the linker may keep either copy.)
  void barrier_after(Part stage, double& since);
  // A thread: `part` took it `seconds` more.
  void add(Part part, double seconds) { slot().t[part] += seconds; }
  // A thread, at its last work in a region: `part` took it from `since` to now, and it waits
  // from now to the region's end.
  void last_work(Part part, double since) {
    Slot& s = slot();
    s.last = now();
    s.t[part] += s.last - since;
    if (omp_get_thread_num() == 0) team_ = omp_get_num_threads();
  }
  // The stepping thread, after a region whose threads called last_work: their waits to its end.
  // Returns the region's time.
  double region_ends(Part wait) {
    const double t = now();
    const int team = std::min<int>(team_, static_cast<int>(slots_.size()));
    for (int k = 0; k < team; ++k) slots_[k].t[wait] += t - slots_[k].last;
    team_seen_ = std::max(team_seen_, team);
    team_ = 1;
    return t - region_start_;
  }
  // The stepping thread: a whole step took `step_seconds`, of which `regions` in the regions
  // and `updates` in list updates.
  void step_done(double step_seconds, double regions, double updates) {
    slots_[0].t[list_update] += updates;
    slots_[0].t[serial] += step_seconds - regions - updates;
    step_seconds_ += step_seconds;
    ++steps_;
  }

  long steps() const { return steps_; }
  // The steps' wall time: the sum over the parts of their means (each thread's parts in a region
  // add up to the region's time).
  double step_seconds() const { return step_seconds_; }
  int threads() const { return team_seen_; }
  // Seconds in `part`: the mean and the largest over the threads (the stepping thread's own for
  // the parts outside the regions).
  double mean(Part part) const { return sum_over_threads(part) / divisor(part); }
  double largest(Part part) const {
    double m = 0.0;
    for (int k = 0; k < team_seen_; ++k) m = std::max(m, slots_[k].t[part]);
    return m;
  }

 private:
  struct alignas(64) Slot {
    std::array<double, part_count> t{};
    double last = 0.0;
  };
  // (Simulation::time_step_phases makes a slot for every processor, more than a team can have;
  // the modulo only keeps a larger team inside the array)
  Slot& slot() { return slots_[static_cast<size_t>(omp_get_thread_num()) % slots_.size()]; }
  double sum_over_threads(Part part) const {
    double s = 0.0;
    for (int k = 0; k < team_seen_; ++k) s += slots_[k].t[part];
    return s;
  }
  double divisor(Part part) const { return part >= thread_parts ? 1.0 : team_seen_; }

  std::vector<Slot> slots_;
  double region_start_ = 0.0;
  int team_ = 1, team_seen_ = 1;
  long steps_ = 0;
  double step_seconds_ = 0.0;
  bool on_ = false;
};

}  // namespace grainlab
