// The per-particle passes of velocity Verlet (core/particle_passes_simd.hpp). Compiled with the
// pair kernel, once per instruction set, with -ffp-contract=off and internal linkage for
// everything but the entry points (src/core/CMakeLists.txt, tests/core/kernel_symbols.sh).
//
// The particle arrays are Vec3 arrays (x, y, z side by side). With AVX-512 the loop takes 8
// particles at a time (with AVX2 4, and 12 doubles): each Vec3 array's 24 doubles are three
// vectors, a per-particle factor (dt/2 times the inverse mass) is spread over them by a
// permutation, the arithmetic runs on the 24 components as the scalar loop does on each, and a
// squared length is formed from the x, y and z vectors that two permutations pick out of the
// three. The particles left over (fewer than 8, or 4) take the scalar loop: the same arithmetic.
// The gather keeps a particle's force and torque in two vectors, to which each of its entries'
// 64-byte results is added whole (with AVX2, two 256-bit vectors and two loads of 4 values from
// each result: docs/performance.md sec. 49).
#include "core/particle_passes_simd.hpp"

#include <immintrin.h>

#include <cstdint>

#ifndef GRAINLAB_SIMD_NS
#error "GRAINLAB_SIMD_NS must name the instruction set's namespace"
#endif

namespace grainlab::GRAINLAB_SIMD_NS {
namespace {

#define GRAINLAB_PASS_INLINE [[gnu::always_inline]] inline

// std::max(largest, x): x where largest < x, so that a NaN x is skipped.
GRAINLAB_PASS_INLINE double raise(double largest, double x) {
  return largest < x ? x : largest;
}
// |a - b|^2 and |a|^2 of Vec3s, summed as core/vec3.hpp's norm2: x, then y, then z.
GRAINLAB_PASS_INLINE double distance2(const double* a, const double* b) {
  const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return dx * dx + dy * dy + dz * dz;
}
GRAINLAB_PASS_INLINE double length2(const double* a) {
  return a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
}
// a += s b, component by component (Vec3's a += s * b)
GRAINLAB_PASS_INLINE void add_scaled(double* a, double s, const double* b) {
  a[0] = a[0] + s * b[0];
  a[1] = a[1] + s * b[1];
  a[2] = a[2] + s * b[2];
}

// a += b and a -= b, component by component
GRAINLAB_PASS_INLINE void add(double* a, const double* b) {
  a[0] = a[0] + b[0], a[1] = a[1] + b[1], a[2] = a[2] + b[2];
}
GRAINLAB_PASS_INLINE void subtract(double* a, const double* b) {
  a[0] = a[0] - b[0], a[1] = a[1] - b[1], a[2] = a[2] - b[2];
}

// One particle of kick_and_drift: the half kick, the drift and the tests asked for.
template <bool Check, bool Rebuild, bool Bound>
GRAINLAB_PASS_INLINE void drift_particle(const ParticlePassInput& in, long i, double half,
                                         DriftTally& tally) {
  const long o = 3 * i;
  double* v = in.velocity + o;
  double* w = in.angular_velocity + o;
  double* x = in.position + o;
  add_scaled(v, half * in.inverse_mass[i], in.force + o);
  add_scaled(w, half * in.inverse_inertia[i], in.torque + o);
  add_scaled(x, in.time_step, v);
  add_scaled(in.rotation + o, in.time_step, w);
  if constexpr (Check) {
    const double d2 = distance2(x, in.position_at_refresh + o);
    tally.stale |= d2 > in.half_list_skin2 ? 1 : 0;
    if constexpr (Bound) {
      tally.displacement2 = raise(tally.displacement2, d2);
      tally.scale2 = raise(tally.scale2, length2(x));
    }
    if constexpr (Rebuild)
      tally.moved |= distance2(x, in.position_at_build + o) > in.half_skin2 ? 1 : 0;
  }
}

// One particle of half_kick.
template <bool Next>
GRAINLAB_PASS_INLINE void kick_particle(const ParticlePassInput& in, long i, double half,
                                        double& max_speed2, double& max_next2) {
  const long o = 3 * i;
  double* v = in.velocity + o;
  const double k = half * in.inverse_mass[i];
  const double* f = in.force + o;
  const double kick[3] = {k * f[0], k * f[1], k * f[2]};
  add(v, kick);
  add_scaled(in.angular_velocity + o, half * in.inverse_inertia[i], in.torque + o);
  const double v2 = length2(v);
  max_speed2 = raise(max_speed2, v2 == v2 ? v2 : __builtin_inf());
  if constexpr (Next) {
    const double next[3] = {v[0] + kick[0], v[1] + kick[1], v[2] + kick[2]};
    const double next2 = length2(next);
    max_next2 = raise(max_next2, next2 == next2 ? next2 : __builtin_inf());
  }
}

#if defined(__AVX512F__)
using v8 = double __attribute__((vector_size(64)));  // GCC's vectors: no undefined-lane intrinsics
using pvec = v8;  // the kick's and drift's vectors: 8 particles' values
constexpr long group_lanes = 8;
GRAINLAB_PASS_INLINE v8 splat(double x) {
  return v8{x, x, x, x, x, x, x, x};
}
GRAINLAB_PASS_INLINE v8 load(const double* p) {
  v8 r;
  __builtin_memcpy(&r, p, sizeof r);
  return r;
}
// 8 consecutive Vec3s: 24 doubles in three vectors.
struct Group {
  v8 a[3];
};
GRAINLAB_PASS_INLINE Group load_group(const double* p) {
  return {{load(p), load(p + 8), load(p + 16)}};
}
// (a vector at a time, as in the AVX2 object below)
GRAINLAB_PASS_INLINE void store_group(double* p, const Group& g) {
  __builtin_memcpy(p, &g.a[0], sizeof g.a[0]);
  __builtin_memcpy(p + 8, &g.a[1], sizeof g.a[1]);
  __builtin_memcpy(p + 16, &g.a[2], sizeof g.a[2]);
}
// The 8 particles' values s in the places of their x, y and z.
GRAINLAB_PASS_INLINE Group spread(v8 s) {
  return {{__builtin_shufflevector(s, s, 0, 0, 0, 1, 1, 1, 2, 2),
           __builtin_shufflevector(s, s, 2, 3, 3, 3, 4, 4, 4, 5),
           __builtin_shufflevector(s, s, 5, 5, 6, 6, 6, 7, 7, 7)}};
}
// Per particle x^2 + y^2 + z^2 (in that order). Of the 24 squares, x of particle p is square
// 3p, y 3p + 1, z 3p + 2: the first two vectors hold 0..15, the third 16..23.
GRAINLAB_PASS_INLINE v8 length2(const Group& d) {
  const v8 s0 = d.a[0] * d.a[0], s1 = d.a[1] * d.a[1], s2 = d.a[2] * d.a[2];
  const v8 x = __builtin_shufflevector(__builtin_shufflevector(s0, s1, 0, 3, 6, 9, 12, 15, 0, 0),
                                       s2, 0, 1, 2, 3, 4, 5, 10, 13);
  const v8 y = __builtin_shufflevector(__builtin_shufflevector(s0, s1, 1, 4, 7, 10, 13, 0, 0, 0),
                                       s2, 0, 1, 2, 3, 4, 8, 11, 14);
  const v8 z = __builtin_shufflevector(__builtin_shufflevector(s0, s1, 2, 5, 8, 11, 14, 0, 0, 0),
                                       s2, 0, 1, 2, 3, 4, 9, 12, 15);
  return (x + y) + z;
}
// (largest < x) ? x : largest per lane, as raise: a NaN x leaves largest
GRAINLAB_PASS_INLINE v8 raise(v8 largest, v8 x) {
  return largest < x ? x : largest;
}
// x, with NaN lanes infinite
GRAINLAB_PASS_INLINE v8 nan_as_infinite(v8 x) {
  return x == x ? x : splat(__builtin_inf());
}
// the lanes where a > b (false for NaN), as bits
GRAINLAB_PASS_INLINE unsigned greater(v8 a, v8 b) {
  return _mm512_cmp_pd_mask(reinterpret_cast<__m512d>(a), reinterpret_cast<__m512d>(b), _CMP_GT_OQ);
}
#elif defined(__AVX2__)
// With AVX2 the kick and the drift take 4 particles at a time: 12 doubles in three 256-bit
// vectors, the same arithmetic as with AVX-512's 8.
using v4 = double __attribute__((vector_size(32)));
using pvec = v4;
constexpr long group_lanes = 4;
GRAINLAB_PASS_INLINE v4 splat(double x) {
  return v4{x, x, x, x};
}
GRAINLAB_PASS_INLINE v4 load(const double* p) {
  v4 r;
  __builtin_memcpy(&r, p, sizeof r);
  return r;
}
// 4 consecutive Vec3s: 12 doubles in three vectors.
struct Group {
  v4 a[3];
};
GRAINLAB_PASS_INLINE Group load_group(const double* p) {
  return {{load(p), load(p + 4), load(p + 8)}};
}
// (a vector at a time: one copy of the three, GCC 12 makes it through the stack and 8-byte
// registers, docs/performance.md sec. 50)
GRAINLAB_PASS_INLINE void store_group(double* p, const Group& g) {
  __builtin_memcpy(p, &g.a[0], sizeof g.a[0]);
  __builtin_memcpy(p + 4, &g.a[1], sizeof g.a[1]);
  __builtin_memcpy(p + 8, &g.a[2], sizeof g.a[2]);
}
// The 4 particles' values s in the places of their x, y and z.
GRAINLAB_PASS_INLINE Group spread(v4 s) {
  return {{__builtin_shufflevector(s, s, 0, 0, 0, 1), __builtin_shufflevector(s, s, 1, 1, 2, 2),
           __builtin_shufflevector(s, s, 2, 3, 3, 3)}};
}
// Per particle x^2 + y^2 + z^2 (in that order): x of particle p is square 3p, y 3p + 1, z 3p + 2;
// the first vector holds 0..3, the second 4..7, the third 8..11.
GRAINLAB_PASS_INLINE v4 length2(const Group& d) {
  const v4 s0 = d.a[0] * d.a[0], s1 = d.a[1] * d.a[1], s2 = d.a[2] * d.a[2];
  const v4 x = __builtin_shufflevector(__builtin_shufflevector(s0, s1, 0, 3, 6, 0), s2, 0, 1, 2, 5);
  const v4 y = __builtin_shufflevector(__builtin_shufflevector(s0, s1, 1, 4, 7, 0), s2, 0, 1, 2, 6);
  const v4 z = __builtin_shufflevector(__builtin_shufflevector(s0, s1, 2, 5, 0, 0), s2, 0, 1, 4, 7);
  return (x + y) + z;
}
// (largest < x) ? x : largest per lane, as raise: a NaN x leaves largest
GRAINLAB_PASS_INLINE v4 raise(v4 largest, v4 x) {
  return largest < x ? x : largest;
}
// x, with NaN lanes infinite
GRAINLAB_PASS_INLINE v4 nan_as_infinite(v4 x) {
  return x == x ? x : splat(__builtin_inf());
}
// the lanes where a > b (false for NaN), as bits
GRAINLAB_PASS_INLINE unsigned greater(v4 a, v4 b) {
  return static_cast<unsigned>(_mm256_movemask_pd(
      _mm256_cmp_pd(reinterpret_cast<__m256d>(a), reinterpret_cast<__m256d>(b), _CMP_GT_OQ)));
}
#endif
#if defined(__AVX512F__) || defined(__AVX2__)
// a + s b, a + b and a - b per component
GRAINLAB_PASS_INLINE Group add_scaled(const Group& a, const Group& s, const Group& b) {
  return {{a.a[0] + s.a[0] * b.a[0], a.a[1] + s.a[1] * b.a[1], a.a[2] + s.a[2] * b.a[2]}};
}
GRAINLAB_PASS_INLINE Group add_scaled(const Group& a, pvec s, const Group& b) {
  return {{a.a[0] + s * b.a[0], a.a[1] + s * b.a[1], a.a[2] + s * b.a[2]}};
}
GRAINLAB_PASS_INLINE Group add(const Group& a, const Group& b) {
  return {{a.a[0] + b.a[0], a.a[1] + b.a[1], a.a[2] + b.a[2]}};
}
GRAINLAB_PASS_INLINE Group subtract(const Group& a, const Group& b) {
  return {{a.a[0] - b.a[0], a.a[1] - b.a[1], a.a[2] - b.a[2]}};
}
GRAINLAB_PASS_INLINE double raise(double largest, pvec lanes) {
  for (int l = 0; l < group_lanes; ++l) largest = raise(largest, lanes[l]);
  return largest;
}
#endif

template <bool Check, bool Rebuild, bool Bound>
void drift_range(const ParticlePassInput& given, long first, long end, DriftTally& tally) {
  const ParticlePassInput in = given;  // (a local copy: see gather)
  const double half = 0.5 * in.time_step;
  long i = first;
#if defined(__AVX512F__) || defined(__AVX2__)
  const pvec half8 = splat(half), dt8 = splat(in.time_step);
  const pvec half_list_skin2 = splat(in.half_list_skin2), half_skin2 = splat(in.half_skin2);
  unsigned stale = 0, moved = 0;
  pvec displacement2{}, scale2{};
  for (; i + group_lanes <= end; i += group_lanes) {
    const long o = 3 * i;
    const Group v = add_scaled(load_group(in.velocity + o),
                               spread(half8 * load(in.inverse_mass + i)), load_group(in.force + o));
    const Group w =
        add_scaled(load_group(in.angular_velocity + o),
                   spread(half8 * load(in.inverse_inertia + i)), load_group(in.torque + o));
    const Group x = add_scaled(load_group(in.position + o), dt8, v);
    store_group(in.velocity + o, v);
    store_group(in.angular_velocity + o, w);
    store_group(in.position + o, x);
    store_group(in.rotation + o, add_scaled(load_group(in.rotation + o), dt8, w));
    if constexpr (Check) {
      const pvec d2 = length2(subtract(x, load_group(in.position_at_refresh + o)));
      stale |= greater(d2, half_list_skin2);
      if constexpr (Bound) {
        displacement2 = raise(displacement2, d2);
        scale2 = raise(scale2, length2(x));
      }
      if constexpr (Rebuild)
        moved |= greater(length2(subtract(x, load_group(in.position_at_build + o))), half_skin2);
    }
  }
  if (i > first) {
    tally.stale |= stale != 0 ? 1 : 0;
    tally.moved |= moved != 0 ? 1 : 0;
    if constexpr (Bound) {
      tally.displacement2 = raise(tally.displacement2, displacement2);
      tally.scale2 = raise(tally.scale2, scale2);
    }
  }
#endif
  for (; i < end; ++i) drift_particle<Check, Rebuild, Bound>(in, i, half, tally);
}

template <bool Next>
void kick_range(const ParticlePassInput& given, long first, long end, double& max_speed2,
                double& max_next2) {
  const ParticlePassInput in = given;  // (a local copy: see gather)
  const double half = 0.5 * in.time_step;
  long i = first;
#if defined(__AVX512F__) || defined(__AVX2__)
  const pvec half8 = splat(half);
  pvec speed2{}, next2{};
  for (; i + group_lanes <= end; i += group_lanes) {
    const long o = 3 * i;
    const Group k = spread(half8 * load(in.inverse_mass + i));
    const Group f = load_group(in.force + o);
    const Group kick{{k.a[0] * f.a[0], k.a[1] * f.a[1], k.a[2] * f.a[2]}};
    const Group v = add(load_group(in.velocity + o), kick);
    store_group(in.velocity + o, v);
    store_group(in.angular_velocity + o, add_scaled(load_group(in.angular_velocity + o),
                                                    spread(half8 * load(in.inverse_inertia + i)),
                                                    load_group(in.torque + o)));
    speed2 = raise(speed2, nan_as_infinite(length2(v)));
    if constexpr (Next) next2 = raise(next2, nan_as_infinite(length2(add(v, kick))));
  }
  if (i > first) {
    max_speed2 = raise(max_speed2, speed2);
    if constexpr (Next) max_next2 = raise(max_next2, next2);
  }
#endif
  for (; i < end; ++i) kick_particle<Next>(in, i, half, max_speed2, max_next2);
}

// The sums of one particle, as core/gather.cpp forms them: its weight, its row, its column (the
// opposite force), its walls, its external force, each Vec3 added component by component; the
// torque of a pair entry is the particle's lever (contact_lever: r - U_n / 2) times the arm.
GRAINLAB_PASS_INLINE void gather_particle(const GatherInput& in, long i) {
  const double r = in.radius[i];
  double f[3] = {}, t[3] = {};
  if (in.inverse_mass[i] > 0.0) {
    const double m = 1.0 / in.inverse_mass[i];
    f[0] = m * in.gravity[0], f[1] = m * in.gravity[1], f[2] = m * in.gravity[2];
  }
  for (uint32_t e = in.row_start[i]; e < in.row_start[i + 1]; ++e) {
    const double* x = in.result + 8 * size_t{e};  // force, torque arm, overlap, F_n
    add(f, x);
    add_scaled(t, r - 0.5 * x[6], x + 3);
  }
  for (uint32_t k = in.col_start[i]; k < in.col_start[i + 1]; ++k) {
    const double* x = in.result + 8 * size_t{in.col_pair[k]};
    subtract(f, x);
    add_scaled(t, r - 0.5 * x[6], x + 3);
  }
  for (uint32_t e = in.wall_row_start[i]; e < in.wall_row_start[i + 1]; ++e) {
    add(f, in.force_on_particle + 3 * size_t{e});
    add(t, in.torque_on_particle + 3 * size_t{e});
  }
  if (in.external_force) add(f, in.external_force + 3 * i);
  double* out_f = in.force + 3 * i;
  double* out_t = in.torque + 3 * i;
  out_f[0] = f[0], out_f[1] = f[1], out_f[2] = f[2];
  out_t[0] = t[0], out_t[1] = t[1], out_t[2] = t[2];
}

#if defined(__AVX512F__)
// The gather's sums hold a force in lanes 0..2 and a torque in lanes 3..5.
constexpr __mmask8 force_lanes = 0x07, torque_lanes = 0x38;
// A Vec3 in lanes 0..2, zeros in the others.
GRAINLAB_PASS_INLINE v8 in_force_lanes(const double* vec3) {
  return reinterpret_cast<v8>(_mm512_maskz_loadu_pd(force_lanes, vec3));
}
// A Vec3 in lanes 3..5, the other lanes those of `rest` (loaded from 3 doubles before it: the
// lanes masked off are not read).
GRAINLAB_PASS_INLINE v8 in_torque_lanes(const double* vec3, v8 rest = v8{}) {
  return reinterpret_cast<v8>(_mm512_mask_loadu_pd(
      reinterpret_cast<__m512d>(rest), torque_lanes,
      reinterpret_cast<const double*>(reinterpret_cast<uintptr_t>(vec3) - 24)));
}
// Particle i's force from lanes 0..2 of f, its torque from lanes 3..5 of t.
GRAINLAB_PASS_INLINE void store_sums(const GatherInput& in, long i, v8 f, v8 t) {
  _mm512_mask_storeu_pd(in.force + 3 * i, force_lanes, reinterpret_cast<__m512d>(f));
  _mm512_mask_storeu_pd(
      reinterpret_cast<double*>(reinterpret_cast<uintptr_t>(in.torque + 3 * i) - 24), torque_lanes,
      reinterpret_cast<__m512d>(t));
}

// gather_particle with a particle's force in lanes 0..2 of one vector and its torque in lanes
// 3..5 of another: a pair entry's result (force, torque arm, overlap, F_n) is one load, its force
// added to the one and its arm, times the lever, to the other; the other lanes are never stored.
GRAINLAB_PASS_INLINE void gather_particle_lanes(const GatherInput& in, long i, v8 gravity) {
  const double r = in.radius[i];
  v8 f{}, t{};
  if (in.inverse_mass[i] > 0.0) f = splat(1.0 / in.inverse_mass[i]) * gravity;
  for (uint32_t e = in.row_start[i]; e < in.row_start[i + 1]; ++e) {
    const double* x = in.result + 8 * size_t{e};
    const v8 result = load(x);
    f = f + result;
    t = t + splat(r - 0.5 * x[6]) * result;
  }
  for (uint32_t k = in.col_start[i]; k < in.col_start[i + 1]; ++k) {
    const double* x = in.result + 8 * size_t{in.col_pair[k]};
    const v8 result = load(x);
    f = f - result;
    t = t + splat(r - 0.5 * x[6]) * result;
  }
  for (uint32_t e = in.wall_row_start[i]; e < in.wall_row_start[i + 1]; ++e) {
    f = f + in_force_lanes(in.force_on_particle + 3 * size_t{e});
    t = t + in_torque_lanes(in.torque_on_particle + 3 * size_t{e});
  }
  if (in.external_force) f = f + in_force_lanes(in.external_force + 3 * i);
  store_sums(in, i, f, t);
}

// The sums of the particles [first, end), at most gather_flat_block of them, each the arithmetic
// of gather_particle_lanes in the same order, the entries walked flat (GatherInput::row_owner):
// the block's row entries in entry order, then its column entries in column order, then its
// wall entries, each added to its particle's sum (force in lanes 0..2, torque in 3..5), then the
// external forces. A particle's entries are contiguous in each walk and in the order its own
// loops take them. An entry adds x * (1, 1, 1, lever, lever, lever) in its row and
// (-x) * (..) in its column: f + 1 x is f + x, and f + (-x) is f - x, exactly.
GRAINLAB_PASS_INLINE void gather_flat(const GatherInput& in, long first, long end, v8 gravity) {
  alignas(64) v8 sum[gather_flat_block];
  const long count = end - first;
  for (long k = 0; k < count; ++k) {
    const double inverse_mass = in.inverse_mass[first + k];
    sum[k] = inverse_mass > 0.0 ? splat(1.0 / inverse_mass) * gravity : v8{};
  }
  const double* const result = in.result;
  const double* const radius = in.radius;
  for (uint32_t e = in.row_start[first], row_end = in.row_start[end]; e < row_end; ++e) {
    const long k = in.row_owner[e] - first;
    const double* x = result + 8 * size_t{e};
    const __m512d v = _mm512_loadu_pd(x);
    // (x in lanes 0..2, the lever times x in lanes 3..5)
    const __m512d c =
        _mm512_mask_mul_pd(v, torque_lanes, v, _mm512_set1_pd(radius[first + k] - 0.5 * x[6]));
    sum[k] = sum[k] + reinterpret_cast<v8>(c);
  }
  for (uint32_t q = in.col_start[first], col_end = in.col_start[end]; q < col_end; ++q) {
    const uint32_t e = in.col_pair[q];
    const long k = in.partner[e] - first;
    const double* x = result + 8 * size_t{e};
    const __m512d v = _mm512_loadu_pd(x);
    // (-x in lanes 0..2, as f + (-x) is f - x exactly; the lever times x in lanes 3..5)
    const __m512d c =
        _mm512_mask_mul_pd(reinterpret_cast<__m512d>(-reinterpret_cast<v8>(v)), torque_lanes, v,
                           _mm512_set1_pd(radius[first + k] - 0.5 * x[6]));
    sum[k] = sum[k] + reinterpret_cast<v8>(c);
  }
  for (uint32_t e = in.wall_row_start[first], wall_end = in.wall_row_start[end]; e < wall_end;
       ++e) {
    const long k = in.wall_owner[e] - first;
    // (the wall's force and torque in one vector: each lane adds what the per-particle loop adds)
    sum[k] = sum[k] + in_torque_lanes(in.torque_on_particle + 3 * size_t{e},
                                      in_force_lanes(in.force_on_particle + 3 * size_t{e}));
  }
  for (long k = 0; k < count; ++k) {
    const long i = first + k;
    v8 s = sum[k];
    if (in.external_force) s = s + in_force_lanes(in.external_force + 3 * i);
    store_sums(in, i, s, s);
  }
}
#elif defined(__AVX2__)
// With AVX2 a particle's force is lanes 0..2 of one 256-bit vector and its torque lanes 0..2 of
// another (lane 3 of each is never stored): a pair entry's force is the first 4 values of its
// result line (force, torque arm, overlap, F_n), its arm the 4 from value 3 on, each one load.
// A Vec3 in lanes 0..2, a zero in lane 3 (nothing is read past the Vec3: it may end its array).
GRAINLAB_PASS_INLINE v4 load3(const double* vec3) {
  return reinterpret_cast<v4>(_mm256_maskload_pd(vec3, _mm256_setr_epi64x(-1, -1, -1, 0)));
}
// Lanes 0..2 of x to a Vec3.
GRAINLAB_PASS_INLINE void store3(double* vec3, v4 x) {
  const __m256d v = reinterpret_cast<__m256d>(x);
  _mm_storeu_pd(vec3, _mm256_castpd256_pd128(v));
  _mm_store_sd(vec3 + 2, _mm256_extractf128_pd(v, 1));
}
// An entry's share of its particle's sums: x in the force's lanes, the lever times the arm in
// the torque's (Vec3's f + x and t + lever * arm, component by component).
struct Sums4 {
  v4 force, torque;
};
GRAINLAB_PASS_INLINE void add_row_entry(Sums4& s, const double* x, double r) {
  s.force = s.force + load(x);
  s.torque = s.torque + splat(r - 0.5 * x[6]) * load(x + 3);
}
GRAINLAB_PASS_INLINE void add_column_entry(Sums4& s, const double* x, double r) {
  s.force = s.force - load(x);
  s.torque = s.torque + splat(r - 0.5 * x[6]) * load(x + 3);
}
GRAINLAB_PASS_INLINE void add_wall_entry(Sums4& s, const GatherInput& in, uint32_t e) {
  s.force = s.force + load3(in.force_on_particle + 3 * size_t{e});
  s.torque = s.torque + load3(in.torque_on_particle + 3 * size_t{e});
}
GRAINLAB_PASS_INLINE Sums4 weight(const GatherInput& in, long i, v4 gravity) {
  const double inverse_mass = in.inverse_mass[i];
  return {inverse_mass > 0.0 ? splat(1.0 / inverse_mass) * gravity : v4{}, v4{}};
}
GRAINLAB_PASS_INLINE void store_sums(const GatherInput& in, long i, Sums4 s) {
  if (in.external_force) s.force = s.force + load3(in.external_force + 3 * i);
  store3(in.force + 3 * i, s.force);
  store3(in.torque + 3 * i, s.torque);
}

// gather_particle on the two vectors.
GRAINLAB_PASS_INLINE void gather_particle_lanes(const GatherInput& in, long i, v4 gravity) {
  const double r = in.radius[i];
  Sums4 s = weight(in, i, gravity);
  for (uint32_t e = in.row_start[i]; e < in.row_start[i + 1]; ++e)
    add_row_entry(s, in.result + 8 * size_t{e}, r);
  for (uint32_t k = in.col_start[i]; k < in.col_start[i + 1]; ++k)
    add_column_entry(s, in.result + 8 * size_t{in.col_pair[k]}, r);
  for (uint32_t e = in.wall_row_start[i]; e < in.wall_row_start[i + 1]; ++e)
    add_wall_entry(s, in, e);
  store_sums(in, i, s);
}

// gather_flat of the AVX-512 object on the two vectors: the block's row entries in entry order,
// then its column entries, then its wall entries, each added to its particle's sums (a
// particle's entries are contiguous in each walk and in the order its own loops take them).
GRAINLAB_PASS_INLINE void gather_flat(const GatherInput& in, long first, long end, v4 gravity) {
  alignas(32) Sums4 sum[gather_flat_block];
  const long count = end - first;
  for (long k = 0; k < count; ++k) sum[k] = weight(in, first + k, gravity);
  const double* const result = in.result;
  const double* const radius = in.radius;
  for (uint32_t e = in.row_start[first], row_end = in.row_start[end]; e < row_end; ++e) {
    const long k = in.row_owner[e] - first;
    add_row_entry(sum[k], result + 8 * size_t{e}, radius[first + k]);
  }
  for (uint32_t q = in.col_start[first], col_end = in.col_start[end]; q < col_end; ++q) {
    const uint32_t e = in.col_pair[q];
    const long k = in.partner[e] - first;
    add_column_entry(sum[k], result + 8 * size_t{e}, radius[first + k]);
  }
  for (uint32_t e = in.wall_row_start[first], wall_end = in.wall_row_start[end]; e < wall_end; ++e)
    add_wall_entry(sum[in.wall_owner[e] - first], in, e);
  for (long k = 0; k < count; ++k) store_sums(in, first + k, sum[k]);
}
#endif

}  // namespace

void kick_and_drift(const ParticlePassInput& in, long first, long end, bool bound,
                    DriftTally& tally) {
  const bool check = in.position_at_refresh != nullptr;
  const bool rebuild = check && in.position_at_build != nullptr;
  if (!check) return drift_range<false, false, false>(in, first, end, tally);
  if (rebuild)
    return bound ? drift_range<true, true, true>(in, first, end, tally)
                 : drift_range<true, true, false>(in, first, end, tally);
  return bound ? drift_range<true, false, true>(in, first, end, tally)
               : drift_range<true, false, false>(in, first, end, tally);
}

void half_kick(const ParticlePassInput& in, long first, long end, double& max_speed2,
               double* next_speed2) {
  double max_next2 = 0.0;
  if (next_speed2 == nullptr) return kick_range<false>(in, first, end, max_speed2, max_next2);
  kick_range<true>(in, first, end, max_speed2, max_next2);
  *next_speed2 = raise(*next_speed2, max_next2);
}

void gather(const GatherInput& in, long first, long end) {
  // (a local copy: the compiler cannot tell that the force and torque stores leave `in` as it
  // is, and would load its pointers again for every particle)
  const GatherInput local = in;
#if defined(__AVX512F__) || defined(__AVX2__)
  // (gravity in the force's lanes, zeros in the others)
#if defined(__AVX512F__)
  const v8 gravity{in.gravity[0], in.gravity[1], in.gravity[2], 0.0, 0.0, 0.0, 0.0, 0.0};
#else
  const v4 gravity{in.gravity[0], in.gravity[1], in.gravity[2], 0.0};
#endif
  if (local.row_owner && local.partner) {
    for (long block_first = first; block_first < end; block_first += gather_flat_block) {
      const long block_end =
          end - block_first > gather_flat_block ? block_first + gather_flat_block : end;
      gather_flat(local, block_first, block_end, gravity);
    }
    return;
  }
  for (long i = first; i < end; ++i) gather_particle_lanes(local, i, gravity);
#else
  for (long i = first; i < end; ++i) gather_particle(local, i);
#endif
}

}  // namespace grainlab::GRAINLAB_SIMD_NS
