#include "core/random_insertion.hpp"

#include <algorithm>
#include <cmath>

namespace grainlab {

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
