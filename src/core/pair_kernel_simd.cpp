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

#include "contact/pair_params.hpp"

#ifndef GRAINLAB_SIMD_NS
#error "GRAINLAB_SIMD_NS must name the instruction set's namespace"
#endif

namespace grainlab::GRAINLAB_SIMD_NS {
namespace {

#define GRAINLAB_LANES_INLINE [[gnu::always_inline]] inline

constexpr int lanes = 8;
using vd = double __attribute__((vector_size(64)));
using vmask = long long __attribute__((vector_size(64)));  // per lane: -1 true, 0 false

GRAINLAB_LANES_INLINE vd splat(double x) {  // x in every lane
  return vd{x, x, x, x, x, x, x, x};
}

GRAINLAB_LANES_INLINE vd lane_sqrt(vd a) {
#if defined(__AVX512F__)
  return _mm512_mask_sqrt_pd(a, 0xFF, a);  // all lanes (the unmasked form warns in GCC 12)
#elif defined(__AVX__)
  const __m256d lo = _mm256_sqrt_pd(__builtin_shufflevector(a, a, 0, 1, 2, 3));
  const __m256d hi = _mm256_sqrt_pd(__builtin_shufflevector(a, a, 4, 5, 6, 7));
  return __builtin_shufflevector(lo, hi, 0, 1, 2, 3, 4, 5, 6, 7);
#else
  const __m128d q0 = _mm_sqrt_pd(__builtin_shufflevector(a, a, 0, 1));
  const __m128d q1 = _mm_sqrt_pd(__builtin_shufflevector(a, a, 2, 3));
  const __m128d q2 = _mm_sqrt_pd(__builtin_shufflevector(a, a, 4, 5));
  const __m128d q3 = _mm_sqrt_pd(__builtin_shufflevector(a, a, 6, 7));
  const auto lo = __builtin_shufflevector(q0, q1, 0, 1, 2, 3);
  const auto hi = __builtin_shufflevector(q2, q3, 0, 1, 2, 3);
  return __builtin_shufflevector(lo, hi, 0, 1, 2, 3, 4, 5, 6, 7);
#endif
}

// A 3-vector per lane, with the operations of core/vec3.hpp in the same association order.
struct V3 {
  vd x, y, z;
};
GRAINLAB_LANES_INLINE V3 operator+(const V3& a, const V3& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
GRAINLAB_LANES_INLINE V3 operator-(const V3& a, const V3& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
GRAINLAB_LANES_INLINE V3 operator*(vd s, const V3& a) {
  return {s * a.x, s * a.y, s * a.z};
}
GRAINLAB_LANES_INLINE V3 operator*(double s, const V3& a) {
  return {s * a.x, s * a.y, s * a.z};
}
GRAINLAB_LANES_INLINE vd dot(const V3& a, const V3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
GRAINLAB_LANES_INLINE V3 cross(const V3& a, const V3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
GRAINLAB_LANES_INLINE V3 select(vmask m, const V3& a, const V3& b) {
  return {m ? a.x : b.x, m ? a.y : b.y, m ? a.z : b.z};
}

// The entry index of each lane, with the offsets of its fields: index for a scalar field,
// 3 index for a Vec3 field. With AVX2 and AVX-512 the lanes are filled by gather instructions
// (plain loads: the values are bit for bit those of scalar loads).
struct LaneIndex {
  const uint32_t* index;
#if defined(__AVX2__)
  __m256i times1, times3;  // 8 x int32
#endif
};
GRAINLAB_LANES_INLINE LaneIndex lane_index(const uint32_t* index) {
  LaneIndex r{};
  r.index = index;
#if defined(__AVX2__)
  r.times1 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(index));
  r.times3 = _mm256_add_epi32(_mm256_add_epi32(r.times1, r.times1), r.times1);
#endif
  return r;
}
// Lane l of the result: base[stride * index[l] + offset] (stride 1 or 3).
GRAINLAB_LANES_INLINE vd load_lanes(const double* base, const LaneIndex& x, int stride,
                                    int offset) {
#if defined(__AVX512F__)
  // (the masked form with all lanes on: the unmasked one warns in GCC 12)
  return _mm512_mask_i32gather_pd(_mm512_setzero_pd(), 0xFF, stride == 3 ? x.times3 : x.times1,
                                  base + offset, 8);
#elif defined(__AVX2__)
  // (the masked form with all lanes on, as for AVX-512)
  const __m256i index = stride == 3 ? x.times3 : x.times1;
  const __m256d all = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
  const __m256d lo = _mm256_mask_i32gather_pd(_mm256_setzero_pd(), base + offset,
                                              _mm256_castsi256_si128(index), all, 8);
  const __m256d hi = _mm256_mask_i32gather_pd(_mm256_setzero_pd(), base + offset,
                                              _mm256_extracti128_si256(index, 1), all, 8);
  return __builtin_shufflevector(lo, hi, 0, 1, 2, 3, 4, 5, 6, 7);
#else
  vd r{};
  for (int l = 0; l < lanes; ++l) r[l] = base[size_t{x.index[l]} * stride + offset];
  return r;
#endif
}
GRAINLAB_LANES_INLINE V3 load_lanes3(const double* base, const LaneIndex& x) {
  return {load_lanes(base, x, 3, 0), load_lanes(base, x, 3, 1), load_lanes(base, x, 3, 2)};
}
GRAINLAB_LANES_INLINE void store_lane3(double* base, uint32_t index, const V3& v, int l) {
  double* out = base + size_t{index} * 3;
  out[0] = v.x[l];
  out[1] = v.y[l];
  out[2] = v.z[l];
}

// 8 x 8 transpose: value[v][l] = r[l][v] (rows of 8 values per lane to one vector per value, or
// back: the transpose is its own inverse). Pairs of rows, then quads, then halves.
GRAINLAB_LANES_INLINE void transpose8(const vd (&r)[lanes], vd (&value)[lanes]) {
  vd a[lanes], b[lanes];
  for (int k = 0; k < 4; ++k) {
    a[2 * k] = __builtin_shufflevector(r[2 * k], r[2 * k + 1], 0, 8, 2, 10, 4, 12, 6, 14);
    a[2 * k + 1] = __builtin_shufflevector(r[2 * k], r[2 * k + 1], 1, 9, 3, 11, 5, 13, 7, 15);
  }
  for (int h = 0; h < 2; ++h)            // rows 0-3, rows 4-7
    for (int odd = 0; odd < 2; ++odd) {  // values 0 2 4 6, values 1 3 5 7
      const vd& x = a[4 * h + odd];
      const vd& y = a[4 * h + 2 + odd];
      b[4 * h + 2 * odd] = __builtin_shufflevector(x, y, 0, 1, 8, 9, 4, 5, 12, 13);
      b[4 * h + 2 * odd + 1] = __builtin_shufflevector(x, y, 2, 3, 10, 11, 6, 7, 14, 15);
    }
  // b[2 odd + s] (rows 0-3) and b[4 + 2 odd + s] (rows 4-7) hold values v and v + 4 with
  // v = odd + 2 s
  for (int odd = 0; odd < 2; ++odd)
    for (int s = 0; s < 2; ++s) {
      const vd& lo = b[2 * odd + s];
      const vd& hi = b[4 + 2 * odd + s];
      const int v = odd + 2 * s;
      value[v] = __builtin_shufflevector(lo, hi, 0, 1, 2, 3, 8, 9, 10, 11);
      value[v + 4] = __builtin_shufflevector(lo, hi, 4, 5, 6, 7, 12, 13, 14, 15);
    }
}

// The velocities of each lane's particle from its record (particle_records): per lane a load of
// values 0..7 and one of values 8..11, each transposed so that a value is one lane vector. The
// two halves are loaded where they are first needed, which keeps fewer vectors live.
using vd4 = double __attribute__((vector_size(32)));
struct RecordHead {  // values 0..7
  V3 velocity, spin;
  vd velocity_at_end_x, velocity_at_end_y;
};
GRAINLAB_LANES_INLINE RecordHead load_record_head(const double* record, const uint32_t* index) {
  vd r[lanes];  // r[l]: values 0..7 of lane l
  for (int l = 0; l < lanes; ++l)
    __builtin_memcpy(&r[l], record + size_t{index[l]} * particle_record_size, sizeof r[l]);
  vd value[lanes];
  transpose8(r, value);
  return {{value[0], value[1], value[2]}, {value[3], value[4], value[5]}, value[6], value[7]};
}
struct RecordTail {  // values 8..11
  vd velocity_at_end_z;
  V3 spin_at_end;
};
GRAINLAB_LANES_INLINE RecordTail load_record_tail(const double* record, const uint32_t* index) {
  vd4 q[lanes];  // q[l]: values 8..11 of lane l
  for (int l = 0; l < lanes; ++l)
    __builtin_memcpy(&q[l], record + size_t{index[l]} * particle_record_size + 8, sizeof q[l]);
  // 4 x 8 transpose: lanes l and l + 4 side by side, then pairs and quads as above.
  vd c[4], d[4], value[4];
  for (int k = 0; k < 4; ++k)
    c[k] = __builtin_shufflevector(q[k], q[k + 4], 0, 1, 2, 3, 4, 5, 6, 7);
  d[0] = __builtin_shufflevector(c[0], c[1], 0, 8, 2, 10, 4, 12, 6, 14);
  d[1] = __builtin_shufflevector(c[0], c[1], 1, 9, 3, 11, 5, 13, 7, 15);
  d[2] = __builtin_shufflevector(c[2], c[3], 0, 8, 2, 10, 4, 12, 6, 14);
  d[3] = __builtin_shufflevector(c[2], c[3], 1, 9, 3, 11, 5, 13, 7, 15);
  value[0] = __builtin_shufflevector(d[0], d[2], 0, 1, 8, 9, 4, 5, 12, 13);
  value[2] = __builtin_shufflevector(d[0], d[2], 2, 3, 10, 11, 6, 7, 14, 15);
  value[1] = __builtin_shufflevector(d[1], d[3], 0, 1, 8, 9, 4, 5, 12, 13);
  value[3] = __builtin_shufflevector(d[1], d[3], 2, 3, 10, 11, 6, 7, 14, 15);
  return {value[0], {value[1], value[2], value[3]}};
}

GRAINLAB_LANES_INLINE void store_zero3(double* out) {
  out[0] = out[1] = out[2] = 0.0;
}

// Touching contacts collected for one pass of the lane arithmetic. The distance test that
// selects them already gave d = x_j - x_i, |d|^2 and r_i + r_j.
struct Batch {
  alignas(64) double dx[lanes], dy[lanes], dz[lanes], dist2[lanes], reach[lanes], ri[lanes],
      rj[lanes];
  uint32_t i[lanes], j[lanes], e[lanes];
  int count = 0;
};

// Runs the contact law on the batch's contacts and stores each result, except for contacts that
// may have begun in this step, whose entries go to `deferred`. Returns the batch's largest
// overlap fraction.
double process_batch(const SimdPairInput& in, Batch& b, uint32_t* deferred, long& deferred_count) {
  // Unused lanes repeat the last contact: valid numbers, never stored.
  for (int l = b.count; l < lanes; ++l) {
    const int last = b.count - 1;
    b.dx[l] = b.dx[last], b.dy[l] = b.dy[last], b.dz[l] = b.dz[last];
    b.dist2[l] = b.dist2[last], b.reach[l] = b.reach[last];
    b.ri[l] = b.ri[last], b.rj[l] = b.rj[last];
    b.i[l] = b.i[last], b.j[l] = b.j[last], b.e[l] = b.e[last];
  }
  vd dx, dy, dz, dist2, reach, ri, rj;
  __builtin_memcpy(&dx, b.dx, sizeof dx);
  __builtin_memcpy(&dy, b.dy, sizeof dy);
  __builtin_memcpy(&dz, b.dz, sizeof dz);
  __builtin_memcpy(&dist2, b.dist2, sizeof dist2);
  __builtin_memcpy(&reach, b.reach, sizeof reach);
  __builtin_memcpy(&ri, b.ri, sizeof ri);
  __builtin_memcpy(&rj, b.rj, sizeof rj);
  const double drift = in.drift;

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
  const V3 &v_i = head_i.velocity, &v_j = head_j.velocity, &w_i = head_i.spin, &w_j = head_j.spin;
  const V3 dv = v_j - v_i;
  const vd overlap_increment = -drift * dot(dv, n);
  const vd shift = 0.5 * 0.5 * overlap_increment;
  const V3 step_relative = dv - cross((lever_j + shift) * w_j + (lever_i + shift) * w_i, n);
  const V3 tangential_displacement = drift * (step_relative - dot(step_relative, n) * n);

  // set_relative_velocity with the end-of-step estimates (particle_records): the dashpots' rates
  const RecordTail tail_i = load_record_tail(in.particle_record, b.i);
  const RecordTail tail_j = load_record_tail(in.particle_record, b.j);
  const V3 v_end_i{head_i.velocity_at_end_x, head_i.velocity_at_end_y, tail_i.velocity_at_end_z};
  const V3 v_end_j{head_j.velocity_at_end_x, head_j.velocity_at_end_y, tail_j.velocity_at_end_z};
  const V3 &w_end_i = tail_i.spin_at_end, &w_end_j = tail_j.spin_at_end;
  const V3 relative = v_end_j - v_end_i - cross(lever_j * w_end_j + lever_i * w_end_i, n);
  const vd normal_speed = dot(relative, n);
  const vd overlap_rate = -normal_speed;
  const V3 tangential_velocity = relative - normal_speed * n;

  // pair_entry: may this contact have begun during the step? Then the scalar law takes it.
  const V3 s = drift * dv;
  const vd s_n = dot(s, n);
  const vd curvature = (dot(s, s) - s_n * s_n) / (2.0 * dist);
  const vmask begun = overlap <= 2.0 * (overlap_increment + curvature);
  const bool drifted = drift > 0.0;

  // the pair's constants
  vd stiffness_per_radius, damping_ratio, rns, rzs, friction;
  if (const PairParams* one = in.one_pair) {  // one material: the same constants in every lane
    stiffness_per_radius = splat(one->stiffness_per_radius);
    damping_ratio = splat(one->damping_ratio);
    rns = splat(one->rns);
    rzs = splat(one->rzs);
    friction = splat(one->friction);
  } else {
    for (int l = 0; l < lanes; ++l) {
      const PairParams& pair =
          in.pair_params[in.material[b.i[l]] * in.material_count + in.material[b.j[l]]];
      stiffness_per_radius[l] = pair.stiffness_per_radius;
      damping_ratio[l] = pair.damping_ratio;
      rns[l] = pair.rns;
      rzs[l] = pair.rzs;
      friction[l] = pair.friction;
    }
  }
  // normal_params: k_n = pi E r* and c_n = 2 zeta sqrt(k_n m*), with r* = r_i r_j / (r_i + r_j)
  // and m* = 1 / (1/m_i + 1/m_j); computed per contact rather than stored per entry (16 B per
  // entry; docs/performance.md sec. 13)
  const vd inverse_mass_i = load_lanes(in.inverse_mass, lane_index(b.i), 1, 0);
  const vd inverse_mass_j = load_lanes(in.inverse_mass, lane_index(b.j), 1, 0);
  const vd normal_stiffness = stiffness_per_radius * (ri * rj / reach);
  const vd normal_damping =
      2.0 * damping_ratio * lane_sqrt(normal_stiffness * (1.0 / (inverse_mass_i + inverse_mass_j)));

  // normal_force: F_n = k_n U_n + c_n dU_n/dt, clamped at 0
  const vd f = normal_stiffness * overlap + normal_damping * overlap_rate;
  const vd normal_force = f > 0.0 ? f : vd{};
  const vd sliding_stiffness = rns * normal_stiffness, sliding_damping = rzs * normal_damping;

  // keep_in_tangent_plane: turn the spring into the current tangent plane, length kept
  V3 spring = load_lanes3(in.sliding_spring, e);
  {
    const vd length2 = dot(spring, spring);
    const V3 in_plane = spring - dot(spring, n) * n;
    const vd in_plane2 = dot(in_plane, in_plane);
    const V3 scaled = lane_sqrt(length2 / in_plane2) * in_plane;
    spring = select(length2 == 0.0, spring, select(in_plane2 > 0.0, scaled, in_plane));
  }
  // spring_slider: advance, respond, cap at mu F_n (slip shortens the spring)
  spring = spring + tangential_displacement;
  V3 tangential = sliding_stiffness * spring + sliding_damping * tangential_velocity;
  {
    const vd cap = friction * normal_force;
    const vd magnitude2 = dot(tangential, tangential);
    const vmask slip = magnitude2 > cap * cap;
    const V3 capped = (cap / lane_sqrt(magnitude2)) * tangential;
    const V3 slipped_spring =
        select(sliding_stiffness > 0.0,
               (1.0 / sliding_stiffness) * (capped - sliding_damping * tangential_velocity), V3{});
    tangential = select(slip, capped, tangential);
    spring = select(slip, slipped_spring, spring);
  }
  // contact_response: force on i and the torque arm n x F_t (each body's torque is its lever
  // times the arm, formed in the gather from the stored overlap)
  const V3 force_on_i = tangential - normal_force * n;
  const V3 arm = cross(n, tangential);
  const vd fraction = overlap / (rj < ri ? rj : ri);

  // Which lanes to store: the batch's contacts, less those handed back to the scalar law.
  double max_fraction = 0.0;
  unsigned store = 0;
  for (int l = 0; l < b.count; ++l) {
    if (max_fraction < fraction[l]) max_fraction = fraction[l];
    if (drifted && begun[l])
      deferred[deferred_count++] = b.e[l];
    else
      store |= 1u << l;
  }
  // The results, one vector per value, transposed to one 64-byte PairResult per lane and stored
  // whole (a line each, where a scatter per value would write 8 values across 8 lines).
  const vd value[lanes] = {force_on_i.x, force_on_i.y, force_on_i.z, arm.x,
                           arm.y,        arm.z,        overlap,      normal_force};
  vd row[lanes];
  transpose8(value, row);
  static_assert(pair_result_size == lanes);
  for (int l = 0; l < b.count; ++l)
    if (store >> l & 1u)
      __builtin_memcpy(in.result + size_t{b.e[l]} * pair_result_size, &row[l], sizeof row[l]);
#if defined(__AVX512F__)
  // the springs: a scatter instruction per component instead of a lane extract and a store per
  // lane
  const __mmask8 m = static_cast<__mmask8>(store);
  _mm512_mask_i32scatter_pd(in.sliding_spring, m, e.times3, spring.x, 8);
  _mm512_mask_i32scatter_pd(in.sliding_spring + 1, m, e.times3, spring.y, 8);
  _mm512_mask_i32scatter_pd(in.sliding_spring + 2, m, e.times3, spring.z, 8);
#else
  for (int l = 0; l < b.count; ++l)
    if (store >> l & 1u) store_lane3(in.sliding_spring, b.e[l], spring, l);
#endif
  return max_fraction;
}

}  // namespace

void particle_records(const SimdPairInput& in, long first, long end) {
  // velocity_at_step_end / spin_at_step_end: v(t + dt/2) + dt/2 F(t)/m, the same operations
  const double half_dt = 0.5 * in.time_step;
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
}

double pair_rows(const SimdPairInput& in, long first_row, long end_row, uint32_t* deferred,
                 long& deferred_count) {
  deferred_count = 0;
  double max_fraction = 0.0;
  Batch b;
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
  for (uint32_t e = first_entry; e < end_entry; ++e) {
    const uint32_t i = owner[e];
    const double* x_i = position + size_t{i} * 3;
    const double r_i = radius[i];
    const uint32_t j = partner[e];
    const double* x_j = position + size_t{j} * 3;
    const double r_j = radius[j];
    const double dx = x_j[0] - x_i[0], dy = x_j[1] - x_i[1], dz = x_j[2] - x_i[2];
    const double reach = r_i + r_j;
    const double dist2 = dx * dx + dy * dy + dz * dz;
    // No branch on touching, which is unpredictable in a packing: an entry apart gets its
    // zero force written here, a touching one writes the same zeros to a scratch record
    // instead; every entry is offered to the batch, and only touching ones advance its count.
    const bool touching = !(dist2 >= reach * reach);  // as the scalar test (NaN: touching)
    // (the destination is chosen by masking addresses: with a select GCC emits a branch)
    uintptr_t to_scratch = uintptr_t{0} - uintptr_t{touching};  // all ones when touching
    asm("" : "+r"(to_scratch));
    const auto destination = [&](double* field, size_t stride) {
      const auto apart = reinterpret_cast<uintptr_t>(field + stride * e);
      return reinterpret_cast<double*>((reinterpret_cast<uintptr_t>(scratch) & to_scratch) |
                                       (apart & ~to_scratch));
    };
    const vd zero{};
    __builtin_memcpy(destination(result, pair_result_size), &zero, sizeof zero);
    store_zero3(destination(sliding_spring, 3));  // apart: the spring is forgotten
    const int l = b.count;
    b.dx[l] = dx, b.dy[l] = dy, b.dz[l] = dz, b.dist2[l] = dist2, b.reach[l] = reach;
    b.ri[l] = r_i, b.rj[l] = r_j;
    b.i[l] = i, b.j[l] = j, b.e[l] = e;
    b.count += touching;
    if (b.count == lanes) {
      const double m = process_batch(in, b, deferred, deferred_count);
      if (max_fraction < m) max_fraction = m;
      b.count = 0;
    }
  }
  if (b.count > 0) {
    const double m = process_batch(in, b, deferred, deferred_count);
    if (max_fraction < m) max_fraction = m;
  }
  return max_fraction;
}

}  // namespace grainlab::GRAINLAB_SIMD_NS
