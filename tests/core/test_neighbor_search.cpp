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
