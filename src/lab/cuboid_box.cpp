#include "lab/cuboid_box.hpp"

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

Vec3 box_low(const std::vector<Wall>& w) {
  return {w[x_low].point.x, w[y_low].point.y, w[bottom].point.z};
}
Vec3 box_high(const std::vector<Wall>& w) {
  return {w[x_high].point.x, w[y_high].point.y, w[top].point.z};
}

double wall_area(const std::vector<Wall>& walls, int k) {
  const Vec3 d = box_high(walls) - box_low(walls);
  switch (k / 2) {
    case 0:
      return d.y * d.z;
    case 1:
      return d.x * d.z;
    default:
      return d.x * d.y;
  }
}

double wall_stress(const std::vector<Wall>& walls, int k) {
  return -dot(walls[k].force, walls[k].normal) / wall_area(walls, k);
}

void set_inward_speed(std::vector<Wall>& walls, int k, double inward_speed) {
  walls[k].velocity = inward_speed * walls[k].normal;
}

}  // namespace grainlab
