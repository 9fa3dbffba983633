#include "measure/boundary.hpp"

namespace grainlab {

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

}  // namespace grainlab
