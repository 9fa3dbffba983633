// Simulated flat-throw restitution test (docs/lab-tests.md). A bead leaves a horizontal launch
// lip with its lowest point at height H above a target (a wall of a chosen material, or the top
// of a fixed bead for glass on glass), rebounds, and the apex of the rebound gives h. As in the
// laboratory, e_sim = sqrt(h/H): heights are those of the bead's lowest point above the target
// surface, so that they equal the centre's fall and rise between touching heights.
#pragma once

#include <toml++/toml.h>

#include <string>
#include <vector>

#include "io/scene_run.hpp"

namespace grainlab {

struct FlatThrowSettings {
  std::string bead_material, target_material;
  double diameter = 2e-3;       // m
  double launch_height = 0.1;   // H, m (bead bottom above target surface)
  double launch_speed = 0.2;    // m/s, horizontal
  double spin = 0.0;            // rad/s about the axis normal to the throw plane (+y)
  bool target_is_bead = false;  // glass on glass: a fixed bead of the target material
  double dt_fraction = 0.002;   // of t_c: single impacts need a fine step (docs/contact-model.md)
  double gravity = 9.81;        // m/s^2
  double frame_rate = 1000.0;   // camera frames per second for the trajectory file
};

struct FlatThrowResult {
  double restitution_input = 0.0;
  double restitution_simulated = 0.0;                // sqrt(h/H)
  double restitution_velocity_ratio = 0.0;           // -v_z after / v_z before the contact
  double launch_height = 0.0, rebound_height = 0.0;  // H, h (m)
  double contact_duration = 0.0;                     // s
  double time_step = 0.0;                            // s
  double dt_fraction = 0.0;                          // time_step / t_c of the bead-target pair
  long contact_steps = 0;
  struct Frame {
    double t, x, z;  // bead centre; target surface at z = 0
  };
  std::vector<Frame> trajectory;
};

class PairTable;
FlatThrowResult simulate_flat_throw(const FlatThrowSettings& s, const PairTable& table,
                                    double bead_density);

// `grainlab run` entry for `[test] type = "flat_throw"`.
void run_flat_throw(const std::string& config_path, const toml::table& root,
                    const RunOptions& options);

}  // namespace grainlab
