// Progress output for long runs: percent, simulated time and ETA on stderr. On a terminal the
// line redraws in place; otherwise a plain line every `interval_s` seconds of wall time.
#pragma once

#include <chrono>
#include <string>

namespace grainlab {

class Progress {
 public:
  Progress(std::string label, bool quiet, double interval_s = 5.0);
  // fraction in [0, 1]; `detail` e.g. "t = 1.2e-3 s" or "axial strain 4.1 %". A negative
  // fraction: how far the run is cannot be told (it stops on a criterion, e.g. equilibrium), so
  // the line shows the detail and the elapsed time, no percentage and no ETA.
  void update(double fraction, const std::string& detail);
  static constexpr double unknown_fraction = -1.0;
  void finish(const std::string& detail);
  // A line of its own (unless quiet), e.g. where a resumed run continues.
  void message(const std::string& text);

 private:
  std::string label_;
  bool quiet_, tty_;
  double interval_s_;
  double first_fraction_ = -1.0;  // at the first update: a resumed run starts part-way
  std::chrono::steady_clock::time_point first_update_;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace grainlab
