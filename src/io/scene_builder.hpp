// Turns a validated SceneConfig into the objects the core runs: the pair table with every
// derived constant, the particles (explicit and randomly inserted), the walls and the time step.
// Problems only visible at this stage (a material pair in use but not defined, particles
// overlapping or outside the walls, a region too small) are ConfigErrors too.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "contact/pair_table.hpp"
#include "contact/stability.hpp"
#include "core/particles.hpp"
#include "core/simulation.hpp"
#include "io/scene_config.hpp"

namespace grainlab {

// Constants of one material pair evaluated for the smallest particles that use it.
struct DerivedPair {
  std::string material_a, material_b;
  bool wall_pair = false;                               // b is a wall material
  double radius_a = 0.0;                                // smallest particle radius of material a, m
  double radius_b = 0.0;                                // of material b (0 for a wall), m
  double effective_radius = 0.0, effective_mass = 0.0;  // m, kg
  double normal_stiffness = 0.0, sliding_stiffness = 0.0,
         rolling_stiffness = 0.0;                      // N/m, N/m, N m/rad
  double normal_damping = 0.0, sliding_damping = 0.0;  // N s/m
  double damping_ratio_textbook = 0.0, damping_ratio = 0.0;
  double restitution = 0.0, friction = 0.0, arf = 0.0;
  double rolling_moment_per_force_at_half_percent = 0.0;  // mu_theta at U_n = 0.5 % of r*, m
  double collision_duration = 0.0;                        // s, Eq. 11 (textbook damping)
  bool can_touch = true;                                  // false: a one-bead material's own pair
  std::vector<SpringDashpot> spring_dashpots;  // every piece in use, with its critical step
  StepLimit step_limit;                        // the stable step of its most restrictive piece
};

struct TimeStepChoice {
  double collision_duration = 0.0;  // smallest t_c over the pairs in use, s
  double time_step = 0.0;           // s
  double dt_fraction = 0.0;         // dt / t_c
  bool explicit_dt = false;
  double stable_limit = INFINITY;     // largest step every spring-dashpot in use allows, s
  bool limited_by_stability = false;  // the stable limit lowered dt_fraction * t_c
  std::string stable_limit_set_by;    // the piece that sets stable_limit
  bool stable_limit_damped = false;   // that piece has a dashpot (lowering it helps)
};

PairTable build_pair_table(const SceneConfig& config);

// Particles of the scene in id order (explicit [[particle]] entries first, then the batches).
ParticleStore build_particles(const SceneConfig& config);

// Pairs in use (particle-particle and particle-wall) with their constants.
std::vector<DerivedPair> derive_pairs(const SceneConfig& config, const PairTable& table,
                                      const ParticleStore& particles);

TimeStepChoice choose_time_step(const SceneConfig& config, const std::vector<DerivedPair>& pairs);

SimulationSettings simulation_settings(const SceneConfig& config, const TimeStepChoice& dt,
                                       const ParticleStore& particles);

}  // namespace grainlab
