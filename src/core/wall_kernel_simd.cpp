// The particle-wall contacts through the kernel's lanes (core/pair_kernel_simd.hpp: wall_law,
// plane_wall_rows, wall_totals). Compiled with the pair kernel, once per instruction set, with
// -ffp-contract=off and internal linkage for everything but the entry points
// (src/core/CMakeLists.txt, tests/core/kernel_symbols.sh). The lanes' arithmetic is the scalar
// wall law's (core/wall_forces.cpp, wall_entry), statement by statement.
//
// plane_wall_rows finds the touching candidates of plane walls 8 at a time with AVX-512: the
// particles' positions, radii and inverse masses by gathers, the walls' points and normals by
// permutations of one vector per value (at most 8 walls), the apart candidates cleared by masked
// stores, the touching ones packed in entry order (compress, then a rotation onto the batch
// being filled, all in registers) and run through the law 8 at a time; wall_totals keeps one
// vector lane per wall. The other instruction sets run the same arithmetic one candidate (one
// entry) at a time.
#include <immintrin.h>

#include <algorithm>
#include <array>

#include "contact/pair_params.hpp"
#include "core/pair_kernel_simd.hpp"

#ifndef GRAINLAB_SIMD_NS
#error "GRAINLAB_SIMD_NS must name the instruction set's namespace"
#endif

// AVX2 without AVX-512: the law on 4 lanes, one 256-bit register per value, as in the pair
// kernel (core/pair_kernel_simd.cpp; on 8 lanes its live values spill; docs/performance.md
// sec. 48, 49). A batch of wall_batch_lanes contacts then runs as two groups of 4.
#if defined(__AVX2__) && !defined(__AVX512F__)
#define GRAINLAB_LANES 4
#endif

