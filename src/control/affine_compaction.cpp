#include "control/affine_compaction.hpp"

#include <algorithm>

#include "core/simulation.hpp"
#include "measure/boundary.hpp"

namespace grainlab {

// Steps over which the mean wall stress is averaged (exponentially).
constexpr double averaging_steps = 100.0;

void AffineCompaction::before_step(Simulation& sim) {
  const std::vector<Wall>& walls = sim.walls();
  const double dt = sim.settings().time_step;
  double sum = 0.0;
  for (int k = 0; k < 6; ++k) sum += wall_stress(walls, k);
  mean_stress_ += (sum / 6.0 - mean_stress_) / averaging_steps;
  strain_rate_ = max_strain_rate_ * std::clamp(-stress_error(), -1.0, 1.0);
  const Vec3 low = box_low(walls), high = box_high(walls);
  const Vec3 centre = 0.5 * (low + high), size = high - low;
  // The beads now, the walls during the step (their velocity), by the same increment.
  sim.scale_positions(centre, 1.0 - strain_rate_ * dt);
  for (int k = 0; k < 6; ++k)
    sim.set_wall_velocity(k, (strain_rate_ * 0.5 * size[k / 2]) * walls[k].normal);
}

}  // namespace grainlab
