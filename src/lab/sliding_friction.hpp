// Simulated sliding-friction test (docs/lab-tests.md). A bed of beads (a few layers, deposited
// by gravity in a box) carries a rigid flat slider faced with the boundary material. The slider
// has mass, is pressed down by a normal load P and pulled horizontally through a spring (the
// rope and force sensor) whose far end moves at speed V. The mean rope force while sliding is F;
// over several loads the slope of F against P (through the origin) is the apparent friction
// coefficient, which need not equal the input contact friction mu_s: beads roll and rearrange
// under the slider (docs/lab-tests.md). By default the slider covers the whole bed for the whole
// pull (an interface shear test), so the bed stays confined and no edge ploughs through it.
#pragma once

#include <toml++/toml.h>

#include <array>
#include <string>
#include <vector>

#include "contact/pair_table.hpp"
#include "io/scene_run.hpp"

namespace grainlab {

struct SlidingFrictionSettings {
  std::string bead_material = "glass", slider_material;
  double diameter = 2e-3;       // m (beads uniform within +-1 %)
  double bed_length = 0.04;     // m, along the pull (x)
  double bed_width = 0.016;     // m
  double slider_length = 0.01;  // m
  // Clearance between each side of the slider and the box's side wall, m (< 0: a fifth of a
  // diameter). Below a bead radius no bead can enter it: with a one-diameter clearance a bead
  // wedged between the slider's edge and the wall and jammed the slider (8.7 N mean rope force
  // at P = 0.2 N).
  double slider_side_gap = -1.0;
  // The slider is longer than the bed by the pull and two diameters, so it covers the whole bed
  // for the whole pull (an interface shear test: the bed is confined by the box and the slider,
  // nothing can be pushed ahead of an edge or squeezed out from under the face).
  // slider_length is then derived.
  bool slider_covers_bed = false;
  int layers = 3;                                 // bead count = layers * (length/d) * (width/d)
  std::vector<double> loads{0.1, 0.2, 0.3, 0.4};  // P, N
  double speed = 0.05;                            // V, m/s
  double slide_distance = 0.012;     // m pulled per load (several diameters: steady sliding)
  double spring_stiffness = 5000.0;  // rope + sensor, N/m
  double slider_mass = 0.01;         // kg
  // Coulomb check: a single layer of fixed beads, in a patch that stays under the slider's face
  // for the whole pull (no edge ever meets a bead), so F = mu_s P exactly.
  bool fixed_bed = false;
  double dt_fraction = 0.1;
  double gravity = 9.81;  // m/s^2
  unsigned long seed = 1;
};

struct LoadRun {
  double load = 0.0;        // P, N
  double mean_force = 0.0;  // F over the second half of the slide, N
  double force_sd = 0.0;    // N
  std::vector<std::array<double, 4>>
      record;  // t (s), pulled distance (m), rope force (N), slider z (m)
};

struct SlidingFrictionResult {
  double friction_input = 0.0;     // mu_s of the slider-bead pair
  double friction_apparent = 0.0;  // slope of F against P through the origin
  double friction_apparent_se = 0.0;
  double r_squared = 0.0;
  int bead_count = 0;
  double bed_height = 0.0;  // m, top of the bed
  double time_step = 0.0;
  std::vector<LoadRun> runs;
};

class Progress;
// The bed is deposited once and reused for every load.
// The time step of the test and the steps one pull takes (slide_distance / speed / dt).
double sliding_time_step(const SlidingFrictionSettings& s, const PairTable& table, double density);

// With `checkpoints`, what an interrupted run did is taken from them and what this run does is
// recorded there (lab/sliding_friction_checkpoint.hpp).
class SlidingFrictionCheckpoints;
SlidingFrictionResult simulate_sliding_friction(const SlidingFrictionSettings& s,
                                                const PairTable& table, double bead_density,
                                                Progress* progress = nullptr,
                                                SlidingFrictionCheckpoints* checkpoints = nullptr);

// `grainlab run` entry for `[test] type = "sliding_friction"` (with optional inverse mode).
void run_sliding_friction(const std::string& config_path, const toml::table& root,
                          const RunOptions& options);

}  // namespace grainlab
