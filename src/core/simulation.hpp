// The step loop. One step of velocity Verlet (kick-drift-kick) for translation and rotation of
// spheres, read top-down as named stages:
//   half kick + drift -> move walls -> neighbour list (if stale) -> pair forces -> wall forces
//   -> gather per particle -> half kick -> health check.
// The core knows nothing of laboratory tests; controllers change wall velocities between steps.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "contact/pair_table.hpp"
#include "core/contact_store.hpp"
#include "core/neighbor_search.hpp"
#include "core/particles.hpp"
#include "core/state_io.hpp"
#include "core/step_listener.hpp"
#include "geometry/wall.hpp"

namespace grainlab {

struct SimulationSettings {
  double time_step = 0.0;              // dt, s
  double dt_fraction = 0.0;            // dt / t_c when dt was derived (0 when given explicitly)
  Vec3 gravity;                        // m/s^2
  double skin = 0.0;                   // Verlet skin, m
  double max_speed = 100.0;            // m/s; a faster particle means the run has blown up
  double max_overlap_fraction = 0.05;  // of the smaller radius
};

// Thrown when the integration has become unphysical; the message says what and how to fix it.
class BlowUpError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Simulation {
 public:
  Simulation(ParticleStore particles, std::vector<Wall> walls, PairTable table,
             SimulationSettings settings);

  // Restores a simulation saved by save_state; `table` must have the same materials.
  Simulation(StateReader& state, PairTable table);
  void save_state(StateWriter& state) const;

  void step();
  void advance(long steps) {
    for (long s = 0; s < steps; ++s) step();
  }

  // Listeners are called in the order attached; the Simulation does not own them.
  void attach(StepListener& listener) { listeners_.push_back(&listener); }
  void detach(StepListener& listener) { std::erase(listeners_, &listener); }

  // Commands (between steps).
  void set_wall_velocity(size_t wall, const Vec3& velocity) { walls_[wall].velocity = velocity; }
  void set_wall_external_force(size_t wall, const Vec3& force) {
    walls_[wall].external_force = force;
  }

  double time() const { return time_; }
  long step_count() const { return step_count_; }
  const SimulationSettings& settings() const { return settings_; }
  const ParticleStore& particles() const { return particles_; }
  ParticleStore& particles() { return particles_; }
  std::vector<Wall>& walls() { return walls_; }
  const std::vector<Wall>& walls() const { return walls_; }
  const PairTable& pair_table() const { return table_; }
  // Material-pair constants may change between steps (e.g. friction during compaction); call
  // pair_table_changed() afterwards. Which optional pieces exist is fixed at construction.
  PairTable& pair_table() { return table_; }
  void pair_table_changed() { refresh_contact_constants(); }
  const PairContacts& pair_contacts() const { return pairs_; }
  const WallContacts& wall_contacts() const { return wall_contacts_; }
  long rebuild_count() const { return neighbors_.rebuild_count(); }

  double kinetic_energy() const;     // translational + rotational, J
  long touching_pair_count() const;  // particle-particle contacts with F_n > 0
  double max_overlap_fraction() const { return max_overlap_fraction_; }

 private:
  void kick_and_drift();
  void half_kick();
  // drift: how long the positions moved since the last force evaluation (dt within step(); 0 for
  // the first evaluation of a fresh state, when no contact spring may advance).
  void compute_forces(double drift);
  void compute_pair_forces(double drift);
  void rebuild_neighbors();
  void refresh_contact_constants();
  void compute_wall_forces(double drift);
  void gather();
  void check_health() const;

  ParticleStore particles_;
  std::vector<Wall> walls_;
  PairTable table_;
  SimulationSettings settings_;
  ContactPieces pieces_;
  NeighborSearch neighbors_;
  PairContacts pairs_;
  WallContacts wall_contacts_;
  double time_ = 0.0;
  long step_count_ = 0;
  double max_overlap_fraction_ = 0.0;
  double max_speed2_ = 0.0;
  std::vector<StepListener*> listeners_;
};

}  // namespace grainlab
