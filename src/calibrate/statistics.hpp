// Descriptive statistics and Student's t distribution for the calibration analyses.
//
// The t quantile is computed here (no statistics library): the t CDF is written through the
// regularized incomplete beta function, F(t; nu) = 1 - I_x(nu/2, 1/2) / 2 for t >= 0 with
// x = nu / (nu + t^2) (Abramowitz & Stegun 26.7.1 / 26.5.27), I_x is evaluated by its continued
// fraction (A&S 26.5.8, modified Lentz algorithm), and the CDF is inverted by safeguarded
// Newton iterations (the density is known in closed form).
#pragma once

#include <span>

namespace grainlab::calibrate {

double mean(std::span<const double> values);
// Sample standard deviation (n - 1 in the denominator); needs n >= 2.
double sample_sd(std::span<const double> values);

// Regularized incomplete beta function I_x(a, b), a, b > 0, 0 <= x <= 1.
double regularized_incomplete_beta(double x, double a, double b);

// Student t distribution with nu > 0 degrees of freedom.
double student_t_pdf(double t, double nu);
double student_t_cdf(double t, double nu);
double student_t_quantile(double p, double nu);  // 0 < p < 1
// Two-sided p-value of a t statistic: P(|T| >= |t|).
double student_t_two_sided_p(double t, double nu);

// A two-sided confidence interval of a mean (or a fitted parameter) from its standard error.
struct ConfidenceInterval {
  double level = 0.95;
  double low = 0.0;
  double high = 0.0;
  double half_width() const { return 0.5 * (high - low); }
  bool contains(double x) const { return low <= x && x <= high; }
};

// A fitted or derived quantity with its standard error and confidence interval.
struct Estimate {
  double value = 0.0;
  double standard_error = 0.0;
  ConfidenceInterval ci;
};

// estimate +- t_{(1+level)/2, dof} * standard_error.
ConfidenceInterval t_interval(double estimate, double standard_error, double dof,
                              double level = 0.95);

}  // namespace grainlab::calibrate
