// The share of a per-particle loop that one thread of an OpenMP team takes: a contiguous block of
// [0, n), the partition schedule(static) makes. The stages of a step's force region start from
// these blocks and share what is left of them (core/chunk_queue.hpp); they run inside one
// parallel region, separated by barriers where one stage reads what another thread wrote, instead
// of one region per stage: each region costs a fork and a join, and with sleeping (passive)
// threads each of those is a wake-up of a few tens of microseconds on a VM (docs/performance.md
// sec. 15).
#pragma once

#include <omp.h>

#include <algorithm>

namespace grainlab {

struct IndexBlock {
  long first = 0, end = 0;
};

// Block `thread` of [0, n) cut into `threads` contiguous blocks.
inline IndexBlock block_of(long n, long threads, long thread) {
  const long block = (n + threads - 1) / threads;
  const long first = std::min(n, thread * block);
  return {first, std::min(n, first + block)};
}

// The calling thread's block of [0, n); outside a parallel region the whole range.
inline IndexBlock thread_block(long n) {
  return block_of(n, omp_get_num_threads(), omp_get_thread_num());
}

}  // namespace grainlab
