// The shear-band finder (measure/local_strain.hpp, measure/shear_band.hpp) on synthetic
// displacement fields whose band is known exactly: particles on a jittered lattice filling a
// 60 x 20 x 100 mm (x, y, z) specimen of 2 mm beads, displaced by a smooth simple shear along a
// band of direction theta (from x towards z) through the specimen's centre,
//   u = (delta / 2) (1 + tanh(s / w)) t,   s = n . (X - centre),
// t = (cos theta, 0, sin theta), n = (-sin theta, 0, cos theta). Its engineering shear strain is
// gamma(s) = (delta / 2w) sech^2(s / w), whose full width at half height is 2 w acosh(sqrt 2)
// = 1.7627 w. The local fit over 2 d neighbourhoods smooths the profile slightly, so the
// thickness is checked within 20 %, the inclination within 1 degree.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "measure/local_strain.hpp"
#include "measure/shear_band.hpp"

using namespace grainlab;

namespace {

constexpr double d = 2e-3;

struct Field {
  std::vector<Vec3> reference, current;
};

Field banded_field(double theta_deg, double w, double delta) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> jitter(-0.15 * d, 0.15 * d);
  const double th = theta_deg * std::numbers::pi / 180.0;
  const Vec3 t{std::cos(th), 0, std::sin(th)}, n{-std::sin(th), 0, std::cos(th)};
  const Vec3 centre{0.030, 0.010, 0.050};
  Field f;
  for (int k = 0; k < 50; ++k)
    for (int j = 0; j < 10; ++j)
      for (int i = 0; i < 30; ++i) {
        const Vec3 x{(i + 0.5) * d + jitter(rng), (j + 0.5) * d + jitter(rng),
                     (k + 0.5) * d + jitter(rng)};
        const double s = dot(n, x - centre);
        f.reference.push_back(x);
        f.current.push_back(x + (0.5 * delta * (1.0 + std::tanh(s / w))) * t);
      }
  return f;
}

ShearBand band_of(const Field& f) {
  const std::vector<Matrix3> g = local_displacement_gradient(f.reference, f.current, 2.0 * d);
  std::vector<double> gamma(g.size());
  for (size_t i = 0; i < g.size(); ++i) gamma[i] = max_shear_strain(g[i], 0, 2);
  return find_shear_band(strain_map(f.current, gamma, 0, 2, d));
}

}  // namespace

// A homogeneous deformation is fitted exactly: the gradient of u = A X is A for every particle.
TEST(LocalStrain, HomogeneousDeformationIsExact) {
  const Field f = banded_field(60, 1.0, 0.0);
  std::vector<Vec3> current(f.reference.size());
  const Matrix3 a{{{0.01, 0.0, 0.02}, {0.0, 0.0, 0.0}, {0.005, 0.0, -0.03}}};
  for (size_t i = 0; i < current.size(); ++i) {
    const Vec3& x = f.reference[i];
    current[i] = x + Vec3{a[0][0] * x.x + a[0][2] * x.z, 0.0, a[2][0] * x.x + a[2][2] * x.z};
  }
  const std::vector<Matrix3> g = local_displacement_gradient(f.reference, current, 2.0 * d);
  for (size_t i = 0; i < g.size(); i += 97)
    for (int p = 0; p < 3; ++p)
      for (int q = 0; q < 3; ++q) ASSERT_NEAR(g[i][p][q], a[p][q], 1e-12);
  const double gamma = std::sqrt(std::pow(0.01 + 0.03, 2) + std::pow(0.02 + 0.005, 2));
  EXPECT_NEAR(max_shear_strain(g[0], 0, 2), gamma, 1e-12);
}

TEST(ShearBandFinder, FindsTheInclinationAndThicknessOfAKnownBand) {
  for (const double theta : {60.0, 125.0}) {  // both conjugate directions
    const double w = 2.5 * d;
    const ShearBand b = band_of(banded_field(theta, w, 0.3 * d * 10));
    ASSERT_TRUE(b.found);
    EXPECT_NEAR(b.direction_deg, theta, 1.0) << theta;
    EXPECT_NEAR(b.inclination_deg, theta <= 90 ? theta : 180 - theta, 1.0);
    const double fwhm = 2.0 * w * std::acosh(std::sqrt(2.0));
    EXPECT_NEAR(b.thickness / fwhm, 1.0, 0.2) << "thickness " << b.thickness / d << " d";
    EXPECT_GT(b.peak, 5.0 * b.background);
  }
}

// No band: a uniform shear has no line of larger strain, and the profile across any line is flat
// (the half-height width spans the map).
TEST(ShearBandFinder, UniformFieldHasNoNarrowBand) {
  const Field f = banded_field(60, 1.0, 0.0);
  std::vector<Vec3> current(f.reference.size());
  for (size_t i = 0; i < current.size(); ++i)
    current[i] = f.reference[i] + Vec3{0.02 * f.reference[i].z, 0.0, 0.0};
  const std::vector<Matrix3> g = local_displacement_gradient(f.reference, current, 2.0 * d);
  std::vector<double> gamma(g.size());
  for (size_t i = 0; i < g.size(); ++i) gamma[i] = max_shear_strain(g[i], 0, 2);
  const ShearBand b = find_shear_band(strain_map(current, gamma, 0, 2, d));
  EXPECT_NEAR(b.peak, b.background, 1e-9);
}
