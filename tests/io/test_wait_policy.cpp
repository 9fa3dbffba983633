// The barrier wait policy chosen from the machine's load (io/wait_policy.hpp): /proc/stat parsed,
// the busy CPUs between two readings, and the choice, against hand-computed values.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>

#include "io/wait_policy.hpp"

using namespace grainlab;

TEST(WaitPolicy, ParsesTheTotalCpuLineOfProcStat) {
  // user nice system idle iowait irq softirq steal guest guest_nice
  const std::string text =
      "cpu  100 5 20 800 10 1 2 3 0 0\n"
      "cpu0 50 2 10 400 5 1 1 1 0 0\n"
      "intr 12345\n";
  const auto t = parse_cpu_times(text);
  ASSERT_TRUE(t);
  EXPECT_DOUBLE_EQ(t->busy, 100 + 5 + 20 + 1 + 2 + 3);
  EXPECT_DOUBLE_EQ(t->total, 131 + 800 + 10);
  EXPECT_DOUBLE_EQ(t->niced, 5);  // the nice column alone
  // an old kernel's line without irq, softirq and steal
  const auto old = parse_cpu_times("cpu 10 0 5 85 0\n");
  ASSERT_TRUE(old);
  EXPECT_DOUBLE_EQ(old->busy, 15);
  EXPECT_DOUBLE_EQ(old->total, 100);
  EXPECT_FALSE(parse_cpu_times("cpu0 1 2 3 4 5\nintr 1\n"));  // no total line
  EXPECT_FALSE(parse_cpu_times("cpu 1 2\n"));                 // too short
}

TEST(WaitPolicy, SumsOnlyTheCpusTheProcessMayRunOn) {
  const std::string text =
      "cpu  100 0 0 300 0 0 0 0\n"
      "cpu0 10 0 0 90 0 0 0 0\n"
      "cpu1 20 0 0 80 0 0 0 0\n"
      "cpu10 70 0 0 130 0 0 0 0\n";
  const auto two = parse_cpu_times(text, {1, 10});  // cpu1 must not be taken for cpu10
  ASSERT_TRUE(two);
  EXPECT_DOUBLE_EQ(two->busy, 20 + 70);
  EXPECT_DOUBLE_EQ(two->total, 100 + 200);
  const auto niced =
      parse_cpu_times("cpu0 10 4 0 86 0\ncpu1 0 30 0 70 0\ncpu2 0 9 0 91 0\n", {0, 1});
  ASSERT_TRUE(niced);
  EXPECT_DOUBLE_EQ(niced->niced, 4 + 30);
  const auto one = parse_cpu_times(text, {0});
  ASSERT_TRUE(one);
  EXPECT_DOUBLE_EQ(one->busy, 10);
  EXPECT_FALSE(parse_cpu_times(text, {0, 3}));  // cpu3 has no line
}

TEST(WaitPolicy, BusyCpusAreTheBusyShareOfTheElapsedJiffies) {
  // 2 CPUs, 200 jiffies elapsed in all, 100 of them busy: one CPU's worth
  EXPECT_DOUBLE_EQ(busy_cpus_between({50, 400}, {150, 600}, 2), 1.0);
  EXPECT_DOUBLE_EQ(busy_cpus_between({50, 400}, {55, 600}, 2), 0.05);
  EXPECT_DOUBLE_EQ(busy_cpus_between({50, 400}, {50, 400}, 2), 0.0);  // no time elapsed
}

TEST(WaitPolicy, NicedJiffiesCompeteOnlyWhereTheyDoNotYield) {
  CpuTimes t;
  t.busy = 130, t.total = 400, t.niced = 100;
  const CpuTimes yielding = competing_times(t, true);
  EXPECT_DOUBLE_EQ(yielding.busy, 30);
  EXPECT_DOUBLE_EQ(yielding.total, 400);
  EXPECT_DOUBLE_EQ(yielding.niced, 0);
  const CpuTimes counted = competing_times(t, false);
  EXPECT_DOUBLE_EQ(counted.busy, 130);
  EXPECT_DOUBLE_EQ(counted.niced, 100);
  // a nice 19 busy loop on one of 2 CPUs over 200 jiffies, this process's threads on the other
  CpuTimes before, after;
  before.busy = 1000, before.total = 5000, before.niced = 600;
  after.busy = 1200, after.total = 5200, after.niced = 700;
  EXPECT_DOUBLE_EQ(
      busy_cpus_between(competing_times(before, true), competing_times(after, true), 2), 1.0);
  EXPECT_DOUBLE_EQ(busy_cpus_between(before, after, 2), 2.0);
}

