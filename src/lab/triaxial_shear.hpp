// The shearing stage of the triaxial test as a resumable loop: everything it carries from step
// to step (the simulation, the servo integrals, the running peaks and error sums, the curve so
// far) is in ShearRun, which a checkpoint saves whole and restores exactly.
#pragma once

#include <array>
#include <string>

#include "core/simulation.hpp"
#include "io/progress.hpp"

namespace grainlab {

struct ShearProgress {  // plain values, saved as they are
  long step = 0, total_steps = 0, next_output = 0, lateral_samples = 0;
  double platen_speed = 0, strain_rate = 0, confining_stress = 0, diameter = 0, density = 0;
  double output_strain_interval = 0;
  Vec3 size0;
  double peak_axial = 0, peak_strain = 0, peak_deviator = 0, peak_ratio = 0, max_inertial = 0;
  double lateral_error2 = 0, max_lateral_error = 0, last_axial = 0, last_strain = 0;
  // Once quasi-static (axial strain > 0.5 %): largest |particle - boundary| / boundary over the
  // three axes, and the running sum of platen stress / boundary axial stress - 1 (the share of
  // the axial load the lateral walls' friction carries).
  double worst_agreement = 0, platen_excess_sum = 0;
  long platen_excess_rows = 0;
  double wall_time_before = 0;     // s spent in earlier sessions of this run
  double vtk_strain_interval = 0;  // 0: no snapshots
  long next_vtk = 0;
  std::array<double, 6> servo_integral{};
  // Averages over the current output interval (a laboratory load cell integrates too): the six
  // wall stresses every step, the Love-Weber and boundary-average diagonals every
  // `stress_sample_steps` steps (the same steps, so they differ only by the particles' inertia).
  std::array<double, 6> wall_stress_sum{};
  long wall_samples = 0;
  std::array<double, 3> particle_stress_sum{}, boundary_stress_sum{};
  long particle_samples = 0;
};

inline constexpr long stress_sample_steps = 50;

struct ShearRun {
  Simulation sim;
  ShearProgress progress;
  std::string curve_rows;  // curve.csv rows written so far (without header)
  std::string run_info;    // JSON text of what the summary needs from before the shearing
  std::string vtk_index;   // <DataSet> lines of particles.pvd so far
  std::string config_path, config_text;
};

inline constexpr const char* curve_header =
    "time_s,axial_strain,lateral_strain_x,lateral_strain_y,volumetric_strain,"
    "axial_stress_walls_Pa,lateral_stress_x_walls_Pa,lateral_stress_y_walls_Pa,"
    "axial_stress_particles_Pa,lateral_stress_x_particles_Pa,lateral_stress_y_particles_Pa,"
    "axial_stress_boundary_Pa,lateral_stress_x_boundary_Pa,lateral_stress_y_boundary_Pa,"
    "deviator_stress_Pa,mean_stress_Pa,stress_ratio,solid_fraction,coordination_number,"
    "inertial_number,unbalanced_force_ratio";

// Runs the shearing to its end. Writes DIR/checkpoint.bin every `checkpoint_interval_s` of wall
// time and, on Ctrl-C / SIGTERM, a last one before throwing Interrupted.
void shear(ShearRun& run, const std::string& dir, double checkpoint_interval_s, Progress& progress);

void save_checkpoint(const ShearRun& run, const std::string& path);
// Throws ConfigError for a missing or damaged checkpoint.
ShearRun load_checkpoint(const std::string& path, PairTable table);
// The config stored in a checkpoint (to rebuild the pair table before load_checkpoint).
void peek_checkpoint_config(const std::string& path, std::string& config_path,
                            std::string& config_text);

}  // namespace grainlab