namespace grainlab::GRAINLAB_SIMD_NS {
namespace {

#include "core/simd_lanes.hpp"  // NOLINT(build/include): part of this file, inside the namespace
// (after the lane primitives it uses)
#include "core/contact_law_lanes.hpp"  // NOLINT(build/include): likewise, after simd_lanes.hpp

// The law on the batch's contacts first .. first + count - 1 (count <= lanes), in lanes
// 0 .. count - 1; returns the lanes it hands back to the scalar law.
unsigned law_on_lanes(const SimdPairInput& in, const SimdWallInput& walls, SimdWallBatch& b,
                      int first, int count) {
  // (the group's fields: lane l is the batch's contact first + l)
  double* const normal_x = b.normal_x + first;
  double* const normal_y = b.normal_y + first;
  double* const normal_z = b.normal_z + first;
  double* const gap_of = b.gap + first;
  double* const overlap_of = b.overlap + first;
  double* const radius_of = b.radius + first;
  uint32_t* const particle = b.particle + first;
  uint32_t* const entry = b.entry + first;
  uint32_t* const wall = b.wall + first;
  // Unused lanes repeat the last contact: valid numbers, never stored (within the batch: a
  // group of fewer than `lanes` contacts is its last).
  for (int l = count; l < lanes; ++l) {
    const int last = count - 1;
    normal_x[l] = normal_x[last], normal_y[l] = normal_y[last], normal_z[l] = normal_z[last];
    gap_of[l] = gap_of[last], overlap_of[l] = overlap_of[last], radius_of[l] = radius_of[last];
    particle[l] = particle[last], entry[l] = entry[last], wall[l] = wall[last];
  }
  V3 n;
  vd gap, overlap, radius;
  __builtin_memcpy(&n.x, normal_x, sizeof n.x);
  __builtin_memcpy(&n.y, normal_y, sizeof n.y);
  __builtin_memcpy(&n.z, normal_z, sizeof n.z);
  __builtin_memcpy(&gap, gap_of, sizeof gap);
  __builtin_memcpy(&overlap, overlap_of, sizeof overlap);
  __builtin_memcpy(&radius, radius_of, sizeof radius);
  const double drift = in.drift;

  // Per lane: its wall's velocities and mass, and the constants of the (bead, wall) pair.
  V3 wall_velocity, wall_velocity_at_end;
  vd wall_inverse_mass;
  LaneConstants k;
  for (int l = 0; l < lanes; ++l) {
    const SimdWallState& w = walls.walls[wall[l]];
    wall_velocity.x[l] = w.velocity[0], wall_velocity.y[l] = w.velocity[1];
    wall_velocity.z[l] = w.velocity[2];
    wall_velocity_at_end.x[l] = w.velocity_at_end[0];
    wall_velocity_at_end.y[l] = w.velocity_at_end[1];
    wall_velocity_at_end.z[l] = w.velocity_at_end[2];
    wall_inverse_mass[l] = w.inverse_mass;
    k.set(l, in.pair_params[in.material[particle[l]] * in.material_count + w.material]);
  }
  // m* = m_p M / (m_p + M): a wall with mass is a second body, a fixed one has M = infinity
  const vd inverse_mass_i = load_lanes(in.inverse_mass, lane_index(particle), 1, 0);
  const vd effective_mass = 1.0 / (inverse_mass_i + wall_inverse_mass);
  const vd lever = gap;  // contact point on the wall surface
  // Body B, the wall, has no spin and no lever: the scalar law multiplies and adds its zeros,
  // and so do the lanes (a zero's sign must come out the same).
  const V3 no_spin{};
  const vd no_lever{};

  // set_step_displacement (half-step velocities, lever_shrink = 1: the lever is r - U_n)
  const RecordHead head = load_record_head(in.particle_record, particle);
  const V3& v_i = head.velocity;
  const auto [dv, overlap_increment, tangential_displacement] =
      step_increment(n, drift, 1.0, v_i, head.spin, lever, wall_velocity, no_spin, no_lever);

  // set_relative_velocity with the end-of-step estimates: the dashpots' rates
  const RecordTail tail = load_record_tail(in.particle_record, particle);
  const V3 v_end_i{head.velocity_at_end_x, head.velocity_at_end_y, tail.velocity_at_end_z};
  const auto [overlap_rate, tangential_velocity] =
      contact_rates(n, v_end_i, tail.spin_at_end, lever, wall_velocity_at_end, no_spin, no_lever);

  // wall_forces: may this contact have begun during the step? Then the scalar law takes it.
  const V3 s = drift * (v_i - wall_velocity);
  const vd s_n = dot(s, n);
  const vmask begun = overlap <= 2.0 * (overlap_increment + (dot(s, s) - s_n * s_n) / (2.0 * gap));
  const bool drifted = drift > 0.0;

  // normal_params with r* = r and m* above
  const vd normal_stiffness = k.stiffness_per_radius * radius;
  const vd normal_damping = 2.0 * k.damping_ratio * lane_sqrt(normal_stiffness * effective_mass);
  const LawResult law = contact_law(n, overlap, overlap_rate, tangential_displacement,
                                    tangential_velocity, normal_stiffness, normal_damping, k,
                                    load_lanes3(walls.sliding_spring, lane_index(entry)));
  const V3 torque = lever * law.arm;

  const auto [store, handed_back] = choose_lanes(count, drifted, begun);
  store_lanes3(walls.force_on_particle, entry, law.force_on_a, store);
  store_lanes3(walls.torque_on_particle, entry, torque, store);
  store_lanes3(walls.sliding_spring, entry, law.spring, store);
  for (int l = 0; l < count; ++l) {
    if (!(store >> l & 1u)) continue;
    const uint32_t e = entry[l];
    walls.normal_stiffness[e] = normal_stiffness[l];
    walls.normal_force[e] = law.normal_force[l];
  }
  return handed_back;
}

// wall_law: the law on the batch's contacts (core/pair_kernel_simd.hpp), `lanes` at a time.
unsigned law_on_batch(const SimdPairInput& in, const SimdWallInput& walls, SimdWallBatch& b) {
  static_assert(wall_batch_lanes % lanes == 0);
  unsigned handed_back = 0;
  for (int first = 0; first < b.count; first += lanes)
    handed_back |= law_on_lanes(in, walls, b, first, std::min(lanes, b.count - first)) << first;
  return handed_back;
}

// The deferred entries of a batch the law has run: the lanes it handed back.
GRAINLAB_LANES_INLINE void run_batch(const SimdPairInput& in, const SimdWallInput& walls,
                                     SimdWallBatch& b, uint32_t* deferred, long& deferred_count) {
  for (unsigned h = law_on_batch(in, walls, b); h != 0; h &= h - 1)
    deferred[deferred_count++] = b.entry[__builtin_ctz(h)];
  b.count = 0;
}

#if defined(__AVX512F__)
// Per mask of 8 entries, the mask of their 24 values in a Vec3 array (entry l: values 3l .. 3l+2).
constexpr std::array<uint32_t, 256> vec3_masks = [] {
  std::array<uint32_t, 256> t{};
  for (unsigned m = 0; m < 256; ++m)
    for (unsigned l = 0; l < 8; ++l)
      if (m >> l & 1u) t[m] |= 7u << (3 * l);
  return t;
}();
// Zeros the Vec3s of the entries e0 + l of `base` for the lanes l in `apart`.
GRAINLAB_LANES_INLINE void clear3(double* base, uint32_t e0, unsigned apart) {
  const uint32_t m = vec3_masks[apart];
  double* p = base + size_t{e0} * 3;
  const __m512d zero = _mm512_setzero_pd();
  _mm512_mask_storeu_pd(p, static_cast<__mmask8>(m), zero);
  _mm512_mask_storeu_pd(p + 8, static_cast<__mmask8>(m >> 8), zero);
  _mm512_mask_storeu_pd(p + 16, static_cast<__mmask8>(m >> 16), zero);
}
// (the masked forms with every lane on: the unmasked ones warn in GCC 12)
GRAINLAB_LANES_INLINE __m512d permute(__m512i index, __m512d x) {
  return _mm512_maskz_permutexvar_pd(0xFF, index, x);
}
GRAINLAB_LANES_INLINE __m512i permute(__m512i index, __m512i x) {
  return _mm512_maskz_permutexvar_epi64(0xFF, index, x);
}
GRAINLAB_LANES_INLINE __m512i widen16(__m128i x) {  // 8 x uint16 to 8 x int64
  return _mm512_maskz_cvtepu16_epi64(0xFF, x);
}
GRAINLAB_LANES_INLINE __m512i widen32(__m256i x) {  // 8 x uint32 to 8 x int64
  return _mm512_maskz_cvtepu32_epi64(0xFF, x);
}
GRAINLAB_LANES_INLINE __m256i narrow(__m512i x) {  // 8 x int64 to 8 x uint32 (each < 2^32)
  return _mm512_maskz_cvtepi64_epi32(0xFF, x);
}
// The touching candidates not yet run, lanes 0 .. count-1 (the batch's fields as vectors; the
// indices as 64-bit lanes, so that one set of permutations serves every field).
struct Pending {
  vd normal_x, normal_y, normal_z, gap, overlap, radius;
  __m512i particle, entry, wall;
};
// a with b's lanes rotated up by `count` in the lanes from `count` on.
GRAINLAB_LANES_INLINE vd append(vd a, vd b, __m512i up, __mmask8 high) {
  return _mm512_mask_blend_pd(high, a, permute(up, b));
}
GRAINLAB_LANES_INLINE __m512i append(__m512i a, __m512i b, __m512i up, __mmask8 high) {
  return _mm512_mask_blend_epi64(high, a, permute(up, b));
}
GRAINLAB_LANES_INLINE void to_batch(const Pending& x, int count, SimdWallBatch& b) {
  __builtin_memcpy(b.normal_x, &x.normal_x, sizeof x.normal_x);
  __builtin_memcpy(b.normal_y, &x.normal_y, sizeof x.normal_y);
  __builtin_memcpy(b.normal_z, &x.normal_z, sizeof x.normal_z);
  __builtin_memcpy(b.gap, &x.gap, sizeof x.gap);
  __builtin_memcpy(b.overlap, &x.overlap, sizeof x.overlap);
  __builtin_memcpy(b.radius, &x.radius, sizeof x.radius);
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(b.particle), narrow(x.particle));
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(b.entry), narrow(x.entry));
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(b.wall), narrow(x.wall));
  b.count = count;
}
#endif

}  // namespace

