// The lane primitives of the vectorised contact kernel (core/pair_kernel_simd.cpp): a vector of
// 8 doubles, 3-vectors of them with the operations of core/vec3.hpp in the same association
// order, loads of per-entry and per-particle data into lanes, the 8 x 8 transpose, and the
// particle records' two halves. Included only by pair_kernel_simd.cpp, inside its
// per-instruction-set namespace and an anonymous one: everything here has internal linkage, so
// nothing compiled for one instruction set can be linked into code that runs on another.
// (No include guard and no includes of its own: it is a part of that one file.)
#ifndef GRAINLAB_SIMD_NS
#error "core/simd_lanes.hpp is part of core/pair_kernel_simd.cpp"
#endif

#define GRAINLAB_LANES_INLINE [[gnu::always_inline]] inline

// Lanes per vector: 8 unless the including file sets GRAINLAB_LANES to 4 (the pair kernel's AVX2
// object: 8 lanes there are two 256-bit registers per value, and AVX2's 16 registers then hold
// only 8 values, so the law's live values spilled to the stack and it ran no faster than the
// scalar loop; docs/performance.md sec. 48).
#ifndef GRAINLAB_LANES
#define GRAINLAB_LANES 8
#endif
constexpr int lanes = GRAINLAB_LANES;
static_assert(lanes == 8 || lanes == 4);
using vd = double __attribute__((vector_size(lanes * sizeof(double))));
using vmask =
    long long __attribute__((vector_size(lanes * sizeof(long long))));  // -1 true, 0 false
using vd4 = double __attribute__((vector_size(32)));

GRAINLAB_LANES_INLINE vd splat(double x) {  // x in every lane
#if GRAINLAB_LANES == 8
  return vd{x, x, x, x, x, x, x, x};
#else
  return vd{x, x, x, x};
#endif
}

// 4 x 4 transpose: value[v][l] = r[l][v] (its own inverse).
GRAINLAB_LANES_INLINE void transpose4(const vd4 (&r)[4], vd4 (&value)[4]) {
  const vd4 t0 = __builtin_shufflevector(r[0], r[1], 0, 4, 2, 6);
  const vd4 t1 = __builtin_shufflevector(r[0], r[1], 1, 5, 3, 7);
  const vd4 t2 = __builtin_shufflevector(r[2], r[3], 0, 4, 2, 6);
  const vd4 t3 = __builtin_shufflevector(r[2], r[3], 1, 5, 3, 7);
  value[0] = __builtin_shufflevector(t0, t2, 0, 1, 4, 5);
  value[1] = __builtin_shufflevector(t1, t3, 0, 1, 4, 5);
  value[2] = __builtin_shufflevector(t0, t2, 2, 3, 6, 7);
  value[3] = __builtin_shufflevector(t1, t3, 2, 3, 6, 7);
}

