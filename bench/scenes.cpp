#include "bench/scenes.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>
#include <stdexcept>

#include "contact/damping.hpp"
#include "contact/stability.hpp"
#include "contact/time_step.hpp"
#include "core/random_insertion.hpp"
#include "geometry/cuboid_box.hpp"
#include "io/progress.hpp"
#include "lab/specimen.hpp"

namespace grainlab::bench {

PairTable reference_table(double youngs_modulus, double restitution, double friction) {
  PairTable t(
      {Material{"glass", youngs_modulus, 0.245, glass_density}, Material{"wall", {}, {}, {}}});
  PairProperties p;
  p.restitution = restitution;
  p.friction = friction;
  p.rns = glass_rns;
  t.set(0, 0, p);
  t.set(0, 1, p);
  return t;
}

SimulationSettings reference_settings(double min_radius, Vec3 gravity) {
  SimulationSettings s;
  // The one time-step rule (contact/stability.hpp) for the benchmark's law.
  const MaterialTimeStep step =
      material_time_step(dt_fraction, reference_table(glass_E, glass_restitution, glass_friction),
                         0, {0, 1}, min_radius, glass_density);
  s.time_step = step.time_step;
  s.dt_fraction = step.dt_fraction;
  s.gravity = gravity;
  s.skin = verlet_skin(2.0 * min_radius);
  return s;
}

std::vector<Wall> box_walls(const Vec3& lo, const Vec3& hi) {
  return cuboid_walls(lo, hi, 1, 1);
}

namespace {

double min_radius_of(const std::vector<double>& r) {
  return *std::min_element(r.begin(), r.end());
}

ParticleStore store_of(const Packing& p, double density) {
  ParticleStore s;
  for (size_t i = 0; i < p.radius.size(); ++i)
    s.add(static_cast<uint32_t>(i), 0, p.radius[i], density, p.position[i], {}, {}, false);
  return s;
}

std::vector<Sphere> insert(long count, const Vec3& lo, const Vec3& hi, uint64_t seed) {
  std::vector<Sphere> spheres;
  spheres.reserve(count);
  std::mt19937_64 rng(seed);
  InsertionRegion box;
  box.box_min = lo;
  box.box_max = hi;
  const long placed = insert_random_spheres(spheres, box, count, 0.99 * bead_diameter,
                                            1.01 * bead_diameter, rng, 20000);
  if (placed != count)
    throw std::runtime_error(fmt::format("insertion placed only {} of {} beads", placed, count));
  return spheres;
}

}  // namespace

Packing make_loose_packing(long count, const Vec3& box_size, uint64_t seed) {
  Packing p;
  p.box_lo = {};
  p.box_hi = box_size;
  for (const Sphere& s : insert(count, p.box_lo, p.box_hi, seed)) {
    p.radius.push_back(s.radius);
    p.position.push_back(s.centre);
  }
  return p;
}

// The dense packings are made by the laboratory's own preparation (lab/specimen.hpp): beads on a
// jittered lattice, compressed isotropically by six servo-held walls to 150 kPa, frictionless
// until the solid fraction reaches 0.60 and with the benchmark's contact law after (glass-glass
// and glass-wall pairs alike), so the benchmark runs on the same kind of specimen the triaxial
// test shears.
Packing make_dense_packing(long count, const Vec3& target_size, uint64_t seed, bool verbose) {
  SpecimenSettings s;
  s.count = count;
  s.diameter = bead_diameter;
  s.diameter_tolerance = 0.01 * bead_diameter;
  s.nominal_box = target_size;
  s.confining_stress = 150e3;
  s.target_solid_fraction = 0.60;  // frictionless compaction to it (fast), then friction on
  s.bead_material = 0;
  s.lateral_material = s.platen_material = 1;
  s.density = glass_density;
  s.dt_fraction = dt_fraction;
  s.seed = seed;
  Progress progress("packing", !verbose);
  const Specimen specimen = prepare_cuboid_specimen(
      s, reference_table(glass_E, glass_restitution, glass_friction), &progress);
  progress.finish(fmt::format("solid fraction {:.4f}, equilibrium {}", specimen.solid_fraction,
                              specimen.equilibrium_reached ? "reached" : "not reached"));
  Packing p;
  const ParticleStore& q = specimen.particles;  // in id order
  p.radius = q.radius;
  p.position = q.position;
  p.box_lo = specimen.low;
  p.box_hi = specimen.high;
  return p;
}

// Every other copy is mirrored, so that across each interface a bead faces its own mirror image:
// a wall contact (k_n = pi E r, overlap U) becomes a pair contact (k_n = pi E r/2, overlap 2U)
// with the same force, and the tiled packing is in the same static equilibrium as the original
// (plain translated copies do not interlock and the whole packing relaxes, losing its contacts).
Packing tile_packing(const Packing& p, int nx, int ny, int nz) {
  Packing t;
  const Vec3 size = p.box_hi - p.box_lo;
  t.box_lo = p.box_lo;
  t.box_hi = p.box_lo + Vec3{nx * size.x, ny * size.y, nz * size.z};
  int c[3];
  for (c[2] = 0; c[2] < nz; ++c[2])
    for (c[1] = 0; c[1] < ny; ++c[1])
      for (c[0] = 0; c[0] < nx; ++c[0])
        for (size_t q = 0; q < p.radius.size(); ++q) {
          Vec3 x = p.position[q];
          for (int d = 0; d < 3; ++d) {
            const double local = x[d] - p.box_lo[d];
            x[d] = p.box_lo[d] + c[d] * size[d] + (c[d] % 2 == 1 ? size[d] - local : local);
          }
          t.radius.push_back(p.radius[q]);
          t.position.push_back(x);
        }
  return t;
}

void write_packing_csv(const Packing& p, const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw std::runtime_error("cannot write " + path);
  std::fprintf(f, "# grainlab benchmark packing; box (wall planes) in m:\n");
  std::fprintf(f, "# box %.17g %.17g %.17g %.17g %.17g %.17g\n", p.box_lo.x, p.box_lo.y, p.box_lo.z,
               p.box_hi.x, p.box_hi.y, p.box_hi.z);
  std::fprintf(f, "radius_m,x_m,y_m,z_m\n");
  for (size_t i = 0; i < p.radius.size(); ++i)
    std::fprintf(f, "%.17g,%.17g,%.17g,%.17g\n", p.radius[i], p.position[i].x, p.position[i].y,
                 p.position[i].z);
  std::fclose(f);
}

bool read_packing_csv(const std::string& path, Packing& p) {
  std::ifstream in(path);
  if (!in) return false;
  std::string line;
  Packing q;
  bool have_box = false;
  while (std::getline(in, line)) {
    if (line.rfind("# box ", 0) == 0) {
      std::istringstream s(line.substr(6));
      s >> q.box_lo.x >> q.box_lo.y >> q.box_lo.z >> q.box_hi.x >> q.box_hi.y >> q.box_hi.z;
      have_box = !s.fail();
      continue;
    }
    if (line.empty() || line[0] == '#' || line[0] == 'r') continue;
    double r, x, y, z;
    if (std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf", &r, &x, &y, &z) != 4) return false;
    q.radius.push_back(r);
    q.position.push_back({x, y, z});
  }
  if (!have_box || q.radius.empty()) return false;
  p = std::move(q);
  return true;
}

void write_lammps_data(const Packing& p, const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw std::runtime_error("cannot write " + path);
  // The simulation box encloses the wall planes with a margin; the walls (fix wall/gran) hold
  // the particles, the box boundaries never touch them.
  const double margin = 2.0 * bead_diameter;
  std::fprintf(f, "grainlab benchmark packing (%zu beads)\n\n%zu atoms\n1 atom types\n\n",
               p.radius.size(), p.radius.size());
  std::fprintf(
      f, "%.17g %.17g xlo xhi\n%.17g %.17g ylo yhi\n%.17g %.17g zlo zhi\n\nAtoms # sphere\n\n",
      p.box_lo.x - margin, p.box_hi.x + margin, p.box_lo.y - margin, p.box_hi.y + margin,
      p.box_lo.z - margin, p.box_hi.z + margin);
  for (size_t i = 0; i < p.radius.size(); ++i)
    std::fprintf(f, "%zu 1 %.17g %.17g %.17g %.17g %.17g\n", i + 1, 2.0 * p.radius[i],
                 glass_density, p.position[i].x, p.position[i].y, p.position[i].z);
  std::fclose(f);

  // The contact constants in the peer codes' form (LAMMPS gran/hooke/history: constant kn, kt in
  // N/m, damping force m* gamma_n v_n, so gamma_n = c_n / m* in 1/s). grainlab's k_n = pi E r*
  // varies by +-1 % with the bead sizes; the peers get the value of the mean bead. A wall
  // contact has r* = r, m* = m: twice the stiffness, the same gamma_n (k_n/m* is the same).
  double r_mean = 0.0;
  for (double r : p.radius) r_mean += r;
  r_mean /= static_cast<double>(p.radius.size());
  const double mass = glass_density * 4.0 / 3.0 * std::numbers::pi * r_mean * r_mean * r_mean;
  const double kn = std::numbers::pi * glass_E * 0.5 * r_mean, m_eff = 0.5 * mass;
  const double zeta = damping_ratio_for_restitution(glass_restitution);
  const double gamma_n = 2.0 * zeta * std::sqrt(kn / m_eff);
  const SimulationSettings s = reference_settings(min_radius_of(p.radius));
  std::FILE* g = std::fopen((path + ".params").c_str(), "w");
  if (!g) throw std::runtime_error("cannot write " + path + ".params");
  std::fprintf(g, "# grainlab reference contact constants for %s (written by grainlab_bench)\n",
               path.c_str());
  std::fprintf(g,
               "variable kn equal %.17g\nvariable kt equal %.17g\nvariable gamma_n equal %.17g\n",
               kn, glass_rns * kn, gamma_n);
  std::fprintf(g, "variable kn_wall equal %.17g\nvariable kt_wall equal %.17g\n", 2.0 * kn,
               2.0 * glass_rns * kn);
  std::fprintf(g, "variable mu equal %.17g\nvariable dt equal %.17g\nvariable skin equal %.17g\n",
               glass_friction, s.time_step, s.skin);
  std::fprintf(g,
               "variable xlo equal %.17g\nvariable xhi equal %.17g\nvariable ylo equal %.17g\n"
               "variable yhi equal %.17g\nvariable zlo equal %.17g\nvariable zhi equal %.17g\n",
               p.box_lo.x, p.box_hi.x, p.box_lo.y, p.box_hi.y, p.box_lo.z, p.box_hi.z);
  std::fclose(g);
}

Simulation make_simulation(const Packing& p, Vec3 gravity) {
  return Simulation(store_of(p, glass_density), box_walls(p.box_lo, p.box_hi),
                    reference_table(glass_E, glass_restitution, glass_friction),
                    reference_settings(min_radius_of(p.radius), gravity));
}

}  // namespace grainlab::bench
