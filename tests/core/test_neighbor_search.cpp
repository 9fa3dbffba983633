// Neighbour search: the half Verlet list holds exactly the pairs within reach (checked against
// brute force), the particles come out sorted by cell, and contact history survives a rebuild.
#include <gtest/gtest.h>

#include <random>
#include <set>

#include "core/neighbor_search.hpp"
#include "core/random_insertion.hpp"
#include "support/scenes.hpp"

using namespace grainlab;
using namespace grainlab::test;

namespace {
ParticleStore random_particles(long count, uint64_t seed) {
  std::vector<Sphere> spheres;
  std::mt19937_64 rng(seed);
  InsertionRegion box;
  box.box_min = {0, 0, 0};
  box.box_max = {0.02, 0.02, 0.03};
  EXPECT_EQ(insert_random_spheres(spheres, box, count, 1.6e-3, 2.4e-3, rng), count);
  ParticleStore p;
  for (size_t i = 0; i < spheres.size(); ++i)
    p.add(static_cast<uint32_t>(i), 0, spheres[i].radius, glass_density, spheres[i].centre, {}, {},
          false);
  return p;
}
}  // namespace

TEST(NeighborSearch, HalfListEqualsBruteForce) {
  ParticleStore p = random_particles(600, 3);
  const double skin = 0.3e-3;
  NeighborSearch search(skin);
  PairContacts pairs;
  WallContacts walls;
  search.rebuild(p, {}, pairs, walls, {});
  std::set<std::pair<uint32_t, uint32_t>> listed, expected;
  for (size_t i = 0; i < p.size(); ++i)
    for (uint32_t e = pairs.row_start[i]; e < pairs.row_start[i + 1]; ++e) {
      ASSERT_GT(pairs.partner[e], i) << "half list: partner index above the particle";
      listed.insert(
          {std::min(p.id[i], p.id[pairs.partner[e]]), std::max(p.id[i], p.id[pairs.partner[e]])});
    }
  for (size_t i = 0; i < p.size(); ++i)
    for (size_t j = i + 1; j < p.size(); ++j) {
      const double reach = p.radius[i] + p.radius[j] + skin;
      if (norm2(p.position[i] - p.position[j]) < reach * reach)
        expected.insert({std::min(p.id[i], p.id[j]), std::max(p.id[i], p.id[j])});
    }
  EXPECT_EQ(listed.size(), pairs.size()) << "no duplicates";
  EXPECT_EQ(listed, expected);
  EXPECT_GT(expected.size(), 300u);
  // transpose lists every entry once, under its second particle
  size_t transposed = 0;
  for (size_t j = 0; j < p.size(); ++j)
    for (uint32_t k = pairs.col_start[j]; k < pairs.col_start[j + 1]; ++k, ++transposed)
      EXPECT_EQ(pairs.partner[pairs.col_pair[k]], j);
  EXPECT_EQ(transposed, pairs.size());
}

TEST(NeighborSearch, HistorySurvivesRebuildAndResort) {
  ParticleStore p = random_particles(300, 5);
  NeighborSearch search(0.3e-3);
  PairContacts pairs;
  WallContacts walls;
  search.rebuild(p, {}, pairs, walls, {});
  // Tag every entry's history with its pair of ids, then shuffle the store and rebuild.
  auto tag = [](uint32_t a, uint32_t b) {
    return Vec3{double(std::min(a, b)), double(std::max(a, b)), 1.0};
  };
  for (size_t i = 0; i < p.size(); ++i)
    for (uint32_t e = pairs.row_start[i]; e < pairs.row_start[i + 1]; ++e)
      pairs.sliding_spring[e] = tag(p.id[i], p.id[pairs.partner[e]]);
  std::vector<uint32_t> reversed(p.size());
  for (size_t k = 0; k < p.size(); ++k) reversed[k] = static_cast<uint32_t>(p.size() - 1 - k);
  p.permute(reversed);
  pairs.row_start.clear();  // the old list no longer matches the permuted store...
  search.rebuild(p, {}, pairs, walls, {});
  size_t carried = 0;
  for (size_t i = 0; i < p.size(); ++i)
    for (uint32_t e = pairs.row_start[i]; e < pairs.row_start[i + 1]; ++e)
      carried += pairs.sliding_spring[e] == tag(p.id[i], p.id[pairs.partner[e]]);
  EXPECT_EQ(carried, 0u) << "...so without a valid old list nothing may be carried";

  for (size_t i = 0; i < p.size(); ++i)
    for (uint32_t e = pairs.row_start[i]; e < pairs.row_start[i + 1]; ++e)
      pairs.sliding_spring[e] = tag(p.id[i], p.id[pairs.partner[e]]);
  for (Vec3& x : p.position) x += Vec3{1e-5, -2e-5, 3e-5};  // small move, then rebuild + resort
  search.rebuild(p, {}, pairs, walls, {});
  carried = 0;
  for (size_t i = 0; i < p.size(); ++i)
    for (uint32_t e = pairs.row_start[i]; e < pairs.row_start[i + 1]; ++e)
      carried += pairs.sliding_spring[e] == tag(p.id[i], p.id[pairs.partner[e]]);
  EXPECT_EQ(carried, pairs.size());
}

