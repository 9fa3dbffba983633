// Measurements on a specimen (docs/lab-tests.md): stresses from the walls and from the
// particles, solid fraction, coordination number, unbalanced force, inertial number.
// Compressive stress is positive.
//
// Love-Weber average stress over the specimen volume V (symmetrised):
//   sigma_ij = -(1/V) [ sum over particle pairs f_i l_j + sum over wall contacts f_i (x_c - x_p)_j
//   ]
// with f the force on the second body / on the wall, l the branch vector from the first centre to
// the second. In static equilibrium it equals the boundary (wall) stress; the agreement is a
// check of equilibrium and of the volume. An external force on a particle (a flexible membrane's
// pressure) counts as a boundary contact at the particle's surface point opposite the force's
// direction, where the membrane touches it: its lever is -r F/|F|.
#pragma once

#include <array>
#include <vector>

#include "core/simulation.hpp"

namespace grainlab {

using Tensor3 = std::array<std::array<double, 3>, 3>;

Tensor3 love_weber_stress(const Simulation& sim, double volume);

// Average stress from the boundary alone (the average-stress theorem):
//   sigma_ij = (1/V) sum over wall contacts f_i (x_c - x_0)_j,
// f the force on the wall (or the membrane), x_c the contact point, x_0 = `centre`; symmetrised,
// compressive positive. Unlike the platen stress F/A it includes the moment of the shear forces the
// walls carry (friction on the lateral walls takes part of the axial load). It differs from the
// Love-Weber average only by sum over particles of (net force) (x_p - x_0): the inertia of the
// particles, small once quasi-static.
Tensor3 boundary_stress(const Simulation& sim, const Vec3& centre, double volume);

// Particle volume / box volume.
double solid_fraction(const ParticleStore& particles, double volume);

// Mean number of touching contacts per particle, Z = (2 N_pp + N_pw) / N.
double coordination_number(const Simulation& sim);

// Touching contacts of each particle (by storage index), walls included.
std::vector<int> contacts_per_particle(const Simulation& sim);

// Mean |net force| on the free particles divided by the mean contact force magnitude.
double unbalanced_force_ratio(const Simulation& sim);

// I = strain_rate * d * sqrt(rho / p).
inline double inertial_number(double strain_rate, double diameter, double density,
                              double pressure) {
  return pressure > 0.0 ? std::abs(strain_rate) * diameter * std::sqrt(density / pressure) : 0.0;
}

}  // namespace grainlab
