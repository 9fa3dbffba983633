// Neighbour search: linked cells feeding a half Verlet list with a skin.
//
// At each rebuild the particles are binned into cells at least (2 r_max + skin) wide and
// re-sorted in cell order (counting sort), so neighbours in space are neighbours in memory and
// every cell's particles are contiguous. Because of that order, "partner index > i" needs only
// the particle's own cell and the cells after it; a pair enters the list when the gap between
// the spheres is below the skin. Walls get a candidate list the same way. Contact histories are
// carried across a rebuild by a sort-merge on the permanent particle ids.
// The list stays valid while no particle and no point of a wall's surface has moved more than
// skin/2 (a wall that grows or turns counts by its farthest point: geometry/wall.hpp).
#pragma once

#include <cstdint>
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

class NeighborSearch {
 public:
  explicit NeighborSearch(double skin) : skin_(skin) {}

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
    return norm2(x - position_at_build_[i]) > 0.25 * skin_ * skin_;
  }

  void rebuild(ParticleStore& particles, const std::vector<Wall>& walls, PairContacts& pairs,
               WallContacts& wall_contacts, ContactPieces pieces);

  double skin() const { return skin_; }
  // What decides the next rebuild (the cell grid is made anew at every rebuild).
  template <class Io>
  void for_each_field(Io&& io) {
    io(position_at_build_), io(wall_pose_at_build_);
  }
  long& rebuild_count_ref() { return rebuild_count_; }
  long rebuild_count() const { return rebuild_count_; }

 private:
  void bin_and_sort(ParticleStore& particles);
  void build_pairs(const ParticleStore& particles, PairContacts& pairs) const;
  void build_wall_candidates(const ParticleStore& particles, const std::vector<Wall>& walls,
                             WallContacts& contacts) const;

  double skin_;
  long rebuild_count_ = 0;
  // cell grid of the last rebuild
  Vec3 grid_origin_;
  double cell_size_ = 0.0;
  int dims_[3] = {1, 1, 1};
  std::vector<uint32_t> cell_start_;  // cells + 1
  std::vector<uint32_t> cell_of_;     // per particle (sorted order)
  std::vector<Vec3> position_at_build_;
  std::vector<WallPose> wall_pose_at_build_;
};

}  // namespace grainlab
