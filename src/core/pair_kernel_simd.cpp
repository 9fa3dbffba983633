// The vectorised particle-pair force loop (core/pair_kernel_simd.hpp). This file is compiled
// three times, with GRAINLAB_SIMD_NS = simd_sse2, simd_avx2 or simd_avx512 and the matching
// -m flags, always with -ffp-contract=off (src/core/CMakeLists.txt). Everything here has
// internal linkage or is a compiler builtin: no inline function compiled for one instruction set
// can be picked by the linker for code that runs on another (ctest
// core.pair_kernel_objects_define_only_their_entry_points checks the objects with nm).
//
// The lane arithmetic mirrors the scalar law statement by statement; the comments name the
// scalar function each block reproduces. Change both together: the bit-identity test
// (tests/core/test_pair_kernel_simd.cpp) fails on any difference.
#include "core/pair_kernel_simd.hpp"

#include <immintrin.h>

#include <algorithm>
#include <array>

#include "contact/pair_params.hpp"

#ifndef GRAINLAB_SIMD_NS
#error "GRAINLAB_SIMD_NS must name the instruction set's namespace"
#endif

// AVX2 without AVX-512: 4 lanes, one 256-bit register per value (core/simd_lanes.hpp)
#if defined(__AVX2__) && !defined(__AVX512F__)
#define GRAINLAB_LANES 4
#endif
// AVX2 and AVX-512: the distance pass tests a vector of entries at a time
// (core/distance_pass_lanes.hpp); SSE2: one entry at a time. (AVX-512F implies AVX2.)
#if defined(__AVX2__)
#define GRAINLAB_DISTANCE_PASS_LANES 1
#else
#define GRAINLAB_DISTANCE_PASS_LANES 0
#endif

