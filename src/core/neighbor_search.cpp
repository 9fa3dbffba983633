#include "core/neighbor_search.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace grainlab {

bool NeighborSearch::walls_and_count_allow(size_t particle_count,
                                           const std::vector<Wall>& walls) const {
  if (position_at_build_.size() != particle_count || wall_pose_at_build_.size() != walls.size())
    return false;
  for (size_t w = 0; w < walls.size(); ++w)
    if (surface_displacement(wall_pose_at_build_[w], walls[w]) > 0.5 * skin_) return false;
  return true;
}

bool NeighborSearch::needs_rebuild(const ParticleStore& p, const std::vector<Wall>& walls) const {
  if (!walls_and_count_allow(p.size(), walls)) return true;
  const long n = static_cast<long>(p.size());
  int moved = 0;
#pragma omp parallel for schedule(static) reduction(| : moved) if (n > parallel_threshold)
  for (long i = 0; i < n; ++i) moved |= moved_beyond_half_skin(i, p.position[i]) ? 1 : 0;
  return moved != 0;
}

void NeighborSearch::bin_and_sort(ParticleStore& p) {
  const size_t n = p.size();
  Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  double max_radius = 0.0;
  for (size_t i = 0; i < n; ++i) {
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], p.position[i][d]);
      hi[d] = std::max(hi[d], p.position[i][d]);
    }
    max_radius = std::max(max_radius, p.radius[i]);
  }
  // Cells at least one cut-off wide; a few far-flying particles must not blow up the grid,
  // so the number of cells is capped near 2 N (cells then grow).
  const double cutoff = 2.0 * max_radius + skin_;
  double size = cutoff;
  const double cap = std::max<double>(27.0, 2.0 * static_cast<double>(n));
  for (;;) {
    double cells = 1.0;
    for (int d = 0; d < 3; ++d) cells *= std::max(1.0, std::floor((hi[d] - lo[d]) / size));
    if (cells <= cap) break;
    size *= 1.25;
  }
  long total = 1;
  for (int d = 0; d < 3; ++d) {
    dims_[d] = static_cast<int>(std::max(1.0, std::floor((hi[d] - lo[d]) / size)));
    total *= dims_[d];
  }
  grid_origin_ = lo;
  cell_size_ = size;
  // Cells may be wider than `size` along an axis (extent / dims); the stencil stays +-1 cell
  // because the width never drops below the cut-off.
  std::vector<uint32_t> cell(n);
  for (size_t i = 0; i < n; ++i) {
    int c[3];
    for (int d = 0; d < 3; ++d) {
      const double width = (hi[d] - lo[d]) / dims_[d];
      const int k = width > 0.0 ? static_cast<int>((p.position[i][d] - lo[d]) / width) : 0;
      c[d] = std::clamp(k, 0, dims_[d] - 1);
    }
    cell[i] = static_cast<uint32_t>((c[2] * dims_[1] + c[1]) * dims_[0] + c[0]);
  }
  cell_start_.assign(static_cast<size_t>(total) + 1, 0);
  for (size_t i = 0; i < n; ++i) ++cell_start_[cell[i] + 1];
  std::partial_sum(cell_start_.begin(), cell_start_.end(), cell_start_.begin());
  std::vector<uint32_t> order(n);
  std::vector<uint32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (size_t i = 0; i < n; ++i) order[fill[cell[i]]++] = static_cast<uint32_t>(i);
  p.permute(order);
  cell_of_.resize(n);
  for (size_t k = 0; k < n; ++k) cell_of_[k] = cell[order[k]];
}

