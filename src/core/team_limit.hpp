// The team of OpenMP threads the steps run with, when the program lets it follow the machine.
//
// On a machine where another process takes a core, a step's team of one thread per core loses
// more than that core: a thread that shares its core with the other process is preempted for a
// whole time slice while its partners wait at the barrier. On the 2-core development VM, with a
// busy loop on one core, two threads ran `dense-11k` at half the speed of one thread
// (docs/performance.md sec. 31). So `grainlab run` and `prepare`, when no thread count is asked
// for, watch how many CPUs other processes keep busy (io/team_follower.hpp) and set here the
// team the next steps take. Results do not depend on the team (each particle's sums are formed in
// a fixed order whoever computes them), so it can change between any two steps.
#pragma once

#include <omp.h>

#include <atomic>

namespace grainlab {

// The team every Simulation's next step runs with, or 0: leave the thread count to OpenMP
// (omp_set_num_threads, OMP_NUM_THREADS). Written by any thread; read at the start of a step.
inline std::atomic<int> step_team_limit{0};

// Called by the thread that runs the steps, between parallel regions: the runtime's thread
// count for the next regions follows step_team_limit where it is set.
inline void follow_step_team_limit() {
  const int team = step_team_limit.load(std::memory_order_relaxed);
  if (team > 0 && team != omp_get_max_threads()) omp_set_num_threads(team);
}

}  // namespace grainlab
