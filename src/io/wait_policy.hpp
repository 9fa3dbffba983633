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
  double niced = 0.0;  // nice alone: processes with a positive nice value (part of busy)
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

// Whether processes with a positive nice value leave their CPU to this process's threads: when
// this process runs at nice 0 or below. Linux's scheduler gives a process at nice 10 about a
// tenth of a CPU against one at nice 0, at nice 19 about 1.5 %; a thread of this process that
// spins at a barrier or wakes from one takes the CPU back from it at once. Counted as busy, a
// `nice 19` busy loop on one of the 2 cores made a run with `--threads 2` sleep at every barrier
// (the short reference shear 12.7-18.6 s; 9.6-14.4 s with the loop not counted, 7.6-9.5 s idle),
// and the team that follows the free CPUs dropped to one thread in some runs
// (docs/performance.md sec. 38).
bool niced_processes_yield();

// The jiffies that compete with this process's threads: `t` less its niced jiffies where
// `niced_yield` (niced_processes_yield), else `t` as it is.
CpuTimes competing_times(const CpuTimes& t, bool niced_yield);

// read_cpu_times as competing_times for this process: what the wait policy and the team that
// follows the free CPUs count as busy.
std::optional<CpuTimes> read_competing_cpu_times(const std::vector<int>& cpus);

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

// How many rounds a thread that waits at a barrier spins before it sleeps (GOMP_SPINCOUNT), for
// threads that spin (bounded_spin).
// - A fixed team (--threads, OMP_NUM_THREADS): 1,000 (about 20 us on the development VM's Zen 5):
//   the least a shared core costs it (a longer spin made one 2.5x slower with a busy loop on the
//   other core; docs/performance.md sec. 36), and the idle speed within the noise there.
// - A team that follows the free CPUs (io/team_follower.hpp: a process that takes a CPU later
//   costs it a thread within two seconds, not a long spin at every barrier): 20,000. On the VM's
//   Zen 5 it was even with 1,000 on the long runs (sec. 36); on its Intel Xeon, with 1,000, the
//   kernel's switching of sleeping threads took 4 % of the short shear's samples, and 20,000
//   (set by hand) was about 1.09x faster on the demo's job and the plane strain test and 1.105x
//   on the short reference shear with --threads 2 (sec. 53).
// - The same team where processes of lower priority keep at least half a CPU busy
//   (`niced_cpus`, counted where niced_processes_yield): 300,000 (libgomp's own): a thread that
//   sleeps hands its CPU to the niced process and waits for the scheduler to take it back;
//   spinning, it keeps it. With a `nice 19` busy loop on one of the 2 cores the short reference
//   shear took 8.0-8.7 s with the team following the free CPUs, against 9.8-16.5 s before (1,000
//   rounds, the loop counted as busy) and 7.6-9.5 s idle (sec. 38).
const char* barrier_spin_rounds(bool team_follows, double niced_cpus);
// Whether barrier_spin_rounds gives the long spin (what a run says on stderr when it does).
bool spins_long_for_niced(bool team_follows, double niced_cpus);

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
// What a run says when its threads spin long for processes of lower priority
// (barrier_spin_rounds).
std::string describe_niced_spin(double niced_cpus, int cpus, const char* spin_rounds);

}  // namespace grainlab
