// The kick and drift of velocity Verlet (core/particle_passes_simd.hpp; the gather is
// core/gather_simd.cpp). Compiled with the pair kernel, once per instruction set, with
// -ffp-contract=off and internal linkage for everything but the entry points
// (src/core/CMakeLists.txt, tests/core/kernel_symbols.sh).
//
// The particle arrays are Vec3 arrays (x, y, z side by side). With AVX-512 the loop takes 8
// particles at a time (with AVX2 4, and 12 doubles): each Vec3 array's 24 doubles are three
// vectors, a per-particle factor (dt/2 times the inverse mass) is spread over them by a
// permutation, the arithmetic runs on the 24 components as the scalar loop does on each, and a
// squared length is formed from the x, y and z vectors that two permutations pick out of the
// three. The particles left over (fewer than 8, or 4) take the scalar loop: the same arithmetic.
#include "core/particle_passes_simd.hpp"

#include <immintrin.h>

#include <cstdint>

#ifndef GRAINLAB_SIMD_NS
#error "GRAINLAB_SIMD_NS must name the instruction set's namespace"
#endif

namespace grainlab::GRAINLAB_SIMD_NS {
namespace {

#include "core/particle_pass_lanes.hpp"  // NOLINT(build/include): part of this file, inside the namespace

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
using pvec = v8;  // the kick's and drift's vectors: 8 particles' values
constexpr long group_lanes = 8;
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
using pvec = v4;
constexpr long group_lanes = 4;
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
  // (a local copy, as in core/gather_simd.cpp: the compiler cannot tell that the stores below
  // leave `given` as it is, and would load its pointers again for every particle)
  const ParticlePassInput in = given;
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
  // (a local copy, as in core/gather_simd.cpp: the compiler cannot tell that the stores below
  // leave `given` as it is, and would load its pointers again for every particle)
  const ParticlePassInput in = given;
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

}  // namespace grainlab::GRAINLAB_SIMD_NS
