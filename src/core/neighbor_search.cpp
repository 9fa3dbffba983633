#include "core/neighbor_search.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

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

std::vector<uint32_t> NeighborSearch::bin_and_sort(ParticleStore& p) {
  const long n = static_cast<long>(p.size());
  double lo_x = 1e300, lo_y = 1e300, lo_z = 1e300, hi_x = -1e300, hi_y = -1e300, hi_z = -1e300;
  double max_radius = 0.0;
#pragma omp parallel for schedule(static) if (n > parallel_threshold) \
    reduction(min                                                     \
              : lo_x, lo_y, lo_z) reduction(max                       \
                                            : hi_x, hi_y, hi_z, max_radius)
  for (long i = 0; i < n; ++i) {
    const Vec3& x = p.position[i];
    lo_x = std::min(lo_x, x.x), lo_y = std::min(lo_y, x.y), lo_z = std::min(lo_z, x.z);
    hi_x = std::max(hi_x, x.x), hi_y = std::max(hi_y, x.y), hi_z = std::max(hi_z, x.z);
    max_radius = std::max(max_radius, p.radius[i]);
  }
  const Vec3 lo{lo_x, lo_y, lo_z}, hi{hi_x, hi_y, hi_z};
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
#pragma omp parallel for schedule(static) if (n > parallel_threshold)
  for (long i = 0; i < n; ++i) {
    int c[3];
    for (int d = 0; d < 3; ++d) {
      const double width = (hi[d] - lo[d]) / dims_[d];
      const int k = width > 0.0 ? static_cast<int>((p.position[i][d] - lo[d]) / width) : 0;
      c[d] = std::clamp(k, 0, dims_[d] - 1);
    }
    cell[i] = static_cast<uint32_t>((c[2] * dims_[1] + c[1]) * dims_[0] + c[0]);
  }
  // (a counting sort, in the particles' order: its count and fill serial, passes over N integers)
  cell_start_.assign(static_cast<size_t>(total) + 1, 0);
  for (long i = 0; i < n; ++i) ++cell_start_[cell[i] + 1];
  sum_counts(cell_start_);
  std::vector<uint32_t> order(n);
  std::vector<uint32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (long i = 0; i < n; ++i) order[fill[cell[i]]++] = static_cast<uint32_t>(i);
  p.permute(order);
  cell_of_.resize(n);
#pragma omp parallel for schedule(static) if (n > parallel_threshold)
  for (long k = 0; k < n; ++k) cell_of_[k] = cell[order[k]];
  return order;
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
  sum_counts(pairs.row_start);
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
  // Calls emit(w) for the walls within the skin of particle i, in the walls' order.
  const auto for_each_wall = [&](long i, auto&& emit) {
    for (size_t w = 0; w < walls.size(); ++w)
      if (wall_gap(walls[w], p.position[i]).gap < p.radius[i] + skin_)
        emit(static_cast<uint16_t>(w));
  };
  c.row_start.assign(static_cast<size_t>(n) + 1, 0);
#pragma omp parallel for schedule(static) if (n > parallel_threshold)
  for (long i = 0; i < n; ++i) {
    uint32_t count = 0;
    for_each_wall(i, [&](uint16_t) { ++count; });
    c.row_start[i + 1] = count;
  }
  sum_counts(c.row_start);
  c.wall.resize(c.row_start[n]);
#pragma omp parallel for schedule(static) if (n > parallel_threshold)
  for (long i = 0; i < n; ++i) {
    uint32_t k = c.row_start[i];
    for_each_wall(i, [&](uint16_t w) { c.wall[k++] = w; });
  }
}

namespace {

// Where each entry of a store that is about to be built anew lay before: a particle keeps its
// permanent id through a rebuild, but not its place (the sort moves it). The old stores are kept
// with their rows and partners (or walls) in the old places, and `order` (new place k held the
// particle of old place order[k]) leads from a new entry to the old row that held it, which is
// searched (a few entries). Only entries with a history are carried.

// The entry of the old store's row `row` that is_it(entry) picks, where it holds a history;
// NeighborSearch::no_old_entry otherwise.
template <class Store, class Match>
uint32_t old_entry_with_history(const Store& old, uint32_t row, Match is_it) {
  for (uint32_t e = old.row_start[row]; e < old.row_start[row + 1]; ++e)
    if (is_it(e)) return entry_has_history(old, e) ? e : NeighborSearch::no_old_entry;
  return NeighborSearch::no_old_entry;
}

// The old pair entry of the particles now at new places i and j (a half list holds a pair once,
// in the row of the lower place).
uint32_t old_pair_entry(const PairContacts& old, const std::vector<uint32_t>& order, uint32_t i,
                        uint32_t j) {
  const uint32_t a = std::min(order[i], order[j]), b = std::max(order[i], order[j]);
  return old_entry_with_history(old, a, [&](uint32_t e) { return old.partner[e] == b; });
}

// The old wall entry of the particle now at new place i with wall w.
uint32_t old_wall_entry(const WallContacts& old, const std::vector<uint32_t>& order, uint32_t i,
                        uint16_t w) {
  return old_entry_with_history(old, order[i], [&](uint32_t e) { return old.wall[e] == w; });
}

// The histories of `store` with the rows and partners (or walls) that say where its entries lie:
// what a rebuild reads of the old store.
template <class Store>
Store histories_with_places(Store&& store) {
  Store h = histories_of(std::move(store));
  h.row_start = std::move(store.row_start);
  if constexpr (std::is_same_v<Store, PairContacts>)
    h.partner = std::move(store.partner);
  else
    h.wall = std::move(store.wall);
  return h;
}

}  // namespace

