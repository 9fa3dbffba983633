// The boundary of a cuboid specimen closed by the six walls of geometry/cuboid_box.hpp, as the
// laboratory measures it: the box from the wall positions, its volume and face areas, the
// strains against a reference size, and the normal stress each wall carries (F / A, the load
// cell's reading). Compressive stress and shortening strain are positive.
// (A flexible membrane's hull will be the second kind of boundary; the tests read the same
// quantities from it.)
#pragma once

#include <vector>

#include "geometry/cuboid_box.hpp"
#include "geometry/wall.hpp"

namespace grainlab {

// Current extent from the wall positions (walls must be those of cuboid_walls, in order).
Vec3 box_low(const std::vector<Wall>& walls);
Vec3 box_high(const std::vector<Wall>& walls);
inline Vec3 box_size(const std::vector<Wall>& w) {
  return box_high(w) - box_low(w);
}
inline double box_volume(const std::vector<Wall>& w) {
  const Vec3 d = box_high(w) - box_low(w);
  return d.x * d.y * d.z;
}

// Area of the face wall k closes, m^2.
double wall_area(const std::vector<Wall>& walls, int k);

// Compressive normal stress the particles exert on wall k, Pa.
double wall_stress(const std::vector<Wall>& walls, int k);

// Shortening strain along each axis against the reference size (size0 - size) / size0, and
// the volumetric strain 1 - V / V0 (compression positive).
inline Vec3 box_strain(const Vec3& size0, const Vec3& size) {
  return {(size0.x - size.x) / size0.x, (size0.y - size.y) / size0.y, (size0.z - size.z) / size0.z};
}
inline double volumetric_strain(const Vec3& size0, const Vec3& size) {
  return 1.0 - (size.x * size.y * size.z) / (size0.x * size0.y * size0.z);
}

}  // namespace grainlab
