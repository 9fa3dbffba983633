// Run-time choice of the vectorised pair kernel (core/pair_kernel_simd.hpp).
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "core/pair_kernel_simd.hpp"

namespace grainlab {

SimdPairKernel select_simd_pair_kernel() {
  __builtin_cpu_init();
  const bool has_avx2 = __builtin_cpu_supports("avx2");
  const bool has_avx512 = __builtin_cpu_supports("avx512f");
  const char* variable = std::getenv("GRAINLAB_SIMD");
  const std::string wanted = variable && *variable ? variable : "auto";
  if (wanted == "off") return {nullptr, nullptr, nullptr, "scalar"};
  if (wanted == "sse2")
    return {&simd_sse2::pair_rows, &simd_sse2::particle_records, &simd_sse2::wall_law,
            "sse2"};  // every x86-64 has SSE2
  if (wanted == "avx2" || (wanted == "auto" && has_avx2 && !has_avx512)) {
    if (!has_avx2) throw std::runtime_error("GRAINLAB_SIMD=avx2, but this CPU has no AVX2");
    return {&simd_avx2::pair_rows, &simd_avx2::particle_records, &simd_avx2::wall_law, "avx2"};
  }
  if (wanted == "avx512" || (wanted == "auto" && has_avx512)) {
    if (!has_avx512) throw std::runtime_error("GRAINLAB_SIMD=avx512, but this CPU has no AVX-512F");
    return {&simd_avx512::pair_rows, &simd_avx512::particle_records, &simd_avx512::wall_law,
            "avx512"};
  }
  if (wanted == "auto")
    return {&simd_sse2::pair_rows, &simd_sse2::particle_records, &simd_sse2::wall_law, "sse2"};
  throw std::runtime_error("GRAINLAB_SIMD=" + wanted +
                           ": expected off, sse2, avx2, avx512 or auto (the default)");
}

}  // namespace grainlab
