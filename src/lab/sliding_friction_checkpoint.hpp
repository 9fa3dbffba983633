// Checkpoints of the sliding-friction test (DIR/checkpoint.bin, sealed with a checksum like every
// grainlab checkpoint, io/checkpoint_file.hpp). A test is a deposited bed and one pull per
// normal load, repeated per trial friction in the inverse mode. The checkpoint holds the pulls
// finished so far (keyed by the slider friction and the load), the bed, and the pull under way
// (its simulation state, rope and record), so `grainlab run --resume DIR` replays the test and
// takes what was done from the file: the results are bit-identical to an uninterrupted run's.
// Written every checkpoint_interval of wall time and on Ctrl-C; the bed's deposition itself (a
// few seconds) is not checkpointed inside.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "contact/pair_table.hpp"
#include "core/particles.hpp"
#include "io/checkpoint_clock.hpp"
#include "io/checkpoint_file.hpp"
#include "lab/sliding_friction.hpp"

namespace grainlab {

// A pull under way, at a point where it can be continued.
struct PullState {
  double friction = 0.0, load = 0.0;  // which pull: slider friction input and normal load (N)
  bool pulling = false;               // false: still settling under the load
  double anchor = 0.0;                // the rope's far end, m (x)
  double start_anchor = 0.0, start_time = 0.0;  // where and when the pull began
  long pull_steps = 0;                          // steps of the pull so far
  std::vector<std::array<double, 4>> record;    // LoadRun::record so far
  std::string simulation;                       // Simulation::save_state bytes
};

// The deposited bed of one trial friction (kept for each, so a resumed inverse search deposits
// none again).
struct SavedBed {
  double friction = 0.0;
  ParticleStore particles;
  double top = 0.0;  // m
};

class SlidingFrictionCheckpoints {
 public:
  // A fresh run (nothing done yet) writing to `path`.
  SlidingFrictionCheckpoints(std::string path, CheckpointHeader header, double interval_s);
  // The checkpoint at `path`, verified (the pull's simulation state restored once with `table`);
  // ConfigError naming it when it is damaged or not a sliding-friction checkpoint of a test with
  // `bead_material` (its index in `table`).
  static SlidingFrictionCheckpoints resume(const std::string& path, double interval_s,
                                           int bead_material, const PairTable& table);
  // Its header (test type and stored config), without loading the rest.
  static CheckpointHeader peek(const std::string& path);
  static bool is_one(const std::string& path);  // the file is a sliding-friction checkpoint

  // What was done before: a finished pull, the bed of a trial friction, the pull under way.
  const LoadRun* finished_pull(double friction, double load) const;
  const SavedBed* bed(double friction) const;
  std::optional<PullState> take_pull(double friction, double load);

  void record_bed(double friction, const ParticleStore& particles, double top);
  void record_pull(double friction, const LoadRun& run);
  // Inside a pull: saves (with `now()`, the pull's state) when the interval has passed, and on
  // Ctrl-C saves and throws Interrupted.
  template <class PullNow>
  void poll(PullNow&& now) {
    clock_.poll([&] { save(now()); }, [&] { return interrupted_message(); });
  }
  // What an interrupted run had done, in words (for the resume's message).
  std::string describe() const;
  double wall_time() const { return wall_time_before_ + clock_.session_time(); }
  const std::string& path() const { return path_; }

 private:
  void save(const PullState& pull) const;
  std::string interrupted_message() const;

  std::string path_;
  CheckpointHeader header_;
  CheckpointClock clock_;
  double wall_time_before_ = 0.0;  // s, sessions before this one
  std::vector<std::pair<double, LoadRun>> pulls_;
  std::vector<SavedBed> beds_;  // one per trial friction
  std::optional<PullState> pull_;
};

}  // namespace grainlab
