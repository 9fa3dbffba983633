// Flat-throw restitution: exact data, units, errors, and the coverage of the reported CI.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <sstream>

#include "calibrate/input_error.hpp"
#include "calibrate/restitution.hpp"

using namespace grainlab::calibrate;

namespace {

std::string error_of(const std::string& csv) {
  try {
    analyse_throws(CsvTable::parse(csv, "throws.csv"));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Restitution, ExactThrowsRecoverEExactly) {
  // h = e^2 H for every throw: each e is exact, sd is zero, the CI collapses on e.
  std::ostringstream csv;
  csv.precision(17);
  csv << "material,H_m,h_m\n";
  for (double H : {0.2, 0.3, 0.45, 0.5}) csv << "glass," << H << "," << 0.926 * 0.926 * H << "\n";
  for (double H : {0.3, 0.6}) csv << "rubber_membrane," << H << "," << 0.58 * 0.58 * H << "\n";
  const auto a = analyse_throws(CsvTable::parse(csv.str(), "t.csv"));
  ASSERT_EQ(a.materials.size(), 2u);
  EXPECT_EQ(a.materials[0].material, "glass");
  EXPECT_EQ(a.materials[0].n, 4u);
  EXPECT_NEAR(a.materials[0].mean, 0.926, 1e-14);
  EXPECT_NEAR(a.materials[0].sd, 0.0, 1e-14);
  EXPECT_NEAR(a.materials[0].ci.low, 0.926, 1e-13);
  EXPECT_NEAR(a.materials[0].ci.high, 0.926, 1e-13);
  EXPECT_NEAR(a.materials[1].mean, 0.58, 1e-14);
  EXPECT_EQ(a.materials[1].throws[1].line, 7u);
}

TEST(Restitution, StatisticsOfKnownThrows) {
  // e = 0.5, 0.6, 0.7: mean 0.6, sd 0.1, CI 0.6 +- t_{0.975,2} 0.1 / sqrt(3).
  const auto a =
      analyse_throws(CsvTable::parse("material,H_m,h_m\nx,1,0.25\nx,1,0.36\nx,1,0.49\n", "t.csv"));
  const auto& m = a.materials[0];
  EXPECT_NEAR(m.mean, 0.6, 1e-14);
  EXPECT_NEAR(m.sd, 0.1, 1e-14);
  EXPECT_NEAR(m.ci.high - m.mean, 4.302652730 * 0.1 / std::sqrt(3.0), 1e-8);
}

TEST(Restitution, MillimetreColumnsAndRenaming) {
  const auto a =
      analyse_throws(CsvTable::parse("h_mm,material,H_mm\n64,porous_stone,100\n", "t.csv"),
                     {{"porous_stone", "filter_paper"}});
  EXPECT_EQ(a.materials[0].material, "filter_paper");
  EXPECT_NEAR(a.materials[0].mean, 0.8, 1e-14);
  EXPECT_NEAR(a.materials[0].throws[0].launch_height_m, 0.1, 1e-15);
  EXPECT_TRUE(std::isnan(a.materials[0].sd));  // one throw: no spread
}

TEST(Restitution, ReboundAboveDropNamesTheLine) {
  const std::string msg =
      error_of("material,H_m,h_m\nglass,0.5,0.4\n# x\nglass,0.5,0.3\nglass,0.5,0.9\n");
  EXPECT_EQ(msg,
            "throws.csv line 5: h_m = 0.9 is larger than H_m = 0.5 (a rebound cannot exceed the "
            "drop)");
}

TEST(Restitution, NonPositiveHeightsAndMissingColumns) {
  EXPECT_NE(error_of("material,H_m,h_m\nglass,0,0\n").find("line 2: H_m = 0 must be positive"),
            std::string::npos);
  EXPECT_NE(error_of("material,H_m,h_m\nglass,0.5,-0.1\n").find("line 2: h_m = -0.1"),
            std::string::npos);
  EXPECT_NE(error_of("material,H_m\nglass,0.5\n").find("missing column 'h_m'"), std::string::npos);
  EXPECT_NE(error_of("material,H_mm\nglass,500\n").find("missing column 'h_mm'"),
            std::string::npos);
  EXPECT_NE(error_of("H_m,h_m\n0.5,0.4\n").find("missing column 'material'"), std::string::npos);
  EXPECT_NE(error_of("material,H_m,h_m\n,0.5,0.4\n").find("line 2: column 'material' is empty"),
            std::string::npos);
}

TEST(Restitution, NoisyThrowsCoverTheTruthAtTheStatedRate) {
  // 200 data sets of 12 throws, e ~ N(0.73, 0.03), readings of h with 1 mm error: the 95 % CI
  // must contain 0.73 in about 95 % of them (>= 90 % allows for the 200-sample spread).
  const double e_true = 0.73;
  int covered = 0;
  for (int seed = 0; seed < 200; ++seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> de(0.0, 0.03), dh(0.0, 0.001), dH(0.0, 0.002);
    std::vector<Throw> throws;
    for (int i = 0; i < 12; ++i) {
      const double H = 0.4 + dH(rng);
      const double e = e_true + de(rng);
      const double h = e * e * H + dh(rng);
      throws.push_back({0, H, h, std::sqrt(h / H)});
    }
    const auto r = summarise_throws("x", throws);
    covered += r.ci.contains(e_true);
  }
  EXPECT_GE(covered, 180) << covered << " of 200";
  EXPECT_LE(covered, 199) << "an interval that always covers is too wide";
}
