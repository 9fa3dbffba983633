// Neighbour search: linked cells feeding a half Verlet list with a skin, and the active list the
// force loop runs over, a subset of it with a thinner skin.
//
// At each rebuild the particles are binned into cells at least (2 r_max + skin) wide and
// re-sorted in cell order (counting sort), so neighbours in space are neighbours in memory and
// every cell's particles are contiguous. Because of that order, "partner index > i" needs only
// the particle's own cell and the cells after it; a pair becomes a candidate when the gap between
// the spheres is below the skin. Walls get a candidate list the same way. Contact histories are
// carried across a rebuild through the sort's order: each new entry looks for its pair (or wall)
// in the old row of its particle's old place.
// The candidates stay valid while no particle and no point of a wall's surface has moved more
// than skin/2 (a wall that grows or turns counts by its farthest point: geometry/wall.hpp).
//
// The active list (the PairContacts the force loop, the gather and the measurements read) holds
// the candidates whose gap is below the thinner list skin, in the candidates' order, and is
// selected again ("refreshed") whenever a particle has moved more than list_skin/2 since the
// last selection: until then no other candidate can touch. A refresh moves no particle and keeps
// the order of the entries, so the forces are summed in the same order as over all candidates:
// the entries left out are apart, and their zero forces change no sum. Results are therefore bit
// for bit those of the full list, with about a third fewer entries to test and sum in a dense
// packing (docs/performance.md sec. 23). Rebuilds come when they did (the skin decides them).
// The selection lives in core/active_pair_list.cpp.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "contact/pair_table.hpp"
#include "core/contact_store.hpp"
#include "core/particles.hpp"
#include "geometry/wall.hpp"

namespace grainlab {

// The one rule for the Verlet skin: a tenth of the particle diameter (the largest diameter of
// a scene, the nominal bead diameter of a specimen). Rebuilds then come every few hundred steps
// in a quasi-static test, and the list holds ~1.5x the touching pairs.
inline double verlet_skin(double diameter) {
  return 0.1 * diameter;
}

// The active list's skin as a fraction of the Verlet skin (docs/performance.md sec. 23): thin
// enough that the list holds little more than the touching pairs, thick enough that refreshes
// stay rare next to the steps.
constexpr double default_list_skin_fraction = 0.05;

// The optional histories of a pair or wall store (rolling, twisting, rolling force): sized to m
// entries, zero, where the pieces in use need them, and empty otherwise.
template <class Store>
void size_optional_histories(Store& s, size_t m, ContactPieces pieces) {
  s.rolling_angle.assign(pieces.rolling ? m : 0, Vec3{});
  s.twisting_angle.assign(pieces.twisting ? m : 0, 0.0);
  s.rolling_force_displacement.assign(pieces.rolling_force ? m : 0, Vec3{});
}

// Entry `from` of `old`'s optional histories, for the pieces in use, into entry `to` of `fresh`.
template <class Store>
void copy_optional_histories(const Store& old, uint32_t from, Store& fresh, size_t to,
                             ContactPieces pieces) {
  if (pieces.rolling) fresh.rolling_angle[to] = old.rolling_angle[from];
  if (pieces.twisting) fresh.twisting_angle[to] = old.twisting_angle[from];
  if (pieces.rolling_force)
    fresh.rolling_force_displacement[to] = old.rolling_force_displacement[from];
}

class NeighborSearch {
 public:
  // list_skin: the active list's skin (<= skin); equal to skin, the active list is every
  // candidate.
  explicit NeighborSearch(double skin) : NeighborSearch(skin, skin) {}
  NeighborSearch(double skin, double list_skin) : skin_(skin), list_skin_(list_skin) {}