unsigned wall_law(const SimdPairInput& in, const SimdWallInput& walls, SimdWallBatch& b) {
  return law_on_batch(in, walls, b);
}

double plane_wall_rows(const SimdPairInput& in, const SimdWallInput& walls,
                       const SimdWallCandidates& candidates, uint32_t first_entry,
                       uint32_t end_entry, uint32_t* deferred, long& deferred_count) {
  deferred_count = 0;
  double max_fraction = 0.0;
  const SimdPlanes& planes = *candidates.planes;
  SimdWallBatch b;
#if defined(__AVX512F__)
  const auto load = [](const double* p) {
    vd x;
    __builtin_memcpy(&x, p, sizeof x);
    return x;
  };
  const vd point_x = load(planes.point_x), point_y = load(planes.point_y),
           point_z = load(planes.point_z), normal_x = load(planes.normal_x),
           normal_y = load(planes.normal_y), normal_z = load(planes.normal_z);
  vd wall_inverse_mass{};
  for (int k = 0; k < planes.count; ++k) wall_inverse_mass[k] = walls.walls[k].inverse_mass;
  const __m512i iota = _mm512_setr_epi64(0, 1, 2, 3, 4, 5, 6, 7), seven = _mm512_set1_epi64(7);
  const vd zero{};
  Pending pending{};
  int count = 0;
  for (uint32_t e0 = first_entry; e0 < end_entry; e0 += lanes) {
    const uint32_t n = std::min<uint32_t>(lanes, end_entry - e0);
    const auto valid = static_cast<__mmask8>((1u << n) - 1u);
    __m256i owner;
    __m512i wall;
    if (n == lanes) {
      owner = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(candidates.owner + e0));
      wall = widen16(_mm_loadu_si128(reinterpret_cast<const __m128i*>(candidates.wall + e0)));
    } else {  // the range's last entries: nothing read beyond it
      alignas(32) uint32_t o[lanes] = {};
      alignas(16) uint16_t w[lanes] = {};
      for (uint32_t l = 0; l < n; ++l)
        o[l] = candidates.owner[e0 + l], w[l] = candidates.wall[e0 + l];
      owner = _mm256_load_si256(reinterpret_cast<const __m256i*>(o));
      wall = widen16(_mm_load_si128(reinterpret_cast<const __m128i*>(w)));
    }
    const __m256i owner3 = _mm256_add_epi32(_mm256_add_epi32(owner, owner), owner);
    const auto gather = [&](__m256i index, const double* base) {
      return vd(_mm512_mask_i32gather_pd(_mm512_setzero_pd(), valid, index, base, 8));
    };
    const vd x = gather(owner3, in.position), y = gather(owner3, in.position + 1),
             z = gather(owner3, in.position + 2);
    const vd radius = gather(owner, in.radius), inverse_mass = gather(owner, in.inverse_mass);
    const auto of_wall = [&](vd table) { return vd(permute(wall, table)); };
    const vd nx = of_wall(normal_x), ny = of_wall(normal_y), nz = of_wall(normal_z);
    // wall_gap of a plane: d = x - point, gap = d . normal
    const vd gap =
        (x - of_wall(point_x)) * nx + (y - of_wall(point_y)) * ny + (z - of_wall(point_z)) * nz;
    const vd overlap = radius - gap;
    // wall_forces_simd's test: apart where overlap <= 0 or both bodies are fixed (NaN: touching)
    const vd inverse_mass_sum = inverse_mass + of_wall(wall_inverse_mass);
    const auto touching =
        static_cast<__mmask8>(valid & _mm512_cmp_pd_mask(overlap, zero, _CMP_NLE_UQ) &
                              _mm512_cmp_pd_mask(inverse_mass_sum, zero, _CMP_NEQ_UQ));
    const auto apart = static_cast<__mmask8>(valid & ~touching);
    if (apart != 0) {  // clear_wall_entry
      clear3(walls.force_on_particle, e0, apart);
      clear3(walls.torque_on_particle, e0, apart);
      clear3(walls.sliding_spring, e0, apart);
      _mm512_mask_storeu_pd(walls.normal_stiffness + e0, apart, zero);
      _mm512_mask_storeu_pd(walls.normal_force + e0, apart, zero);
    }
    if (touching == 0) continue;
    const double largest = largest_ordered(overlap / radius, touching);
    if (max_fraction < largest) max_fraction = largest;
    // The touching lanes packed at the bottom, then rotated onto the pending ones.
    const auto pack = [&](vd v) { return vd(_mm512_maskz_compress_pd(touching, v)); };
    const auto pack_index = [&](__m512i v) { return _mm512_maskz_compress_epi64(touching, v); };
    const Pending packed{pack(-nx),
                         pack(-ny),
                         pack(-nz),
                         pack(gap),
                         pack(overlap),
                         pack(radius),
                         pack_index(widen32(owner)),
                         pack_index(_mm512_add_epi64(_mm512_set1_epi64(e0), iota)),
                         pack_index(wall)};
    const int added = __builtin_popcount(touching);
    const __m512i up = _mm512_and_epi64(_mm512_sub_epi64(iota, _mm512_set1_epi64(count)), seven);
    const auto high = static_cast<__mmask8>(0xFFu << count);
    const Pending merged{append(pending.normal_x, packed.normal_x, up, high),
                         append(pending.normal_y, packed.normal_y, up, high),
                         append(pending.normal_z, packed.normal_z, up, high),
                         append(pending.gap, packed.gap, up, high),
                         append(pending.overlap, packed.overlap, up, high),
                         append(pending.radius, packed.radius, up, high),
                         append(pending.particle, packed.particle, up, high),
                         append(pending.entry, packed.entry, up, high),
                         append(pending.wall, packed.wall, up, high)};
    if (count + added < lanes) {
      pending = merged;
      count += added;
      continue;
    }
    to_batch(merged, lanes, b);
    run_batch(in, walls, b, deferred, deferred_count);
    // what did not fit: packed lanes lanes - count .. added - 1, rotated down to the bottom
    const __m512i down =
        _mm512_and_epi64(_mm512_add_epi64(iota, _mm512_set1_epi64(lanes - count)), seven);
    pending = {permute(down, packed.normal_x), permute(down, packed.normal_y),
               permute(down, packed.normal_z), permute(down, packed.gap),
               permute(down, packed.overlap),  permute(down, packed.radius),
               permute(down, packed.particle), permute(down, packed.entry),
               permute(down, packed.wall)};
    count += added - lanes;
  }
  if (count > 0) {
    to_batch(pending, count, b);
    run_batch(in, walls, b, deferred, deferred_count);
  }
