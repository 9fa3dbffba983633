// The team of threads follows the CPUs that other processes leave free.
//
// When `grainlab run` or `prepare` is given no thread count (no --threads, no OMP_NUM_THREADS) and
// the threads are not bound to CPUs, it runs one thread per CPU it may use, as OpenMP does, but
// only while those CPUs are free: every second a background thread reads /proc/stat for those
// CPUs and this process's own CPU time (getrusage), and from the two how many CPUs other
// processes kept busy. The steps then take the most threads, up to one per CPU, that each find a
// free CPU (team_for_free_cpus, io/wait_policy.hpp: within half a CPU), through step_team_limit
// (core/team_limit.hpp). Why: a thread that shares its core with another busy process is
// preempted for whole time slices while the other threads wait for it at every barrier. On the
// 2-core development VM with a busy loop on one core, 2 threads ran `dense-11k` at half the
// speed of 1 thread (docs/performance.md sec. 31). Results do not depend on the team.
//
// A change of team takes two readings in a row that ask for it, so that a burst of another
// process (a compiler's one file, an editor) does not move the team back and forth. A hypervisor's
// steal time counts as busy: on a virtual machine those CPUs are not free either.
// Processes of lower priority (a positive nice value) do not count where this process runs at
// nice 0 or below: they leave the CPU to its threads (read_competing_cpu_times,
// io/wait_policy.hpp).
#pragma once

#include <condition_variable>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "io/wait_policy.hpp"

namespace grainlab {

// How many CPUs processes other than this one kept busy between two readings of /proc/stat for
// `cpus` CPUs: the busy jiffies less `own_cpu_s` (this process's CPU time between the readings,
// s) at `ticks_per_s` jiffies per second, over the elapsed time (the total jiffies over `cpus`).
// In [0, cpus]; 0 when no time passed. (busy_cpus_between less this process's share)
double other_busy_cpus(const CpuTimes& before, const CpuTimes& after, int cpus, double own_cpu_s,
                       double ticks_per_s);

// The team from successive readings: it starts at `most` and changes to a wanted team when two
// readings in a row want it.
class TeamChoice {
 public:
  explicit TeamChoice(int most) : team_(most) {}
  // One reading's wanted team; true when the team changed with it.
  bool observe(int wanted);
  int team() const { return team_; }

 private:
  int team_;
  int pending_ = 0;  // the team the last reading wanted where it differed, else 0
};

// Whether a run's team follows the free CPUs: no thread count given (`threads_given`: --threads),
// OMP_NUM_THREADS unset, threads not bound to CPUs (openmp_binds_threads) and more than one CPU
// to run on.
bool team_follows_free_cpus(bool threads_given);

// While it lives, a background thread sets step_team_limit every `interval_s` seconds to the
// team for the CPUs other processes leave free (TeamChoice over team_for_free_cpus, at most one
// thread per CPU of `cpus`, the CPUs this process may run on), and on stderr one line per change
// when `report`. Destroyed, it stops the thread and clears step_team_limit. Where /proc/stat
// cannot be read, the team stays at one thread per CPU.
class TeamFollower {
 public:
  TeamFollower(std::vector<int> cpus, bool report, double interval_s = 1.0);
  ~TeamFollower();
  TeamFollower(const TeamFollower&) = delete;
  TeamFollower& operator=(const TeamFollower&) = delete;

 private:
  void follow(std::vector<int> cpus, bool report, double interval_s);
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::thread thread_;
};

// A TeamFollower for a run when team_follows_free_cpus(threads_given), else null.
std::unique_ptr<TeamFollower> follow_free_cpus(bool threads_given, bool quiet);

}  // namespace grainlab
