// Small scenes built in code for the verification tests: glass-like spheres, a pair table with
// chosen restitution and friction, optional walls.
#pragma once

#include <numbers>
#include <vector>

#include "contact/pair_table.hpp"
#include "contact/time_step.hpp"
#include "core/simulation.hpp"

namespace grainlab::test {

inline constexpr double glass_E = 46.2e9;        // Pa (reference beads)
inline constexpr double glass_density = 2500.0;  // kg/m^3

// Mass of a sphere, kg (glass unless a density is given).
inline double sphere_mass(double radius, double density = glass_density) {
  return density * 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
}

// A pair's restitution and friction, the other properties at their defaults.
inline PairProperties pair_properties(double restitution, double friction) {
  PairProperties p;
  p.restitution = restitution;
  p.friction = friction;
  return p;
}

// Material 0: "glass" particles; material 1: "wall" (no E or density of its own).
inline PairTable two_material_table(double restitution, double friction, double arf = 0.0) {
  PairTable t({Material{"glass", glass_E, 0.245, glass_density}, Material{"wall", {}, {}, {}}});
  PairProperties p;
  p.restitution = restitution;
  p.friction = friction;
  p.arf = arf;
  t.set(0, 0, p);
  t.set(0, 1, p);
  return t;
}

inline Wall plane_wall(const Vec3& point, const Vec3& normal) {
  Wall w;
  w.shape = WallShape::plane;
  w.material = 1;
  w.point = point;
  w.normal = normal;
  finish_wall_geometry(w);
  return w;
}

// Site k of a cubic lattice `side` sites wide and `spacing` apart (x fastest, then y, then z),
// each coordinate moved by jitter() (called for x, y, z in that order).
template <class Jitter>
Vec3 cubic_lattice_site(int k, int side, double spacing, Jitter&& jitter) {
  return {spacing * (k % side + 0.5) + jitter(), spacing * (k / side % side + 0.5) + jitter(),
          spacing * (k / (side * side) + 0.5) + jitter()};
}

// The six plane walls of the box [0, l]^3, their normals inwards: floor, x = 0, x = l, y = 0,
// y = l, lid (last).
inline std::vector<Wall> cube_walls(double l) {
  return {plane_wall({0, 0, 0}, {0, 0, 1}),  plane_wall({0, 0, 0}, {1, 0, 0}),
          plane_wall({l, 0, 0}, {-1, 0, 0}), plane_wall({0, 0, 0}, {0, 1, 0}),
          plane_wall({0, l, 0}, {0, -1, 0}), plane_wall({0, 0, l}, {0, 0, -1})};
}

inline SimulationSettings settings_for(double min_radius, double restitution, double dt_fraction,
                                       Vec3 gravity = {}) {
  SimulationSettings s;
  s.time_step = dt_fraction * collision_duration(min_radius, glass_density, glass_E, restitution);
  s.dt_fraction = dt_fraction;
  s.gravity = gravity;
  s.skin = 0.2 * min_radius;
  return s;
}

}  // namespace grainlab::test
