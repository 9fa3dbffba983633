// The gather of velocity Verlet (core/particle_passes_simd.hpp): each particle's force and
// torque from its weight, its pair entries' 64-byte results, its wall contacts and its external
// force, as core/gather.cpp forms them. Compiled with the pair kernel, once per instruction set,
// with -ffp-contract=off and internal linkage for everything but the entry point
// (src/core/CMakeLists.txt, tests/core/kernel_symbols.sh).
//
// The gather keeps a particle's force and torque in two vectors, to which each of its entries'
// 64-byte results is added whole (with AVX2, two 256-bit vectors and two loads of 4 values from
// each result: docs/performance.md sec. 49).
#include <immintrin.h>

#include <cstdint>

#include "core/particle_passes_simd.hpp"

#ifndef GRAINLAB_SIMD_NS
#error "GRAINLAB_SIMD_NS must name the instruction set's namespace"
#endif

namespace grainlab::GRAINLAB_SIMD_NS {
namespace {

#include "core/particle_pass_lanes.hpp"  // NOLINT(build/include): part of this file, inside the namespace

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
