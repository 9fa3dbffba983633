// The six plane walls of a cuboid specimen (x-, x+, y-, y+, bottom platen, top platen), each
// with its inward normal, and the measurements made on them.
#pragma once

#include <array>
#include <vector>

#include "geometry/wall.hpp"

namespace grainlab {

enum BoxWall { x_low = 0, x_high = 1, y_low = 2, y_high = 3, bottom = 4, top = 5 };

std::vector<Wall> cuboid_walls(const Vec3& lo, const Vec3& hi, int lateral_material,
                               int platen_material);

// Current extent from the wall positions (walls must be those of cuboid_walls, in order).
Vec3 box_low(const std::vector<Wall>& walls);
Vec3 box_high(const std::vector<Wall>& walls);
inline double box_volume(const std::vector<Wall>& w) {
  const Vec3 d = box_high(w) - box_low(w);
  return d.x * d.y * d.z;
}

// Area of wall k of the box (the face it closes), m^2.
double wall_area(const std::vector<Wall>& walls, int k);

// Compressive normal stress the particles exert on wall k, Pa.
double wall_stress(const std::vector<Wall>& walls, int k);

// Sets wall k's velocity to `inward_speed` along its inward normal.
void set_inward_speed(std::vector<Wall>& walls, int k, double inward_speed);

}  // namespace grainlab