namespace grainlab::GRAINLAB_SIMD_NS {
namespace {

#include "core/simd_lanes.hpp"  // NOLINT(build/include): part of this file, inside the namespace
// (after the lane primitives it uses)
#include "core/contact_law_lanes.hpp"  // NOLINT(build/include): likewise, after simd_lanes.hpp

// How many batches of touching contacts the distance pass collects before the lane arithmetic
// runs on them. A batch's law is some 860 instructions with 4 lanes (AVX2), more than the reorder
// buffer holds, and the branch of the distance pass that ends a batch is taken at random (it
// depends on which entries touch): collecting 8 batches first runs their laws back to back and
// takes that branch once in 8 (measured with AVX2 on a Zen 3; 1.08-1.14x with AVX-512
// on a Sapphire Rapids class Xeon, where 4 and 8 measured the same: docs/performance.md sec. 50,
// 51). The SSE2 object, which has no vector distance pass, keeps one batch.
constexpr int batches_per_pass = GRAINLAB_DISTANCE_PASS_LANES ? 8 : 1;
constexpr int batch_capacity = batches_per_pass * lanes;

// Touching contacts collected for the lane arithmetic, in entry order, `lanes` at a time from
// the start. The distance test that selects them already gave d = x_j - x_i and the radii;
// the lanes compute |d|^2 and r_i + r_j again, by the same operations (two stores fewer per
// entry, in a pass bound by its stores: docs/performance.md sec. 50).
// (`lanes` values of room past the capacity: the AVX2 distance pass stores whole vectors at
// the count, which is below the capacity)
constexpr int batch_room = batch_capacity + lanes;
struct Batch {
  alignas(64) double dx[batch_room], dy[batch_room], dz[batch_room], ri[batch_room], rj[batch_room];
  uint32_t i[batch_room], j[batch_room], e[batch_room];
};

#include "core/distance_pass_lanes.hpp"  // NOLINT(build/include): part of this file, after Batch

// Runs the contact law on the `count` (1 to lanes) contacts of the batch from `first` on and
// stores each result, except for contacts that may have begun in this step, whose entries go to
// `deferred`. Returns their largest overlap fraction.
double process_batch(const SimdPairInput& in, Batch& whole, int first, int count,
                     uint32_t* deferred, long& deferred_count) {
  // the batch's lanes as arrays from `first` on
  struct Lanes {
    double *dx, *dy, *dz, *ri, *rj;
    uint32_t *i, *j, *e;
  } b{whole.dx + first, whole.dy + first, whole.dz + first, whole.ri + first,
      whole.rj + first, whole.i + first,  whole.j + first,  whole.e + first};
  // Unused lanes repeat the last contact: valid numbers, never stored. (Only the pass's last
  // batch has any, and it is the last in the arrays: a lane past it is free.)
  for (int l = count; l < lanes; ++l) {
    const int last = count - 1;
    b.dx[l] = b.dx[last], b.dy[l] = b.dy[last], b.dz[l] = b.dz[last];
    b.ri[l] = b.ri[last], b.rj[l] = b.rj[last];
    b.i[l] = b.i[last], b.j[l] = b.j[last], b.e[l] = b.e[last];
  }
  vd dx, dy, dz, ri, rj;
  __builtin_memcpy(&dx, b.dx, sizeof dx);
  __builtin_memcpy(&dy, b.dy, sizeof dy);
  __builtin_memcpy(&dz, b.dz, sizeof dz);
  __builtin_memcpy(&ri, b.ri, sizeof ri);
  __builtin_memcpy(&rj, b.rj, sizeof rj);
  const double drift = in.drift;
  // as the distance pass computed them
  const vd dist2 = dx * dx + dy * dy + dz * dz, reach = ri + rj;

  // pair_entry: normal, overlap and the levers (contact point halfway through the overlap)
  const vd dist = lane_sqrt(dist2);
  const vd inverse_dist = 1.0 / dist;
  const V3 n{inverse_dist * dx, inverse_dist * dy, inverse_dist * dz};
  const vd overlap = reach - dist;
  const vd lever_i = ri - 0.5 * overlap, lever_j = rj - 0.5 * overlap;

  // set_step_displacement (half-step velocities, lever_shrink = 1/2): the springs' increment
  const LaneIndex e = lane_index(b.e);
  const RecordHead head_i = load_record_head(in.particle_record, b.i);
  const RecordHead head_j = load_record_head(in.particle_record, b.j);
  const auto [dv, overlap_increment, tangential_displacement] = step_increment(
      n, drift, 0.5, head_i.velocity, head_i.spin, lever_i, head_j.velocity, head_j.spin, lever_j);

  // set_relative_velocity with the end-of-step estimates (particle_records): the dashpots' rates
  const RecordTail tail_i = load_record_tail(in.particle_record, b.i);
  const RecordTail tail_j = load_record_tail(in.particle_record, b.j);
  const V3 v_end_i{head_i.velocity_at_end_x, head_i.velocity_at_end_y, tail_i.velocity_at_end_z};
  const V3 v_end_j{head_j.velocity_at_end_x, head_j.velocity_at_end_y, tail_j.velocity_at_end_z};
  const auto [overlap_rate, tangential_velocity] =
      contact_rates(n, v_end_i, tail_i.spin_at_end, lever_i, v_end_j, tail_j.spin_at_end, lever_j);

  // pair_entry: may this contact have begun during the step? Then the scalar law takes it. Its
  // test costs 10 multiplications per lane, and multiplications bound this loop on the VM's Zen 5
  // (one more per batch: 0.3 % of the step; docs/performance.md sec. 30): it runs only where some
  // lane of the batch might pass it, which a bound of its curvature term rules out for almost every
  // batch in a dense packing (SimdPairInput::curvature_bound; a lane with a NaN runs it).
  const bool drifted = drift > 0.0;
  vmask begun{};
  if (drifted) {
    const vd growth_bound = overlap_increment + in.curvature_bound * inverse_dist;
    const unsigned used = (1u << count) - 1u;
    if ((~lane_bits(overlap > growth_bound + growth_bound) & used) != 0) {
      const V3 s = drift * dv;
      const vd s_n = dot(s, n);
      const vd curvature = (dot(s, s) - s_n * s_n) / (2.0 * dist);
      begun = overlap <= 2.0 * (overlap_increment + curvature);
    }
  }

  // the pair's constants
  LaneConstants k;
  if (const PairParams* one = in.one_pair) {  // one material: the same constants in every lane
    k = {splat(one->stiffness_per_radius), splat(one->damping_ratio), splat(one->rns),
         splat(one->rzs), splat(one->friction)};
  } else {
    for (int l = 0; l < lanes; ++l)
      k.set(l, in.pair_params[in.material[b.i[l]] * in.material_count + in.material[b.j[l]]]);
  }
  // normal_params: k_n = pi E r* and c_n = 2 zeta sqrt(k_n m*), with r* = r_i r_j / (r_i + r_j)
  // and m* = 1 / (1/m_i + 1/m_j); computed per contact rather than stored per entry (16 B per
  // entry; docs/performance.md sec. 13)
  const vd inverse_mass_i = load_lanes(in.inverse_mass, lane_index(b.i), 1, 0);
  const vd inverse_mass_j = load_lanes(in.inverse_mass, lane_index(b.j), 1, 0);
  const vd normal_stiffness = k.stiffness_per_radius * (ri * rj / reach);
  const vd normal_damping = 2.0 * k.damping_ratio *
                            lane_sqrt(normal_stiffness * (1.0 / (inverse_mass_i + inverse_mass_j)));

  const LawResult law =
      contact_law(n, overlap, overlap_rate, tangential_displacement, tangential_velocity,
                  normal_stiffness, normal_damping, k, load_lanes3(in.sliding_spring, e));
  const V3 &force_on_i = law.force_on_a, &arm = law.arm, &spring = law.spring;
  const vd& normal_force = law.normal_force;
  const vd fraction = overlap / (rj < ri ? rj : ri);

  // Which lanes to store: the batch's contacts, less those handed back to the scalar law (as
  // mask bits, without a branch per lane).
  const auto [store, handed_back] = choose_lanes(count, drifted, begun);
  for (unsigned h = handed_back; h != 0; h &= h - 1)
    deferred[deferred_count++] = b.e[__builtin_ctz(h)];
  const double max_fraction = largest_ordered(fraction, (1u << count) - 1u);
  // The results, one vector per value, transposed to one 64-byte PairResult per lane and stored
  // whole (a line each, where a scatter per value would write 8 values across 8 lines).
  static_assert(pair_result_size == 8);
#if GRAINLAB_LANES == 8
  const vd value[pair_result_size] = {force_on_i.x, force_on_i.y, force_on_i.z, arm.x,
                                      arm.y,        arm.z,        overlap,      normal_force};
  vd row[lanes];
  transpose8(value, row);
  // (a loop of constant length, unrolled: the rows stay in registers)
#pragma GCC unroll 8
  for (int l = 0; l < lanes; ++l)
    if (store >> l & 1u)
      __builtin_memcpy(in.result + size_t{b.e[l]} * pair_result_size, &row[l], sizeof row[l]);
#else
  // 4 lanes: values 0..3 and 4..7 of each lane's line from two 4 x 4 transposes
  const vd4 low[4] = {force_on_i.x, force_on_i.y, force_on_i.z, arm.x};
  const vd4 high[4] = {arm.y, arm.z, overlap, normal_force};
  vd4 row_low[4], row_high[4];
  transpose4(low, row_low);
  transpose4(high, row_high);
#pragma GCC unroll 4
  for (int l = 0; l < lanes; ++l)
    if (store >> l & 1u) {
      double* line = in.result + size_t{b.e[l]} * pair_result_size;
      __builtin_memcpy(line, &row_low[l], sizeof row_low[l]);
      __builtin_memcpy(line + 4, &row_high[l], sizeof row_high[l]);
    }
#endif
  store_lanes3(in.sliding_spring, b.e, spring, store);
  return max_fraction;
}

// How many entries ahead the rows prefetch: about 8 beads' rows, some 0.2 us of the pass,
// more than a miss to memory takes. 12 to 96 measured the same on 88,400 beads.
constexpr uint32_t prefetch_distance = 24;

// pair_rows with or without the prefetch (in.prefetch_ahead); the same results.
template <bool Prefetch>
double rows(const SimdPairInput& in, long first_row, long end_row, uint32_t* deferred,
            long& deferred_count) {
  deferred_count = 0;
  double max_fraction = 0.0;
  Batch b;
  int count = 0;
  // local copies: the compiler cannot tell that the stores below leave `in` unchanged
  const double* const position = in.position;
  const double* const radius = in.radius;
  const uint32_t* const row_start = in.row_start;
  const uint32_t* const partner = in.partner;
  double* const result = in.result;
  double* const sliding_spring = in.sliding_spring;
  alignas(64) double scratch[pair_result_size];
  // One flat pass over the entries of the rows (short rows would cost a mispredicted loop exit
  // each): the entry's first particle comes from the owner array.
  const uint32_t* const owner = in.owner;
  const uint32_t first_entry = row_start[first_row], end_entry = row_start[end_row];
  // Ask the caches for what the entries some way ahead will use (docs/performance.md sec. 26):
  // their result lines and springs, written or read and written in this pass, and the partner's
  // velocity record (its two lines), which the lanes read. A partner lies up to one layer of
  // cells further on in the particle order: in a large packing (88,400 beads: about 2,000 beads a
  // layer) the streams of a layer's entries evict its record from the L2 before the lanes reach
  // it, and the hardware's prefetchers, which follow streams, do not fetch it. In a small one
  // everything is in the caches and the prefetch is only more instructions.
  const auto prefetch = [&](uint32_t e) {
    const uint32_t ahead = end_entry - e > prefetch_distance ? e + prefetch_distance : e;
    __builtin_prefetch(result + size_t{ahead} * pair_result_size, 1);
    __builtin_prefetch(sliding_spring + size_t{ahead} * 3, 1);
    const double* record = in.particle_record + size_t{partner[ahead]} * particle_record_size;
    __builtin_prefetch(record, 0);
    __builtin_prefetch(record + 8, 0);
  };
  // No branch on touching, which is unpredictable in a packing: an entry apart gets its zeros
  // written in place, a touching one writes the same zeros to a scratch record instead. (The
  // destination is chosen by masking addresses: with a select GCC emits a branch.)
  const auto scratch_if_touching = [&](double* apart, bool touching) {
    uintptr_t to_scratch = uintptr_t{0} - uintptr_t{touching};  // all ones when touching
    asm("" : "+r"(to_scratch));
    return reinterpret_cast<double*>((reinterpret_cast<uintptr_t>(scratch) & to_scratch) |
                                     (reinterpret_cast<uintptr_t>(apart) & ~to_scratch));
  };
  const auto zero_spring = [&](uint32_t e, bool touching) {
    store_zero3(scratch_if_touching(sliding_spring + size_t{3} * e, touching));  // forgotten
  };
  // The result line's zeros. With AVX2 and AVX-512 every entry's line is zeroed whatever the test
  // says (the lanes or the scalar law write a touching one's afterwards): the stores then wait for
  // no distance test, which their masked address made them do, the hottest spot of the pass
  // (docs/performance.md sec. 50; core/distance_pass_lanes.hpp).
  const auto write_zeros = [&](uint32_t e, bool touching) {
#if GRAINLAB_DISTANCE_PASS_LANES
    zero_result_line(result, e);
#else
    using result_line = double __attribute__((vector_size(pair_result_size * sizeof(double))));
    const result_line zero{};
    __builtin_memcpy(scratch_if_touching(result + size_t{pair_result_size} * e, touching), &zero,
                     sizeof zero);
#endif
    zero_spring(e, touching);
  };
  // Runs the law on the collected batches once `count` reaches the capacity; a part batch stays
  // (moved to the front), so that the batches are the touching entries `lanes` at a time in
  // entry order however the pass collects them.
  const auto run_full_batches = [&] {
    const int full = count - count % lanes;
    for (int first = 0; first < full; first += lanes) {
      const double m = process_batch(in, b, first, lanes, deferred, deferred_count);
      if (max_fraction < m) max_fraction = m;
    }
    for (int l = 0; l < count - full; ++l) {
      b.dx[l] = b.dx[full + l], b.dy[l] = b.dy[full + l], b.dz[l] = b.dz[full + l];
      b.ri[l] = b.ri[full + l], b.rj[l] = b.rj[full + l];
      b.i[l] = b.i[full + l], b.j[l] = b.j[full + l], b.e[l] = b.e[full + l];
    }
    count -= full;
  };
  uint32_t e = first_entry;
#if GRAINLAB_DISTANCE_PASS_LANES
  e = distance_pass_lanes<Prefetch>(in, e, end_entry, b, count, prefetch, zero_spring,
                                    run_full_batches);
#endif
  for (; e < end_entry; ++e) {
    if constexpr (Prefetch) prefetch(e);
    const uint32_t i = owner[e];
    const double* x_i = position + size_t{i} * 3;
    const double r_i = radius[i];
    const uint32_t j = partner[e];
    const double* x_j = position + size_t{j} * 3;
    const double r_j = radius[j];
    const double dx = x_j[0] - x_i[0], dy = x_j[1] - x_i[1], dz = x_j[2] - x_i[2];
    const double reach = r_i + r_j;
    const double dist2 = dx * dx + dy * dy + dz * dz;
    const bool touching = !(dist2 >= reach * reach);  // as the scalar test (NaN: touching)
    write_zeros(e, touching);
    // every entry is offered to the batch, and only touching ones advance its count (the count
    // in a register)
    const int l = count;
    b.dx[l] = dx, b.dy[l] = dy, b.dz[l] = dz;
    b.ri[l] = r_i, b.rj[l] = r_j;
    b.i[l] = i, b.j[l] = j, b.e[l] = e;
    count += touching;
    if (count == batch_capacity) run_full_batches();
  }
  // the rest: full batches, then the last one's `count % lanes` contacts
  for (int first = 0; first < count; first += lanes) {
    const double m =
        process_batch(in, b, first, std::min(lanes, count - first), deferred, deferred_count);
    if (max_fraction < m) max_fraction = m;
  }
  return max_fraction;
}

}  // namespace

void particle_records(const SimdPairInput& given, long first, long end) {
  // (a local copy: the compiler cannot tell that the records' stores leave `given` as it is, and
  // would load its pointers again for every particle)
  const SimdPairInput in = given;
  // velocity_at_step_end / spin_at_step_end: v(t + dt/2) + dt/2 F(t)/m, the same operations
  const double half_dt = 0.5 * in.time_step;
#if defined(__AVX512F__) || defined(__AVX2__)
  // A particle's Vec3s as 4-double vectors, the fourth value the next particle's x; its record in
  // four overlapping stores in order, each fourth value overwritten by the next store. The last
  // particle of the range loads and stores only its own values (masked): the next record may be
  // another thread's, and the arrays may end with it.
  const auto record_one = [&](long i, auto load3, auto store3) {
    const long o = 3 * i;
    const vd4 v = load3(in.velocity + o), w = load3(in.angular_velocity + o);
    const vd4 f = load3(in.force + o), t = load3(in.torque + o);
    const double kick = half_dt * in.inverse_mass[i], spin_kick = half_dt * in.inverse_inertia[i];
    double* r = in.particle_record + particle_record_size * i;
    store3(r, v);
    store3(r + 3, w);
    store3(r + 6, v + vd4{kick, kick, kick, kick} * f);
    store3(r + 9, w + vd4{spin_kick, spin_kick, spin_kick, spin_kick} * t);
  };
  const auto load4 = [](const double* p) {
    vd4 x;
    __builtin_memcpy(&x, p, sizeof x);
    return x;
  };
  const auto store4 = [](double* p, vd4 x) { __builtin_memcpy(p, &x, sizeof x); };
#if defined(__AVX512F__)
  const auto masked_load3 = [](const double* p) {
    const vd x = reinterpret_cast<vd>(_mm512_maskz_loadu_pd(0x07, p));
    return __builtin_shufflevector(x, x, 0, 1, 2, 3);
  };
  const auto masked_store3 = [](double* p, vd4 x) {
    _mm512_mask_storeu_pd(
        p, 0x07, reinterpret_cast<__m512d>(__builtin_shufflevector(x, x, 0, 1, 2, 3, 0, 1, 2, 3)));
  };
#else
  const __m256i first_three = _mm256_setr_epi64x(-1, -1, -1, 0);
  const auto masked_load3 = [&](const double* p) {
    return reinterpret_cast<vd4>(_mm256_maskload_pd(p, first_three));
  };
  const auto masked_store3 = [&](double* p, vd4 x) {
    _mm256_maskstore_pd(p, first_three, reinterpret_cast<__m256d>(x));
  };
#endif
  if (end <= first) return;
  for (long i = first; i < end - 1; ++i) record_one(i, load4, store4);
  record_one(end - 1, masked_load3, masked_store3);
#else
  for (long i = first; i < end; ++i) {
    const double* v = in.velocity + 3 * i;
    const double* w = in.angular_velocity + 3 * i;
    const double* f = in.force + 3 * i;
    const double* t = in.torque + 3 * i;
    const double kick = half_dt * in.inverse_mass[i], spin_kick = half_dt * in.inverse_inertia[i];
    double* r = in.particle_record + particle_record_size * i;
    r[0] = v[0], r[1] = v[1], r[2] = v[2];
    r[3] = w[0], r[4] = w[1], r[5] = w[2];
    r[6] = v[0] + kick * f[0], r[7] = v[1] + kick * f[1], r[8] = v[2] + kick * f[2];
    r[9] = w[0] + spin_kick * t[0], r[10] = w[1] + spin_kick * t[1],
    r[11] = w[2] + spin_kick * t[2];
  }
#endif
}

double pair_rows(const SimdPairInput& in, long first_row, long end_row, uint32_t* deferred,
                 long& deferred_count) {
  return in.prefetch_ahead ? rows<true>(in, first_row, end_row, deferred, deferred_count)
                           : rows<false>(in, first_row, end_row, deferred, deferred_count);
}

}  // namespace grainlab::GRAINLAB_SIMD_NS
