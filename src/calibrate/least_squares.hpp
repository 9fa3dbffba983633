// Ordinary linear least squares, y ~ X b, by Householder QR (no normal equations, so the
// polynomial and piecewise bases used by the fits stay well conditioned).
//
// Parameter covariance: s^2 (X^T X)^-1 = s^2 R^-1 R^-T with s^2 = SSR / (n - p), the usual
// unbiased residual variance (Seber & Lee, Linear Regression Analysis, 2nd ed., ch. 3).
#pragma once

#include <cstddef>
#include <stdexcept>
#include <vector>

namespace grainlab::calibrate {

// Thrown when the columns of X are (numerically) linearly dependent, e.g. a quadratic asked
// of two distinct speeds. Callers add what the data lacked to the message.
class RankDeficient : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct LinearFit {
  std::vector<double> coefficients;  // b, p values
  std::vector<double> covariance;    // p x p, row-major, s^2 (X^T X)^-1 (zero when dof == 0)
  std::vector<double> residuals;     // y - X b, n values
  double ssr = 0.0;                  // sum of squared residuals
  std::size_t dof = 0;               // n - p
  double residual_sd() const;        // s = sqrt(SSR / dof); NaN when dof == 0
  double standard_error(std::size_t i) const;  // sqrt(covariance(i, i)); NaN when dof == 0
  double cov(std::size_t i, std::size_t j) const { return covariance[i * coefficients.size() + j]; }
};

// Design matrix given row by row: rows[k] holds the p regressors of observation k.
LinearFit least_squares(const std::vector<std::vector<double>>& rows, const std::vector<double>& y);

}  // namespace grainlab::calibrate