GRAINLAB_LANES_INLINE vd lane_sqrt(vd a) {
#if defined(__AVX512F__)
  return _mm512_mask_sqrt_pd(a, 0xFF, a);  // all lanes (the unmasked form warns in GCC 12)
#elif defined(__AVX__) && GRAINLAB_LANES == 4
  return _mm256_sqrt_pd(a);
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

// The lanes where m is true, as bits (lane l: bit l).
GRAINLAB_LANES_INLINE unsigned lane_bits(vmask m) {
#if defined(__AVX512F__)
  return _mm512_cmpneq_epi64_mask(reinterpret_cast<__m512i>(m), _mm512_setzero_si512());
#elif defined(__AVX__) && GRAINLAB_LANES == 4
  return static_cast<unsigned>(_mm256_movemask_pd(reinterpret_cast<__m256d>(m)));  // -1: sign set
#else
  unsigned bits = 0;
  for (int l = 0; l < lanes; ++l) bits |= (m[l] != 0 ? 1u : 0u) << l;
  return bits;
#endif
}

// Of the first `count` lanes of a batch: those handed back to the scalar law (the contacts that
// may have begun in this step, flagged by `begun`, when the positions have drifted) and those
// whose results the lanes store (the rest).
struct LaneChoice {
  unsigned store, handed_back;
};
GRAINLAB_LANES_INLINE LaneChoice choose_lanes(int count, bool drifted, vmask begun) {
  const unsigned used = (1u << count) - 1u;
  const unsigned handed_back = drifted ? lane_bits(begun) & used : 0u;
  return {used & ~handed_back, handed_back};
}

// The largest of 0 and the lanes in `used` that are not NaN: what a scalar loop
// `if (largest < x[l]) largest = x[l]` from 0 gives (a maximum is exact, so the order does not
// matter).
GRAINLAB_LANES_INLINE double largest_ordered(vd x, unsigned used) {
#if defined(__AVX512F__)
  const __mmask8 ordered = _mm512_cmp_pd_mask(x, x, _CMP_ORD_Q);
  // (lanes left out count as 0; no NaN is left, so each step is an exact maximum)
  vd v = _mm512_mask_blend_pd(static_cast<__mmask8>(ordered & used), splat(0.0), x);
  vd w = __builtin_shufflevector(v, v, 4, 5, 6, 7, 0, 1, 2, 3);
  v = v > w ? v : w;
  w = __builtin_shufflevector(v, v, 2, 3, 0, 1, 6, 7, 4, 5);
  v = v > w ? v : w;
  w = __builtin_shufflevector(v, v, 1, 0, 3, 2, 5, 4, 7, 6);
  v = v > w ? v : w;
  return v[0];
#else
  double largest = 0.0;
  for (int l = 0; l < lanes; ++l)
    if ((used >> l & 1u) && largest < x[l]) largest = x[l];
  return largest;
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
#if defined(__AVX2__) && GRAINLAB_LANES == 4
  __m128i times1, times3;  // 4 x int32
#elif defined(__AVX2__)
  __m256i times1, times3;  // 8 x int32
#endif
};
GRAINLAB_LANES_INLINE LaneIndex lane_index(const uint32_t* index) {
  LaneIndex r{};
  r.index = index;
#if defined(__AVX2__) && GRAINLAB_LANES == 4
  r.times1 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(index));
  r.times3 = _mm_add_epi32(_mm_add_epi32(r.times1, r.times1), r.times1);
#elif defined(__AVX2__)
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
#elif defined(__AVX2__) && GRAINLAB_LANES == 4
  // (the masked form with all lanes on, as for AVX-512)
  const __m256d all = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
  return _mm256_mask_i32gather_pd(_mm256_setzero_pd(), base + offset,
                                  stride == 3 ? x.times3 : x.times1, all, 8);
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
#if defined(__AVX512F__)
  // The inverse of store_lanes3: two lanes' (x, y, z) per vector, lane 2k in values 0..2 and lane
  // 2k + 1 in values 4..6 (the second loaded from 4 values before its place under a mask: the
  // values masked off are not read), then permuted into one vector per component. 8 masked loads
  // and 7 permutations in place of three 8-value gathers (about 6 cycles each on the development
  // VM's Zen 5).
  __m512d pair[4];
#pragma GCC unroll 4
  for (int k = 0; k < 4; ++k) {
    const __m512d first = _mm512_maskz_loadu_pd(0x07, base + size_t{x.index[2 * k]} * 3);
    const uintptr_t at = reinterpret_cast<uintptr_t>(base + size_t{x.index[2 * k + 1]} * 3) - 32;
    pair[k] = _mm512_mask_loadu_pd(first, 0x70, reinterpret_cast<const double*>(at));
  }
  // x0 x1 x2 x3 y0 y1 y2 y3 from pairs 0 and 1 (z0..z3 twice), the same for lanes 4..7 from pairs
  // 2 and 3; then the halves side by side
  const __m512i xy = _mm512_setr_epi64(0, 4, 8, 12, 1, 5, 9, 13);
  const __m512i zz = _mm512_setr_epi64(2, 6, 10, 14, 2, 6, 10, 14);
  const __m512d xy_low = _mm512_permutex2var_pd(pair[0], xy, pair[1]);
  const __m512d xy_high = _mm512_permutex2var_pd(pair[2], xy, pair[3]);
  const __m512d z_low = _mm512_permutex2var_pd(pair[0], zz, pair[1]);
  const __m512d z_high = _mm512_permutex2var_pd(pair[2], zz, pair[3]);
  const vd xy0 = reinterpret_cast<vd>(xy_low), xy1 = reinterpret_cast<vd>(xy_high);
  const vd z0 = reinterpret_cast<vd>(z_low), z1 = reinterpret_cast<vd>(z_high);
  return {__builtin_shufflevector(xy0, xy1, 0, 1, 2, 3, 8, 9, 10, 11),
          __builtin_shufflevector(xy0, xy1, 4, 5, 6, 7, 12, 13, 14, 15),
          __builtin_shufflevector(z0, z1, 0, 1, 2, 3, 8, 9, 10, 11)};
#elif defined(__AVX2__) && GRAINLAB_LANES == 4
  // Each lane's (x, y, z) in one masked load (the fourth value is not read), then a 4 x 4
  // transpose: 4 loads and 8 shuffles in place of three 4-value gathers.
  const __m256i first_three = _mm256_setr_epi64x(-1, -1, -1, 0);
  vd4 row[4], value[4];
#pragma GCC unroll 4
  for (int l = 0; l < 4; ++l)
    row[l] = reinterpret_cast<vd4>(_mm256_maskload_pd(base + size_t{x.index[l]} * 3, first_three));
  transpose4(row, value);
  return {value[0], value[1], value[2]};
#else
  return {load_lanes(base, x, 3, 0), load_lanes(base, x, 3, 1), load_lanes(base, x, 3, 2)};
#endif
}
GRAINLAB_LANES_INLINE void store_lane3(double* base, uint32_t index, const V3& v, int l) {
  double* out = base + size_t{index} * 3;
  out[0] = v.x[l];
  out[1] = v.y[l];
  out[2] = v.z[l];
}

