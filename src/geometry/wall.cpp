#include "geometry/wall.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace grainlab {

WallGap wall_gap(const Wall& w, const Vec3& centre) {
  const Vec3 d = centre - w.point;
  switch (w.shape) {
    case WallShape::plane:
      return {-w.normal, dot(d, w.normal)};
    case WallShape::rectangle: {
      const double u = std::clamp(dot(d, w.axis_u), -w.half_u, w.half_u);
      const double v = std::clamp(dot(d, w.axis_v), -w.half_v, w.half_v);
      const Vec3 to_centre = d - u * w.axis_u - v * w.axis_v;  // nearest point -> centre
      const double distance = norm(to_centre);
      if (distance == 0.0) return {-w.normal, 0.0};
      return {(-1.0 / distance) * to_centre, distance};
    }
    case WallShape::cylinder: {
      const Vec3 radial = d - dot(d, w.axis) * w.axis;
      const double rho = norm(radial);
      if (rho == 0.0) return {w.axis_u, w.radius};  // on the axis: any radial direction
      return {(1.0 / rho) * radial, w.radius - rho};
    }
  }
  return {};
}

bool inside_wall(const Wall& w, const Vec3& centre) {
  switch (w.shape) {
    case WallShape::plane:
      return dot(centre - w.point, w.normal) > 0.0;
    case WallShape::rectangle:
      return true;
    case WallShape::cylinder:
      return wall_gap(w, centre).gap > 0.0;
  }
  return true;
}

namespace {
Vec3 unit(const Vec3& v, const char* what) {
  const double n = norm(v);
  if (!(n > 0.0)) throw std::invalid_argument(std::string(what) + " must be a non-zero vector");
  return (1.0 / n) * v;
}
// Some unit vector perpendicular to n.
Vec3 any_perpendicular(const Vec3& n) {
  const Vec3 trial = std::abs(n.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  return unit(trial - dot(trial, n) * n, "normal");
}
}  // namespace

void finish_wall_geometry(Wall& w) {
  switch (w.shape) {
    case WallShape::plane:
      w.normal = unit(w.normal, "normal");
      break;
    case WallShape::rectangle:
      w.normal = unit(w.normal, "normal");
      if (norm2(w.axis_u) == 0.0) w.axis_u = any_perpendicular(w.normal);
      w.axis_u = unit(w.axis_u - dot(w.axis_u, w.normal) * w.normal, "axis_u (in the plane)");
      w.axis_v = cross(w.normal, w.axis_u);
      if (!(w.half_u > 0.0 && w.half_v > 0.0))
        throw std::invalid_argument("size must be two lengths > 0");
      break;
    case WallShape::cylinder:
      w.axis = unit(w.axis, "axis");
      w.axis_u = any_perpendicular(w.axis);
      if (!(w.radius > 0.0)) throw std::invalid_argument("radius must be > 0");
      break;
  }
}

WallPose pose_of(const Wall& w) {
  return {w.point, w.normal, w.axis_u, w.axis_v, w.axis, w.half_u, w.half_v, w.radius};
}

double surface_displacement(const WallPose& b, const Wall& w) {
  const double moved = norm(w.point - b.point);
  switch (w.shape) {
    case WallShape::plane:
      return w.normal == b.normal ? moved : INFINITY;
    case WallShape::rectangle:
      return moved + std::abs(w.half_u - b.half_u) + std::abs(w.half_v - b.half_v) +
             w.half_u * norm(w.axis_u - b.axis_u) + w.half_v * norm(w.axis_v - b.axis_v);
    case WallShape::cylinder:
      return w.axis == b.axis ? moved + std::abs(w.radius - b.radius) : INFINITY;
  }
  return INFINITY;
}

const char* shape_name(WallShape s) {
  switch (s) {
    case WallShape::plane:
      return "plane";
    case WallShape::rectangle:
      return "rectangle";
    case WallShape::cylinder:
      return "cylinder";
  }
  return "?";
}

}  // namespace grainlab