void NeighborSearch::build_pairs(const ParticleStore& p, PairContacts& pairs) const {
  const long n = static_cast<long>(p.size());
  const int nx = dims_[0], ny = dims_[1], nz = dims_[2];
  // Visits the partners j > i of particle i: its own cell (after i) and the neighbouring cells
  // with a higher index (all their particles come after i in the sorted order).
  auto for_each_partner = [&](long i, auto&& emit) {
    const uint32_t c = cell_of_[i];
    const int cx = static_cast<int>(c % nx), cy = static_cast<int>((c / nx) % ny),
              cz = static_cast<int>(c / (nx * ny));
    const Vec3 xi = p.position[i];
    const double ri = p.radius[i];
    const bool i_fixed = p.inverse_mass[i] == 0.0;
    for (int dz = -1; dz <= 1; ++dz) {
      const int z = cz + dz;
      if (z < 0 || z >= nz) continue;
      for (int dy = -1; dy <= 1; ++dy) {
        const int y = cy + dy;
        if (y < 0 || y >= ny) continue;
        for (int dx = -1; dx <= 1; ++dx) {
          const int x = cx + dx;
          if (x < 0 || x >= nx) continue;
          const uint32_t other = static_cast<uint32_t>((z * ny + y) * nx + x);
          if (other < c) continue;
          const uint32_t begin = other == c ? static_cast<uint32_t>(i + 1) : cell_start_[other];
          for (uint32_t j = begin; j < cell_start_[other + 1]; ++j) {
            if (i_fixed && p.inverse_mass[j] == 0.0) continue;  // two fixed bodies never interact
            const double reach = ri + p.radius[j] + skin_;
            if (norm2(p.position[j] - xi) < reach * reach) emit(j);
          }
        }
      }
    }
  };

  pairs.row_start.assign(static_cast<size_t>(n) + 1, 0);
#pragma omp parallel for schedule(static) if (n > parallel_threshold)
  for (long i = 0; i < n; ++i) {
    uint32_t count = 0;
    for_each_partner(i, [&](uint32_t) { ++count; });
    pairs.row_start[i + 1] = count;
  }
  std::partial_sum(pairs.row_start.begin(), pairs.row_start.end(), pairs.row_start.begin());
  pairs.partner.resize(pairs.row_start[n]);
#pragma omp parallel for schedule(static) if (n > parallel_threshold)
  for (long i = 0; i < n; ++i) {
    uint32_t k = pairs.row_start[i];
    for_each_partner(i, [&](uint32_t j) { pairs.partner[k++] = j; });
  }
}

void NeighborSearch::build_wall_candidates(const ParticleStore& p, const std::vector<Wall>& walls,
                                           WallContacts& c) const {
  const long n = static_cast<long>(p.size());
  c.row_start.assign(static_cast<size_t>(n) + 1, 0);
  for (long i = 0; i < n; ++i) {
    uint32_t count = 0;
    for (const Wall& w : walls) count += wall_gap(w, p.position[i]).gap < p.radius[i] + skin_;
    c.row_start[i + 1] = c.row_start[i] + count;
  }
  c.wall.resize(c.row_start[n]);
  for (long i = 0; i < n; ++i) {
    uint32_t k = c.row_start[i];
    for (size_t w = 0; w < walls.size(); ++w)
      if (wall_gap(walls[w], p.position[i]).gap < p.radius[i] + skin_)
        c.wall[k++] = static_cast<uint16_t>(w);
  }
}

namespace {

// Keys of the contacts that carry history, sorted, with their entry index in the old store.
struct KeyedEntry {
  uint64_t key;
  uint32_t entry;
  bool operator<(const KeyedEntry& o) const { return key < o.key; }
};

// Sizes the history arrays of `fresh` and copies each entry's history from `old` where the key
// of the entry was present before.
template <class Store, class KeyOfNew>
void carry_history(const Store& old, const std::vector<KeyedEntry>& old_keys, Store& fresh,
                   ContactPieces pieces, KeyOfNew key_of_new) {
  const size_t m = fresh.size();
  fresh.sliding_spring.assign(m, Vec3{});
  fresh.rolling_angle.assign(pieces.rolling ? m : 0, Vec3{});
  fresh.twisting_angle.assign(pieces.twisting ? m : 0, 0.0);
  fresh.rolling_force_displacement.assign(pieces.rolling_force ? m : 0, Vec3{});
  if (old_keys.empty()) return;
  const long count = static_cast<long>(m);
#pragma omp parallel for schedule(static)
  for (long e = 0; e < count; ++e) {
    const KeyedEntry probe{key_of_new(e), 0};
    auto it = std::lower_bound(old_keys.begin(), old_keys.end(), probe);
    if (it == old_keys.end() || it->key != probe.key) continue;
    fresh.sliding_spring[e] = old.sliding_spring[it->entry];
    if (pieces.rolling) fresh.rolling_angle[e] = old.rolling_angle[it->entry];
    if (pieces.twisting) fresh.twisting_angle[e] = old.twisting_angle[it->entry];
    if (pieces.rolling_force)
      fresh.rolling_force_displacement[e] = old.rolling_force_displacement[it->entry];
  }
}

// The keys of the entries of `s` (CSR rows per particle) that carry history, sorted; counted
// first so that the vector is allocated once, at its size.
template <class Store, class KeyOf>
std::vector<KeyedEntry> history_keys(const Store& s, size_t particles, KeyOf key_of) {
  std::vector<KeyedEntry> keys;
  if (s.row_start.size() != particles + 1) return keys;
  size_t count = 0;
  for (size_t e = 0; e < s.size(); ++e) count += entry_has_history(s, e);
  keys.reserve(count);
  for (size_t i = 0; i < particles; ++i)
    for (uint32_t e = s.row_start[i]; e < s.row_start[i + 1]; ++e)
      if (entry_has_history(s, e)) keys.push_back({key_of(i, e), e});
  std::sort(keys.begin(), keys.end());
  return keys;
}

uint64_t pair_key(uint32_t id_a, uint32_t id_b) {
  const uint32_t lo = std::min(id_a, id_b), hi = std::max(id_a, id_b);
  return (static_cast<uint64_t>(lo) << 32) | hi;
}

}  // namespace