TEST(NeighborSearch, RebuildTriggeredByHalfSkinMotion) {
  ParticleStore p = random_particles(50, 9);
  const double skin = 0.2e-3;
  NeighborSearch search(skin);
  PairContacts pairs;
  WallContacts walls;
  search.rebuild(p, {}, pairs, walls, {});
  EXPECT_FALSE(search.needs_rebuild(p, {}));
  p.position[7].x += 0.49 * skin;
  EXPECT_FALSE(search.needs_rebuild(p, {}));
  p.position[7].x += 0.02 * skin;
  EXPECT_TRUE(search.needs_rebuild(p, {}));
}

namespace {
// The pairs of `ids` (ordered by id) within `skin` of touching, by brute force.
std::set<std::pair<uint32_t, uint32_t>> pairs_within(const ParticleStore& p, double skin) {
  std::set<std::pair<uint32_t, uint32_t>> out;
  for (size_t i = 0; i < p.size(); ++i)
    for (size_t j = i + 1; j < p.size(); ++j) {
      const double reach = p.radius[i] + p.radius[j] + skin;
      if (norm2(p.position[i] - p.position[j]) < reach * reach)
        out.insert({std::min(p.id[i], p.id[j]), std::max(p.id[i], p.id[j])});
    }
  return out;
}
std::set<std::pair<uint32_t, uint32_t>> listed_pairs(const ParticleStore& p,
                                                     const std::vector<uint32_t>& row_start,
                                                     const std::vector<uint32_t>& partner) {
  std::set<std::pair<uint32_t, uint32_t>> out;
  for (size_t i = 0; i < p.size(); ++i)
    for (uint32_t e = row_start[i]; e < row_start[i + 1]; ++e)
      out.insert({std::min(p.id[i], p.id[partner[e]]), std::max(p.id[i], p.id[partner[e]])});
  return out;
}
// Whether each row of `active` lists its partners in the order of the same row of candidates
// (a subsequence), so that the force sums keep their order.
bool rows_are_ordered_subsets(const NeighborSearch& s, const PairContacts& active, size_t n) {
  for (size_t i = 0; i < n; ++i) {
    uint32_t c = s.candidate_row_start()[i];
    for (uint32_t e = active.row_start[i]; e < active.row_start[i + 1]; ++e) {
      while (c < s.candidate_row_start()[i + 1] && s.candidate_partner()[c] != active.partner[e])
        ++c;
      if (c == s.candidate_row_start()[i + 1]) return false;
      ++c;
    }
  }
  return true;
}
// A search with the given skins, rebuilt once on p (no walls), and its active list.
struct BuiltSearch {
  NeighborSearch search;
  PairContacts active;
  WallContacts walls;
  BuiltSearch(ParticleStore& p, double skin, double list_skin) : search(skin, list_skin) {
    search.rebuild(p, {}, active, walls, {});
  }
};
}  // namespace

TEST(NeighborSearch, ActiveListHoldsThePairsWithinTheListSkin) {
  ParticleStore p = random_particles(600, 3);
  const double skin = 0.3e-3, list_skin = 0.1e-3;
  BuiltSearch built(p, skin, list_skin);
  NeighborSearch& search = built.search;
  PairContacts& active = built.active;
  const auto candidates = pairs_within(p, skin), within = pairs_within(p, list_skin);
  EXPECT_EQ(listed_pairs(p, search.candidate_row_start(), search.candidate_partner()), candidates);
  EXPECT_EQ(listed_pairs(p, active.row_start, active.partner), within);
  EXPECT_EQ(active.size(), within.size()) << "no duplicates";
  EXPECT_LT(within.size(), candidates.size()) << "the thinner skin must leave pairs out";
  EXPECT_GT(within.size(), 100u);
  EXPECT_TRUE(rows_are_ordered_subsets(search, active, p.size()));
  size_t transposed = 0;
  for (size_t j = 0; j < p.size(); ++j)
    for (uint32_t k = active.col_start[j]; k < active.col_start[j + 1]; ++k, ++transposed)
      EXPECT_EQ(active.partner[active.col_pair[k]], j);
  EXPECT_EQ(transposed, active.size());
  EXPECT_EQ(active.result.size(), active.size());
  EXPECT_EQ(search.inconsistency(p.size(), active.size()), "");
  EXPECT_NE(search.inconsistency(p.size(), active.size() + 1), "");
}

