#include "calibrate/least_squares.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace grainlab::calibrate {

double LinearFit::residual_sd() const {
  if (dof == 0) return std::numeric_limits<double>::quiet_NaN();
  return std::sqrt(ssr / static_cast<double>(dof));
}

double LinearFit::standard_error(std::size_t i) const {
  if (dof == 0) return std::numeric_limits<double>::quiet_NaN();
  return std::sqrt(cov(i, i));
}

LinearFit least_squares(const std::vector<std::vector<double>>& rows,
                        const std::vector<double>& y) {
  const std::size_t n = rows.size();
  if (n == 0 || y.size() != n) throw std::invalid_argument("least_squares: bad sizes");
  const std::size_t p = rows.front().size();
  if (p == 0 || n < p) throw RankDeficient("fewer observations than parameters");

  // Column-major copy of X and of y, reduced in place to R and Q^T y.
  std::vector<double> a(n * p);
  auto at = [&](std::size_t i, std::size_t j) -> double& { return a[j * n + i]; };
  std::vector<double> column_norm(p, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    if (rows[i].size() != p) throw std::invalid_argument("least_squares: ragged design matrix");
    for (std::size_t j = 0; j < p; ++j) {
      at(i, j) = rows[i][j];
      column_norm[j] += rows[i][j] * rows[i][j];
    }
  }
  for (double& c : column_norm) c = std::sqrt(c);
  std::vector<double> qty = y;

  for (std::size_t k = 0; k < p; ++k) {
    double norm = 0.0;
    for (std::size_t i = k; i < n; ++i) norm += at(i, k) * at(i, k);
    norm = std::sqrt(norm);
    // A column that is (numerically) in the span of the previous ones leaves ~nothing here.
    if (!(norm > 1e-10 * column_norm[k]) || column_norm[k] == 0.0)
      throw RankDeficient("the fit's parameters are not all determined by the data");
    const double alpha = at(k, k) > 0 ? -norm : norm;
    // Householder vector v = x - alpha e_k, stored over column k.
    at(k, k) -= alpha;
    double vtv = 0.0;
    for (std::size_t i = k; i < n; ++i) vtv += at(i, k) * at(i, k);
    for (std::size_t j = k + 1; j < p; ++j) {
      double s = 0.0;
      for (std::size_t i = k; i < n; ++i) s += at(i, k) * at(i, j);
      s = 2.0 * s / vtv;
      for (std::size_t i = k; i < n; ++i) at(i, j) -= s * at(i, k);
    }
    double s = 0.0;
    for (std::size_t i = k; i < n; ++i) s += at(i, k) * qty[i];
    s = 2.0 * s / vtv;
    for (std::size_t i = k; i < n; ++i) qty[i] -= s * at(i, k);
    at(k, k) = alpha;  // R(k, k); the rest of column k below the diagonal is scratch now
  }

  // Back substitution R b = (Q^T y)[0..p).
  LinearFit fit;
  fit.coefficients.assign(p, 0.0);
  for (std::size_t k = p; k-- > 0;) {
    double s = qty[k];
    for (std::size_t j = k + 1; j < p; ++j) s -= at(k, j) * fit.coefficients[j];
    fit.coefficients[k] = s / at(k, k);
  }
  fit.residuals.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    double pred = 0.0;
    for (std::size_t j = 0; j < p; ++j) pred += rows[i][j] * fit.coefficients[j];
    fit.residuals[i] = y[i] - pred;
    fit.ssr += fit.residuals[i] * fit.residuals[i];
  }
  fit.dof = n - p;

  // (X^T X)^-1 = R^-1 R^-T: invert the upper-triangular R column by column.
  std::vector<double> rinv(p * p, 0.0);  // row-major
  for (std::size_t c = 0; c < p; ++c) {
    for (std::size_t k = c + 1; k-- > 0;) {
      double s = (k == c) ? 1.0 : 0.0;
      for (std::size_t j = k + 1; j <= c; ++j) s -= at(k, j) * rinv[j * p + c];
      rinv[k * p + c] = s / at(k, k);
    }
  }
  const double s2 = fit.dof > 0 ? fit.ssr / static_cast<double>(fit.dof) : 0.0;
  fit.covariance.assign(p * p, 0.0);
  for (std::size_t i = 0; i < p; ++i)
    for (std::size_t j = 0; j < p; ++j) {
      double s = 0.0;
      for (std::size_t k = std::max(i, j); k < p; ++k) s += rinv[i * p + k] * rinv[j * p + k];
      fit.covariance[i * p + j] = s2 * s;
    }
  return fit;
}

}  // namespace grainlab::calibrate