#if GRAINLAB_LANES == 8
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
#endif

// The velocities of each lane's particle from its record (particle_records): per lane a load of
// values 0..7 and one of values 8..11, each transposed so that a value is one lane vector. (On the
// development VM's Zen 5 a 512-bit shuffle is a scarce operation: 96 more per batch made the step
// 11 % slower.) The two halves are loaded where they are first needed, which keeps fewer vectors
// live.
struct RecordHead {  // values 0..7
  V3 velocity, spin;
  vd velocity_at_end_x, velocity_at_end_y;
};
#if defined(__AVX512F__)
// Two 4-value halves in one vector: `low` in values 0..3, `high` in 4..7, each loaded from memory
// (the second by a broadcast under a mask, which the load unit carries out: no shuffle).
GRAINLAB_LANES_INLINE vd load_halves(const double* low, const double* high) {
  return reinterpret_cast<vd>(_mm512_mask_broadcast_f64x4(
      _mm512_castpd256_pd512(_mm256_loadu_pd(low)), 0xF0, _mm256_loadu_pd(high)));
}
#endif
GRAINLAB_LANES_INLINE RecordHead load_record_head(const double* record, const uint32_t* index) {
#if defined(__AVX512F__)
  // The first stage of the 8 x 8 transpose by the loads: lanes k and k + 4 side by side, values
  // 0..3 in one vector and 4..7 in another; then per 256-bit half a 4 x 4 transpose.
  vd half[lanes];  // half[k]: values 0..3 of lanes k, k + 4; half[4 + k]: values 4..7
#pragma GCC unroll 4
  for (int k = 0; k < 4; ++k) {
    const double* a = record + size_t{index[k]} * particle_record_size;
    const double* b = record + size_t{index[k + 4]} * particle_record_size;
    half[k] = load_halves(a, b);
    half[4 + k] = load_halves(a + 4, b + 4);
  }
  vd value[lanes];
#pragma GCC unroll 2
  for (int h = 0; h < 2; ++h) {  // values 0..3, values 4..7
    const vd* q = half + 4 * h;
    const vd t0 = __builtin_shufflevector(q[0], q[1], 0, 8, 2, 10, 4, 12, 6, 14);
    const vd t1 = __builtin_shufflevector(q[0], q[1], 1, 9, 3, 11, 5, 13, 7, 15);
    const vd t2 = __builtin_shufflevector(q[2], q[3], 0, 8, 2, 10, 4, 12, 6, 14);
    const vd t3 = __builtin_shufflevector(q[2], q[3], 1, 9, 3, 11, 5, 13, 7, 15);
    value[4 * h] = __builtin_shufflevector(t0, t2, 0, 1, 8, 9, 4, 5, 12, 13);
    value[4 * h + 1] = __builtin_shufflevector(t1, t3, 0, 1, 8, 9, 4, 5, 12, 13);
    value[4 * h + 2] = __builtin_shufflevector(t0, t2, 2, 3, 10, 11, 6, 7, 14, 15);
    value[4 * h + 3] = __builtin_shufflevector(t1, t3, 2, 3, 10, 11, 6, 7, 14, 15);
  }
  return {{value[0], value[1], value[2]}, {value[3], value[4], value[5]}, value[6], value[7]};
#elif GRAINLAB_LANES == 4
  // values 0..3 and 4..7 of each lane, each 4 x 4 block transposed
  vd4 low[4], high[4], v[4], w[4];  // v: values 0..3, w: values 4..7
#pragma GCC unroll 4  // (a loop would copy the rows through the stack)
  for (int l = 0; l < 4; ++l) {
    const double* r = record + size_t{index[l]} * particle_record_size;
    __builtin_memcpy(&low[l], r, sizeof low[l]);
    __builtin_memcpy(&high[l], r + 4, sizeof high[l]);
  }
  transpose4(low, v);
  transpose4(high, w);
  return {{v[0], v[1], v[2]}, {v[3], w[0], w[1]}, w[2], w[3]};
#else
  vd r[lanes];  // r[l]: values 0..7 of lane l
  for (int l = 0; l < lanes; ++l)
    __builtin_memcpy(&r[l], record + size_t{index[l]} * particle_record_size, sizeof r[l]);
  vd value[lanes];
  transpose8(r, value);
  return {{value[0], value[1], value[2]}, {value[3], value[4], value[5]}, value[6], value[7]};
#endif
}
struct RecordTail {  // values 8..11
  vd velocity_at_end_z;
  V3 spin_at_end;
};
GRAINLAB_LANES_INLINE RecordTail load_record_tail(const double* record, const uint32_t* index) {
#if GRAINLAB_LANES == 4
  vd4 q[4], value[4];  // q[l]: values 8..11 of lane l
#pragma GCC unroll 4   // (a loop would copy the rows through the stack)
  for (int l = 0; l < 4; ++l)
    __builtin_memcpy(&q[l], record + size_t{index[l]} * particle_record_size + 8, sizeof q[l]);
  transpose4(q, value);
  return {value[0], {value[1], value[2], value[3]}};
#else
  // 4 x 8 transpose: lanes l and l + 4 side by side (with AVX-512 by the loads, as in
  // load_record_head), then pairs and quads as above.
  vd c[4], d[4], value[4];
#if defined(__AVX512F__)
  for (int k = 0; k < 4; ++k)
    c[k] = load_halves(record + size_t{index[k]} * particle_record_size + 8,
                       record + size_t{index[k + 4]} * particle_record_size + 8);
#else
  vd4 q[lanes];  // q[l]: values 8..11 of lane l
  for (int l = 0; l < lanes; ++l)
    __builtin_memcpy(&q[l], record + size_t{index[l]} * particle_record_size + 8, sizeof q[l]);
  for (int k = 0; k < 4; ++k)
    c[k] = __builtin_shufflevector(q[k], q[k + 4], 0, 1, 2, 3, 4, 5, 6, 7);
#endif
  d[0] = __builtin_shufflevector(c[0], c[1], 0, 8, 2, 10, 4, 12, 6, 14);
  d[1] = __builtin_shufflevector(c[0], c[1], 1, 9, 3, 11, 5, 13, 7, 15);
  d[2] = __builtin_shufflevector(c[2], c[3], 0, 8, 2, 10, 4, 12, 6, 14);
  d[3] = __builtin_shufflevector(c[2], c[3], 1, 9, 3, 11, 5, 13, 7, 15);
  value[0] = __builtin_shufflevector(d[0], d[2], 0, 1, 8, 9, 4, 5, 12, 13);
  value[2] = __builtin_shufflevector(d[0], d[2], 2, 3, 10, 11, 6, 7, 14, 15);
  value[1] = __builtin_shufflevector(d[1], d[3], 0, 1, 8, 9, 4, 5, 12, 13);
  value[3] = __builtin_shufflevector(d[1], d[3], 2, 3, 10, 11, 6, 7, 14, 15);
  return {value[0], {value[1], value[2], value[3]}};
#endif
}

