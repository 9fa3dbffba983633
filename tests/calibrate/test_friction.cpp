// Friction fits: through-origin and free-intercept lines, the speed curve, errors, coverage.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <sstream>

#include "calibrate/friction.hpp"
#include "calibrate/input_error.hpp"

using namespace grainlab::calibrate;

namespace {

// A curve of the fitted family: quadratic below 5 mm/min, linear above, continuous.
double curve(double v) {
  const double u = std::min(v, 5.0);
  return 0.2116 - 0.0025 * u + 0.00017 * u * u + 0.0021 * std::max(v - 5.0, 0.0);
}

std::vector<LoadPoint> make_points(const std::vector<double>& speeds, double noise,
                                   std::uint64_t seed, double offset_n = 0.0) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0.0, 1.0);
  std::vector<LoadPoint> p;
  for (double v : speeds)
    for (double load : {0.25, 0.5, 0.75, 1.0, 1.25})
      p.push_back({p.size() + 2, v, load, curve(v) * load + offset_n + noise * n(rng)});
  return p;
}

std::string csv_of(const std::vector<LoadPoint>& p, const std::string& material) {
  std::ostringstream s;
  s.precision(17);
  s << "material,speed_mm_per_min,normal_load_N,friction_force_N\n";
  for (const auto& q : p)
    s << material << "," << q.speed_mm_per_min << "," << q.normal_load_n << ","
      << q.friction_force_n << "\n";
  return s.str();
}

