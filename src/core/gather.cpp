// Simulation::gather: the force and torque on each particle, summed from the contact stores
// (with the reference law, whose pairs carry no moments, by the particle passes:
// core/particle_passes_simd.hpp).
//
// Compiled with -ffp-contract=off (src/core/CMakeLists.txt): a torque is formed here as lever ×
// torque arm (core/contact_store.hpp), and unfused it is bit for bit the product the contact law
// forms, whichever build; a fused multiply-add would round the lever and the sum differently.
#include <string_view>

#include "core/simulation.hpp"

namespace grainlab {
namespace {

// The sums of particles [first, end) where the pairs carry rolling or twisting moments (the
// reference law's, without them, are the particle passes': core/particle_passes_simd.hpp, the
// same arithmetic less the moments).
void gather_block(ParticleStore& p, const PairContacts& c, const WallContacts& wc, const Vec3& g,
                  bool external, long first, long end) {
  for (long i = first; i < end; ++i) {
    const double r = p.radius[i];
    Vec3 f = p.inverse_mass[i] > 0.0 ? (1.0 / p.inverse_mass[i]) * g : Vec3{};
    Vec3 t;
    // first body: the entry's force; second body: the opposite. Either way the torque of the
    // tangential force is the body's lever times the arm.
    for (uint32_t e = c.row_start[i]; e < c.row_start[i + 1]; ++e) {
      const PairResult& x = c.result[e];
      f += x.force_on_first;
      t += contact_lever(r, x.overlap) * x.torque_arm;
      t += c.moment[e];
    }
    for (uint32_t k = c.col_start[i]; k < c.col_start[i + 1]; ++k) {
      const uint32_t e = c.col_pair[k];
      const PairResult& x = c.result[e];
      f -= x.force_on_first;
      t += contact_lever(r, x.overlap) * x.torque_arm;
      t -= c.moment[e];
    }
    for (uint32_t e = wc.row_start[i]; e < wc.row_start[i + 1]; ++e) {
      f += wc.force_on_particle[e];
      t += wc.torque_on_particle[e];
    }
    if (external) f += p.external_force[i];
    p.force[i] = f;
    p.torque[i] = t;
  }
}

}  // namespace

// Sums, per particle of the block and in a fixed order, gravity, the entries where it is first,
// the entries where it is second (opposite force), its wall contacts and its external force
// (only while some particle has one, so that a run without them adds nothing, not even a zero).
void Simulation::gather_particles(IndexBlock b) {
  if (!pairs_.moment.empty()) {
    gather_block(particles_, pairs_, wall_contacts_, settings_.gravity, external_forces_, b.first,
                 b.end);
    return;
  }
  ParticleStore& p = particles_;
  const PairContacts& c = pairs_;
  const WallContacts& wc = wall_contacts_;
  const Vec3& g = settings_.gravity;
  static_assert(sizeof(PairResult) == 8 * sizeof(double));
  GatherInput in{c.row_start.data(),
                 c.col_start.data(),
                 c.col_pair.data(),
                 reinterpret_cast<const double*>(c.result.data()),
                 wc.row_start.data(),
                 components(wc.force_on_particle),
                 components(wc.torque_on_particle),
                 p.radius.data(),
                 p.inverse_mass.data(),
                 external_forces_ ? components(p.external_force) : nullptr,
                 {g.x, g.y, g.z},
                 components(p.force),
                 components(p.torque)};
  // (the owners are the kernel's: index_entry_owners)
  if (flat_gather_ && entry_owners_.size() == c.size() && wall_entry_owners_.size() == wc.size()) {
    in.row_owner = entry_owners_.data();
    in.partner = c.partner.data();
    in.wall_owner = wall_entry_owners_.data();
  }
  particle_passes_.gather(in, b.first, b.end);
}

// Both walks exist where the kernel runs (its entry owners) and its passes are AVX2 or AVX-512
// (the SSE2 object ignores the owners).
bool Simulation::times_gather_walks() const {
  return uses_pair_kernel() && std::string_view(particle_passes_.name) != "sse2";
}

// Wall totals, serial in entry order (few entries; deterministic).
void Simulation::gather_walls() {
  const WallContacts& wc = wall_contacts_;
  if (simd_pair_kernel_.wall_totals && walls_.size() <= max_lane_walls) {
    // one lane per wall (core/pair_kernel_simd.hpp): the same sums
    SimdWallTotals totals;
    simd_pair_kernel_.wall_totals(components(wc.force_on_particle), wc.normal_stiffness.data(),
                                  wc.wall.data(), static_cast<uint32_t>(wc.size()),
                                  static_cast<int>(walls_.size()), totals);
    for (size_t k = 0; k < walls_.size(); ++k) {
      Wall& w = walls_[k];
      w.force = {totals.force_x[k], totals.force_y[k], totals.force_z[k]};
      w.contact_stiffness = totals.stiffness[k];
      w.contact_count = static_cast<int>(totals.count[k]);
    }
    return;
  }
  for (Wall& w : walls_) {
    w.force = Vec3{};
    w.contact_stiffness = 0.0;
    w.contact_count = 0;
  }
  for (size_t e = 0; e < wc.size(); ++e) {
    if (wc.normal_stiffness[e] == 0.0) continue;
    Wall& w = walls_[wc.wall[e]];
    w.force -= wc.force_on_particle[e];
    w.contact_stiffness += wc.normal_stiffness[e];
    ++w.contact_count;
  }
}

}  // namespace grainlab
