// grainlab: a virtual granular laboratory (DEM). See README.md and docs/.
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <exception>
#include <optional>
#include <string_view>
#include <thread>
#include <vector>

#include "command.hpp"
#include "grainlab/version.hpp"
#include "io/output_files.hpp"
#include "io/team_follower.hpp"
#include "io/wait_policy.hpp"

namespace {

// The thread count of --threads N, or 0 when the command line gives none.
int threads_option(int argc, char** argv) {
  for (int k = 1; k < argc; ++k) {
    const std::string_view a = argv[k];
    if (a == "--threads" && k + 1 < argc) return std::max(1, std::atoi(argv[k + 1]));
    if (a.starts_with("--threads=")) return std::max(1, std::atoi(argv[k] + 10));
  }
  return 0;
}

// The OpenMP threads a run will start: --threads N, else OMP_NUM_THREADS, else one per CPU.
int requested_threads(int argc, char** argv, int cpus) {
  if (const int n = threads_option(argc, argv); n > 0) return n;
  if (const char* n = std::getenv("OMP_NUM_THREADS")) return std::max(1, std::atoi(n));
  return cpus;
}

// How long an OpenMP thread that waits at a barrier spins before it sleeps. GCC's runtime spins
// 300,000 rounds by default: on an idle machine the fastest, but when another process holds one
// of the cores, the spinning thread keeps its core while the thread it waits for shares the
// other, and a run takes 2.4 times as long (docs/performance.md sec. 15). Sleeping at once
// (OMP_WAIT_POLICY=passive) is safe but pays a wake-up at every barrier (up to 1.2x slower on
// an idle machine). 1,000 rounds keep the idle speed within the noise, but a run still took
// 2.25x its idle time with a busy loop on the other core (sec. 18). So `run` and `prepare` measure
// first, for 0.1 s, how many CPUs other processes keep busy (those of lower priority, nice, apart:
// niced_processes_yield). With a thread count (--threads, OMP_NUM_THREADS) the threads sleep at
// once when they would not each find a free CPU (io/wait_policy.hpp). Without one, their team
// follows the free CPUs while they run (io/team_follower.hpp, sec. 31) and its threads spin
// longer (sec. 53), a long while where processes of lower priority are busy (barrier_spin_rounds,
// sec. 38).
// libgomp reads its settings when it is loaded, before main, so the setting takes a restart of
// the program with it in the environment; a user's own OMP_WAIT_POLICY or GOMP_SPINCOUNT is kept,
// and threads bound by OMP_PROC_BIND, OMP_PLACES or GOMP_CPU_AFFINITY get no restart (it would
// inherit the first thread's single CPU).
void choose_barrier_waiting(int argc, char** argv) {
  using namespace grainlab;
  if (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT")) return;
  const std::string_view command = argc > 1 ? argv[1] : "";
  const bool long_run = command == "run" || command == "prepare";
  const bool quiet = std::find_if(argv, argv + argc, [](const char* a) {
                       return std::string_view(a) == "--quiet";
                     }) != argv + argc;
  // Bound threads: the runtime has already bound this first thread, and a restart would keep
  // only its CPU (io/wait_policy.hpp), so no restart and the runtime's own policy.
  if (openmp_binds_threads(std::getenv("OMP_PROC_BIND"), std::getenv("OMP_PLACES"),
                           std::getenv("GOMP_CPU_AFFINITY"))) {
    if (long_run && !quiet) fmt::print(stderr, "grainlab: {}\n", describe_bound_threads());
    return;
  }
  WaitPolicy policy = WaitPolicy::bounded_spin;
  const char* spin_rounds = barrier_spin_rounds(false, 0.0);
  // A team that follows the free CPUs (io/team_follower.hpp) leaves a CPU that another process
  // holds within two seconds: its threads spin a while, the fastest on free CPUs, and a long
  // while where only processes of lower priority (nice) are busy.
  const bool follows = team_follows_free_cpus(threads_option(argc, argv) > 0);
  if (long_run) {
    const std::vector<int> usable = usable_cpus();
    const int cpus = usable.empty() ? static_cast<int>(std::max(1L, sysconf(_SC_NPROCESSORS_ONLN)))
                                    : static_cast<int>(usable.size());
    const int threads = requested_threads(argc, argv, cpus);
    const std::optional<CpuTimes> before = threads > 1 ? read_cpu_times(usable) : std::nullopt;
    if (before) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    const std::optional<CpuTimes> after = before ? read_cpu_times(usable) : std::nullopt;
    if (before && after) {
      const bool niced_yield = niced_processes_yield();
      const double busy = busy_cpus_between(competing_times(*before, niced_yield),
                                            competing_times(*after, niced_yield), cpus);
      const double niced = niced_yield ? busy_cpus_between({before->niced, before->total},
                                                           {after->niced, after->total}, cpus)
                                       : 0.0;
      if (!follows) {
        policy = choose_wait_policy(threads, cpus, busy);
        if (policy == WaitPolicy::passive && !quiet)
          fmt::print(stderr, "grainlab: {}\n", describe_passive_choice(threads, cpus, busy));
      }
      spin_rounds = barrier_spin_rounds(follows, niced);
      if (spins_long_for_niced(follows, niced) && !quiet)
        fmt::print(stderr, "grainlab: {}\n", describe_niced_spin(niced, cpus, spin_rounds));
    }
  }
  const bool set = policy == WaitPolicy::passive ? setenv("OMP_WAIT_POLICY", "passive", 0) == 0
                                                 : setenv("GOMP_SPINCOUNT", spin_rounds, 0) == 0;
  if (!set) return;
  execv("/proc/self/exe", argv);  // returns only on failure: then go on with the default
}

}  // namespace

int main(int argc, char** argv) {
  using namespace grainlab::app;
  choose_barrier_waiting(argc, argv);
  CLI::App app{"grainlab: discrete element virtual granular laboratory"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("grainlab ") + grainlab::version_string);
  std::vector<Command> commands{add_run_command(app), add_params_command(app),
                                add_prepare_command(app), add_calibrate_command(app)};
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? exit_ok : exit_bad_input;
  }
  try {
    for (const Command& c : commands)
      if (c.subcommand->parsed()) return c.run();
  } catch (const std::exception& e) {
    fmt::print(stderr, "grainlab: error: {}\n", e.what());
    return exit_failed;
  }
  return exit_bad_input;
}
