// Solid fraction profile and interior solid fraction (measure/solid_fraction.hpp). Checked
// against an independent midpoint-rule integration of the sphere's cross-sections, against the
// exact solid fraction of a simple-cubic lattice (pi d^3 / (6 a^3) in every lattice-aligned
// region), and against the bulk value (the profile's mean over a box holding every bead).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "measure/solid_fraction.hpp"
#include "measure/specimen_state.hpp"

using namespace grainlab;

namespace {

// Sphere volume between two planes by the midpoint rule over 200,000 slices of the chord.
double slab_volume_by_slices(double c, double r, double a, double b) {
  const int n = 200000;
  double v = 0.0;
  const double h = 2.0 * r / n;
  for (int k = 0; k < n; ++k) {
    const double t = -r + (k + 0.5) * h;
    if (c + t >= a && c + t < b) v += M_PI * (r * r - t * t) * h;
  }
  return v;
}

// n^3 spheres of radius r on a simple-cubic lattice of spacing a in the box [0, n a]^3.
ParticleStore cubic_lattice(int n, double a, double r) {
  ParticleStore p;
  uint32_t id = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k)
        p.add(id++, 0, r, 2500.0, {(i + 0.5) * a, (j + 0.5) * a, (k + 0.5) * a}, {}, {}, false);
  return p;
}

}  // namespace

TEST(SolidFraction, SlabVolumeMatchesSlicedIntegration) {
  const double r = 1e-3, c = 0.4e-3;
  EXPECT_NEAR(sphere_slab_volume(c, r, -1.0, 1.0) / (4.0 / 3.0 * M_PI * r * r * r), 1.0, 1e-14);
  EXPECT_EQ(sphere_slab_volume(c, r, 2e-3, 3e-3), 0.0);
  for (auto [a, b] : {std::pair{-0.3e-3, 0.9e-3}, {0.1e-3, 5e-3}, {-5e-3, 0.0}, {1.2e-3, 1.3e-3}})
    EXPECT_NEAR(sphere_slab_volume(c, r, a, b) / slab_volume_by_slices(c, r, a, b), 1.0, 1e-6);
}

TEST(SolidFraction, CubicLatticeHasItsExactSolidFractionEverywhere) {
  const int n = 6;
  const double a = 2.2e-3, r = 1e-3;
  const ParticleStore p = cubic_lattice(n, a, r);
  const double exact = M_PI * 8 * r * r * r / (6 * a * a * a);
  const Vec3 low{0, 0, 0}, high{n * a, n * a, n * a};
  for (int axis = 0; axis < 3; ++axis)
    for (double phi : solid_fraction_profile(p, low, high, axis, n)) EXPECT_NEAR(phi, exact, 1e-12);
  // Regions on lattice-cell boundaries hold whole cells.
  EXPECT_NEAR(interior_solid_fraction(p, low, high, a), exact, 1e-12);
  EXPECT_NEAR(interior_solid_fraction(p, low, high, 2 * a), exact, 1e-12);
  EXPECT_EQ(interior_solid_fraction(p, low, high, 3 * a), 0.0);  // no interior left
  // A region cutting the beads through their centres holds half of each bead on a face, a
  // quarter on an edge, an eighth at a corner (the quadrature's part): cells of the lattice
  // shifted by half a spacing, the same solid fraction.
  EXPECT_NEAR(interior_solid_fraction(p, low, high, 0.5 * a) / exact, 1.0, 5e-5);
}

// Beads across an edge and a corner of the region, off their centres: the inside volume against
// a brute-force count of a 400^3 point lattice over each bead's bounding cube (they agree to 2e-5).
TEST(SolidFraction, BeadsAcrossEdgesAndCornersMatchABruteForceCount) {
  const double r = 1e-3;
  const Vec3 low{0, 0, 0}, high{0.02, 0.02, 0.02};
  const double margin = 0.004;
  const Vec3 a{margin, margin, margin}, b = high - a;
  ParticleStore p;
  p.add(0, 0, r, 2500.0, {a.x + 0.3e-3, a.y - 0.45e-3, 0.01}, {}, {}, false);         // an edge
  p.add(1, 0, r, 2500.0, {b.x - 0.2e-3, b.y + 0.6e-3, b.z - 0.7e-3}, {}, {}, false);  // a corner
  p.add(2, 0, r, 2500.0, {0.01, 0.01, 0.01}, {}, {}, false);                          // inside
  double brute = 0.0;
  const int g = 400;
  const double h = 2 * r / g;
  for (size_t i = 0; i < p.size(); ++i) {
    const Vec3 c = p.position[i];
    long count = 0;
    for (int u = 0; u < g; ++u)
      for (int v = 0; v < g; ++v)
        for (int w = 0; w < g; ++w) {
          const Vec3 q{c.x - r + (u + 0.5) * h, c.y - r + (v + 0.5) * h, c.z - r + (w + 0.5) * h};
          const Vec3 d = q - c;
          if (d.x * d.x + d.y * d.y + d.z * d.z <= r * r && q.x > a.x && q.x < b.x && q.y > a.y &&
              q.y < b.y && q.z > a.z && q.z < b.z)
            ++count;
        }
    brute += count * h * h * h;
  }
  const double region = std::pow(high.x - 2 * margin, 3);
  EXPECT_NEAR(interior_solid_fraction(p, low, high, margin) * region / brute, 1.0, 5e-5);
}

// Jittered beads in a box: the profile's mean is the bulk solid fraction, for any bin count; a
// wall-adjacent slab is looser than the middle ones.
TEST(SolidFraction, ProfileMeanIsTheBulkValueAndTheWallLayerIsLoose) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> jitter(-0.09e-3, 0.09e-3);
  const int n = 8;
  const double a = 2.2e-3, r = 1e-3;
  ParticleStore p;
  uint32_t id = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k)
        p.add(
            id++, 0, r, 2500.0,
            {(i + 0.5) * a + jitter(rng), (j + 0.5) * a + jitter(rng), (k + 0.5) * a + jitter(rng)},
            {}, {}, false);
  const Vec3 low{0, 0, 0}, high{n * a, n * a, n * a};
  const double bulk = solid_fraction(p, n * a * n * a * n * a);
  for (int bins : {1, 7, 40}) {
    const std::vector<double> profile = solid_fraction_profile(p, low, high, 2, bins);
    double mean = 0.0;
    for (double phi : profile) mean += phi / bins;
    EXPECT_NEAR(mean / bulk, 1.0, 1e-12) << bins << " bins";
  }
  const std::vector<double> fine = solid_fraction_profile(p, low, high, 0, 10 * n);
  EXPECT_LT(fine.front(), 0.5 * fine[5]);  // within 0.22 mm of the wall: the gap before a sphere
}
