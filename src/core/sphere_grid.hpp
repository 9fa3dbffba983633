// A sparse cell hash over spheres, cells at least one largest diameter wide: every sphere that
// can touch a given one lies in its cell or the 26 around it. Used where spheres are placed or
// checked one by one before a simulation exists (random insertion, the overlap check of a
// packing read from a file), so such checks cost O(N) instead of O(N^2) for packings of
// similar sizes (a few spheres far larger than the rest make the cells coarse).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "core/vec3.hpp"

namespace grainlab {

struct Sphere {
  Vec3 centre;
  double radius;
};

class SphereGrid {
 public:
  explicit SphereGrid(double cell) : cell_(cell) {}
  void add(const Sphere& s, uint32_t index) { cells_[key(s.centre)].push_back(index); }

  // Calls visit(j) for every sphere added so far whose cell neighbours that of `s` (a superset
  // of the spheres that can touch it), until visit returns true; returns whether it did.
  template <class Visit>
  bool find_near(const Sphere& s, Visit&& visit) const {
    const long cx = coord(s.centre.x), cy = coord(s.centre.y), cz = coord(s.centre.z);
    for (long dz = -1; dz <= 1; ++dz)
      for (long dy = -1; dy <= 1; ++dy)
        for (long dx = -1; dx <= 1; ++dx) {
          auto it = cells_.find(pack(cx + dx, cy + dy, cz + dz));
          if (it == cells_.end()) continue;
          for (uint32_t j : it->second)
            if (visit(j)) return true;
        }
    return false;
  }

  bool overlaps(const std::vector<Sphere>& all, const Sphere& s) const {
    return find_near(s, [&](uint32_t j) {
      const double reach = s.radius + all[j].radius;
      return norm2(all[j].centre - s.centre) < reach * reach;
    });
  }

 private:
  // Cell index along one axis, clamped so that absurd coordinates stay defined behaviour.
  long coord(double x) const {
    const double c = std::floor(x / cell_);
    return static_cast<long>(std::clamp(c, -0x1p60, 0x1p60));
  }
  // 21 bits per axis: cells more than 2^21 apart share a key, which only adds candidates.
  static uint64_t pack(long x, long y, long z) {
    return (static_cast<uint64_t>(x & 0x1FFFFF) << 42) |
           (static_cast<uint64_t>(y & 0x1FFFFF) << 21) | static_cast<uint64_t>(z & 0x1FFFFF);
  }
  uint64_t key(const Vec3& c) const { return pack(coord(c.x), coord(c.y), coord(c.z)); }
  double cell_;
  std::unordered_map<uint64_t, std::vector<uint32_t>> cells_;
};

}  // namespace grainlab
