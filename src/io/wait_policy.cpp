#include "io/wait_policy.hpp"

#include <fmt/format.h>
#include <sched.h>
#include <sys/resource.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <sstream>
#include <string_view>
#include <vector>

#include "io/output_files.hpp"

namespace grainlab {

namespace {

// The jiffies of one line "cpu..." after its name: user nice system idle iowait irq softirq
// steal (guest time is already in user); nullopt when it has fewer than the first five.
std::optional<CpuTimes> line_times(std::istringstream& fields) {
  std::vector<double> v;
  double x;
  while (v.size() < 8 && fields >> x) v.push_back(x);
  if (v.size() < 5) return std::nullopt;
  v.resize(8, 0.0);
  CpuTimes t;
  t.busy = v[0] + v[1] + v[2] + v[5] + v[6] + v[7];
  t.total = t.busy + v[3] + v[4];
  t.niced = v[1];
  return t;
}

// Whether a line named `name` is wanted: "cpu" (the total) when `cpus` is empty, else "cpuK"
// for K in `cpus` (sorted, as the affinity mask lists them); one lookup per line, not a name
// built per CPU (a server has hundreds of lines).
bool wanted_cpu_line(std::string_view name, const std::vector<int>& cpus) {
  if (!name.starts_with("cpu")) return false;
  name.remove_prefix(3);
  if (cpus.empty()) return name.empty();
  int k = -1;
  const auto [end, error] = std::from_chars(name.data(), name.data() + name.size(), k);
  return error == std::errc{} && end == name.data() + name.size() &&
         std::binary_search(cpus.begin(), cpus.end(), k);
}

}  // namespace

std::optional<CpuTimes> parse_cpu_times(const std::string& proc_stat,
                                        const std::vector<int>& cpus) {
  std::istringstream lines(proc_stat);
  std::string line;
  CpuTimes sum;
  size_t found = 0;
  while (std::getline(lines, line)) {
    std::istringstream fields(line);
    std::string name;
    fields >> name;
    if (!wanted_cpu_line(name, cpus)) continue;
    const std::optional<CpuTimes> t = line_times(fields);
    if (!t) return std::nullopt;
    sum.busy += t->busy;
    sum.total += t->total;
    sum.niced += t->niced;
    ++found;
  }
  if (found != (cpus.empty() ? 1 : cpus.size())) return std::nullopt;
  return sum;
}

std::vector<int> usable_cpus() {
  std::vector<int> cpus;
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) == 0)
    for (int k = 0; k < CPU_SETSIZE; ++k)
      if (CPU_ISSET(k, &set)) cpus.push_back(k);
  return cpus;
}

// (an unreadable /proc/stat reads as "", which parse_cpu_times refuses)
std::optional<CpuTimes> read_cpu_times(const std::vector<int>& cpus) {
  return parse_cpu_times(read_file("/proc/stat"), cpus);
}

bool niced_processes_yield() {
  errno = 0;
  const int own_nice = getpriority(PRIO_PROCESS, 0);  // (-1 is a valid value: errno tells)
  return errno == 0 && own_nice <= 0;
}

CpuTimes competing_times(const CpuTimes& t, bool niced_yield) {
  if (!niced_yield) return t;
  CpuTimes c = t;
  c.busy -= t.niced;
  c.niced = 0.0;
  return c;
}

std::optional<CpuTimes> read_competing_cpu_times(const std::vector<int>& cpus) {
  const std::optional<CpuTimes> t = read_cpu_times(cpus);
  if (!t) return std::nullopt;
  return competing_times(*t, niced_processes_yield());
}

double busy_cpus_between(const CpuTimes& before, const CpuTimes& after, int cpus) {
  const double total = after.total - before.total;
  if (!(total > 0.0)) return 0.0;
  return std::clamp((after.busy - before.busy) / total, 0.0, 1.0) * cpus;
}

int team_for_free_cpus(int most, int cpus, double busy_cpus) {
  const double free_cpus = cpus - busy_cpus;
  int team = std::max(most, 1);
  while (team > 1 && free_cpus < team - 0.5) --team;
  return team;
}

WaitPolicy choose_wait_policy(int threads, int cpus, double busy_cpus) {
  return team_for_free_cpus(threads, cpus, busy_cpus) < threads ? WaitPolicy::passive
                                                                : WaitPolicy::bounded_spin;
}

bool spins_long_for_niced(bool team_follows, double niced_cpus) {
  return team_follows && niced_cpus >= 0.5;
}

const char* barrier_spin_rounds(bool team_follows, double niced_cpus) {
  if (spins_long_for_niced(team_follows, niced_cpus)) return "300000";
  return team_follows ? "20000" : "1000";
}

bool openmp_binds_threads(const char* proc_bind, const char* places,
                          const char* gomp_cpu_affinity) {
  // An environment value without its blanks, in lower case; "" when unset or blank.
  const auto normalized = [](const char* v) {
    std::string out;
    for (; v && *v; ++v)
      if (!std::isspace(static_cast<unsigned char>(*v)))
        out += static_cast<char>(std::tolower(static_cast<unsigned char>(*v)));
    return out;
  };
  const std::string bind = normalized(proc_bind);
  if (!bind.empty()) return bind != "false";
  return !normalized(places).empty() || !normalized(gomp_cpu_affinity).empty();
}

std::string describe_bound_threads() {
  return "OpenMP threads are bound (OMP_PROC_BIND, OMP_PLACES or GOMP_CPU_AFFINITY): grainlab "
         "keeps the runtime's own wait policy, which spins long at every barrier; with another "
         "process busy on these CPUs set OMP_WAIT_POLICY=passive (docs/performance.md sec. 21)";
}

std::string describe_passive_choice(int threads, int cpus, double busy_cpus) {
  return fmt::format(
      "other processes keep {:.1f} of {} CPUs busy: the {} threads sleep when they wait "
      "(OMP_WAIT_POLICY=passive; set it or GOMP_SPINCOUNT yourself to choose)",
      busy_cpus, cpus, threads);
}

std::string describe_niced_spin(double niced_cpus, int cpus, const char* spin_rounds) {
  return fmt::format(
      "processes of lower priority (nice) keep {:.1f} of {} CPUs busy: the threads spin at "
      "barriers rather than sleep, which keeps their CPUs (GOMP_SPINCOUNT={}; set it "
      "yourself to choose)",
      niced_cpus, cpus, spin_rounds);
}

}  // namespace grainlab
