#include "lab/deposition.hpp"

#include <cmath>

namespace grainlab {

DepositionResult deposit(ParticleStore particles, const std::vector<Wall>& walls,
                         const PairTable& table, const SimulationSettings& settings,
                         const DepositionSettings& d) {
  Simulation sim(std::move(particles), walls, table, settings);
  const long check_steps = std::max(1L, static_cast<long>(d.check_interval / settings.time_step));
  DepositionResult out;
  while (sim.time() < d.max_time) {
    sim.advance(check_steps);
    double speed_sum = 0.0;
    const ParticleStore& p = sim.particles();
    for (size_t i = 0; i < p.size(); ++i) speed_sum += norm(p.velocity[i]);
    out.mean_speed = speed_sum / static_cast<double>(p.size());
    if (sim.time() >= d.min_time && out.mean_speed < d.rest_speed) {
      out.at_rest = true;
      break;
    }
  }
  out.time = sim.time();
  out.particles = sim.particles();
  return out;
}

}  // namespace grainlab
