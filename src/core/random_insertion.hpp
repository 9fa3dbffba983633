// Random sequential insertion of non-overlapping spheres in a box or an upright cylinder.
// Candidates are drawn uniformly (centres kept one radius inside the region) and rejected when
// they overlap a sphere already there; a cell grid makes each test O(1). Random sequential
// insertion saturates near a solid fraction of 0.3-0.38, so a dense specimen is made by
// inserting loosely and compressing (lab/ specimen preparation).
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "core/sphere_grid.hpp"
#include "core/vec3.hpp"

namespace grainlab {

struct InsertionRegion {
  bool cylinder = false;
  Vec3 box_min, box_max;              // box
  Vec3 base;                          // cylinder bottom centre, axis +z
  double radius = 0.0, height = 0.0;  // cylinder
};

// Deterministic uniform double in [0, 1) from a 64-bit generator (same on every platform).
inline double uniform01(std::mt19937_64& rng) {
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

// Appends `count` spheres with diameters uniform in [d_min, d_max] to `spheres` (which may hold
// obstacles already). Returns the number placed (less than count when the region is full).
long insert_random_spheres(std::vector<Sphere>& spheres, const InsertionRegion& region, long count,
                           double diameter_min, double diameter_max, std::mt19937_64& rng,
                           long attempts_per_sphere = 2000);

}  // namespace grainlab