#else
  for (uint32_t e = first_entry; e < end_entry; ++e) {
    const uint32_t i = candidates.owner[e];
    const uint16_t k = candidates.wall[e];
    const double r = in.radius[i];
    const double* x = in.position + size_t{i} * 3;
    // wall_gap of a plane: d = x - point, gap = d . normal
    const double nx = planes.normal_x[k], ny = planes.normal_y[k], nz = planes.normal_z[k];
    const double gap = (x[0] - planes.point_x[k]) * nx + (x[1] - planes.point_y[k]) * ny +
                       (x[2] - planes.point_z[k]) * nz;
    const double overlap = r - gap;
    if (overlap <= 0.0 || in.inverse_mass[i] + walls.walls[k].inverse_mass == 0.0) {
      double* f = walls.force_on_particle + size_t{e} * 3;  // clear_wall_entry
      double* t = walls.torque_on_particle + size_t{e} * 3;
      double* s = walls.sliding_spring + size_t{e} * 3;
      f[0] = f[1] = f[2] = t[0] = t[1] = t[2] = s[0] = s[1] = s[2] = 0.0;
      walls.normal_stiffness[e] = walls.normal_force[e] = 0.0;
      continue;
    }
    const int l = b.count++;
    b.normal_x[l] = -nx, b.normal_y[l] = -ny, b.normal_z[l] = -nz;
    b.gap[l] = gap, b.overlap[l] = overlap, b.radius[l] = r;
    b.particle[l] = i, b.entry[l] = e, b.wall[l] = k;
    const double fraction = overlap / r;
    if (max_fraction < fraction) max_fraction = fraction;
    if (b.count == wall_batch_lanes) run_batch(in, walls, b, deferred, deferred_count);
  }
  if (b.count > 0) run_batch(in, walls, b, deferred, deferred_count);
