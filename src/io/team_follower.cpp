#include "io/team_follower.hpp"

#include <fmt/format.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <optional>

#include "core/team_limit.hpp"

namespace grainlab {

double other_busy_cpus(const CpuTimes& before, const CpuTimes& after, int cpus, double own_cpu_s,
                       double ticks_per_s) {
  // (the elapsed time: the set's total jiffies over its CPUs)
  const double elapsed_s = (after.total - before.total) / std::max(cpus, 1) / ticks_per_s;
  if (!(elapsed_s > 0.0)) return 0.0;
  return std::clamp(busy_cpus_between(before, after, cpus) - own_cpu_s / elapsed_s, 0.0,
                    static_cast<double>(cpus));
}

bool TeamChoice::observe(int wanted) {
  if (wanted == team_) {
    pending_ = 0;
    return false;
  }
  if (wanted != pending_) {
    pending_ = wanted;
    return false;
  }
  team_ = wanted;
  pending_ = 0;
  return true;
}

bool team_follows_free_cpus(bool threads_given) {
  return !threads_given && !std::getenv("OMP_NUM_THREADS") &&
         !openmp_binds_threads(std::getenv("OMP_PROC_BIND"), std::getenv("OMP_PLACES"),
                               std::getenv("GOMP_CPU_AFFINITY")) &&
         usable_cpus().size() > 1;
}

namespace {

// This process's CPU time so far, s (user and system, every thread).
double own_cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

}  // namespace

TeamFollower::TeamFollower(std::vector<int> cpus, bool report, double interval_s)
    : thread_([this, cpus = std::move(cpus), report, interval_s] {
        follow(cpus, report, interval_s);
      }) {}

TeamFollower::~TeamFollower() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
  step_team_limit.store(0, std::memory_order_relaxed);
}

void TeamFollower::follow(std::vector<int> cpus, bool report, double interval_s) {
  const int count = static_cast<int>(cpus.size());
  const double ticks_per_s = static_cast<double>(sysconf(_SC_CLK_TCK));
  TeamChoice choice(count);
  std::optional<CpuTimes> before = read_competing_cpu_times(cpus);
  double own_before = own_cpu_seconds();
  if (!before || !(ticks_per_s > 0.0)) return;  // (the team stays OpenMP's)
  const auto interval = std::chrono::duration<double>(interval_s);
  std::unique_lock<std::mutex> lock(mutex_);
  while (!wake_.wait_for(lock, interval, [this] { return stop_; })) {
    const std::optional<CpuTimes> after = read_competing_cpu_times(cpus);
    const double own_after = own_cpu_seconds();
    if (!after) return;
    const double others =
        other_busy_cpus(*before, *after, count, own_after - own_before, ticks_per_s);
    before = after;
    own_before = own_after;
    if (!choice.observe(team_for_free_cpus(count, count, others))) continue;
    step_team_limit.store(choice.team(), std::memory_order_relaxed);
    if (report)
      fmt::print(stderr,
                 "{}grainlab: other processes keep {:.1f} of {} CPUs busy: the steps go on with "
                 "{} thread{} (without --threads the team follows the free CPUs; results do not "
                 "depend on it)\n",
                 isatty(STDERR_FILENO) ? "\n" : "", others, count, choice.team(),
                 choice.team() == 1 ? "" : "s");
  }
}

std::unique_ptr<TeamFollower> follow_free_cpus(bool threads_given, bool quiet) {
  if (!team_follows_free_cpus(threads_given)) return nullptr;
  return std::make_unique<TeamFollower>(usable_cpus(), !quiet);
}

}  // namespace grainlab
