// Gravity deposition: particles fall inside walls and come to rest. Used to make beds (sliding-
// friction test) and offered for specimen preparation.
#pragma once

#include <vector>

#include "contact/pair_table.hpp"
#include "core/simulation.hpp"

namespace grainlab {

struct DepositionSettings {
  double min_time = 0.0;         // s before rest is checked (e.g. the free-fall time)
  double max_time = 1.0;         // s of simulated time at most
  double rest_speed = 2e-3;      // m/s: at rest when the mean particle speed falls below
  double check_interval = 1e-3;  // s between checks
};

struct DepositionResult {
  ParticleStore particles;
  double time = 0.0;        // s simulated
  double mean_speed = 0.0;  // m/s at the end
  bool at_rest = false;
};

DepositionResult deposit(ParticleStore particles, const std::vector<Wall>& walls,
                         const PairTable& table, const SimulationSettings& settings,
                         const DepositionSettings& deposition);

}  // namespace grainlab
