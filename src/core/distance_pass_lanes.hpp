// The pair rows' distance pass on whole vectors of entries (core/pair_kernel_simd.cpp): the
// distance test of `lanes` entries at once and the touching ones packed into the batch. Part of
// pair_kernel_simd.cpp, included after its Batch inside the per-instruction-set namespace and an
// anonymous one (no include guard and no includes of its own), like core/simd_lanes.hpp.
//
// Each pass takes the entries from `e` on, `lanes` at a time, while a whole vector remains, and
// returns the first entry it left to the scalar loop. Per entry it zeroes the result line whatever
// the test says (the lanes or the scalar law write a touching one's afterwards: the stores wait
// for no distance test, docs/performance.md sec. 50) and hands the spring to `zero_spring(e,
// touching)`; the touching entries' d = x_j - x_i, radii and indices go to the batch at `count`,
// in entry order, and `run_full_batches` runs once `count` reaches the batch capacity. The test
// is the scalar loop's, by the same operations (touching unless |d|^2 >= (r_i + r_j)^2, NaN:
// touching), so both make the same decisions and the batches hold the same contacts.
#ifndef GRAINLAB_SIMD_NS
#error "core/distance_pass_lanes.hpp is part of core/pair_kernel_simd.cpp"
#endif

#if GRAINLAB_DISTANCE_PASS_LANES  // (set by pair_kernel_simd.cpp: AVX2 and AVX-512)

// Zeroes the `pair_result_size` values of entry e's result line.
GRAINLAB_LANES_INLINE void zero_result_line(double* result, uint32_t e) {
  double* const line = result + size_t{e} * pair_result_size;
#if defined(__AVX512F__)
  _mm512_storeu_pd(line, _mm512_setzero_pd());
#else
  // as two 32-byte stores (GCC splits a 64-byte vector into four 16-byte ones here)
  const vd4 zero{};
  __builtin_memcpy(line, &zero, sizeof zero);
  __builtin_memcpy(line + 4, &zero, sizeof zero);
#endif
}

