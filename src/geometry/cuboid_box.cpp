#include "geometry/cuboid_box.hpp"

namespace grainlab {

std::vector<Wall> cuboid_walls(const Vec3& lo, const Vec3& hi, int lateral_material,
                               int platen_material) {
  const char* names[6] = {"x_low", "x_high", "y_low", "y_high", "bottom_platen", "top_platen"};
  std::vector<Wall> walls(6);
  for (int k = 0; k < 6; ++k) {
    const int axis = k / 2;
    const bool high = k % 2 == 1;
    Wall& w = walls[k];
    w.name = names[k];
    w.shape = WallShape::plane;
    w.material = axis == 2 ? platen_material : lateral_material;
    w.point = high ? hi : lo;
    Vec3 n{};
    n[axis] = high ? -1.0 : 1.0;
    w.normal = n;
    finish_wall_geometry(w);
  }
  return walls;
}

}  // namespace grainlab
