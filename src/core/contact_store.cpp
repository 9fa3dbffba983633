#include "core/contact_store.hpp"

#include "core/particles.hpp"

namespace grainlab {

void index_rows_of_entries(const std::vector<uint32_t>& row_start, std::vector<uint32_t>& row) {
  const long rows = row_start.empty() ? 0 : static_cast<long>(row_start.size()) - 1;
  row.resize(rows > 0 ? row_start.back() : 0);
#pragma omp parallel for schedule(static) if (rows > parallel_threshold)
  for (long i = 0; i < rows; ++i)
    for (uint32_t e = row_start[i]; e < row_start[i + 1]; ++e) row[e] = static_cast<uint32_t>(i);
}

}  // namespace grainlab
