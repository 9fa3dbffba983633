// The gather's walk chosen by timing the steps (core/gather_walk_trial.hpp): the trial's
// schedule, its choice from given step times, and that a change of team starts it again. The
// times are made up here (no clock is read), so the choice each test expects follows from the
// rule alone: the walk whose median step took less.
#include <gtest/gtest.h>

#include <functional>
#include <vector>

#include "core/gather_walk_trial.hpp"

namespace grainlab {
namespace {

using Trial = GatherWalkTrial;
constexpr long particles = 11636;
constexpr int team = 2;

// Runs `steps` steps: each asks for its walk (the rule's walk: `rule`), then reports the time
// `seconds(step, flat)`. Returns the walks taken.
std::vector<bool> run(Trial& trial, long steps, bool rule,
                      const std::function<double(long, bool)>& seconds, long first = 0) {
  std::vector<bool> walks;
  for (long s = first; s < first + steps; ++s) {
    const bool flat = trial.flat(particles, team, rule);
    EXPECT_EQ(flat, trial.flat(particles, team, rule)) << "step " << s << ": asked twice";
    walks.push_back(flat);
    trial.step_took(seconds(s, flat));
  }
  return walks;
}

// flat takes `flat_s`, one by one `one_s`
std::function<double(long, bool)> constant(double flat_s, double one_s) {
  return [=](long, bool flat) { return flat ? flat_s : one_s; };
}

TEST(GatherWalkTrial, KeepsTheRuleThroughTheWarmUpThenAlternatesFlatOneOneFlatInBlocks) {
  for (const bool rule : {false, true}) {
    Trial trial;
    const std::vector<bool> walks =
        run(trial, Trial::warm_up_steps + Trial::trial_steps, rule, constant(1e-3, 1e-3));
    for (long s = 0; s < Trial::warm_up_steps; ++s) EXPECT_EQ(walks[s], rule) << "step " << s;
    long flat = 0;
    for (int s = 0; s < Trial::trial_steps; ++s) {
      const int block = s / Trial::block_steps;
      const bool expected = block == 0 || block == 3 || block == 4 || block == 7;
      EXPECT_EQ(walks[Trial::warm_up_steps + s], expected) << "trial step " << s;
      flat += walks[Trial::warm_up_steps + s];
    }
    EXPECT_EQ(flat, Trial::trial_steps / 2);
    EXPECT_EQ(trial.trials_done(), 1);
  }
}

TEST(GatherWalkTrial, KeepsTheWalkWithTheSmallerMedianStepUntilTheNextTrial) {
  const long until_next = Trial::warm_up_steps + Trial::trial_steps + Trial::settled_steps;
  for (const bool flat_faster : {true, false}) {
    SCOPED_TRACE(flat_faster ? "flat faster" : "one by one faster");
    Trial trial;
    // 1 % apart, against the rule's walk
    const auto seconds = flat_faster ? constant(0.99e-3, 1e-3) : constant(1e-3, 0.99e-3);
    const std::vector<bool> walks = run(trial, until_next, !flat_faster, seconds);
    EXPECT_EQ(trial.trials_done(), 1);
    EXPECT_DOUBLE_EQ(trial.last_flat_median(), flat_faster ? 0.99e-3 : 1e-3);
    EXPECT_DOUBLE_EQ(trial.last_one_by_one_median(), flat_faster ? 1e-3 : 0.99e-3);
    for (long s = Trial::warm_up_steps + Trial::trial_steps; s < until_next; ++s)
      ASSERT_EQ(walks[s], flat_faster) << "step " << s;
    // the next trial, where the other walk has become the faster, turns the choice
    const auto turned = flat_faster ? constant(1e-3, 0.99e-3) : constant(0.99e-3, 1e-3);
    const std::vector<bool> next = run(trial, Trial::trial_steps + 1, !flat_faster, turned);
    EXPECT_EQ(trial.trials_done(), 2);
    EXPECT_EQ(next.back(), !flat_faster);
  }
}

// Steps that rebuild the list or write output take many times longer; fewer than half of either
// walk's steps do. A mean would follow them; the median does not.
TEST(GatherWalkTrial, IsNotMovedBySlowStepsOfEitherWalk) {
  for (const bool flat_faster : {true, false}) {
    Trial trial;
    // every fifth step 20 times slower, and the faster walk's every fourth as well (40 % of its
    // steps: its mean is then the larger)
    const auto seconds = [&](long s, bool flat) {
      const double base = flat == flat_faster ? 0.98e-3 : 1e-3;
      const bool slow = s % 5 == 0 || (flat == flat_faster && s % 4 == 0);
      return slow ? 20.0 * base : base;
    };
    run(trial, Trial::warm_up_steps + Trial::trial_steps, !flat_faster, seconds);
    ASSERT_EQ(trial.trials_done(), 1);
    EXPECT_EQ(trial.flat(particles, team, !flat_faster), flat_faster);
  }
}

// The machine slows down steadily through the trial by 10 %, ten times the walks' difference:
// both walks' blocks lie symmetrically in time (flat, one, one, flat twice), so the faster wins.
TEST(GatherWalkTrial, SeesThroughASteadyDriftOfTheMachinesSpeed) {
  for (const bool flat_faster : {true, false}) {
    Trial trial;
    const long start = Trial::warm_up_steps;
    const auto seconds = [&](long s, bool flat) {
      const double drift = 1.0 + 0.1 * static_cast<double>(s - start) / Trial::trial_steps;
      return drift * (flat == flat_faster ? 0.99e-3 : 1e-3);
    };
    run(trial, Trial::warm_up_steps + Trial::trial_steps, !flat_faster, seconds);
    ASSERT_EQ(trial.trials_done(), 1);
    EXPECT_EQ(trial.flat(particles, team, !flat_faster), flat_faster);
  }
}

// A new team (the step's team follows the free CPUs) or particle count: the rule's walk again,
// and a trial after a fresh warm-up.
TEST(GatherWalkTrial, StartsAgainWhenTheTeamOrTheParticleCountChanges) {
  Trial trial;
  run(trial, Trial::warm_up_steps + Trial::trial_steps, false, constant(0.9e-3, 1e-3));
  ASSERT_EQ(trial.trials_done(), 1);
  ASSERT_TRUE(trial.flat(particles, team, false));
  EXPECT_FALSE(trial.flat(particles, team + 1, false));  // the rule's
  for (long s = 0; s < Trial::warm_up_steps; ++s) {
    EXPECT_FALSE(trial.flat(particles, team + 1, false)) << "warm-up step " << s;
    trial.step_took(1e-3);
  }
  EXPECT_TRUE(trial.flat(particles, team + 1, false));  // the trial's first block: flat
  EXPECT_FALSE(trial.flat(particles + 1, team + 1, false));
}

}  // namespace
}  // namespace grainlab
