#include "core/contact_store.hpp"

#include <omp.h>

#include "core/particles.hpp"

namespace grainlab {

void index_rows_of_entries(const std::vector<uint32_t>& row_start, std::vector<uint32_t>& row) {
  const long rows = row_start.empty() ? 0 : static_cast<long>(row_start.size()) - 1;
  row.resize(rows > 0 ? row_start.back() : 0);
#pragma omp parallel for schedule(static) if (rows > parallel_threshold)
  for (long i = 0; i < rows; ++i)
    for (uint32_t e = row_start[i]; e < row_start[i + 1]; ++e) row[e] = static_cast<uint32_t>(i);
}

void sum_counts(std::vector<uint32_t>& starts) {
  const long n = static_cast<long>(starts.size());
  // (below this many, one thread: a region costs more than the sum)
  constexpr long parallel_counts = 4 * parallel_threshold;
  const int team = n > parallel_counts ? omp_get_max_threads() : 1;
  std::vector<uint32_t> part_total(static_cast<size_t>(team) + 1, 0);
#pragma omp parallel num_threads(team) if (team > 1)
  {
    const long t = omp_get_thread_num(), threads = omp_get_num_threads();
    const long first = n * t / threads, end = n * (t + 1) / threads;
    uint32_t sum = 0;
    for (long k = first; k < end; ++k) sum = starts[k] += sum;
    part_total[t + 1] = sum;
#pragma omp barrier
    uint32_t before = 0;
    for (long s = 0; s <= t; ++s) before += part_total[s];
    if (before != 0)
      for (long k = first; k < end; ++k) starts[k] += before;
  }
}

}  // namespace grainlab