TEST(NeighborSearch, RefreshFollowsMotionAndKeepsHistories) {
  ParticleStore p = random_particles(600, 4);
  const double skin = 0.3e-3, list_skin = 0.05e-3;
  BuiltSearch built(p, skin, list_skin);
  NeighborSearch& search = built.search;
  PairContacts& active = built.active;
  // A history on every second entry, tagged with its pair of ids.
  auto tag = [](uint32_t a, uint32_t b) {
    return Vec3{double(std::min(a, b)), double(std::max(a, b)), 1.0};
  };
  std::set<std::pair<uint32_t, uint32_t>> tagged;
  for (size_t i = 0; i < p.size(); ++i)
    for (uint32_t e = active.row_start[i]; e < active.row_start[i + 1]; e += 2) {
      const uint32_t a = p.id[i], b = p.id[active.partner[e]];
      active.sliding_spring[e] = tag(a, b);
      tagged.insert({std::min(a, b), std::max(a, b)});
    }
  // Move every bead by up to just under half the skin (the candidates stay valid), in random
  // directions, and select again.
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (Vec3& x : p.position) {
    const Vec3 d{u(rng), u(rng), u(rng)};
    x += (0.49 * skin / std::sqrt(3.0)) * d;
  }
  EXPECT_FALSE(search.needs_rebuild(p, {}));
  // Results of a last force computation everywhere: the new list's results start at zero
  // (allocated without zeroing and zeroed by the threads, core/uninitialized_allocator.hpp)
  for (PairResult& r : active.result) r = {{1, 2, 3}, {4, 5, 6}, 7, 8};
  const long before = search.refresh_count();
  search.refresh(p, active, {});
  EXPECT_EQ(search.refresh_count(), before + 1);
  EXPECT_TRUE(rows_are_ordered_subsets(search, active, p.size()));
  ASSERT_EQ(active.result.size(), active.size());
  for (const PairResult& r : active.result)
    ASSERT_TRUE(r.force_on_first == Vec3{} && r.torque_arm == Vec3{} && r.overlap == 0.0 &&
                r.normal_force == 0.0);
  // Every pair now within the list skin is active; so is every tagged pair, with its tag, even
  // where the motion took it beyond the list skin; every other entry starts without a history.
  const auto within = pairs_within(p, list_skin),
             listed = listed_pairs(p, active.row_start, active.partner);
  for (const auto& pair : within) EXPECT_TRUE(listed.count(pair));
  size_t tags_kept = 0, tagged_beyond = 0;
  for (size_t i = 0; i < p.size(); ++i)
    for (uint32_t e = active.row_start[i]; e < active.row_start[i + 1]; ++e) {
      const uint32_t a = p.id[i], b = p.id[active.partner[e]];
      const std::pair<uint32_t, uint32_t> pair{std::min(a, b), std::max(a, b)};
      if (tagged.count(pair)) {
        EXPECT_EQ(active.sliding_spring[e], tag(a, b));
        ++tags_kept;
        tagged_beyond += !within.count(pair);
      } else {
        EXPECT_TRUE(within.count(pair)) << "only pairs within the list skin or with a history";
        EXPECT_EQ(active.sliding_spring[e], Vec3{});
      }
    }
  EXPECT_EQ(tags_kept, tagged.size());
  EXPECT_GT(tagged_beyond, 0u) << "the motion must carry some tagged pair beyond the list skin";
  EXPECT_GT(listed.size() - tags_kept, 0u);
  EXPECT_EQ(search.inconsistency(p.size(), active.size()), "");
}

TEST(NeighborSearch, RefreshTriggeredByHalfListSkinMotion) {
  ParticleStore p = random_particles(50, 9);
  const double skin = 0.2e-3, list_skin = 0.02e-3;
  BuiltSearch built(p, skin, list_skin);
  NeighborSearch& search = built.search;
  PairContacts& pairs = built.active;
  EXPECT_FALSE(search.moved_beyond_half_list_skin(7, p.position[7]));
  p.position[7].x += 0.49 * list_skin;
  EXPECT_FALSE(search.moved_beyond_half_list_skin(7, p.position[7]));
  p.position[7].x += 0.02 * list_skin;
  EXPECT_TRUE(search.moved_beyond_half_list_skin(7, p.position[7]));
  search.refresh(p, pairs, {});
  EXPECT_FALSE(search.moved_beyond_half_list_skin(7, p.position[7])) << "measured from the refresh";
  EXPECT_FALSE(search.needs_rebuild(p, {})) << "the rebuild still counts from the rebuild";
}
