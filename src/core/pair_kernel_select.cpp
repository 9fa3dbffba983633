// Run-time choice of the vectorised pair kernel (core/pair_kernel_simd.hpp) and of the particle
// passes (core/particle_passes_simd.hpp).
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "core/pair_kernel_simd.hpp"
#include "core/particle_passes_simd.hpp"

namespace grainlab {

SimdPairKernel select_simd_pair_kernel() {
  __builtin_cpu_init();
  const bool has_avx2 = __builtin_cpu_supports("avx2");
  const bool has_avx512 = __builtin_cpu_supports("avx512f");
  const char* variable = std::getenv("GRAINLAB_SIMD");
  const std::string wanted = variable && *variable ? variable : "auto";
  if (wanted == "off") return {nullptr, nullptr, nullptr, nullptr, nullptr, "scalar"};
  if (wanted == "sse2")
    return {&simd_sse2::pair_rows,   &simd_sse2::particle_records,
            &simd_sse2::wall_law,    &simd_sse2::plane_wall_rows,
            &simd_sse2::wall_totals, "sse2"};  // every x86-64 has SSE2
  if (wanted == "avx2" || (wanted == "auto" && has_avx2 && !has_avx512)) {
    if (!has_avx2) throw std::runtime_error("GRAINLAB_SIMD=avx2, but this CPU has no AVX2");
    return {&simd_avx2::pair_rows,       &simd_avx2::particle_records, &simd_avx2::wall_law,
            &simd_avx2::plane_wall_rows, &simd_avx2::wall_totals,      "avx2"};
  }
  if (wanted == "avx512" || (wanted == "auto" && has_avx512)) {
    if (!has_avx512) throw std::runtime_error("GRAINLAB_SIMD=avx512, but this CPU has no AVX-512F");
    return {&simd_avx512::pair_rows,       &simd_avx512::particle_records, &simd_avx512::wall_law,
            &simd_avx512::plane_wall_rows, &simd_avx512::wall_totals,      "avx512"};
  }
  if (wanted == "auto")
    return {&simd_sse2::pair_rows,       &simd_sse2::particle_records, &simd_sse2::wall_law,
            &simd_sse2::plane_wall_rows, &simd_sse2::wall_totals,      "sse2"};
  throw std::runtime_error("GRAINLAB_SIMD=" + wanted +
                           ": expected off, sse2, avx2, avx512 or auto (the default)");
}

SimdParticlePasses select_simd_particle_passes() {
  const std::string kernel = select_simd_pair_kernel().name;
  if (kernel == "avx512")
    return {&simd_avx512::kick_and_drift, &simd_avx512::half_kick, &simd_avx512::gather, "avx512"};
  if (kernel == "avx2")
    return {&simd_avx2::kick_and_drift, &simd_avx2::half_kick, &simd_avx2::gather, "avx2"};
  // (also where the pair kernel is off: the same arithmetic)
  return {&simd_sse2::kick_and_drift, &simd_sse2::half_kick, &simd_sse2::gather, "sse2"};
}

namespace {
constexpr double touched_bytes_per_bead = 1536.0;  // what a step touches per bead, about
}  // namespace

bool prefetch_pays(double partner_reach, long l2_cache_bytes) {
  return partner_reach * touched_bytes_per_bead > static_cast<double>(l2_cache_bytes);
}

int one_sweep_team(double partner_reach, long max_partner_ahead, long l2_cache_bytes,
                   long l3_cache_bytes) {
  if (static_cast<double>(max_partner_ahead) * touched_bytes_per_bead >
      0.5 * static_cast<double>(l3_cache_bytes))
    return 0;
  return prefetch_pays(partner_reach, l2_cache_bytes) ? 2 : 1;
}

PartnerReach partner_reach(const uint32_t* row_start, const uint32_t* partner, size_t rows) {
  // (integer sums and maxima: the same for any thread count)
  long sum = 0, counted = 0, farthest_ahead = 0;
  const long n = static_cast<long>(rows);
#pragma omp parallel for schedule(static) reduction(+ : sum, counted) \
    reduction(max : farthest_ahead) if (n > 4096)
  for (long i = 0; i < n; ++i) {
    if (row_start[i] == row_start[i + 1]) continue;
    uint32_t farthest = 0;
    for (uint32_t e = row_start[i]; e < row_start[i + 1]; ++e)
      farthest = std::max(farthest, partner[e]);
    const long ahead = farthest > i ? static_cast<long>(farthest) - i : 0;
    sum += ahead;
    farthest_ahead = std::max(farthest_ahead, ahead);
    ++counted;
  }
  PartnerReach reach;
  reach.farthest = farthest_ahead;
  reach.mean = counted > 0 ? static_cast<double>(sum) / static_cast<double>(counted) : 0.0;
  return reach;
}

long l2_cache_bytes() {
  static const long bytes = [] {
    const long reported = sysconf(_SC_LEVEL2_CACHE_SIZE);
    return reported > 0 ? reported : 1L << 20;
  }();
  return bytes;
}

long l3_cache_bytes() {
  static const long bytes = [] {
    // Linux's own account of the cache first: glibc's sysconf reports the sum over the host's
    // caches in some virtual machines (320 MiB on the development VM, whose one L3 is 32 MiB).
    long size = 0;
    char unit = 'B';
    if (std::FILE* f = std::fopen("/sys/devices/system/cpu/cpu0/cache/index3/size", "r")) {
      if (std::fscanf(f, "%ld%c", &size, &unit) < 1) size = 0;
      std::fclose(f);
    }
    if (size > 0) return unit == 'K' ? size << 10 : unit == 'M' ? size << 20 : size;
    const long reported = sysconf(_SC_LEVEL3_CACHE_SIZE);
    return reported > 0 ? reported : 8L << 20;
  }();
  return bytes;
}

}  // namespace grainlab
