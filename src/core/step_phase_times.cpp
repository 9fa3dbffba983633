#include "core/step_phase_times.hpp"

namespace grainlab {

void StepPhaseTimes::barrier_after(Part stage, double& since) {
  const double done = now();
  if (on_) add(stage, done - since);
#pragma omp barrier
  since = now();
  if (on_) add(static_cast<Part>(stage + 1), since - done);
}

}  // namespace grainlab
