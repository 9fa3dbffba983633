// The particle-wall force loop over the wall candidates (CSR by particle, core/contact_store.hpp):
// the scalar law of contact/contact_law.hpp with body B a wall of any shape (geometry/wall.hpp),
// and for the reference law the same contacts through the vectorised kernel's lanes
// (core/pair_kernel_simd.hpp, wall_law). Each candidate writes its own result; Simulation::gather
// sums them per particle, Simulation::gather_walls per wall.
#include <algorithm>
#include <cstdint>

#include "contact/contact_law.hpp"
#include "core/force_loop.hpp"
#include "core/simulation.hpp"

namespace grainlab {
namespace {

using force_loop::dispatch;
using force_loop::spin_at_step_end;
using force_loop::velocity_at_step_end;

// The velocity of a wall at the end of the step, for the dashpots: a wall with mass is
// integrated like a particle (its velocity is a half-step one here); a fixed one moves as
// prescribed.
inline Vec3 wall_velocity_at_end(const Wall& w, double dt) {
  return w.mass > 0.0 ? w.velocity + (0.5 * dt / w.mass) * (w.force + w.external_force)
                      : w.velocity;
}

// 1/M of a wall: a wall with mass (a slider) is a second body, m* = m_p M / (m_p + M); a fixed
// wall has M = infinity.
inline double wall_inverse_mass(const Wall& w) {
  return w.mass > 0.0 ? 1.0 / w.mass : 0.0;
}

// A candidate apart from its wall (or a fixed particle on a fixed wall): no force, and the
// contact forgets its history.
template <bool R, bool T, bool RF>
void clear_wall_entry(WallContacts& c, uint32_t e) {
  c.force_on_particle[e] = c.torque_on_particle[e] = Vec3{};
  c.normal_stiffness[e] = c.normal_force[e] = 0.0;
  c.sliding_spring[e] = Vec3{};
  if constexpr (R) c.rolling_angle[e] = Vec3{};
  if constexpr (T) c.twisting_angle[e] = 0.0;
  if constexpr (RF) c.rolling_force_displacement[e] = Vec3{};
}

// The wall candidate e of particle i: writes its result and history and returns overlap / r, 0
// when the sphere does not touch the wall.
template <bool R, bool T, bool RF>
double wall_entry(const ParticleStore& p, const std::vector<Wall>& walls, const PairTable& table,
                  WallContacts& c, double dt, double drift, size_t i, uint32_t e) {
  const double r = p.radius[i];
  const Wall& w = walls[c.wall[e]];
  const WallGap g = wall_gap(w, p.position[i]);
  const double overlap = r - g.gap;
  // A fixed particle touches only walls that have mass.
  const double inverse_mass_sum = p.inverse_mass[i] + wall_inverse_mass(w);
  if (overlap <= 0.0 || inverse_mass_sum == 0.0) {
    clear_wall_entry<R, T, RF>(c, e);
    return 0.0;
  }
  ContactKinematics k;
  k.normal = g.normal;
  k.overlap = overlap;
  k.effective_radius = r;
  k.effective_mass = 1.0 / inverse_mass_sum;
  const double lever = g.gap;  // contact point on the wall surface
  set_step_displacement(k, drift, p.velocity[i], p.angular_velocity[i], lever, w.velocity, Vec3{},
                        0.0, 1.0);
  // A wall with mass is integrated like a particle: its velocity too is a half-step one here.
  const Vec3 wall_velocity_at_step_end = wall_velocity_at_end(w, dt);
  set_relative_velocity(k, velocity_at_step_end(p, i, dt), spin_at_step_end(p, i, dt), lever,
                        wall_velocity_at_step_end, Vec3{}, 0.0);
  double inertia = 0.0, contact_radius = 0.0;
  if constexpr (R || T) {
    inertia = p.inverse_inertia[i] > 0.0 ? 1.0 / p.inverse_inertia[i] : 0.0;
    contact_radius = contact_circle_radius_on_wall(r, overlap);
  }
  ContactHistoryRef h{&c.sliding_spring[e], R ? &c.rolling_angle[e] : nullptr,
                      T ? &c.twisting_angle[e] : nullptr,
                      RF ? &c.rolling_force_displacement[e] : nullptr};
  const PairParams& pair = table(p.material[i], w.material);
  // First touch in this step (see the pair loop): the gap before the drift, with the wall
  // and the particle moved back (exact for any wall shape). The gate allows for rectangle
  // edges and cylinders, where the gap is not linear in the positions: sideways drift s_t
  // changes it by at most |s_t|^2 / (2 gap).
  double touch_fraction = 0.0;
  if (drift > 0.0) {
    const Vec3 s = drift * (p.velocity[i] - w.velocity);
    const double s_n = dot(s, g.normal);
    if (overlap <= 2.0 * (k.overlap_increment + (norm2(s) - s_n * s_n) / (2.0 * g.gap))) {
      Wall before = w;
      before.point -= drift * w.velocity;
      const double overlap_before = r - wall_gap(before, p.position[i] - drift * p.velocity[i]).gap;
      touch_fraction = first_touch_fraction(overlap_before, overlap);
      if (touch_fraction > 0.0) scale_step_increments(k, touch_fraction);
    }
  }
  const NormalParams normal = normal_params(pair, k.effective_radius, k.effective_mass);
  ContactResponse resp = contact_response<R, T, RF>(pair, normal, k, inertia, contact_radius, h);
  if (touch_fraction > 0.0)
    charge_first_touch<R, T, RF>(pair, normal, k, touch_fraction, inertia, resp);
  c.force_on_particle[e] = resp.force_on_a;
  if constexpr (R || T)
    c.torque_on_particle[e] = resp.torque_on_a(lever);
  else
    c.torque_on_particle[e] = lever * resp.torque_arm;
  c.normal_stiffness[e] = resp.normal_stiffness;
  c.normal_force[e] = resp.normal_force;
  return overlap / r;
}

// The wall contacts of particles [first, end).
template <bool R, bool T, bool RF>
double wall_forces(const ParticleStore& p, const std::vector<Wall>& walls, const PairTable& table,
                   WallContacts& c, double dt, double drift, long first, long end) {
  double max_fraction = 0.0;
  for (long i = first; i < end; ++i)
    for (uint32_t e = c.row_start[i]; e < c.row_start[i + 1]; ++e)
      max_fraction = std::max(max_fraction, wall_entry<R, T, RF>(p, walls, table, c, dt, drift,
                                                                 static_cast<size_t>(i), e));
  return max_fraction;
}

// The reference law's wall contacts through the kernel's lanes (core/pair_kernel_simd.hpp) for
// the particles [block.first, block.end): the gap to each candidate's wall here (any shape), the
// touching ones to the lanes in batches of 8, and the contacts the lanes hand back (first touch
// in the step) to the scalar law. The particle records must have been written. owners: per wall
// entry, its particle.
double wall_forces_simd(const SimdPairKernel& kernel, const SimdPairInput& in,
                        const SimdWallInput& lanes, const ParticleStore& p,
                        const std::vector<Wall>& walls, const PairTable& table, WallContacts& c,
                        const std::vector<uint32_t>& owners, double dt, double drift,
                        IndexBlock block, long& handed_back) {
  double max_fraction = 0.0;
  SimdWallBatch b;
  const auto run_batch = [&] {
    const unsigned back = kernel.walls(in, lanes, b);
    for (int l = 0; l < b.count; ++l)
      if (back >> l & 1u) {
        wall_entry<false, false, false>(p, walls, table, c, dt, drift, b.particle[l], b.entry[l]);
        ++handed_back;
      }
    b.count = 0;
  };
  const uint32_t first_entry = c.row_start[block.first], end_entry = c.row_start[block.end];
  for (uint32_t e = first_entry; e < end_entry; ++e) {
    const uint32_t i = owners[e];
    const uint16_t k = c.wall[e];
    const double r = p.radius[i];
    const WallGap g = wall_gap(walls[k], p.position[i]);
    const double overlap = r - g.gap;
    if (overlap <= 0.0 || p.inverse_mass[i] + lanes.walls[k].inverse_mass == 0.0) {
      clear_wall_entry<false, false, false>(c, e);
      continue;
    }
    const int l = b.count++;
    b.normal_x[l] = g.normal.x, b.normal_y[l] = g.normal.y, b.normal_z[l] = g.normal.z;
    b.gap[l] = g.gap, b.overlap[l] = overlap, b.radius[l] = r;
    b.particle[l] = i, b.entry[l] = e, b.wall[l] = k;
    max_fraction = std::max(max_fraction, overlap / r);
    if (b.count == wall_batch_lanes) run_batch();
  }
  if (b.count > 0) run_batch();
  return max_fraction;
}

template <bool R, bool T, bool RF>
struct WallKernel {
  static double run(const ParticleStore& p, const std::vector<Wall>& w, const PairTable& t,
                    WallContacts& c, double dt, double drift, IndexBlock b) {
    return wall_forces<R, T, RF>(p, w, t, c, dt, drift, b.first, b.end);
  }
};

}  // namespace

void Simulation::prepare_wall_lanes() {
  if (!uses_pair_kernel() || !simd_pair_kernel_.walls) return;
  // Plane walls only (a cuboid box): the kernel finds the touching candidates as well.
  const bool planes = simd_pair_kernel_.plane_walls && walls_.size() <= max_lane_walls &&
                      std::all_of(walls_.begin(), walls_.end(),
                                  [](const Wall& w) { return w.shape == WallShape::plane; });
  wall_planes_ = SimdPlanes{};
  if (planes) {
    for (size_t k = 0; k < walls_.size(); ++k) {
      const Wall& w = walls_[k];
      wall_planes_.point_x[k] = w.point.x, wall_planes_.point_y[k] = w.point.y;
      wall_planes_.point_z[k] = w.point.z;
      wall_planes_.normal_x[k] = w.normal.x, wall_planes_.normal_y[k] = w.normal.y;
      wall_planes_.normal_z[k] = w.normal.z;
    }
    wall_planes_.count = static_cast<int>(walls_.size());
    if (deferred_walls_.size() < wall_contacts_.size())
      deferred_walls_.resize(wall_contacts_.size());
  }
  wall_lane_state_.resize(walls_.size());
  for (size_t k = 0; k < walls_.size(); ++k) {
    const Wall& w = walls_[k];
    SimdWallState& s = wall_lane_state_[k];
    const Vec3 at_end = wall_velocity_at_end(w, settings_.time_step);
    s.velocity[0] = w.velocity.x, s.velocity[1] = w.velocity.y, s.velocity[2] = w.velocity.z;
    s.velocity_at_end[0] = at_end.x, s.velocity_at_end[1] = at_end.y;
    s.velocity_at_end[2] = at_end.z;
    s.inverse_mass = wall_inverse_mass(w);
    s.material = w.material;
  }
}

double Simulation::compute_wall_forces(double drift, IndexBlock block, long& handed_back) {
  if (wall_contacts_.size() == 0) return 0.0;
  if (uses_pair_kernel() && simd_pair_kernel_.walls) {
    const SimdPairInput in = kernel_input(drift);
    WallContacts& c = wall_contacts_;
    const SimdWallInput lanes{wall_lane_state_.data(),         components(c.sliding_spring),
                              components(c.force_on_particle), components(c.torque_on_particle),
                              c.normal_stiffness.data(),       c.normal_force.data()};
    if (wall_planes_.count > 0) {
      const SimdWallCandidates candidates{wall_entry_owners_.data(), c.wall.data(), &wall_planes_};
      const uint32_t first_entry = c.row_start[block.first], end_entry = c.row_start[block.end];
      uint32_t* deferred = deferred_walls_.data() + first_entry;
      long deferred_count = 0;
      const double m = simd_pair_kernel_.plane_walls(in, lanes, candidates, first_entry, end_entry,
                                                     deferred, deferred_count);
      // (the largest overlap counts these contacts already)
      for (long k = 0; k < deferred_count; ++k)
        wall_entry<false, false, false>(particles_, walls_, table_, c, settings_.time_step, drift,
                                        wall_entry_owners_[deferred[k]], deferred[k]);
      handed_back += deferred_count;
      return m;
    }
    return wall_forces_simd(simd_pair_kernel_, in, lanes, particles_, walls_, table_, c,
                            wall_entry_owners_, settings_.time_step, drift, block, handed_back);
  }
  return dispatch<WallKernel>(pieces_, particles_, walls_, table_, wall_contacts_,
                              settings_.time_step, drift, block);
}

}  // namespace grainlab
