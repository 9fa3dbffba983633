// The six plane walls of a cuboid specimen (x-, x+, y-, y+, bottom platen, top platen), each
// with its inward normal: the box every element test, the benchmark and the sliding-friction bed
// are built in. What is measured on it is in measure/boundary.hpp.
#pragma once

#include <vector>

#include "geometry/wall.hpp"

namespace grainlab {

enum BoxWall { x_low = 0, x_high = 1, y_low = 2, y_high = 3, bottom = 4, top = 5 };

// Walls k = 0..5 in BoxWall order; wall k closes the face normal to axis k / 2.
std::vector<Wall> cuboid_walls(const Vec3& lo, const Vec3& hi, int lateral_material,
                               int platen_material);

}  // namespace grainlab