std::string error_of(const std::string& csv) {
  try {
    analyse_friction(CsvTable::parse(csv, "slide.csv"));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

const std::vector<double> speeds{0.5, 1.0, 2.5, 5.0, 12.5, 25.0};

}  // namespace

TEST(Friction, ExactLineThroughOriginIsRecovered) {
  const auto p = make_points({25.0}, 0.0, 0);
  const auto f = fit_through_origin(p);
  EXPECT_NEAR(f.slope, curve(25.0), 1e-14);
  EXPECT_NEAR(f.r_squared, 1.0, 1e-12);
  EXPECT_NEAR(f.standard_error, 0.0, 1e-14);
  const auto g = fit_free_intercept(p);
  EXPECT_NEAR(g.slope, curve(25.0), 1e-12);
  EXPECT_NEAR(g.intercept_n, 0.0, 1e-12);
}

TEST(Friction, KnownSmallFit) {
  // P = 1, 2; F = 1, 3: through origin mu = (1 + 6) / 5 = 1.4, residuals -0.4, 0.2,
  // s^2 = 0.2 / 1, se = sqrt(0.2 / 5) = 0.2; the free line is F = 2 P - 1 exactly.
  const std::vector<LoadPoint> p{{2, 1, 1.0, 1.0}, {3, 1, 2.0, 3.0}};
  const auto f = fit_through_origin(p);
  EXPECT_NEAR(f.slope, 1.4, 1e-14);
  EXPECT_NEAR(f.standard_error, 0.2, 1e-14);
  EXPECT_NEAR(f.ci.high - f.slope, 12.706204736 * 0.2, 1e-7);
  const auto g = fit_free_intercept(p);
  EXPECT_NEAR(g.slope, 2.0, 1e-13);
  EXPECT_NEAR(g.intercept_n, -1.0, 1e-13);
  EXPECT_TRUE(std::isnan(g.intercept_standard_error_n));  // two points: no dof
}

TEST(Friction, OffsetIsFlaggedAsSignificant) {
  const auto clean = fit_free_intercept(make_points({5.0}, 0.001, 3));
  const auto offset = fit_free_intercept(make_points({5.0}, 0.001, 3, 0.01));
  EXPECT_NEAR(offset.intercept_n, 0.01, 0.004);
  EXPECT_TRUE(offset.intercept_significant);
  EXPECT_FALSE(clean.intercept_significant);
}

TEST(Friction, ExactSpeedCurveIsRecovered) {
  const auto f = fit_speed_curve(make_points(speeds, 0.0, 0), 5.0);
  ASSERT_EQ(f.coefficients.size(), 4u);
  EXPECT_NEAR(f.coefficients[0], 0.2116, 1e-12);
  EXPECT_NEAR(f.coefficients[1], -0.0025, 1e-12);
  EXPECT_NEAR(f.coefficients[2], 0.00017, 1e-12);
  EXPECT_NEAR(f.coefficients[3], 0.0021, 1e-12);
  EXPECT_NEAR(f.quasi_static.value, 0.2116, 1e-12);
  for (double v : {0.0, 3.0, 5.0, 7.0, 25.0}) EXPECT_NEAR(f.friction_at(v), curve(v), 1e-12);
  // Eq. 2 form: the two pieces meet at the breakpoint.
  EXPECT_NEAR(f.high_slope() * 5.0 + f.high_intercept(),
              f.low_q0() + f.low_q1() * 5.0 + f.low_q2() * 25.0, 1e-14);
}

TEST(Friction, SpeedCurveWithoutFastSpeedsIsQuadraticOnly) {
  const auto f = fit_speed_curve(make_points({0.5, 2.5, 5.0}, 0.0, 0), 5.0);
  EXPECT_FALSE(f.has_linear_part);
  EXPECT_EQ(f.coefficients.size(), 3u);
  EXPECT_NEAR(f.quasi_static.value, 0.2116, 1e-12);
}

TEST(Friction, NoisyDataCoverTheTruthAtTheStatedRate) {
  // 200 synthetic tests (noise 0.003 N): the 95 % CIs of the quasi-static coefficient and of
  // mu at 25 mm/min must cover the true values in >= 90 % of them.
  int covered_qs = 0, covered_25 = 0;
  for (int seed = 0; seed < 200; ++seed) {
    const auto a = analyse_friction(
        CsvTable::parse(csv_of(make_points(speeds, 0.003, seed), "m"), "slide.csv"));
    const auto& m = a.materials.at(0);
    ASSERT_TRUE(m.speed_fit);
    covered_qs += m.speed_fit->quasi_static.ci.contains(0.2116);
    covered_25 += m.speeds.back().origin.ci.contains(curve(25.0));
  }
  EXPECT_GE(covered_qs, 180) << covered_qs;
  EXPECT_GE(covered_25, 180) << covered_25;
  EXPECT_LE(covered_qs, 199);
}

TEST(Friction, AnalysisGroupsAndSortsSpeeds) {
  auto p = make_points({25.0, 2.5, 5.0, 1.0}, 0.0, 0);
  const auto a = analyse_friction(CsvTable::parse(csv_of(p, "rubber_membrane"), "s.csv"));
  ASSERT_EQ(a.materials.size(), 1u);
  ASSERT_EQ(a.materials[0].speeds.size(), 4u);
  EXPECT_DOUBLE_EQ(a.materials[0].speeds[0].speed_mm_per_min, 1.0);
  EXPECT_NEAR(a.materials[0].speeds[3].origin.slope, curve(25.0), 1e-13);
  ASSERT_TRUE(a.materials[0].speed_fit);
  EXPECT_NEAR(a.materials[0].speed_fit->quasi_static.value, 0.2116, 1e-12);
}

TEST(Friction, PublishedSpeedsAloneCannotDetermineTheCurve) {
  // 2.5, 5, 12.5, 25 mm/min: only two speeds at or below 5 -> no speed fit, and it says why.
  const auto a = analyse_friction(
      CsvTable::parse(csv_of(make_points({25.0, 12.5, 5.0, 2.5}, 0.001, 1), "m"), "s.csv"));
  EXPECT_FALSE(a.materials[0].speed_fit);
  EXPECT_NE(a.materials[0].speed_fit_note.find("2.5, 5, 12.5, 25"), std::string::npos)
      << a.materials[0].speed_fit_note;
  EXPECT_NE(a.materials[0].speed_fit_note.find("three different speeds"), std::string::npos);
}

TEST(Friction, OneLoadAtASpeedNamesTheLine) {
  const std::string msg = error_of(
      "material,speed_mm_per_min,normal_load_N,friction_force_N\n"
      "rm,25,0.5,0.12\nrm,25,1.0,0.24\n# the next speed has one load, twice\n"
      "rm,5,0.5,0.10\nrm,5,0.5,0.11\n");
  EXPECT_EQ(msg,
            "slide.csv line 5: rm at 5 mm/min has only one normal load (P = 0.5 N, lines 5, 6); "
            "an F-P fit needs at least two different loads");
}

TEST(Friction, BadCellsAreErrorsWithLines) {
  const std::string head = "material,speed_mm_per_min,normal_load_N,friction_force_N\n";
  EXPECT_NE(error_of(head + "rm,25,0.5,0.12\nrm,25,-1,0.2\n").find("line 3: normal_load_N = -1"),
            std::string::npos);
  EXPECT_NE(error_of(head + "rm,0,0.5,0.12\n").find("line 2: speed_mm_per_min = 0"),
            std::string::npos);
  EXPECT_NE(error_of(head + "rm,25,0.5,-0.1\n").find("line 2: friction_force_N = -0.1"),
            std::string::npos);
  EXPECT_NE(error_of(head + "rm,25,0.5,0.1N\n").find("line 2: column 'friction_force_N'"),
            std::string::npos);
  EXPECT_NE(error_of("material,speed_mm_per_min,normal_load_N\nrm,25,0.5\n")
                .find("slide.csv line 1: missing column 'friction_force_N'"),
            std::string::npos);
}

// Plausibility: clean data of the fitted family gives no warning; a force in the wrong unit
// (9.2e18 N on a 0.25 N load) and scatter that swamps the F-P line each warn, naming the line
// or the speed.
TEST(FrictionAnalysis, WarnsAboutImplausibleDataAndFits) {
  const std::vector<LoadPoint> clean = make_points({1, 2, 3, 5, 10, 25}, 0.002, 7);
  EXPECT_TRUE(
      analyse_friction(CsvTable::parse(csv_of(clean, "membrane"), "clean.csv")).warnings.empty());

  std::vector<LoadPoint> slipped = clean;
  slipped[3].friction_force_n = 9.2e18;
  const FrictionAnalysis a =
      analyse_friction(CsvTable::parse(csv_of(slipped, "membrane"), "x.csv"));
  ASSERT_FALSE(a.warnings.empty());
  EXPECT_NE(a.warnings[0].find("x.csv line 5"), std::string::npos) << a.warnings[0];
  EXPECT_NE(a.warnings[0].find("10000 N"), std::string::npos) << a.warnings[0];

  std::vector<LoadPoint> noisy = make_points({1, 2, 3, 5, 10, 25}, 0.1, 7);
  for (LoadPoint& p : noisy) p.friction_force_n = std::abs(p.friction_force_n);
  const FrictionAnalysis b = analyse_friction(CsvTable::parse(csv_of(noisy, "membrane"), "n.csv"));
  bool low_r2 = false;
  for (const auto& w : b.warnings) low_r2 |= w.find("R^2") != std::string::npos;
  EXPECT_TRUE(low_r2);
}
