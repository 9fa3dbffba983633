#include "core/random_insertion.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace grainlab {
namespace {

// A sparse cell hash over all spheres, cells one maximum diameter wide.
class SphereGrid {
 public:
  explicit SphereGrid(double cell) : cell_(cell) {}
  void add(const Sphere& s, uint32_t index) { cells_[key(s.centre)].push_back(index); }
  bool overlaps(const std::vector<Sphere>& all, const Sphere& s) const {
    const long cx = coord(s.centre.x), cy = coord(s.centre.y), cz = coord(s.centre.z);
    for (long dz = -1; dz <= 1; ++dz)
      for (long dy = -1; dy <= 1; ++dy)
        for (long dx = -1; dx <= 1; ++dx) {
          auto it = cells_.find(pack(cx + dx, cy + dy, cz + dz));
          if (it == cells_.end()) continue;
          for (uint32_t j : it->second) {
            const double reach = s.radius + all[j].radius;
            if (norm2(all[j].centre - s.centre) < reach * reach) return true;
          }
        }
    return false;
  }

 private:
  long coord(double x) const { return static_cast<long>(std::floor(x / cell_)); }
  static uint64_t pack(long x, long y, long z) {
    return (static_cast<uint64_t>(x & 0x1FFFFF) << 42) |
           (static_cast<uint64_t>(y & 0x1FFFFF) << 21) | static_cast<uint64_t>(z & 0x1FFFFF);
  }
  uint64_t key(const Vec3& c) const { return pack(coord(c.x), coord(c.y), coord(c.z)); }
  double cell_;
  std::unordered_map<uint64_t, std::vector<uint32_t>> cells_;
};

}  // namespace

long insert_random_spheres(std::vector<Sphere>& spheres, const InsertionRegion& region, long count,
                           double diameter_min, double diameter_max, std::mt19937_64& rng,
                           long attempts_per_sphere) {
  double largest = diameter_max;
  for (const Sphere& s : spheres) largest = std::max(largest, 2.0 * s.radius);
  SphereGrid grid(largest);
  for (size_t i = 0; i < spheres.size(); ++i) grid.add(spheres[i], static_cast<uint32_t>(i));
  long placed = 0;
  for (; placed < count; ++placed) {
    const double r = 0.5 * (diameter_min + (diameter_max - diameter_min) * uniform01(rng));
    bool done = false;
    for (long attempt = 0; attempt < attempts_per_sphere && !done; ++attempt) {
      Sphere s{{}, r};
      if (!region.cylinder) {
        for (int d = 0; d < 3; ++d)
          s.centre[d] = region.box_min[d] + r +
                        (region.box_max[d] - region.box_min[d] - 2 * r) * uniform01(rng);
      } else {
        const double reach = region.radius - r;
        const double rho = reach * std::sqrt(uniform01(rng)), phi = 2.0 * M_PI * uniform01(rng);
        s.centre = region.base + Vec3{rho * std::cos(phi), rho * std::sin(phi),
                                      r + (region.height - 2 * r) * uniform01(rng)};
      }
      if (grid.overlaps(spheres, s)) continue;
      grid.add(s, static_cast<uint32_t>(spheres.size()));
      spheres.push_back(s);
      done = true;
    }
    if (!done) break;
  }
  return placed;
}

}  // namespace grainlab
