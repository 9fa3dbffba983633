// The particle store: spheres as a structure of arrays (one contiguous array per field), the
// layout the force and integration loops stream through. Hot fields (read or written every step)
// come first; `id` is the particle's permanent number, which survives spatial re-sorting.
// A particle with inverse_mass = 0 is fixed (it neither moves nor rotates).
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

#include "core/vec3.hpp"

namespace grainlab {

// Below this many particles a loop runs on one thread: the cost of waking the team would exceed
// the work. (The results are the same either way.)
inline constexpr long parallel_threshold = 512;

struct ParticleStore {
  // hot: 24 B per Vec3 field, 8 B per scalar, 4 B per index -> 172 B per particle
  std::vector<Vec3> position;           // m
  std::vector<Vec3> velocity;           // m/s
  std::vector<Vec3> angular_velocity;   // rad/s
  std::vector<Vec3> force;              // N, total of the current step
  std::vector<Vec3> torque;             // N m
  std::vector<double> radius;           // m
  std::vector<double> inverse_mass;     // 1/kg (0: fixed)
  std::vector<double> inverse_inertia;  // 1/(kg m^2), sphere: I = 2/5 m r^2
  std::vector<int32_t> material;        // index into the pair table
  // cold
  std::vector<uint32_t> id;            // permanent number (0..N-1 in input order)
  std::vector<Vec3> rotation;          // accumulated rotation vector (integral of w dt), rad
  std::vector<Vec3> initial_position;  // m, for displacement output
  // A force applied from outside the contact law, e.g. a flexible membrane's pressure on a
  // boundary particle; set by a controller (Simulation::set_external_force), kept across steps.
  std::vector<Vec3> external_force;  // N

  size_t size() const { return position.size(); }
  // m; of an empty store, +infinity
  double smallest_radius() const {
    double r_min = std::numeric_limits<double>::infinity();
    for (double r : radius) r_min = std::min(r_min, r);
    return r_min;
  }

  void add(uint32_t particle_id, int32_t material_index, double sphere_radius, double density,
           const Vec3& x, const Vec3& v, const Vec3& w, bool fixed) {
    const double mass =
        density * 4.0 / 3.0 * std::numbers::pi * sphere_radius * sphere_radius * sphere_radius;
    const double inertia = 0.4 * mass * sphere_radius * sphere_radius;
    position.push_back(x);
    velocity.push_back(fixed ? Vec3{} : v);
    angular_velocity.push_back(fixed ? Vec3{} : w);
    force.push_back({});
    torque.push_back({});
    radius.push_back(sphere_radius);
    inverse_mass.push_back(fixed ? 0.0 : 1.0 / mass);
    inverse_inertia.push_back(fixed ? 0.0 : 1.0 / inertia);
    material.push_back(material_index);
    id.push_back(particle_id);
    rotation.push_back({});
    initial_position.push_back(x);
    external_force.push_back({});
  }

  // Reorders every field so that new index k holds the particle at old index order[k].
  void permute(const std::vector<uint32_t>& order);

  // Every field, for checkpoints (core/state_io.hpp).
  template <class Io>
  void for_each_field(Io&& io) {
    io(position), io(velocity), io(angular_velocity), io(force), io(torque), io(radius),
        io(inverse_mass), io(inverse_inertia), io(material), io(id), io(rotation),
        io(initial_position), io(external_force);
  }
};

}  // namespace grainlab
