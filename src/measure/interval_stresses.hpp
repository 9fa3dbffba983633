// Stresses averaged over an output interval, as a laboratory load cell integrates: the six wall
// stresses of a box every step, and the Love-Weber and boundary-average diagonals every few steps
// (a pass over all contacts; sampled on the same steps, so the two differ only by the particles'
// inertia). Plain values, saved in a checkpoint as they are.
#pragma once

#include <array>

#include "core/simulation.hpp"

namespace grainlab {

struct IntervalStresses {
  std::array<double, 6> wall_sum{};  // Pa, per wall of the box
  long wall_samples = 0;
  std::array<double, 3> particle_sum{}, boundary_sum{};  // Pa, diagonals
  long particle_samples = 0;

  void add_walls(const Simulation& sim);
  void add_specimen(const Simulation& sim);

  struct Averages {
    std::array<double, 6> wall;
    std::array<double, 3> particle, boundary;
  };
  // The averages since the last call (the current state if nothing was added), and a reset.
  Averages take(const Simulation& sim);
};

}  // namespace grainlab
