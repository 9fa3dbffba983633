// The particle-pair force loop over the entries of the half Verlet list (the wall candidates:
// core/wall_forces.cpp). Each entry writes its result into the contact arrays (no shared
// accumulators); Simulation::gather sums them per particle. The optional pieces of the contact
// law are chosen once per call through the template switches.
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "contact/contact_law.hpp"
#include "core/force_loop.hpp"
#include "core/simulation.hpp"

namespace grainlab {
namespace {

using force_loop::dispatch;
using force_loop::spin_at_step_end;
using force_loop::velocity_at_step_end;

// One entry e (row i) of the half list: writes its result (PairResult) and history and returns
// overlap / min(r_i, r_j), 0 when the spheres do not touch. dt: the time step (for the
// end-of-step velocity estimate); drift: the time the positions last drifted over, dt after a
// drift and 0 when forces are evaluated on a fresh state (at construction), when no spring may
// advance and no contact can have begun "during" a step.
// xi, ri: position and radius of particle i, read once per row by the caller.
template <bool R, bool T, bool RF>
[[gnu::always_inline]] inline double pair_entry(const ParticleStore& p,
                                                const PairParams* row_params, PairContacts& c,
                                                size_t i, const Vec3& xi, double ri, uint32_t e,
                                                double dt, double drift) {
  const uint32_t j = c.partner[e];
  const double rj = p.radius[j];
  const Vec3 d = p.position[j] - xi;
  const double reach = ri + rj;
  const double dist2 = norm2(d);
  if (dist2 >= reach * reach) {  // apart: no force, and the contact forgets its history
    c.result[e] = PairResult{};
    if constexpr (R || T) c.moment[e] = Vec3{};
    c.sliding_spring[e] = Vec3{};
    if constexpr (R) c.rolling_angle[e] = Vec3{};
    if constexpr (T) c.twisting_angle[e] = 0.0;
    if constexpr (RF) c.rolling_force_displacement[e] = Vec3{};
    return 0.0;
  }
  const double dist = std::sqrt(dist2);
  ContactKinematics k;
  k.normal = (1.0 / dist) * d;
  k.overlap = reach - dist;
  if constexpr (R || T || RF) k.effective_radius = ri * rj / reach;
  // contact point halfway through the overlap
  const double lever_i = contact_lever(ri, k.overlap), lever_j = contact_lever(rj, k.overlap);
  set_step_displacement(k, drift, p.velocity[i], p.angular_velocity[i], lever_i, p.velocity[j],
                        p.angular_velocity[j], lever_j, 0.5);
  set_relative_velocity(k, velocity_at_step_end(p, i, dt), spin_at_step_end(p, i, dt), lever_i,
                        velocity_at_step_end(p, j, dt), spin_at_step_end(p, j, dt), lever_j);
  double inertia = 0.0, contact_radius = 0.0;
  if constexpr (R || T) {
    inertia = 1.0 / (p.inverse_inertia[i] + p.inverse_inertia[j]);
    contact_radius = contact_circle_radius(ri, rj, dist);
  }
  ContactHistoryRef h{&c.sliding_spring[e], R ? &c.rolling_angle[e] : nullptr,
                      T ? &c.twisting_angle[e] : nullptr,
                      RF ? &c.rolling_force_displacement[e] : nullptr};
  // A contact whose overlap is no more than twice the step's growth may have begun in this
  // step: undo the drift (exactly: positions moved by drift v) to find the overlap before it.
  // The growth is the normal increment plus the curvature term |s_t|^2 / (2 D) of the
  // relative drift s (sideways motion also closes the distance).
  double touch_fraction = 0.0;
  if (drift > 0.0) {
    const Vec3 s = drift * (p.velocity[j] - p.velocity[i]);
    const double s_n = dot(s, k.normal);
    const double curvature = (norm2(s) - s_n * s_n) / (2.0 * dist);
    if (k.overlap <= 2.0 * (k.overlap_increment + curvature)) {
      touch_fraction = first_touch_fraction(reach - norm(d - s), k.overlap);
      if (touch_fraction > 0.0) scale_step_increments(k, touch_fraction);
    }
  }
  const PairParams& pair = row_params[p.material[j]];
  // k_n and c_n from r* and m*, per contact per step: caching them per entry saved ~2.5 %
  // (about the noise) and cost 16 B per entry (docs/performance.md sec. 13)
  const NormalParams normal =
      normal_params(pair, ri * rj / reach, 1.0 / (p.inverse_mass[i] + p.inverse_mass[j]));
  ContactResponse r = contact_response<R, T, RF>(pair, normal, k, inertia, contact_radius, h);
  if (touch_fraction > 0.0)
    charge_first_touch<R, T, RF>(pair, normal, k, touch_fraction, inertia, r);
  c.result[e] = {r.force_on_a, r.torque_arm, k.overlap, r.normal_force};
  if constexpr (R || T) c.moment[e] = r.moment;
  return k.overlap / std::min(ri, rj);
}

// The rows of particles [first, end).
template <bool R, bool T, bool RF>
double pair_forces(const ParticleStore& p, const PairTable& table, PairContacts& c, double dt,
                   double drift, long first, long end) {
  const int materials = table.material_count();
  const PairParams* params = &table(0, 0);
  double max_fraction = 0.0;
  for (long i = first; i < end; ++i) {
    const PairParams* row_params = params + p.material[i] * materials;
    const Vec3 xi = p.position[i];
    const double ri = p.radius[i];
    for (uint32_t e = c.row_start[i]; e < c.row_start[i + 1]; ++e)
      max_fraction =
          std::max(max_fraction, pair_entry<R, T, RF>(p, row_params, c, i, xi, ri, e, dt, drift));
  }
  return max_fraction;
}

// The reference law through the vectorised kernel (core/pair_kernel_simd.hpp) for the rows of
// particles [block.first, block.end): computes them and runs the scalar law on the entries the
// kernel hands back (contacts that may have begun in this step). Every particle's record must
// have been written (Simulation::write_particle_records, then a barrier): the rows read their
// partners' records. `deferred` must have one slot per entry (Simulation::prepare_pair_forces).
// Every contact's arithmetic is the same whichever thread or lane computes it.
static_assert(sizeof(PairResult) == pair_result_size * sizeof(double));

double pair_forces_simd(const SimdPairKernel& kernel, const SimdPairInput& in,
                        const ParticleStore& p, const PairTable& table, PairContacts& c,
                        const std::vector<uint32_t>& owners, std::vector<uint32_t>& deferred,
                        long& handed_back, double dt, double drift, IndexBlock block) {
  const int materials = table.material_count();
  uint32_t* my_deferred = deferred.data() + c.row_start[block.first];
  long deferred_count = 0;
  double m = kernel.rows(in, block.first, block.end, my_deferred, deferred_count);
  for (long k = 0; k < deferred_count; ++k) {
    const uint32_t e = my_deferred[k];
    const uint32_t i = owners[e];
    const PairParams* row_params = &table(0, 0) + p.material[i] * materials;
    m = std::max(m, pair_entry<false, false, false>(p, row_params, c, i, p.position[i], p.radius[i],
                                                    e, dt, drift));
  }
  handed_back += deferred_count;
  return m;
}

template <bool R, bool T, bool RF>
struct PairKernel {
  static double run(const ParticleStore& p, const PairTable& t, PairContacts& c, double dt,
                    double drift, IndexBlock b) {
    return pair_forces<R, T, RF>(p, t, c, dt, drift, b.first, b.end);
  }
};
}  // namespace

bool Simulation::uses_pair_kernel() const {
  // The kernel's gathers and scatters of entry data index with 32-bit signed offsets (3 per
  // Vec3): beyond 2^31 / 3 entries (and, conservatively, particles: about 180 million beads)
  // the scalar loop takes over.
  constexpr size_t kernel_index_limit = size_t{INT32_MAX} / 3;
  return simd_pair_kernel_.rows && pieces_ == ContactPieces{} && pairs_.size() > 0 &&
         pairs_.size() < kernel_index_limit && particles_.size() < kernel_index_limit;
}

void Simulation::index_entry_owners(bool walls_changed) {
  const PairContacts& c = pairs_;
  if (!uses_pair_kernel()) {  // only the kernel reads them
    one_sweep_wanted_ = false;
    entry_owners_.clear();
    wall_entry_owners_.clear();
    particle_records_.clear();
    return;
  }
  particle_records_.resize(particles_.size() * particle_record_size);
  index_rows_of_entries(c.row_start, entry_owners_);
  if (walls_changed || wall_entry_owners_.size() != wall_contacts_.size())
    index_rows_of_entries(wall_contacts_.row_start, wall_entry_owners_);
  // the rows prefetch, and a step may run as one sweep, where the partners lie far ahead
  // (core/pair_kernel_simd.hpp)
  using Prefetch = SimulationSettings::Prefetch;
  partner_reach_ = partner_reach(c.row_start.data(), c.partner.data(), particles_.size());
  prefetch_ahead_ = settings_.prefetch == Prefetch::always ||
                    (settings_.prefetch == Prefetch::automatic &&
                     prefetch_pays(partner_reach_.mean, l2_cache_bytes()));
  choose_one_sweep();
  const std::vector<int32_t>& material = particles_.material;
  one_material_ = !material.empty() && std::all_of(material.begin(), material.end(),
                                                   [&](int32_t m) { return m == material[0]; })
                      ? material[0]
                      : -1;
}

SimdPairInput Simulation::kernel_input(double drift) {
  const ParticleStore& p = particles_;
  PairContacts& c = pairs_;
  const PairTable& table = table_;
  return SimdPairInput{components(p.position),
                       components(p.velocity),
                       components(p.angular_velocity),
                       components(p.force),
                       components(p.torque),
                       p.radius.data(),
                       p.inverse_mass.data(),
                       p.inverse_inertia.data(),
                       p.material.data(),
                       particle_records_.data(),
                       &table(0, 0),
                       table.material_count(),
                       one_material_ >= 0 ? &table(one_material_, one_material_) : nullptr,
                       c.row_start.data(),
                       c.partner.data(),
                       entry_owners_.data(),
                       components(c.sliding_spring),
                       &c.result[0].force_on_first.x,
                       settings_.time_step,
                       drift,
                       prefetch_ahead_,
                       begun_curvature_bound(drift, next_speed2_)};
}

void Simulation::prepare_pair_forces() {
  if (uses_pair_kernel() && deferred_pairs_.size() < pairs_.size())
    deferred_pairs_.resize(pairs_.size());
}

void Simulation::write_particle_records(double drift, IndexBlock block) {
  simd_pair_kernel_.records(kernel_input(drift), block.first, block.end);
}

double Simulation::compute_pair_forces(double drift, IndexBlock block, long& handed_back) {
  if (uses_pair_kernel()) {
    return pair_forces_simd(simd_pair_kernel_, kernel_input(drift), particles_, table_, pairs_,
                            entry_owners_, deferred_pairs_, handed_back, settings_.time_step, drift,
                            block);
  }
  return dispatch<PairKernel>(pieces_, particles_, table_, pairs_, settings_.time_step, drift,
                              block);
}

}  // namespace grainlab
