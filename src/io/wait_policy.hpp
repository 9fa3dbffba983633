// How OpenMP threads wait at a barrier, chosen when a long run starts from how busy the machine is.
//
// Spinning a while before sleeping is the fastest on an idle machine: a sleeping thread costs a
// wake-up of tens of microseconds at every barrier on a VM, up to 1.2x on the step. It collapses
// when another process holds a core: the thread that shares that core is preempted, and the
// others spin and then sleep and wake at every barrier; the reference triaxial test took 2.25x
// its idle time with a busy loop on the other core. Threads that sleep at once lose less: the
// short reference shear 19.8 s against 24.8 s, the whole test 1,012 s against 1,078 s, one run
// each (docs/performance.md sec. 15 and 18). libgomp reads its
// policy once, when it is loaded, so grainlab measures the load before its OpenMP runtime starts
// and restarts itself with the policy in its environment (apps/grainlab/main.cpp).
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace grainlab {

// Busy and total jiffies of a set of CPUs together, from /proc/stat.
struct CpuTimes {
  double busy = 0.0;   // user, nice, system, irq, softirq, steal
  double total = 0.0;  // the above with idle and iowait
};

// From the text of /proc/stat, the sum of the lines "cpuK" for K in `cpus`, sorted (the CPUs this
// process may run on: in a container or under taskset these are not all of the machine's), or the
// total line "cpu" when `cpus` is empty; nullopt when a line is missing or malformed.
std::optional<CpuTimes> parse_cpu_times(const std::string& proc_stat,
                                        const std::vector<int>& cpus = {});

// The CPUs this process may run on (its affinity mask; in a container or under taskset not all
// of the machine's), sorted, as OpenMP counts them for its default thread count; empty where the
// mask cannot be read.
std::vector<int> usable_cpus();

// parse_cpu_times of this machine's /proc/stat now; nullopt where it cannot be read.
std::optional<CpuTimes> read_cpu_times(const std::vector<int>& cpus);

// How many of `cpus` CPUs were busy on average between two readings of the same set.
double busy_cpus_between(const CpuTimes& before, const CpuTimes& after, int cpus);

// The most threads, from 1 to `most`, that each find a free CPU among `cpus` CPUs of which other
// processes keep `busy_cpus` busy: t threads do when t <= cpus - busy_cpus + 0.5 (within half a
// CPU). The team a run without --threads takes (io/team_follower.hpp).
int team_for_free_cpus(int most, int cpus, double busy_cpus);

// The wait policy for `threads` OpenMP threads on `cpus` CPUs of which `busy_cpus` are already
// busy with other work: spin a while when the threads find a free CPU each
// (team_for_free_cpus), sleep at once otherwise.
enum class WaitPolicy { bounded_spin, passive };
WaitPolicy choose_wait_policy(int threads, int cpus, double busy_cpus);

// Whether the OpenMP environment binds threads to CPUs, from the values of OMP_PROC_BIND,
// OMP_PLACES and GOMP_CPU_AFFINITY (null: unset). libgomp then binds the program's first thread
// as it loads, before main: a restart would inherit that one thread's CPU as the whole
// process's affinity and run every thread there (measured: OMP_PROC_BIND=spread gave a 2-thread
// run the places {0}). So grainlab does not restart itself when this holds. OMP_PROC_BIND=false
// binds nothing, whatever the other two say; OMP_PLACES alone binds (libgomp's reading).
bool openmp_binds_threads(const char* proc_bind, const char* places, const char* gomp_cpu_affinity);

// One line for the user when a run keeps the runtime's own wait policy because the threads are
// bound (openmp_binds_threads).
std::string describe_bound_threads();

// One line for the user when the threads will sleep at once: what was measured, what was chosen
// and how to choose otherwise.
std::string describe_passive_choice(int threads, int cpus, double busy_cpus);

}  // namespace grainlab
