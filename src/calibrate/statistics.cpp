#include "calibrate/statistics.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace grainlab::calibrate {
namespace {

// Continued fraction of the incomplete beta function (A&S 26.5.8), modified Lentz method;
// converges quickly for x < (a + 1) / (a + b + 2).
double beta_continued_fraction(double x, double a, double b) {
  constexpr double tiny = 1e-300;
  constexpr double eps = 1e-15;
  double c = 1.0;
  double d = 1.0 - (a + b) * x / (a + 1.0);
  if (std::abs(d) < tiny) d = tiny;
  d = 1.0 / d;
  double f = d;
  for (int m = 1; m <= 10000; ++m) {
    const double m2 = 2.0 * m;
    // even step: d_{2m} = m (b - m) x / ((a + 2m - 1)(a + 2m))
    double num = m * (b - m) * x / ((a + m2 - 1.0) * (a + m2));
    d = 1.0 + num * d;
    if (std::abs(d) < tiny) d = tiny;
    c = 1.0 + num / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    f *= d * c;
    // odd step: d_{2m+1} = -(a + m)(a + b + m) x / ((a + 2m)(a + 2m + 1))
    num = -(a + m) * (a + b + m) * x / ((a + m2) * (a + m2 + 1.0));
    d = 1.0 + num * d;
    if (std::abs(d) < tiny) d = tiny;
    c = 1.0 + num / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double delta = d * c;
    f *= delta;
    if (std::abs(delta - 1.0) < eps) return f;
  }
  return f;  // not converged to eps; still accurate to far better than the data
}

}  // namespace

double mean(std::span<const double> values) {
  if (values.empty()) throw std::invalid_argument("mean of no values");
  double sum = 0.0;
  for (double v : values) sum += v;
  return sum / static_cast<double>(values.size());
}

double sample_sd(std::span<const double> values) {
  if (values.size() < 2) throw std::invalid_argument("standard deviation needs two values");
  const double m = mean(values);
  double ss = 0.0;
  for (double v : values) ss += (v - m) * (v - m);
  return std::sqrt(ss / static_cast<double>(values.size() - 1));
}

double regularized_incomplete_beta(double x, double a, double b) {
  if (!(a > 0.0) || !(b > 0.0) || !(x >= 0.0) || !(x <= 1.0))
    throw std::invalid_argument("regularized_incomplete_beta: bad arguments");
  if (x == 0.0) return 0.0;
  if (x == 1.0) return 1.0;
  // prefactor x^a (1-x)^b / (a B(a,b)), in logs
  const double log_front =
      std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x);
  const double front = std::exp(log_front);
  if (x < (a + 1.0) / (a + b + 2.0)) return front * beta_continued_fraction(x, a, b) / a;
  // symmetry I_x(a, b) = 1 - I_{1-x}(b, a) where the fraction converges
  return 1.0 - front * beta_continued_fraction(1.0 - x, b, a) / b;
}

double student_t_pdf(double t, double nu) {
  const double log_c =
      std::lgamma(0.5 * (nu + 1.0)) - std::lgamma(0.5 * nu) - 0.5 * std::log(nu * std::numbers::pi);
  return std::exp(log_c - 0.5 * (nu + 1.0) * std::log1p(t * t / nu));
}

double student_t_cdf(double t, double nu) {
  if (!(nu > 0.0)) throw std::invalid_argument("student_t_cdf: nu must be positive");
  if (std::isinf(t)) return t > 0 ? 1.0 : 0.0;
  // A&S 26.7.1: the upper tail is I_x(nu/2, 1/2) / 2 with x = nu / (nu + t^2).
  const double x = nu / (nu + t * t);
  const double tail = 0.5 * regularized_incomplete_beta(x, 0.5 * nu, 0.5);
  return t >= 0.0 ? 1.0 - tail : tail;
}

double student_t_two_sided_p(double t, double nu) {
  const double x = nu / (nu + t * t);
  return regularized_incomplete_beta(x, 0.5 * nu, 0.5);
}

double student_t_quantile(double p, double nu) {
  if (!(p > 0.0 && p < 1.0)) throw std::invalid_argument("student_t_quantile: p not in (0, 1)");
  if (!(nu > 0.0)) throw std::invalid_argument("student_t_quantile: nu must be positive");
  if (p == 0.5) return 0.0;
  // Work in the upper half (symmetry) and bracket the root of F(t) - p.
  const bool upper = p > 0.5;
  const double q = upper ? p : 1.0 - p;
  double lo = 0.0;
  double hi = 1.0;
  while (student_t_cdf(hi, nu) < q) {
    lo = hi;
    hi *= 2.0;
    if (hi > 1e300) break;
  }
  // Newton steps from the bracket midpoint, falling back to bisection when a step leaves it.
  double t = 0.5 * (lo + hi);
  for (int it = 0; it < 200; ++it) {
    const double f = student_t_cdf(t, nu) - q;
    if (f > 0.0)
      hi = t;
    else
      lo = t;
    const double density = student_t_pdf(t, nu);
    double next = density > 0.0 ? t - f / density : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - t) <= 1e-14 * std::max(1.0, std::abs(t))) {
      t = next;
      break;
    }
    t = next;
  }
  return upper ? t : -t;
}

ConfidenceInterval t_interval(double estimate, double standard_error, double dof, double level) {
  const double t = student_t_quantile(0.5 * (1.0 + level), dof);
  return {level, estimate - t * standard_error, estimate + t * standard_error};
}

}  // namespace grainlab::calibrate