template <bool Prefetch, class PrefetchAhead, class ZeroSpring, class RunFullBatches>
GRAINLAB_LANES_INLINE uint32_t distance_pass_lanes(const SimdPairInput& in, uint32_t e,
                                                   uint32_t end_entry, Batch& b, int& count,
                                                   const PrefetchAhead& prefetch,
                                                   const ZeroSpring& zero_spring,
                                                   const RunFullBatches& run_full_batches) {
  const double* const position = in.position;
  const double* const radius = in.radius;
  const uint32_t* const owner = in.owner;
  const uint32_t* const partner = in.partner;
  double* const result = in.result;
#if defined(__AVX512F__)
  // Eight entries at a time: positions by masked loads and permutations (load_lanes3), radii by
  // gathers, and the touching lanes packed to the front of each vector by the compress
  // instruction into a register (its form that stores to memory is microcoded on Zen 4), then
  // stored whole at the batch's count (the batch has a vector of room past its capacity).
  const __m256i lane_number = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  for (; end_entry - e >= 8; e += 8) {
    if constexpr (Prefetch)
      for (uint32_t k = 0; k < 8; ++k) prefetch(e + k);
    const uint32_t* const oi = owner + e;
    const uint32_t* const pj = partner + e;
    const LaneIndex li = lane_index(oi), lj = lane_index(pj);
    const vd r_i = load_lanes(radius, li, 1, 0), r_j = load_lanes(radius, lj, 1, 0);
    const V3 x_i = load_lanes3(position, li), x_j = load_lanes3(position, lj);
    const vd dx = x_j.x - x_i.x, dy = x_j.y - x_i.y, dz = x_j.z - x_i.z;
    const vd reach = r_i + r_j;
    const vd dist2 = dx * dx + dy * dy + dz * dz;
    const __mmask8 touching = _mm512_cmp_pd_mask(dist2, reach * reach, _CMP_NGE_UQ);
#pragma GCC unroll 8
    for (uint32_t k = 0; k < 8; ++k) {
      zero_result_line(result, e + k);
      zero_spring(e + k, touching >> k & 1u);
    }
    _mm512_storeu_pd(b.dx + count, _mm512_maskz_compress_pd(touching, dx));
    _mm512_storeu_pd(b.dy + count, _mm512_maskz_compress_pd(touching, dy));
    _mm512_storeu_pd(b.dz + count, _mm512_maskz_compress_pd(touching, dz));
    _mm512_storeu_pd(b.ri + count, _mm512_maskz_compress_pd(touching, r_i));
    _mm512_storeu_pd(b.rj + count, _mm512_maskz_compress_pd(touching, r_j));
    // the indices: 8 x int32 in the low half of a 512-bit vector (AVX-512F compresses those)
    const auto pack_index = [&](uint32_t* to, __m256i x) {
      using int16 = int32_t __attribute__((vector_size(64)));
      using int8 = int32_t __attribute__((vector_size(32)));
      const auto packed =
          reinterpret_cast<int16>(_mm512_maskz_compress_epi32(touching, _mm512_castsi256_si512(x)));
      // (the low half by a shuffle: GCC 12's _mm512_castsi512_si256 warns of an undefined value)
      const int8 low = __builtin_shufflevector(packed, packed, 0, 1, 2, 3, 4, 5, 6, 7);
      __builtin_memcpy(to, &low, sizeof low);
    };
    pack_index(b.i + count, li.times1);
    pack_index(b.j + count, lj.times1);
    pack_index(b.e + count, _mm256_add_epi32(_mm256_set1_epi32(static_cast<int>(e)), lane_number));
    count += __builtin_popcount(touching);
    if (count >= batch_capacity) run_full_batches();
  }
#else
  // Four entries at a time: each particle's position by one masked load and the four as a 4 x 4
  // transpose (load_lanes3; gather instructions measured slower here), and the touching entries
  // packed to the front of each vector by a permutation chosen by the lanes' bits and stored at
  // the batch's count: 5 vector and 3 half-vector stores for 4 entries in place of 8 stores for
  // each (docs/performance.md sec. 50).
  // pack[bits]: the 32-bit index pairs that move the lanes set in `bits` to the front, in order
  alignas(32) static constexpr auto pack = [] {
    std::array<std::array<int32_t, 8>, 16> t{};
    for (unsigned bits = 0; bits < 16; ++bits) {
      int n = 0;
      for (int l = 0; l < 4; ++l)
        if (bits >> l & 1u) t[bits][2 * n] = 2 * l, t[bits][2 * n + 1] = 2 * l + 1, ++n;
    }
    return t;
  }();
  const auto pack_pd = [](__m256d x, __m256i p) {
    return _mm256_castsi256_pd(_mm256_permutevar8x32_epi32(_mm256_castpd_si256(x), p));
  };
  // (the even 32-bit lanes of a pair permutation, halved, give the permutation of 4 x int32)
  const __m256i halve = _mm256_setr_epi32(0, 2, 4, 6, 0, 0, 0, 0);
  for (; end_entry - e >= 4; e += 4) {
    if constexpr (Prefetch)
      for (uint32_t k = 0; k < 4; ++k) prefetch(e + k);
    const uint32_t* const oi = owner + e;
    const uint32_t* const pj = partner + e;
    const LaneIndex li = lane_index(oi), lj = lane_index(pj);  // (4 x int32 in times1)
    const __m256d r_i = _mm256_setr_pd(radius[oi[0]], radius[oi[1]], radius[oi[2]], radius[oi[3]]);
    const __m256d r_j = _mm256_setr_pd(radius[pj[0]], radius[pj[1]], radius[pj[2]], radius[pj[3]]);
    const V3 x_i = load_lanes3(position, li), x_j = load_lanes3(position, lj);
    const __m256d dx = _mm256_sub_pd(x_j.x, x_i.x);
    const __m256d dy = _mm256_sub_pd(x_j.y, x_i.y);
    const __m256d dz = _mm256_sub_pd(x_j.z, x_i.z);
    const __m256d reach = _mm256_add_pd(r_i, r_j);
    const __m256d dist2 = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy)),
                                        _mm256_mul_pd(dz, dz));
    const auto bits = static_cast<unsigned>(
        _mm256_movemask_pd(_mm256_cmp_pd(dist2, _mm256_mul_pd(reach, reach), _CMP_NGE_UQ)));
    for (uint32_t k = 0; k < 4; ++k) {
      zero_result_line(result, e + k);
      zero_spring(e + k, bits >> k & 1u);
    }
    const __m256i p = _mm256_load_si256(reinterpret_cast<const __m256i*>(pack[bits].data()));
    const __m256i p4 = _mm256_permutevar8x32_epi32(p, halve);  // 2 l for each packed lane
    const __m256i q = _mm256_srli_epi32(p4, 1);                // l for each packed lane
    const auto pack_epi32 = [&](__m128i x) {
      return _mm256_castsi256_si128(_mm256_permutevar8x32_epi32(_mm256_castsi128_si256(x), q));
    };
    _mm256_storeu_pd(b.dx + count, pack_pd(dx, p));
    _mm256_storeu_pd(b.dy + count, pack_pd(dy, p));
    _mm256_storeu_pd(b.dz + count, pack_pd(dz, p));
    _mm256_storeu_pd(b.ri + count, pack_pd(r_i, p));
    _mm256_storeu_pd(b.rj + count, pack_pd(r_j, p));
    const __m128i entry =
        _mm_add_epi32(_mm_set1_epi32(static_cast<int>(e)), _mm_setr_epi32(0, 1, 2, 3));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(b.i + count), pack_epi32(li.times1));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(b.j + count), pack_epi32(lj.times1));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(b.e + count), pack_epi32(entry));
    count += __builtin_popcount(bits);
    if (count >= batch_capacity) run_full_batches();
  }
#endif
  return e;
}
#endif