void NeighborSearch::rebuild(ParticleStore& p, const std::vector<Wall>& walls, PairContacts& pairs,
                             WallContacts& wall_contacts, ContactPieces pieces) {
  const long n = static_cast<long>(p.size());
  // Only the histories of the old stores, with where their entries lie, are read from here on:
  // the rest of them is freed before the new stores are built, so that the rebuild does not hold
  // two whole contact stores (docs/performance.md sec. 13). Stores of another particle count
  // (none yet) carry nothing.
  const bool pairs_carried = pairs.row_start.size() == p.size() + 1;
  const bool walls_carried = wall_contacts.row_start.size() == p.size() + 1;
  PairContacts old_pairs = histories_with_places(std::move(pairs));
  WallContacts old_walls = histories_with_places(std::move(wall_contacts));
  pairs = PairContacts{};
  wall_contacts = WallContacts{};

  const std::vector<uint32_t> order = bin_and_sort(p);
  build_pairs(p, pairs);
  build_wall_candidates(p, walls, wall_contacts);

  // The candidates keep only their rows and partners. Each finds its old entry, if it had a
  // history; the active entries selected from them take those histories.
  candidate_row_start_ = std::move(pairs.row_start);
  candidate_partner_ = std::move(pairs.partner);
  pairs = PairContacts{};
  std::vector<uint32_t, UninitializedAllocator<uint32_t>> old_entry(candidate_partner_.size());
#pragma omp parallel for schedule(static) if (n > parallel_threshold)
  for (long i = 0; i < n; ++i)
    for (uint32_t c = candidate_row_start_[i]; c < candidate_row_start_[i + 1]; ++c)
      old_entry[c] = pairs_carried ? old_pair_entry(old_pairs, order, static_cast<uint32_t>(i),
                                                    candidate_partner_[c])
                                   : no_old_entry;
  select_active(p, old_pairs, old_entry, pairs, pieces);
  old_entry = {};
  // the walls' histories, each entry's from its old entry (zero where it had none)
  const size_t mw = wall_contacts.size();
  WallContacts& fresh = wall_contacts;
  fresh.sliding_spring.assign(mw, Vec3{});
  size_optional_histories(fresh, mw, pieces);
  if (walls_carried) {
#pragma omp parallel for schedule(static) if (n > parallel_threshold)
    for (long i = 0; i < n; ++i)
      for (uint32_t e = fresh.row_start[i]; e < fresh.row_start[i + 1]; ++e) {
        const uint32_t from =
            old_wall_entry(old_walls, order, static_cast<uint32_t>(i), fresh.wall[e]);
        if (from == no_old_entry) continue;
        fresh.sliding_spring[e] = old_walls.sliding_spring[from];
        copy_optional_histories(old_walls, from, fresh, e, pieces);
      }
  }
  // and the old histories before the results are allocated
  old_pairs = PairContacts{}, old_walls = WallContacts{};

  allocate_results(pairs, pieces);
  fresh.force_on_particle.assign(mw, Vec3{});
  fresh.torque_on_particle.assign(mw, Vec3{});
  fresh.normal_stiffness.assign(mw, 0.0);
  fresh.normal_force.assign(mw, 0.0);

  position_at_build_.resize(p.size());
#pragma omp parallel for schedule(static) if (n > parallel_threshold)
  for (long i = 0; i < n; ++i) position_at_build_[i] = p.position[i];
  wall_pose_at_build_.resize(walls.size());
  for (size_t w = 0; w < walls.size(); ++w) wall_pose_at_build_[w] = pose_of(walls[w]);
  watch_for_rebuild();
  ++rebuild_count_;
}

}  // namespace grainlab
