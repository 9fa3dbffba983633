// The gather's walk chosen by measurement (core/gather_walk_trial.hpp).
#include "core/gather_walk_trial.hpp"

#include <algorithm>

namespace grainlab {

namespace {
// (for an even count the mean of the two middle values: with the lower one alone, a drift over
// the trial would put the flat blocks' median 16 steps later than the other's)
template <size_t N>
double median(std::array<double, N> seconds, int count) {
  const auto end = seconds.begin() + count, upper = seconds.begin() + count / 2;
  std::nth_element(seconds.begin(), upper, end);
  if (count % 2 == 1) return *upper;
  return 0.5 * (*std::max_element(seconds.begin(), upper) + *upper);
}
}  // namespace

// ABBA ABBA: blocks 0, 3, 4 and 7 flat
bool GatherWalkTrial::trial_walk() const {
  const int block = trial_step_ / block_steps;
  return block % 4 == 0 || block % 4 == 3;
}

bool GatherWalkTrial::flat(long n, int team, bool rule) {
  if (n != particles_ || team != team_) {
    particles_ = n;
    team_ = team;
    chosen_flat_ = rule;
    countdown_ = warm_up_steps;
    trial_step_ = -1;
  }
  return in_trial() ? trial_walk() : chosen_flat_;
}

void GatherWalkTrial::step_took(double seconds) {
  if (particles_ < 0) return;  // (no step has asked for its walk yet)
  if (!in_trial()) {
    if (countdown_ > 0) --countdown_;
    if (countdown_ == 0) {  // the next step opens a trial
      trial_step_ = 0;
      flat_count_ = one_by_one_count_ = 0;
    }
    return;
  }
  if (trial_walk())
    flat_seconds_[flat_count_++] = seconds;
  else
    one_by_one_seconds_[one_by_one_count_++] = seconds;
  if (++trial_step_ < trial_steps) return;
  last_flat_median_ = median(flat_seconds_, flat_count_);
  last_one_by_one_median_ = median(one_by_one_seconds_, one_by_one_count_);
  chosen_flat_ = last_flat_median_ <= last_one_by_one_median_;
  ++trials_done_;
  trial_step_ = -1;
  countdown_ = settled_steps;
}

}  // namespace grainlab
