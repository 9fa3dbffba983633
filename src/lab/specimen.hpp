// Specimen preparation for element tests (docs/lab-tests.md): N spheres placed without
// overlap in a cuboid, then compressed isotropically by six stress-controlled walls to the
// confining stress, with the friction during compaction steered so that the solid fraction
// hits a target. The prepared specimen is saved and reused by any number of tests.
//
// Placement: random sequential insertion jams near a solid fraction of 0.35, far below the
// reference case's 11,636 beads in 35 x 35 x 80 mm (0.50). grainlab therefore places the beads
// on randomly chosen, randomly jittered sites of a cubic lattice 1.1 largest diameters
// apart, in the smallest box of the nominal aspect ratio that holds them (solid fraction about
// 0.42); the compression then shrinks the specimen, and the final dimensions are reported.
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <string>

#include "contact/pair_table.hpp"
#include "contact/stability.hpp"
#include "core/particles.hpp"
#include "core/simulation.hpp"
#include "io/checkpoint_file.hpp"

namespace grainlab {

class Progress;

// How the specimen is compacted to the confining stress: by the six walls' servos (the beads
// follow the walls), or by an affine strain of the whole box (control/affine_compaction.hpp; the
// stress builds everywhere at once, needed for large specimens), then held by the walls' servos.
enum class Compaction { walls, affine };

struct SpecimenSettings {
  long count = 11636;
  double diameter = 2e-3;                       // m, mean
  double diameter_tolerance = 0.02e-3;          // m: diameters uniform in [d - tol, d + tol]
  Vec3 nominal_box{0.035, 0.035, 0.08};         // m: sets the aspect ratio
  double confining_stress = 150e3;              // Pa
  std::optional<double> target_solid_fraction;  // steer the compaction friction to hit it
  // Bead-bead friction while compacting: below the measured one packs denser, above it looser
  // (the measured friction is switched on at the target, or once the packing has settled or its
  // solid fraction has stopped changing).
  // Unset: 0 with a target solid fraction, else the measured friction.
  std::optional<double> compaction_friction;
  // false: the walls are frictionless for the whole preparation (no shear locked into the wall
  // contacts, so the specimen starts isotropic); their measured friction acts only in the test.
  bool wall_friction_while_preparing = true;
  int bead_material = 0, lateral_material = 0, platen_material = 0;
  double density = 2500.0;  // kg/m^3
  double dt_fraction = 0.1;
  double max_strain_rate = 10.0;  // 1/s, wall speed cap during compaction
  Compaction compaction = Compaction::walls;
  // e of every bead contact while compacting (faster rest); the preparation's step is lowered as
  // far as these contacts need (0.3: 0.075 t_c for the reference beads, 0.4 keeps 0.1 t_c)
  double compaction_restitution = 0.3;
  double stress_tolerance = 0.005;     // equilibrium: wall stresses within 0.5 % of the target
  double unbalanced_tolerance = 1e-4;  // and mean unbalanced / mean contact force below this
  double max_time = 0.5;               // s simulated at most
  uint64_t seed = 1;

  double min_radius() const { return 0.5 * (diameter - diameter_tolerance); }  // m, smallest bead
};

// The time step of a test on this kind of specimen (contact/stability.hpp, material_time_step):
// the beads with each other, with the lateral walls and with the platens, at `min_radius`.
MaterialTimeStep specimen_time_step(const SpecimenSettings& s, const PairTable& table,
                                    double min_radius);

// The bead contacts of `measured` with their restitution lowered as far as a run at `time_step`
// stays stable (contact/stability.hpp), but not below compaction_restitution: the most damped
// contacts that can bring a specimen to rest at the test's own step. Only the static state is
// kept, which does not depend on e (a re-equilibration before the loading).
PairTable resting_contacts(const SpecimenSettings& s, const PairTable& measured, double time_step,
                           double min_radius);

struct Specimen {
  ParticleStore particles;
  Vec3 low, high;  // box (wall positions), m
  double solid_fraction = 0.0;
  double coordination_number = 0.0;
  double unbalanced_force_ratio = 0.0;
  double max_stress_error = 0.0;     // relative, over the six walls
  double compaction_friction = 0.0;  // bead-bead friction used while compacting
  bool wall_friction_while_preparing = true;
  // Love-Weber average stress at the end of the preparation (Pa, compression positive): equal to
  // the confining stress on every axis when the specimen is isotropic; none for a specimen read
  // from a file, which carries no contact forces.
  std::optional<std::array<double, 3>> love_weber_diagonal;
  double earlier_wall_time = 0.0;  // s, the preparation's sessions before a resume
  double compaction_restitution = 0.0;
  bool equilibrium_reached = false;
  bool target_reached = true;   // false: the target solid fraction was out of reach
  double simulated_time = 0.0;  // s
  double time_step = 0.0;       // s, the preparation's step (0: read from a file)
  long steps = 0;               // the preparation's steps
  Vec3 inserted_box;            // m, the box the beads were placed in
  double inserted_solid_fraction = 0.0;
};

// Holds the six walls of a cuboid specimen (geometry/cuboid_box.hpp) at an isotropic stress by
// servo control until the wall stresses are within stress_tolerance of the target and the
// unbalanced force ratio is below unbalanced_tolerance, or max_time more has been simulated.
// `on_check` runs every 200 steps and returns whether the run may stop there (e.g. false while the
// compaction friction is still being steered).
struct HoldCriteria {
  double confining_stress;  // Pa
  double max_strain_rate;   // 1/s, wall speed cap
  double stress_tolerance;  // relative
  double unbalanced_tolerance;
  double max_time;  // s
};
struct HoldState {
  double solid_fraction = 0.0, max_stress_error = 0.0, unbalanced = 1.0;
  bool reached = false;
};
HoldState hold_isotropic(Simulation& sim, const HoldCriteria& criteria,
                         const std::function<bool(const HoldState&)>& on_check);

// Periodic checkpoints of a preparation: every `interval_s` of wall time, on Ctrl-C and at its
// end, the preparation's whole state goes to `path` (sealed, io/checkpoint_file.hpp) with the
// test type and config it belongs to; with `resume` the preparation continues from that file
// and ends with the same specimen, bit for bit, as an uninterrupted one.
struct PreparationCheckpoints {
  std::string path;
  double interval_s = 600.0;
  CheckpointHeader header;  // test type and config
  bool resume = false;
};

Specimen prepare_cuboid_specimen(const SpecimenSettings& s, PairTable table, Progress* progress,
                                 const PreparationCheckpoints* checkpoints = nullptr);

// The test type and config stored in a preparation checkpoint; ConfigError if it is damaged.
CheckpointHeader peek_preparation_checkpoint(const std::string& path);

// Exactly reloadable text form (17 significant digits): one header line with the box, then
// id,material,radius,x,y,z per particle.
void save_specimen(const std::string& path, const Specimen& specimen);
// Every record is checked before use (ConfigError naming the file and line): ids 0, 1, 2, ...,
// the material index equal to the config's bead material, finite coordinates inside the box,
// a finite radius > 0.
Specimen load_specimen(const std::string& path, double density, int bead_material);

}  // namespace grainlab