// Stores lane l of v at base + 3 index[l] for the lanes in `store`.
GRAINLAB_LANES_INLINE void store_lanes3(double* base, const uint32_t* index, const V3& v,
                                        unsigned store) {
#if defined(__AVX512F__)
  // Two lanes' (x, y, z) per vector, in its two halves, each half stored under a 3-value mask
  // (the second half from 4 values before the lane's place: the masked-off values are neither
  // read nor written): 6 permutations and 8 masked stores in place of three 8-value scatters.
  const __m512i low = _mm512_setr_epi64(0, 8, 1, 9, 2, 10, 3, 11);  // x0 y0 x1 y1 x2 y2 x3 y3
  const __m512i high = _mm512_setr_epi64(4, 12, 5, 13, 6, 14, 7, 15);
  const __m512d xy[2] = {_mm512_permutex2var_pd(v.x, low, v.y),
                         _mm512_permutex2var_pd(v.x, high, v.y)};
#pragma GCC unroll 4
  for (int k = 0; k < 4; ++k) {  // lanes 2k and 2k + 1
    const int q = 4 * (k % 2);
    const __m512i pick = _mm512_setr_epi64(q, q + 1, 8 + 2 * k, 0, q + 2, q + 3, 9 + 2 * k, 0);
    const __m512d pair = _mm512_permutex2var_pd(xy[k / 2], pick, v.z);
    const auto first = static_cast<__mmask8>(0x07u & (0u - (store >> (2 * k) & 1u)));
    const auto second = static_cast<__mmask8>(0x70u & (0u - (store >> (2 * k + 1) & 1u)));
    _mm512_mask_storeu_pd(base + size_t{index[2 * k]} * 3, first, pair);
    const uintptr_t at = reinterpret_cast<uintptr_t>(base + size_t{index[2 * k + 1]} * 3) - 32;
    _mm512_mask_storeu_pd(reinterpret_cast<double*>(at), second, pair);
  }
#elif defined(__AVX2__) && GRAINLAB_LANES == 4
  // The inverse of load_lanes3: a 4 x 4 transpose gives each lane's (x, y, z, 0), stored as its
  // first two values and its third.
  const vd4 value[4] = {v.x, v.y, v.z, vd4{}};
  vd4 row[4];
  transpose4(value, row);
#pragma GCC unroll 4
  for (int l = 0; l < 4; ++l)
    if (store >> l & 1u) {
      double* out = base + size_t{index[l]} * 3;
      _mm_storeu_pd(out, _mm256_castpd256_pd128(reinterpret_cast<__m256d>(row[l])));
      _mm_store_sd(out + 2, _mm256_extractf128_pd(reinterpret_cast<__m256d>(row[l]), 1));
    }
#else
  for (int l = 0; l < lanes; ++l)
    if (store >> l & 1u) store_lane3(base, index[l], v, l);
#endif
}

GRAINLAB_LANES_INLINE void store_zero3(double* out) {
  out[0] = out[1] = out[2] = 0.0;
}