  bool needs_rebuild(const ParticleStore& particles, const std::vector<Wall>& walls) const;
  // The parts of needs_rebuild, for a caller that checks the particles inside its own loop
  // (Simulation::kick_and_drift): whether the list was built for these particles and walls and
  // no wall has moved a half skin; whether it was built for this many particles; then whether
  // particle i at x has moved more than a half skin.
  bool walls_and_count_allow(size_t particle_count, const std::vector<Wall>& walls) const;
  bool built_for(size_t particle_count) const {
    return position_at_build_.size() == particle_count;
  }
  bool moved_beyond_half_skin(size_t i, const Vec3& x) const {
    return norm2(x - position_at_build_[i]) > half_skin2();
  }
  double half_skin2() const { return 0.25 * skin_ * skin_; }
  // Whether particle i at x has moved more than half the list skin since the active list was
  // selected (then refresh it).
  bool moved_beyond_half_list_skin(size_t i, const Vec3& x) const {
    return list_displacement2(i, x) > half_list_skin2();
  }
  // The parts of that test: the square of particle i's displacement since the selection (m^2),
  // and the square of half the list skin.
  double list_displacement2(size_t i, const Vec3& x) const {
    return norm2(x - position_at_refresh_[i]);
  }
  double half_list_skin2() const { return 0.25 * list_skin_ * list_skin_; }
  // The positions those tests measure from (per particle; where built_for the particles):
  // at the last build and at the last selection.
  const std::vector<Vec3>& position_at_build() const { return position_at_build_; }
  const std::vector<Vec3>& position_at_refresh() const { return position_at_refresh_; }
  // Whether a step must test moved_beyond_half_skin at all: false while every particle, at the
  // last selection, was so close to where the list was built that moving another half list skin
  // cannot take it beyond half the skin. Then only a step that refreshes needs the test
  // (needs_rebuild), and the drift reads one array of positions, not two.
  bool rebuild_possible_before_refresh() const { return rebuild_possible_before_refresh_; }

  // Bins, sorts and finds the candidates, then selects the active list (`pairs`) from them.
  void rebuild(ParticleStore& particles, const std::vector<Wall>& walls, PairContacts& pairs,
               WallContacts& wall_contacts, ContactPieces pieces);
  // Selects the active list again from the same candidates; the histories of the entries kept
  // are kept. The particles' order does not change.
  void refresh(const ParticleStore& particles, PairContacts& pairs, ContactPieces pieces);

  double skin() const { return skin_; }
  double list_skin() const { return list_skin_; }
  // The candidates, CSR rows per particle, partner index above the particle's (tests).
  const std::vector<uint32_t>& candidate_row_start() const { return candidate_row_start_; }
  const std::vector<uint32_t>& candidate_partner() const { return candidate_partner_; }
  // What decides the next rebuild and refresh (the cell grid is made anew at every rebuild),
  // and the candidates with the active entries' place among them.
  template <class Io>
  void for_each_field(Io&& io) {
    io(position_at_build_), io(wall_pose_at_build_), io(candidate_row_start_),
        io(candidate_partner_), io(active_candidate_), io(position_at_refresh_);
    watch_for_rebuild();  // derived from the two sets of positions (after a restore too)
  }
  // "" when the saved fields fit particles and an active list of active_entries entries, else
  // what does not (a damaged or foreign checkpoint).
  std::string inconsistency(size_t particles, size_t active_entries) const;
  long& rebuild_count_ref() { return rebuild_count_; }
  long rebuild_count() const { return rebuild_count_; }
  long& refresh_count_ref() { return refresh_count_; }
  long refresh_count() const { return refresh_count_; }

  // An entry of an old store that none takes over (no history to carry).
  static constexpr uint32_t no_old_entry = UINT32_MAX;

 private:
  // Sorts the particles into cell order; returns the order (new place k holds the particle of
  // old place order[k]).
  std::vector<uint32_t> bin_and_sort(ParticleStore& particles);
  void build_pairs(const ParticleStore& particles, PairContacts& pairs) const;
  void build_wall_candidates(const ParticleStore& particles, const std::vector<Wall>& walls,
                             WallContacts& contacts) const;
  // The active list from the candidates now (rows, partners, transpose, histories; the results
  // are allocate_results'): those within the list skin, and any that holds a history.
  // old_entry[c]: candidate c's entry in `old`, which holds histories, or no_old_entry.
  void select_active(const ParticleStore& particles, const PairContacts& old,
                     std::span<const uint32_t> old_entry, PairContacts& active,
                     ContactPieces pieces);
  static void allocate_results(PairContacts& pairs, ContactPieces pieces);

  // rebuild_possible_before_refresh_ from the positions of the last build and selection
  void watch_for_rebuild();

  double skin_;
  double list_skin_;
  bool rebuild_possible_before_refresh_ = true;
  long refresh_count_ = 0;  // selections of the active list (one per rebuild, and the refreshes)
  long rebuild_count_ = 0;
  // cell grid of the last rebuild
  Vec3 grid_origin_;
  double cell_size_ = 0.0;
  int dims_[3] = {1, 1, 1};
  std::vector<uint32_t> cell_start_;  // cells + 1
  std::vector<uint32_t> cell_of_;     // per particle (sorted order)
  std::vector<Vec3> position_at_build_;
  std::vector<WallPose> wall_pose_at_build_;
  std::vector<uint32_t> candidate_row_start_, candidate_partner_;  // CSR, N + 1 and per candidate
  std::vector<uint32_t> active_candidate_;  // per active entry: its candidate entry
  std::vector<Vec3> position_at_refresh_;
};

}  // namespace grainlab
