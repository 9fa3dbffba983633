// The active pair list (core/neighbor_search.hpp): the candidates within the list skin, selected
// at each rebuild and refreshed between rebuilds, with the entries' histories carried by
// candidate; and the watch that tells the drift whether it must test for a rebuild.
#include <algorithm>
#include <numeric>

#include "core/neighbor_search.hpp"

namespace grainlab {
namespace {

// The transpose of a pair list (col_start, col_pair), in increasing entry order (fixed,
// thread-independent).
void index_columns(PairContacts& pairs, size_t particles) {
  pairs.col_start.assign(particles + 1, 0);
  for (uint32_t j : pairs.partner) ++pairs.col_start[j + 1];
  std::partial_sum(pairs.col_start.begin(), pairs.col_start.end(), pairs.col_start.begin());
  pairs.col_pair.resize(pairs.partner.size());
  std::vector<uint32_t> fill(pairs.col_start.begin(), pairs.col_start.end() - 1);
  for (uint32_t e = 0; e < pairs.partner.size(); ++e) pairs.col_pair[fill[pairs.partner[e]]++] = e;
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
                                   const std::vector<uint32_t>& old_entry, PairContacts& active,
                                   ContactPieces pieces) {
  const long n = static_cast<long>(p.size());
  // Calls emit(candidate, old entry or -1) for the candidates of row i that are kept, in order:
  // within the list skin now, or holding a history (a contact that has just come apart: its
  // entry forgets the history at the next force evaluation, as it would in the full list).
  auto for_each_kept = [&](long i, auto&& emit) {
    const Vec3 xi = p.position[i];
    const double ri = p.radius[i];
    for (uint32_t c = candidate_row_start_[i]; c < candidate_row_start_[i + 1]; ++c) {
      const long from = old_entry[c] == no_old_entry ? -1 : static_cast<long>(old_entry[c]);
      const uint32_t j = candidate_partner_[c];
      const double reach = ri + p.radius[j] + list_skin_;
      if (norm2(p.position[j] - xi) < reach * reach || (from >= 0 && entry_has_history(old, from)))
        emit(c, from);
    }
  };
  active.row_start.assign(static_cast<size_t>(n) + 1, 0);
#pragma omp parallel for schedule(static) if (n > parallel_threshold)
  for (long i = 0; i < n; ++i) {
    uint32_t count = 0;
    for_each_kept(i, [&](uint32_t, long) { ++count; });
    active.row_start[i + 1] = count;
  }
  std::partial_sum(active.row_start.begin(), active.row_start.end(), active.row_start.begin());
  const size_t m = active.row_start[n];
  std::vector<uint32_t> candidate_of(m);
  active.partner.resize(m);
  active.sliding_spring.assign(m, Vec3{});
  active.rolling_angle.assign(pieces.rolling ? m : 0, Vec3{});
  active.twisting_angle.assign(pieces.twisting ? m : 0, 0.0);
  active.rolling_force_displacement.assign(pieces.rolling_force ? m : 0, Vec3{});
#pragma omp parallel for schedule(static) if (n > parallel_threshold)
  for (long i = 0; i < n; ++i) {
    uint32_t e = active.row_start[i];
    for_each_kept(i, [&](uint32_t c, long from) {
      candidate_of[e] = c;
      active.partner[e] = candidate_partner_[c];
      if (from >= 0) {
        active.sliding_spring[e] = old.sliding_spring[from];
        if (pieces.rolling) active.rolling_angle[e] = old.rolling_angle[from];
        if (pieces.twisting) active.twisting_angle[e] = old.twisting_angle[from];
        if (pieces.rolling_force)
          active.rolling_force_displacement[e] = old.rolling_force_displacement[from];
      }
      ++e;
    });
  }
  index_columns(active, static_cast<size_t>(n));
  active_candidate_ = std::move(candidate_of);
  position_at_refresh_ = p.position;
  ++refresh_count_;
}

void NeighborSearch::allocate_results(PairContacts& pairs, ContactPieces pieces) {
  const size_t m = pairs.size();
  // Sized without zeroing, then zeroed by every thread, each its own part (page faults
  // included): serially it had taken a third of a refresh (core/uninitialized_allocator.hpp).
  pairs.result.clear();
  pairs.result.resize(m);
  const long entries = static_cast<long>(m);
#pragma omp parallel for schedule(static) if (entries > parallel_threshold)
  for (long e = 0; e < entries; ++e) pairs.result[e] = PairResult{};
  pairs.moment.assign(pieces.rolling || pieces.twisting ? m : 0, Vec3{});
}

void NeighborSearch::refresh(const ParticleStore& p, PairContacts& pairs, ContactPieces pieces) {
  // Only the histories of the old list are read: the rest is freed before the new list is
  // built, so that a refresh does not hold two whole lists.
  std::vector<uint32_t> old_entry(candidate_partner_.size(), no_old_entry);
  for (size_t k = 0; k < active_candidate_.size(); ++k)
    old_entry[active_candidate_[k]] = static_cast<uint32_t>(k);
  const PairContacts old = histories_of(std::move(pairs));
  pairs = PairContacts{};
  select_active(p, old, old_entry, pairs, pieces);
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
