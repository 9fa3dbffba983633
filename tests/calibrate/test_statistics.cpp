// Student t and incomplete beta against tabulated values and closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "calibrate/statistics.hpp"

using namespace grainlab::calibrate;

// Two-sided 95 % quantiles t_{0.975, nu} (e.g. NIST/SEMATECH e-Handbook, table 1.3.6.7.2;
// values to 9 digits from R's qt()).
TEST(Statistics, StudentQuantileMatchesTables) {
  struct Row {
    double nu, p, t;
  };
  const std::vector<Row> rows{
      {1, 0.975, 12.706204736}, {2, 0.975, 4.302652730},    {3, 0.975, 3.182446305},
      {5, 0.975, 2.570581836},  {10, 0.975, 2.228138852},   {19, 0.975, 2.093024054},
      {30, 0.975, 2.042272456}, {1000, 0.975, 1.962339081}, {4, 0.995, 4.604094871},
      {9, 0.95, 1.833112933},   {2, 0.025, -4.302652730},   {1, 0.75, 1.0}};
  for (const auto& r : rows)
    EXPECT_NEAR(student_t_quantile(r.p, r.nu), r.t, 1e-8 * std::abs(r.t) + 1e-10)
        << "nu = " << r.nu << ", p = " << r.p;
}

TEST(Statistics, StudentQuantileApproachesNormal) {
  EXPECT_NEAR(student_t_quantile(0.975, 1e7), 1.959963985, 1e-6);
}

TEST(Statistics, CauchyIsStudentWithOneDegree) {
  for (double t : {-30.0, -2.0, -0.3, 0.0, 0.7, 5.0, 100.0})
    EXPECT_NEAR(student_t_cdf(t, 1.0), 0.5 + std::atan(t) / std::numbers::pi, 1e-13);
}

TEST(Statistics, QuantileInvertsCdf) {
  for (double nu : {0.5, 1.0, 2.5, 7.0, 56.0, 400.0})
    for (double p : {1e-6, 0.01, 0.2, 0.5, 0.8, 0.975, 0.999999})
      EXPECT_NEAR(student_t_cdf(student_t_quantile(p, nu), nu), p, 1e-11 * std::max(1.0, 1 / p))
          << nu << " " << p;
}

TEST(Statistics, TwoSidedPValue) {
  EXPECT_NEAR(student_t_two_sided_p(2.228138852, 10), 0.05, 1e-9);
  EXPECT_NEAR(student_t_two_sided_p(0.0, 10), 1.0, 1e-15);
}

TEST(Statistics, IncompleteBetaClosedForms) {
  for (double x : {0.0, 0.1, 0.37, 0.5, 0.93, 1.0}) {
    EXPECT_NEAR(regularized_incomplete_beta(x, 1.0, 1.0), x, 1e-14);
    EXPECT_NEAR(regularized_incomplete_beta(x, 3.5, 1.0), std::pow(x, 3.5), 1e-13);
    EXPECT_NEAR(regularized_incomplete_beta(x, 1.0, 2.0), 1.0 - (1.0 - x) * (1.0 - x), 1e-13);
  }
  for (double a : {0.5, 2.0, 17.0}) EXPECT_NEAR(regularized_incomplete_beta(0.5, a, a), 0.5, 1e-13);
  // I_x(1/2, 1/2) = (2/pi) asin(sqrt(x))
  EXPECT_NEAR(regularized_incomplete_beta(0.3, 0.5, 0.5),
              2.0 / std::numbers::pi * std::asin(std::sqrt(0.3)), 1e-13);
}

TEST(Statistics, MeanSdAndInterval) {
  const std::vector<double> v{2, 4, 4, 4, 5, 5, 7, 9};
  EXPECT_DOUBLE_EQ(mean(v), 5.0);
  EXPECT_NEAR(sample_sd(v), std::sqrt(32.0 / 7.0), 1e-14);
  const auto ci = t_interval(5.0, 0.5, 10);
  EXPECT_NEAR(ci.low, 5.0 - 0.5 * 2.228138852, 1e-8);
  EXPECT_NEAR(ci.high, 5.0 + 0.5 * 2.228138852, 1e-8);
  EXPECT_THROW(sample_sd(std::vector<double>{1.0}), std::invalid_argument);
}
