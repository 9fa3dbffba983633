// Walls: rigid surfaces that particles touch. Each has a material (row of the pair table), a
// prescribed translational velocity (set by the scene or by a controller between steps), and
// accumulates per step the force the particles exert on it and the summed normal stiffness of
// its contacts (what a stress controller needs to choose its gain).
//
//   plane      infinite, one-sided: particles live on the side `normal` points to
//   rectangle  finite, two-sided: centre `point`, unit `normal`, in-plane unit axes u and v,
//              half-sizes; contact with the nearest point, so edges and corners act too
//   cylinder   infinite, particles inside: a point on the axis, unit `axis`, `radius`
#pragma once

#include <string>

#include "core/vec3.hpp"

namespace grainlab {

enum class WallShape { plane, rectangle, cylinder };

struct Wall {
  std::string name;
  WallShape shape = WallShape::plane;
  int material = 0;
  Vec3 point;                         // m
  Vec3 normal{0.0, 0.0, 1.0};         // plane, rectangle (unit)
  Vec3 axis_u, axis_v;                // rectangle (unit, in-plane)
  double half_u = 0.0, half_v = 0.0;  // rectangle, m
  Vec3 axis{0.0, 0.0, 1.0};           // cylinder (unit)
  double radius = 0.0;                // cylinder, m
  Vec3 velocity;                      // m/s (prescribed, or integrated when mass > 0)
  // A wall with mass > 0 translates under the particles' force plus external_force (a load or
  // a rope set by a test between steps), e.g. the slider of the sliding-friction test.
  double mass = 0.0;    // kg; 0 = motion prescribed
  Vec3 external_force;  // N

  // Per-step outputs of the force computation.
  Vec3 force;                      // N, exerted by the particles on the wall
  double contact_stiffness = 0.0;  // N/m, sum of k_n over touching contacts
  int contact_count = 0;
};

// Where a sphere centre stands relative to a wall: `gap` is the distance from the centre to the
// wall surface (overlap = radius - gap) and `normal` the unit vector from the centre towards the
// wall (the contact normal, body A = particle, body B = wall).
struct WallGap {
  Vec3 normal;
  double gap;
};

WallGap wall_gap(const Wall& wall, const Vec3& centre);

// The geometry of a wall at one moment (what the neighbour list was built against).
struct WallPose {
  Vec3 point, normal, axis_u, axis_v, axis;
  double half_u = 0.0, half_v = 0.0, radius = 0.0;
};
WallPose pose_of(const Wall& wall);

// An upper bound on how far any point of the wall's surface has moved since `before`, m: the
// translation plus what a change of size or a turn moves the farthest point of a rectangle by
// (its half-sizes times the change of its in-plane axes). An infinite plane or cylinder that
// has turned at all has moved without bound (infinity).
double surface_displacement(const WallPose& before, const Wall& now);

// True when a sphere centre lies on the side of the wall where particles belong (for the
// one-sided plane and the cylinder); rectangles are two-sided and always accept.
bool inside_wall(const Wall& wall, const Vec3& centre);

// Makes unit vectors and completes the rectangle's in-plane axes; throws std::invalid_argument.
void finish_wall_geometry(Wall& wall);

const char* shape_name(WallShape shape);

}  // namespace grainlab