TEST(WaitPolicy, NicedProcessesYieldToAProcessAtNiceZeroOrBelowOnly) {
  const int own = (errno = 0, getpriority(PRIO_PROCESS, 0));
  ASSERT_EQ(errno, 0);
  EXPECT_EQ(niced_processes_yield(), own <= 0);
  // A child at a higher nice value than the processes it would count as niced: they do not
  // yield to it (raising one's own nice value needs no privilege).
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    if (setpriority(PRIO_PROCESS, 0, std::max(own, 0) + 5) != 0) _exit(2);
    _exit(niced_processes_yield() ? 1 : 0);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
}

TEST(WaitPolicy, AFollowingTeamSpinsLongerAndLongestForProcessesOfLowerPriority) {
  EXPECT_STREQ(barrier_spin_rounds(false, 0.0), "1000");
  EXPECT_STREQ(barrier_spin_rounds(true, 0.0), "20000");   // idle machine, a following team
  EXPECT_STREQ(barrier_spin_rounds(true, 0.45), "20000");  // less than half a CPU niced
  EXPECT_STREQ(barrier_spin_rounds(true, 0.5), "300000");  // a nice 19 loop on one of 2 CPUs
  EXPECT_STREQ(barrier_spin_rounds(false, 1.0), "1000");   // a fixed team: never long
  EXPECT_TRUE(spins_long_for_niced(true, 0.5));
  EXPECT_FALSE(spins_long_for_niced(true, 0.45));
  EXPECT_FALSE(spins_long_for_niced(false, 1.0));
  const std::string said = describe_niced_spin(1.02, 2, barrier_spin_rounds(true, 1.02));
  EXPECT_NE(said.find("1.0 of 2 CPUs"), std::string::npos) << said;
  EXPECT_NE(said.find("GOMP_SPINCOUNT=300000"), std::string::npos) << said;
}

TEST(WaitPolicy, ThreadsSleepAtOnceOnlyWhenTheyWouldNotEachFindAFreeCpu) {
  // idle 2-core machine, 2 threads: spin; a busy loop on one core: sleep
  EXPECT_EQ(choose_wait_policy(2, 2, 0.05), WaitPolicy::bounded_spin);
  EXPECT_EQ(choose_wait_policy(2, 2, 1.0), WaitPolicy::passive);
  // up to half a CPU of background load is tolerated
  EXPECT_EQ(choose_wait_policy(2, 2, 0.45), WaitPolicy::bounded_spin);
  EXPECT_EQ(choose_wait_policy(2, 2, 0.55), WaitPolicy::passive);
  // one thread never waits at a barrier; fewer threads than free CPUs spin
  EXPECT_EQ(choose_wait_policy(1, 2, 2.0), WaitPolicy::bounded_spin);
  EXPECT_EQ(choose_wait_policy(8, 16, 7.0), WaitPolicy::bounded_spin);
  EXPECT_EQ(choose_wait_policy(16, 16, 1.0), WaitPolicy::passive);
  const std::string said = describe_passive_choice(2, 2, 1.04);
  EXPECT_NE(said.find("1.0 of 2 CPUs busy"), std::string::npos) << said;
  EXPECT_NE(said.find("OMP_WAIT_POLICY=passive"), std::string::npos) << said;
}

TEST(WaitPolicy, BindingIsReadAsLibgompReadsIt) {
  // nothing set: no binding (grainlab may restart itself)
  EXPECT_FALSE(openmp_binds_threads(nullptr, nullptr, nullptr));
  // OMP_PROC_BIND: any policy binds, false does not, whatever the places say (case and blanks
  // as the runtime accepts them)
  EXPECT_TRUE(openmp_binds_threads("spread", nullptr, nullptr));
  EXPECT_TRUE(openmp_binds_threads("TRUE", nullptr, nullptr));
  EXPECT_TRUE(openmp_binds_threads("spread,close", nullptr, nullptr));
  EXPECT_FALSE(openmp_binds_threads("false", "threads", nullptr));
  EXPECT_FALSE(openmp_binds_threads(" FALSE ", nullptr, "0-1"));
  // places or a GOMP CPU list alone bind
  EXPECT_TRUE(openmp_binds_threads(nullptr, "threads", nullptr));
  EXPECT_TRUE(openmp_binds_threads(nullptr, nullptr, "0-1"));
  // set but empty: as unset
  EXPECT_FALSE(openmp_binds_threads("", " ", ""));
  EXPECT_NE(describe_bound_threads().find("OMP_WAIT_POLICY=passive"), std::string::npos);
}
