// machine_ceilings: what this machine's cores do together, measured without grainlab. These are
// the ceilings against which the step loop's thread scaling (bench/thread_scaling.sh) is read:
// if even a loop that touches no memory runs slower per core on 16 threads than on one, the
// clock falls with the number of busy cores (turbo, the AVX-512 licence) or the "cores" share
// physical ones, and no program reaches an efficiency of 1 there.
//
// For 1, 2, 4, ... threads (powers of two up to the processor count, and the count itself):
// - compute: each thread runs 8 independent chains of the contact law's slow operations, a
//   square root and a division per link, in registers (AVX-512 lanes where the CPU has them,
//   as the pair kernel uses, else scalar), for a fixed number of links;
// - triad in cache / out of cache: a[i] = b[i] + s c[i] over three arrays of 16 MB in all
//   (per thread count, within a server's L3) and of 1.5 GB (far beyond it), counted as 24 B per
//   element, the STREAM convention; the best of several passes.
// Prints each figure with its speed-up and efficiency against 1 thread.
//   machine_ceilings [--max-threads N]
#include <immintrin.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace {

constexpr long links_per_thread = 20'000'000;

// One link of each chain: x <- sqrt(x * 1.0000001 + 0.5) / (x + 0.25) + 1.0; x stays near 1.5,
// positive and finite, and each link needs the previous one (a dependent chain, as a contact's).
__attribute__((target("avx512f"))) double chains_avx512(long links, double seed) {
  __m512d x = _mm512_set_pd(seed, seed + 0.1, seed + 0.2, seed + 0.3, seed + 0.4, seed + 0.5,
                            seed + 0.6, seed + 0.7);
  const __m512d a = _mm512_set1_pd(1.0000001), b = _mm512_set1_pd(0.5), c = _mm512_set1_pd(0.25),
                one = _mm512_set1_pd(1.0);
  for (long k = 0; k < links; ++k) {
    const __m512d y = _mm512_add_pd(_mm512_mul_pd(x, a), b);
    // (the masked form with all lanes set: GCC 12 warns on _mm512_sqrt_pd's undefined source)
    x = _mm512_add_pd(_mm512_div_pd(_mm512_mask_sqrt_pd(y, 0xFF, y), _mm512_add_pd(x, c)), one);
  }
  alignas(64) double lanes[8];
  _mm512_store_pd(lanes, x);
  double s = 0;
  for (double v : lanes) s += v;
  return s;
}

double chains_scalar(long links, double seed) {
  double x[8];
  for (int l = 0; l < 8; ++l) x[l] = seed + 0.1 * l;
  for (long k = 0; k < links; ++k)
    for (int l = 0; l < 8; ++l) x[l] = std::sqrt(x[l] * 1.0000001 + 0.5) / (x[l] + 0.25) + 1.0;
  double s = 0;
  for (double v : x) s += v;
  return s;
}

// links per second, all threads together
double compute_rate(int threads, bool avx512) {
  double sink = 0;
  const double start = omp_get_wtime();
#pragma omp parallel num_threads(threads) reduction(+ : sink)
  sink += avx512 ? chains_avx512(links_per_thread, 1.0 + omp_get_thread_num())
                 : chains_scalar(links_per_thread / 4, 1.0 + omp_get_thread_num());
  const double seconds = omp_get_wtime() - start;
  if (!std::isfinite(sink)) std::fprintf(stderr, "chains diverged\n");
  return static_cast<double>(threads) * (avx512 ? links_per_thread : links_per_thread / 4) * 8 /
         seconds;
}

// bytes per second (24 B per element), best of `passes`
double triad_rate(int threads, std::vector<double>& a, const std::vector<double>& b,
                  const std::vector<double>& c, long n, int passes) {
  double best = 0;
  for (int p = 0; p < passes; ++p) {
    const double start = omp_get_wtime();
#pragma omp parallel for schedule(static) num_threads(threads)
    for (long i = 0; i < n; ++i) a[i] = b[i] + 0.5 * c[i];
    best = std::max(best, 24.0 * n / (omp_get_wtime() - start));
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  int max_threads = omp_get_num_procs();
  for (int k = 1; k < argc; ++k) {
    if (std::strcmp(argv[k], "--max-threads") == 0 && k + 1 < argc) {
      max_threads = std::atoi(argv[++k]);
    } else {
      std::fprintf(stderr, "usage: machine_ceilings [--max-threads N]\n");
      return 2;
    }
  }
  if (max_threads < 1) {
    std::fprintf(stderr, "machine_ceilings: --max-threads wants a positive count\n");
    return 2;
  }
  std::vector<int> counts;
  for (int t = 1; t <= max_threads; t *= 2) counts.push_back(t);
  if (counts.back() != max_threads) counts.push_back(max_threads);
  const bool avx512 = __builtin_cpu_supports("avx512f");

  const long big = 64L << 20, small = (16L << 20) / 24;  // elements per array
  std::vector<double> a(big), b(big), c(big);
#pragma omp parallel for schedule(static) num_threads(max_threads)  // first touch, as used
  for (long i = 0; i < big; ++i) a[i] = 0.0, b[i] = 1.0, c[i] = 2.0;

  std::printf("%d processors; compute chains on %s\n", omp_get_num_procs(),
              avx512 ? "AVX-512 lanes" : "scalar lanes");
  std::printf("%7s %14s %8s %6s %14s %8s %6s %14s %8s %6s\n", "threads", "compute Glink/s",
              "speed-up", "eff", "triad 16MB GB/s", "speed-up", "eff", "triad 1.5GB GB/s",
              "speed-up", "eff");
  double one[3] = {};
  for (int t : counts) {
    const double r[3] = {compute_rate(t, avx512) / 1e9, triad_rate(t, a, b, c, small, 200) / 1e9,
                         triad_rate(t, a, b, c, big, 5) / 1e9};
    if (t == 1) std::copy(r, r + 3, one);
    std::printf("%7d", t);
    for (int k = 0; k < 3; ++k)
      std::printf(" %14.3f %8.2f %6.2f", r[k], r[k] / one[k], r[k] / one[k] / t);
    std::printf("\n");
    std::fflush(stdout);
  }
  return 0;
}
