#include "measure/interval_stresses.hpp"

#include <algorithm>

#include "measure/boundary.hpp"
#include "measure/specimen_state.hpp"

namespace grainlab {

void IntervalStresses::add_walls(const Simulation& sim) {
  for (int k = 0; k < 6; ++k) wall_sum[k] += wall_stress(sim.walls(), k);
  ++wall_samples;
}

void IntervalStresses::add_specimen(const Simulation& sim) {
  const Vec3 lo = box_low(sim.walls()), hi = box_high(sim.walls());
  const double volume = box_volume(sim.walls());
  const Tensor3 particles = love_weber_stress(sim, volume);
  const Tensor3 boundary = boundary_stress(sim, 0.5 * (lo + hi), volume);
  for (int a = 0; a < 3; ++a) {
    particle_sum[a] += particles[a][a];
    boundary_sum[a] += boundary[a][a];
  }
  ++particle_samples;
}

IntervalStresses::Averages IntervalStresses::take(const Simulation& sim) {
  if (wall_samples == 0) {  // nothing accumulated (the first row): the state itself
    for (int k = 0; k < 6; ++k) wall_sum[k] = wall_stress(sim.walls(), k);
    wall_samples = 1;
    particle_sum = {}, boundary_sum = {}, particle_samples = 0;
    add_specimen(sim);
  }
  Averages a;
  for (int k = 0; k < 6; ++k) a.wall[k] = wall_sum[k] / wall_samples;
  for (int d = 0; d < 3; ++d) {
    a.particle[d] = particle_sum[d] / std::max(1L, particle_samples);
    a.boundary[d] = boundary_sum[d] / std::max(1L, particle_samples);
  }
  *this = IntervalStresses{};
  return a;
}

}  // namespace grainlab
