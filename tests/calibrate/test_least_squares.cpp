// Householder least squares against exact data and the textbook covariance of a line.
#include <gtest/gtest.h>

#include <cmath>

#include "calibrate/least_squares.hpp"

using namespace grainlab::calibrate;

TEST(LeastSquares, ExactCubicIsRecovered) {
  std::vector<std::vector<double>> rows;
  std::vector<double> y;
  for (int i = 0; i < 12; ++i) {
    const double x = 0.3 * i - 1.0;
    rows.push_back({1.0, x, x * x, x * x * x});
    y.push_back(2.0 - 0.5 * x + 0.25 * x * x - 3.0 * x * x * x);
  }
  const LinearFit f = least_squares(rows, y);
  EXPECT_NEAR(f.coefficients[0], 2.0, 1e-12);
  EXPECT_NEAR(f.coefficients[1], -0.5, 1e-12);
  EXPECT_NEAR(f.coefficients[2], 0.25, 1e-12);
  EXPECT_NEAR(f.coefficients[3], -3.0, 1e-12);
  EXPECT_NEAR(f.ssr, 0.0, 1e-20);
  EXPECT_EQ(f.dof, 8u);
}

TEST(LeastSquares, LineCovarianceMatchesTextbook) {
  // y = a + b x with residuals: Var(b) = s^2 / Sxx, Var(a) = s^2 (1/n + xbar^2 / Sxx).
  const std::vector<double> x{1, 2, 3, 4, 5, 6}, y{1.1, 1.9, 3.2, 3.9, 5.2, 5.8};
  std::vector<std::vector<double>> rows;
  for (double xi : x) rows.push_back({1.0, xi});
  const LinearFit f = least_squares(rows, y);
  const double n = 6, xbar = 3.5;
  double sxx = 0, sxy = 0, ybar = 0;
  for (double yi : y) ybar += yi / n;
  for (int i = 0; i < 6; ++i) {
    sxx += (x[i] - xbar) * (x[i] - xbar);
    sxy += (x[i] - xbar) * (y[i] - ybar);
  }
  const double b = sxy / sxx, a = ybar - b * xbar;
  double ssr = 0;
  for (int i = 0; i < 6; ++i) ssr += std::pow(y[i] - a - b * x[i], 2);
  const double s2 = ssr / (n - 2);
  EXPECT_NEAR(f.coefficients[1], b, 1e-13);
  EXPECT_NEAR(f.coefficients[0], a, 1e-13);
  EXPECT_NEAR(f.cov(1, 1), s2 / sxx, 1e-14);
  EXPECT_NEAR(f.cov(0, 0), s2 * (1 / n + xbar * xbar / sxx), 1e-14);
  EXPECT_NEAR(f.cov(0, 1), -s2 * xbar / sxx, 1e-14);
  EXPECT_NEAR(f.cov(0, 1), f.cov(1, 0), 1e-16);
}

TEST(LeastSquares, DependentColumnsAreRejected) {
  std::vector<std::vector<double>> rows{{1, 2, 3}, {2, 4, 1}, {3, 6, 0}, {4, 8, 5}};
  EXPECT_THROW(least_squares(rows, {1, 2, 3, 4}), RankDeficient);
  EXPECT_THROW(least_squares({{1.0, 2.0}}, {1.0}), RankDeficient);  // fewer rows than columns
}
