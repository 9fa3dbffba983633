// The active pair list (core/neighbor_search.hpp): the candidates within the list skin, selected
// at each rebuild and refreshed between rebuilds, with the entries' histories carried by
// candidate; and the watch that tells the drift whether it must test for a rebuild.
#include <omp.h>

#include <algorithm>

#include "core/neighbor_search.hpp"

namespace grainlab {
namespace {

// Below this many rows a pass of the selection runs on one thread.
constexpr long parallel_rows = 4 * parallel_threshold;

// A vector about to be written whole: sized to n, its old values left where its storage
// suffices (the list's arrays are written anew at every selection; zeroing them first would
// be a serial pass over each), freed and made anew with a sixteenth to spare where it does not.
template <class Vector>
void size_to_overwrite(Vector& v, size_t n) {
  if (n > v.capacity()) {
    v = Vector{};
    v.reserve(n + n / 16);
  }
  v.resize(n);
}

// The transpose of a pair list (col_start, col_pair), in increasing entry order (fixed,
// thread-independent). A partner j of row i lies after it (i < j <= i + farthest): the thread
// that owns the columns of particles [first, end) finds their entries in rows
// [first - farthest, end), in entry order, and writes only its own columns. Where the partners
// reach far (farthest above a quarter of the rows) one thread does it all.
void index_columns(PairContacts& pairs, long particles, long farthest) {
  size_to_overwrite(pairs.col_start, static_cast<size_t>(particles) + 1);
  size_to_overwrite(pairs.col_pair, pairs.partner.size());
  const uint32_t* row_start = pairs.row_start.data();
  const uint32_t* partner = pairs.partner.data();
  uint32_t* col_start = pairs.col_start.data();
  uint32_t* col_pair = pairs.col_pair.data();
  const long n = particles;
  const int team = n > parallel_rows && 4 * farthest < n ? omp_get_max_threads() : 1;
  // Calls visit(entry, column) for the entries of the calling thread's columns, in entry order.
  const auto for_each_own_entry = [&](auto&& visit) {
    const long t = omp_get_thread_num(), threads = omp_get_num_threads();
    const uint32_t first = static_cast<uint32_t>(n * t / threads);
    const uint32_t end = static_cast<uint32_t>(n * (t + 1) / threads);
    const uint32_t scan_end = row_start[end];
    for (uint32_t e = row_start[std::max(0L, static_cast<long>(first) - farthest)]; e < scan_end;
         ++e)
      if (partner[e] >= first && partner[e] < end) visit(e, partner[e]);
  };
  col_start[0] = 0;
#pragma omp parallel num_threads(team) if (team > 1)
  {
    const long t = omp_get_thread_num(), threads = omp_get_num_threads();
    for (long j = n * t / threads; j < n * (t + 1) / threads; ++j) col_start[j + 1] = 0;
    for_each_own_entry([&](uint32_t, uint32_t j) { ++col_start[j + 1]; });
  }
  sum_counts(pairs.col_start);
#pragma omp parallel num_threads(team) if (team > 1)
  {
    const long t = omp_get_thread_num(), threads = omp_get_num_threads();
    const long first = n * t / threads, end = n * (t + 1) / threads;
    std::vector<uint32_t> next(col_start + first, col_start + end);  // each column's next place
    for_each_own_entry([&](uint32_t e, uint32_t j) { col_pair[next[j - first]++] = e; });
  }
}

}  // namespace

void NeighborSearch::watch_for_rebuild() {
  // A particle within d of its position at the build, moving at most half the list skin before
  // the next refresh, stays within d + list_skin/2; that is below skin/2 for every particle when
  // d < (skin - list_skin)/2, less a margin far above the rounding of these norms.
  const long n = static_cast<long>(position_at_refresh_.size());
  if (position_at_build_.size() != position_at_refresh_.size()) {
    rebuild_possible_before_refresh_ = true;
    return;
  }
  const double allowance = 0.5 * (skin_ - list_skin_) - 1e-9 * skin_;
  if (!(allowance > 0.0)) {
    rebuild_possible_before_refresh_ = true;
    return;
  }
  double farthest2 = 0.0;
#pragma omp parallel for schedule(static) reduction(max : farthest2) if (n > parallel_threshold)
  for (long i = 0; i < n; ++i)
    farthest2 = std::max(farthest2, norm2(position_at_refresh_[i] - position_at_build_[i]));
  rebuild_possible_before_refresh_ = !(farthest2 < allowance * allowance);
}

void NeighborSearch::select_active(const ParticleStore& p, const PairContacts& old,
                                   std::span<const uint32_t> old_entry, PairContacts& active,
                                   ContactPieces pieces) {
  const long n = static_cast<long>(p.size());
  // Calls decide(candidate, kept) for the candidates of row i, in order. One is kept when it
  // lies within the list skin now, or holds a history (a contact that has just come apart: its
  // entry forgets the history at the next force evaluation, as it would in the full list).
  auto for_each_candidate = [&](long i, auto&& decide) {
    const Vec3 xi = p.position[i];
    const double ri = p.radius[i];
    for (uint32_t c = candidate_row_start_[i]; c < candidate_row_start_[i + 1]; ++c) {
      const uint32_t from = old_entry[c];
      const uint32_t j = candidate_partner_[c];
      const double reach = ri + p.radius[j] + list_skin_;
      // (the history is looked up only for a candidate beyond the list skin: few of them)
      bool keep = norm2(p.position[j] - xi) < reach * reach;
      if (!keep && from != no_old_entry) keep = entry_has_history(old, from);
      decide(c, keep);
    }
  };
  // Which candidates are kept, one flag each (not a character type, whose stores would make the
  // compiler load every array's address again), and how many per row; then the rows' starts.
  enum class Kept : uint8_t { no, yes };
  std::vector<Kept, UninitializedAllocator<Kept>> kept(candidate_partner_.size());
  size_to_overwrite(active.row_start, static_cast<size_t>(n) + 1);
  active.row_start[0] = 0;
#pragma omp parallel for schedule(static) if (n > parallel_rows)
  for (long i = 0; i < n; ++i) {
    uint32_t count = 0;
    for_each_candidate(i, [&](uint32_t c, bool keep) {
      kept[c] = keep ? Kept::yes : Kept::no;
      count += keep;
    });
    active.row_start[i + 1] = count;
  }
  sum_counts(active.row_start);
  const size_t m = active.row_start[n];
  // The entries: their candidates, partners and histories (zero where the old list had none),
  // each row written by the thread that counted it. The old selection's candidates are read
  // only through old_entry: their array is written anew here.
  std::vector<uint32_t> candidate_of = std::move(active_candidate_);
  size_to_overwrite(candidate_of, m);
  size_to_overwrite(active.partner, m);
  active.sliding_spring.resize(m);
  size_optional_histories(active, m, pieces);
  long farthest = 0;  // the farthest a partner lies after its row (index_columns)
#pragma omp parallel for schedule(static) reduction(max : farthest) if (n > parallel_rows)
  for (long i = 0; i < n; ++i) {
    uint32_t e = active.row_start[i];
    for (uint32_t c = candidate_row_start_[i]; c < candidate_row_start_[i + 1]; ++c) {
      if (kept[c] == Kept::no) continue;
      const uint32_t j = candidate_partner_[c];
      const uint32_t from = old_entry[c];
      candidate_of[e] = c;
      active.partner[e] = j;
      farthest = std::max(farthest, static_cast<long>(j) - i);
      active.sliding_spring[e] = from != no_old_entry ? old.sliding_spring[from] : Vec3{};
      if (from != no_old_entry) copy_optional_histories(old, from, active, e, pieces);
      ++e;
    }
  }
  kept = {};
  index_columns(active, n, farthest);
  active_candidate_ = std::move(candidate_of);
  position_at_refresh_.resize(p.size());
#pragma omp parallel for schedule(static) if (n > parallel_rows)
  for (long i = 0; i < n; ++i) position_at_refresh_[i] = p.position[i];
  ++refresh_count_;
}

void NeighborSearch::allocate_results(PairContacts& pairs, ContactPieces pieces) {
  const size_t m = pairs.size();
  // Sized without zeroing, then zeroed by every thread, each its own part (page faults
  // included): serially it had taken a third of a refresh (core/uninitialized_allocator.hpp).
  size_to_overwrite(pairs.result, m);
  const long entries = static_cast<long>(m);
#pragma omp parallel for schedule(static) if (entries > parallel_threshold)
  for (long e = 0; e < entries; ++e) pairs.result[e] = PairResult{};
  pairs.moment.assign(pieces.rolling || pieces.twisting ? m : 0, Vec3{});
}

void NeighborSearch::refresh(const ParticleStore& p, PairContacts& pairs, ContactPieces pieces) {
  // Each candidate's entry in the old list, row by row: the old entries of row i are those of
  // its candidates that were selected, in order.
  const long n = static_cast<long>(p.size());
  std::vector<uint32_t, UninitializedAllocator<uint32_t>> old_entry(candidate_partner_.size());
#pragma omp parallel for schedule(static) if (n > parallel_rows)
  for (long i = 0; i < n; ++i) {
    for (uint32_t c = candidate_row_start_[i]; c < candidate_row_start_[i + 1]; ++c)
      old_entry[c] = no_old_entry;
    for (uint32_t e = pairs.row_start[i]; e < pairs.row_start[i + 1]; ++e)
      old_entry[active_candidate_[e]] = e;
  }
  // Only the histories of the old list are read. Its other arrays are written anew in place
  // (the results zeroed), so that a refresh allocates nothing the list already holds and never
  // holds two whole lists.
  PairContacts old = histories_of(std::move(pairs));
  pairs.moment.clear();
  select_active(p, old, old_entry, pairs, pieces);
  old = PairContacts{}, old_entry = {};  // before the results are zeroed
  allocate_results(pairs, pieces);
  watch_for_rebuild();
}

std::string NeighborSearch::inconsistency(size_t particles, size_t active_entries) const {
  const std::vector<uint32_t>& rows = candidate_row_start_;
  if (rows.size() != particles + 1 || rows.front() != 0 || rows.back() != candidate_partner_.size())
    return "neighbour candidate rows do not match the particles";
  for (size_t i = 0; i < particles; ++i)
    if (rows[i] > rows[i + 1]) return "neighbour candidate rows are not ordered";
  for (uint32_t j : candidate_partner_)
    if (j >= particles) return "a neighbour candidate names a particle that does not exist";
  if (active_candidate_.size() != active_entries)
    return "the active pair list does not match its candidates";
  for (uint32_t c : active_candidate_)
    if (c >= candidate_partner_.size())
      return "an active pair names a candidate that does not exist";
  if (position_at_refresh_.size() != position_at_build_.size())
    return "the positions of the last list refresh do not match the particles";
  return "";
}

}  // namespace grainlab