#endif
  return max_fraction;
}

void wall_totals(const double* force_on_particle, const double* normal_stiffness,
                 const uint16_t* wall, uint32_t entries, int wall_count, SimdWallTotals& totals) {
#if defined(__AVX512F__)
  // One lane per wall: each entry's values broadcast and subtracted (added) in its wall's lane
  // only, so that every lane sums its wall's entries in entry order; the chains run in registers
  // where the scalar loop's ran through memory.
  __m512d force_x = _mm512_setzero_pd(), force_y = force_x, force_z = force_x, stiffness = force_x;
  __m512i count = _mm512_setzero_si512();
  const __m512i one = _mm512_set1_epi64(1);
  for (uint32_t e = 0; e < entries; ++e) {
    const double k_n = normal_stiffness[e];
    const auto lane = static_cast<__mmask8>(static_cast<unsigned>(k_n != 0.0) << wall[e]);
    const double* f = force_on_particle + size_t{e} * 3;
    force_x = _mm512_mask_sub_pd(force_x, lane, force_x, _mm512_set1_pd(f[0]));
    force_y = _mm512_mask_sub_pd(force_y, lane, force_y, _mm512_set1_pd(f[1]));
    force_z = _mm512_mask_sub_pd(force_z, lane, force_z, _mm512_set1_pd(f[2]));
    stiffness = _mm512_mask_add_pd(stiffness, lane, stiffness, _mm512_set1_pd(k_n));
    count = _mm512_mask_add_epi64(count, lane, count, one);
  }
  _mm512_storeu_pd(totals.force_x, force_x);
  _mm512_storeu_pd(totals.force_y, force_y);
  _mm512_storeu_pd(totals.force_z, force_z);
  _mm512_storeu_pd(totals.stiffness, stiffness);
  static_assert(sizeof(long) == 8 && max_lane_walls == lanes);
  _mm512_storeu_si512(totals.count, count);
  (void)wall_count;
#else
  for (int k = 0; k < wall_count; ++k) {
    totals.force_x[k] = totals.force_y[k] = totals.force_z[k] = totals.stiffness[k] = 0.0;
    totals.count[k] = 0;
  }
  for (uint32_t e = 0; e < entries; ++e) {
    const double k_n = normal_stiffness[e];
    if (k_n == 0.0) continue;
    const int k = wall[e];
    const double* f = force_on_particle + size_t{e} * 3;
    totals.force_x[k] -= f[0];
    totals.force_y[k] -= f[1];
    totals.force_z[k] -= f[2];
    totals.stiffness[k] += k_n;
    ++totals.count[k];
  }
#endif
}

}  // namespace grainlab::GRAINLAB_SIMD_NS
