// The local strain of a granular specimen from the particle displacements, as digital image
// correlation measures it on a laboratory specimen's face.
//
// For each particle i, the displacement gradient L_i is the least-squares fit of
//   u_j - u_i = L_i (X_j - X_i)
// over the particles j whose reference centres X lie within `radius` of X_i (about two
// diameters: some 30 neighbours in a dense packing), i.e. L_i = (sum du dX^T)(sum dX dX^T)^-1.
// The small-strain tensor is its symmetric part; the in-plane maximum shear strain (engineering,
// in the plane of axes a and b) is gamma = sqrt((e_aa - e_bb)^2 + (2 e_ab)^2). Particles with
// fewer than 4 neighbours or a singular neighbourhood get NaN.
#pragma once

#include <array>
#include <vector>

#include "core/vec3.hpp"

namespace grainlab {

using Matrix3 = std::array<std::array<double, 3>, 3>;

// Displacement gradient per particle (reference positions `reference`, current `current`).
std::vector<Matrix3> local_displacement_gradient(const std::vector<Vec3>& reference,
                                                 const std::vector<Vec3>& current, double radius);

// gamma in the plane of axes a and b (e.g. x and z for a plane strain specimen).
double max_shear_strain(const Matrix3& gradient, int a, int b);

}  // namespace grainlab
