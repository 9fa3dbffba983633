// Solid fraction where it means something. A box's bulk value (bead volume / box volume)
// includes the loose layer along every wall: a sphere cannot fill the space between its surface
// and a flat wall, so the first diameter next to a wall is looser than the interior, and the bulk
// value of a small specimen is well below that of its interior. Two measures that separate them:
// the profile across the specimen, and the interior value, away from every wall.
//
// Both rest on the exact volume of a sphere (centre c, radius r) between two planes x = a and
// x = b, from the area of its cross-sections pi (r^2 - t^2):
//   V = pi [r^2 t - t^3 / 3] from t1 = clamp(a - c, -r, r) to t2 = clamp(b - c, -r, r).
#pragma once

#include <vector>

#include "core/particles.hpp"

namespace grainlab {

// Volume of the sphere between the planes at `a` and `b` (a <= b) of one axis, m^3.
double sphere_slab_volume(double centre, double radius, double a, double b);

// Solid fraction in `bins` slabs of equal width across `axis` (0 x, 1 y, 2 z) of the box
// [low, high]: each slab's exact bead volume over the slab's volume. Its mean is the bulk value
// when every bead lies inside the box.
std::vector<double> solid_fraction_profile(const ParticleStore& particles, const Vec3& low,
                                           const Vec3& high, int axis, int bins);

// Solid fraction of the interior box [low + margin, high - margin] in every direction, 0 when
// the margin leaves no interior. A bead inside it, or cut by faces of one axis only, counts with
// its exact volume inside (the slab formula); a bead across an edge or a corner of the region by
// a 60 x 60 quadrature of its cross-sections (relative error about 1e-5 on that bead).
double interior_solid_fraction(const ParticleStore& particles, const Vec3& low, const Vec3& high,
                               double margin);

}  // namespace grainlab