void NeighborSearch::rebuild(ParticleStore& p, const std::vector<Wall>& walls, PairContacts& pairs,
                             WallContacts& wall_contacts, ContactPieces pieces) {
  // Remember the histories under permanent keys before indices change.
  std::vector<KeyedEntry> old_pair_keys = history_keys(pairs, p.size(), [&](size_t i, uint32_t e) {
    return pair_key(p.id[i], p.id[pairs.partner[e]]);
  });
  std::vector<KeyedEntry> old_wall_keys =
      history_keys(wall_contacts, p.size(), [&](size_t i, uint32_t e) {
        return (static_cast<uint64_t>(p.id[i]) << 16) | wall_contacts.wall[e];
      });
  // Only the histories of the old stores are read from here on: the rest of them is freed
  // before the new stores are built, so that the rebuild does not hold two whole contact stores
  // (docs/performance.md sec. 13).
  PairContacts old_pairs = histories_of(std::move(pairs));
  WallContacts old_walls = histories_of(std::move(wall_contacts));
  pairs = PairContacts{};
  wall_contacts = WallContacts{};

  bin_and_sort(p);
  build_pairs(p, pairs);
  build_wall_candidates(p, walls, wall_contacts);

  // The candidates keep only their rows and partners. Each finds its old entry, if it had a
  // history, by its pair of ids; the active entries selected from them take those histories.
  candidate_row_start_ = std::move(pairs.row_start);
  candidate_partner_ = std::move(pairs.partner);
  pairs = PairContacts{};
  std::vector<uint32_t> old_entry(candidate_partner_.size(), no_old_entry);
  if (!old_pair_keys.empty()) {
    const std::vector<uint32_t> first = row_of_each_entry(candidate_row_start_);
    const long count = static_cast<long>(old_entry.size());
#pragma omp parallel for schedule(static)
    for (long c = 0; c < count; ++c) {
      const KeyedEntry probe{pair_key(p.id[first[c]], p.id[candidate_partner_[c]]), 0};
      auto it = std::lower_bound(old_pair_keys.begin(), old_pair_keys.end(), probe);
      if (it != old_pair_keys.end() && it->key == probe.key) old_entry[c] = it->entry;
    }
  }
  select_active(p, old_pairs, old_entry, pairs, pieces);
  old_entry = {};
  {
    const std::vector<uint32_t> owner = row_of_each_entry(wall_contacts.row_start);
    carry_history(old_walls, old_wall_keys, wall_contacts, pieces, [&](long e) {
      return (static_cast<uint64_t>(p.id[owner[e]]) << 16) | wall_contacts.wall[e];
    });
  }
  // and the old histories and keys before the results are allocated
  old_pairs = PairContacts{}, old_walls = WallContacts{};
  old_pair_keys = {}, old_wall_keys = {};

  allocate_results(pairs, pieces);
  const size_t mw = wall_contacts.size();
  wall_contacts.force_on_particle.assign(mw, Vec3{});
  wall_contacts.torque_on_particle.assign(mw, Vec3{});
  wall_contacts.normal_stiffness.assign(mw, 0.0);
  wall_contacts.normal_force.assign(mw, 0.0);

  position_at_build_ = p.position;
  wall_pose_at_build_.resize(walls.size());
  for (size_t w = 0; w < walls.size(); ++w) wall_pose_at_build_[w] = pose_of(walls[w]);
  watch_for_rebuild();
  ++rebuild_count_;
}

}  // namespace grainlab
