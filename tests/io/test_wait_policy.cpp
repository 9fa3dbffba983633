// The barrier wait policy chosen from the machine's load (io/wait_policy.hpp): /proc/stat parsed,
// the busy CPUs between two readings, and the choice, against hand-computed values.
#include <gtest/gtest.h>

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
