// Benchmark workloads, built with the library API like the test scenes (tests/support/scenes.hpp):
//
//   dense-11k  11,636 reference glass beads (d = 2 mm +- 1 %) prepared by the triaxial test's own
//              preparation in a 35 x 35 x 80 mm nominal box at 150 kPa (the triaxial specimen)
//   dense-88k  88,400 beads in 60 wide x 100 thick x 100 high mm at 150 kPa: the plane strain
//              reference specimen made by the lab's own preparation (grainlab prepare
//              examples/plane_strain/reference.toml), read by grainlab_bench --specimen
//   settle-1M  a million beads inserted loosely in a tall box, settling under gravity (opt-in)
//
// A dense packing is expensive to make, so it is made once and cached as a CSV (positions and
// radii at %.17g, which round-trips doubles exactly); the LAMMPS data file is written from the
// same CSV, so grainlab and the peer codes start from the same particle positions.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "contact/pair_table.hpp"
#include "core/simulation.hpp"

namespace grainlab::bench {

// The reference beads and pairs (docs/contact-model.md): glass-glass and glass-wall with the same
// e and mu so that the peer codes, which have one wall law, see the same model.
inline constexpr double glass_E = 46.2e9;        // Pa
inline constexpr double glass_density = 2500.0;  // kg/m^3
inline constexpr double glass_restitution = 0.926;
inline constexpr double glass_friction = 0.16;
inline constexpr double glass_rns = 0.5;
inline constexpr double bead_diameter = 2.0e-3;  // m (uniform in +-1 %)
inline constexpr double dt_fraction = 0.1;       // dt = 0.1 t_c (grainlab default)

struct Packing {
  std::vector<double> radius;
  std::vector<Vec3> position;
  Vec3 box_lo, box_hi;  // wall planes, m
};

// Material 0 glass, material 1 wall (E taken from the glass).
PairTable reference_table(double youngs_modulus, double restitution, double friction);

// The benchmark settings: dt = 0.1 t_c of the smallest bead, skin = 0.2 r_min.
SimulationSettings reference_settings(double min_radius, Vec3 gravity = {});

// Six plane walls on the faces of the box (geometry/cuboid_box.hpp), all of material 1.
std::vector<Wall> box_walls(const Vec3& lo, const Vec3& hi);

// The laboratory's preparation (lab/specimen.hpp) of `count` beads in a box of the target
// aspect ratio, compressed isotropically to 150 kPa with the benchmark's contact law.
Packing make_dense_packing(long count, const Vec3& target_size, uint64_t seed, bool verbose);

// Loose random insertion for the settling workload (no compression).
Packing make_loose_packing(long count, const Vec3& box_size, uint64_t seed);

// n_x x n_y x n_z copies of a packing side by side (a bigger dense workload with the same local
// structure: the cost per particle-step versus N without a new compression run).
Packing tile_packing(const Packing& p, int nx, int ny, int nz);

void write_packing_csv(const Packing& p, const std::string& path);
bool read_packing_csv(const std::string& path, Packing& p);  // false if missing or malformed

// LAMMPS data file (atom_style sphere: id type diameter density x y z), box = wall planes.
void write_lammps_data(const Packing& p, const std::string& path);

// A Simulation of the packing at rest with the reference contact law and walls.
Simulation make_simulation(const Packing& p, Vec3 gravity = {});

}  // namespace grainlab::bench
