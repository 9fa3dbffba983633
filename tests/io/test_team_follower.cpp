// The steps' team following the CPUs other processes leave free (io/team_follower.hpp): the
// other processes' load from two readings of /proc/stat and this process's CPU time, the team for
// it, and the two readings a change takes, against hand-computed values.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>

#include "core/team_limit.hpp"
#include "io/team_follower.hpp"

using namespace grainlab;

namespace {
CpuTimes times(double busy, double total) {
  CpuTimes t;
  t.busy = busy;
  t.total = total;
  return t;
}
}  // namespace

TEST(TeamFollower, OtherProcessesLoadIsTheBusyTimeLessThisProcesss) {
  // 2 CPUs for 1 s at 100 jiffies per second: 200 jiffies in all
  const CpuTimes before = times(1000, 5000);
  // both busy; this process used 1.0 s of CPU: the other processes one CPU
  EXPECT_DOUBLE_EQ(other_busy_cpus(before, times(1200, 5200), 2, 1.0, 100), 1.0);
  // both busy, all of it this process's: none
  EXPECT_DOUBLE_EQ(other_busy_cpus(before, times(1200, 5200), 2, 2.0, 100), 0.0);
  // 30 jiffies busy, this process 0.1 s: the others 0.2 CPU
  EXPECT_DOUBLE_EQ(other_busy_cpus(before, times(1030, 5200), 2, 0.1, 100), 0.2);
  // the process's time counted more finely than the jiffies: never below 0
  EXPECT_DOUBLE_EQ(other_busy_cpus(before, times(1100, 5200), 2, 1.2, 100), 0.0);
  // 4 CPUs for 0.5 s at 250 jiffies per second: 500 jiffies; 400 busy, 0.8 s this process's
  EXPECT_DOUBLE_EQ(other_busy_cpus(before, times(1400, 5500), 4, 0.8, 250), 1.6);
  // no time between the readings
  EXPECT_DOUBLE_EQ(other_busy_cpus(before, before, 2, 0.0, 100), 0.0);
}

TEST(TeamFollower, TheTeamTakesTheCpusLeftFreeWithinHalfACpu) {
  EXPECT_EQ(team_for_free_cpus(2, 2, 0.0), 2);
  EXPECT_EQ(team_for_free_cpus(2, 2, 0.5), 2);  // 1.5 free: two threads within half a CPU
  EXPECT_EQ(team_for_free_cpus(2, 2, 0.6), 1);
  EXPECT_EQ(team_for_free_cpus(2, 2, 1.0), 1);
  EXPECT_EQ(team_for_free_cpus(2, 2, 2.0), 1);  // never fewer than one
  EXPECT_EQ(team_for_free_cpus(16, 16, 3.2), 13);
  EXPECT_EQ(team_for_free_cpus(8, 16, 3.2), 8);  // never more than `most`
}

TEST(TeamFollower, ATeamChangesWhenTwoReadingsInARowAskForIt) {
  TeamChoice choice(2);
  EXPECT_EQ(choice.team(), 2);
  EXPECT_FALSE(choice.observe(2));
  EXPECT_FALSE(choice.observe(1));  // one reading: not yet
  EXPECT_EQ(choice.team(), 2);
  EXPECT_TRUE(choice.observe(1));
  EXPECT_EQ(choice.team(), 1);
  EXPECT_FALSE(choice.observe(2));
  EXPECT_FALSE(choice.observe(1));  // the burst is over: the next 2 starts afresh
  EXPECT_FALSE(choice.observe(2));
  EXPECT_EQ(choice.team(), 1);
  EXPECT_TRUE(choice.observe(2));
  EXPECT_EQ(choice.team(), 2);
  TeamChoice wide(16);  // a reading that wants another new team starts afresh too
  EXPECT_FALSE(wide.observe(12));
  EXPECT_FALSE(wide.observe(13));
  EXPECT_TRUE(wide.observe(13));
  EXPECT_EQ(wide.team(), 13);
}

TEST(TeamFollower, AGivenThreadCountIsKept) {
  EXPECT_FALSE(team_follows_free_cpus(true));
  setenv("OMP_NUM_THREADS", "2", 1);
  EXPECT_FALSE(team_follows_free_cpus(false));
  unsetenv("OMP_NUM_THREADS");
  setenv("OMP_PROC_BIND", "close", 1);
  EXPECT_FALSE(team_follows_free_cpus(false));
  unsetenv("OMP_PROC_BIND");
  EXPECT_EQ(team_follows_free_cpus(false), usable_cpus().size() > 1);
  EXPECT_EQ(follow_free_cpus(true, true), nullptr);
}

TEST(TeamFollower, StopsAtOnceAndClearsTheLimit) {
  const auto start = std::chrono::steady_clock::now();
  {
    TeamFollower follower({0, 1}, false, 0.01);
    step_team_limit = 2;  // as if it had chosen
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(step_team_limit.load(), 0);
  {
    TeamFollower slow({0, 1}, false, 60.0);  // woken, not waited for
  }
  const double slow_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 5.0);
  EXPECT_LT(slow_seconds, 5.0) << "the follower must stop when destroyed, not after its interval";
}
