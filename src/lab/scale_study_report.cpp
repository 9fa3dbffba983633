#include "lab/scale_study_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "calibrate/least_squares.hpp"
#include "calibrate/statistics.hpp"
#include "io/output_files.hpp"

namespace grainlab {
namespace {

// The published scale study's fit (reference paper, Eq. 12): sigma = 0.4469 d^2 + 5.311 d +
// 0.3033 with R^2 0.9981, which gives its 313 kPa at d = 2 mm only when read with d in m and
// sigma in MPa (the paper states no units).
double published_fit_Pa(double d) {
  return 1e6 * (0.4469 * d * d + 5.311 * d + 0.3033);
}
constexpr double reference_diameter = 0.002;  // m, the laboratory's beads
constexpr double laboratory_peak = 276.83e3;  // Pa, plane strain, 150 kPa
constexpr double published_peak = 313e3;      // Pa, the published extrapolation to 2 mm
constexpr double confidence = 0.95;

struct Fit {
  calibrate::LinearFit f;
  double r2 = NAN;
  bool ok = false;
};

Fit fit(const std::vector<std::vector<double>>& rows, const std::vector<double>& y) {
  Fit out;
  if (rows.empty() || rows.size() <= rows[0].size()) return out;  // needs one dof at least
  try {
    out.f = calibrate::least_squares(rows, y);
  } catch (const calibrate::RankDeficient&) {
    return out;
  }
  const double m = calibrate::mean(y);
  double sst = 0.0;
  for (double v : y) sst += (v - m) * (v - m);
  out.r2 = sst > 0 ? 1.0 - out.f.ssr / sst : NAN;
  out.ok = true;
  return out;
}

// The fit's value at regressors x0 and the half-width of its confidence interval (of the mean
// response: x0' C x0 with the parameters' covariance C, Student t with the fit's dof).
std::pair<double, double> predict(const Fit& fit, const std::vector<double>& x0) {
  double value = 0.0, variance = 0.0;
  const size_t p = x0.size();
  for (size_t i = 0; i < p; ++i) {
    value += x0[i] * fit.f.coefficients[i];
    for (size_t j = 0; j < p; ++j) variance += x0[i] * fit.f.cov(i, j) * x0[j];
  }
  const double t = calibrate::student_t_quantile(0.5 + 0.5 * confidence, fit.f.dof);
  return {value, t * std::sqrt(std::max(variance, 0.0))};
}

nlohmann::json coefficients_json(const Fit& fit, const std::vector<std::string>& names) {
  nlohmann::json j = nlohmann::json::object();
  if (!fit.ok) return j;
  for (size_t i = 0; i < names.size(); ++i)
    j[names[i]] = {{"value", fit.f.coefficients[i]}, {"standard_error", fit.f.standard_error(i)}};
  j["r_squared"] = fit.r2;
  j["points"] = fit.f.residuals.size();
  return j;
}

nlohmann::json extrapolation_json(const std::pair<double, double>& p) {
  return {{"peak_axial_stress_Pa", p.first},
          {"confidence_half_width_Pa", p.second},
          {"confidence", confidence},
          {"vs_published_313kPa", p.first / published_peak - 1.0},
          {"vs_laboratory_276.83kPa", p.first / laboratory_peak - 1.0}};
}

std::string csv_row(const ScaleRun& r, double sigma3) {
  std::string status = r.status;
  std::replace(status.begin(), status.end(), ',', ';');
  std::replace(status.begin(), status.end(), '\n', ' ');
  return fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},\"{}\"\n", exact(r.diameter),
                     exact(r.gravity), r.name, r.particles, exact(r.size.x), exact(r.size.y),
                     exact(r.size.z), exact(r.peak_axial_stress), exact(r.axial_strain_at_peak),
                     exact(r.peak_axial_stress / sigma3), exact(r.self_weight_ratio),
                     exact(r.max_inertial_number), exact(r.wall_time), status);
}

}  // namespace

std::string write_scale_study_report(const std::vector<ScaleRun>& runs, const ScaleStudyFacts& f,
                                     const std::string& dir, nlohmann::json j) {
  const double s3 = f.confining_stress;
  std::string csv =
      "diameter_m,gravity_m_per_s2,run,particles,width_m,thickness_m,height_m,"
      "peak_axial_stress_Pa,axial_strain_at_peak,peak_over_confining_stress,"
      "self_weight_over_confining_stress,max_inertial_number,wall_time_s,status\n";
  nlohmann::json table = nlohmann::json::array();
  for (const ScaleRun& r : runs) {
    csv += csv_row(r, s3);
    table.push_back({{"diameter_m", r.diameter},
                     {"gravity_m_per_s2", r.gravity},
                     {"run", r.name},
                     {"particles", r.particles},
                     {"size_m", {r.size.x, r.size.y, r.size.z}},
                     {"peak_axial_stress_Pa", r.peak_axial_stress},
                     {"axial_strain_at_peak", r.axial_strain_at_peak},
                     {"peak_over_confining_stress", r.peak_axial_stress / s3},
                     {"self_weight_over_confining_stress", r.self_weight_ratio},
                     {"max_inertial_number", r.max_inertial_number},
                     {"wall_time_s", r.wall_time},
                     {"status", r.status}});
  }
  write_file_atomically(dir + "/scale.csv", csv);

  j["confining_stress_Pa"] = s3;
  j["loading"] = f.loading;
  j["runs"] = table;
  j["published"] = {
      {"fit", "sigma = 0.4469 d^2 + 5.311 d + 0.3033, R^2 0.9981 (Eq. 12)"},
      {"units",
       "d in m and sigma in MPa: the only reading that gives the published 313 kPa at "
       "d = 2 mm (the paper states none)"},
      {"peak_at_2mm_Pa", published_peak}};
  j["laboratory_peak_axial_stress_Pa"] = laboratory_peak;

  // Per gravity setting: the published quadratic form and the dimensional-analysis form on the
  // runs that gave a peak.
  std::string off_text, on_text, published_text, slump_text;
  {
    std::vector<std::string> slumped;
    for (const ScaleRun& r : runs)
      if (r.gravity > 0 && r.status.rfind("not at rest", 0) == 0)
        slumped.push_back(fmt::format("{:g}", r.diameter));
    std::vector<std::string> stopped;
    for (const ScaleRun& r : runs)
      if (r.gravity > 0 && r.status.rfind("the run blew up", 0) == 0)
        stopped.push_back(fmt::format("{:g}", r.diameter));
    if (!stopped.empty())
      slump_text += fmt::format(
          " With gravity at d = {} m the runs stopped before a peak: beads passed the speed "
          "limit as the specimen gave way under its own weight (status column).",
          fmt::join(stopped, ", "));
    if (!slumped.empty())
      slump_text += fmt::format(
          " At d = {} m the specimen was still settling under its own weight at sigma_3 = {:.0f} "
          "kPa when the loading began (flagged, left out of the fits).",
          fmt::join(slumped, ", "), 1e-3 * s3);
  }
  nlohmann::json fits = nlohmann::json::object();
  for (bool on : {false, true}) {
    std::vector<const ScaleRun*> ok;
    for (const ScaleRun& r : runs)
      if ((r.gravity > 0) == on && r.status == "ok") ok.push_back(&r);
    if (ok.empty()) continue;
    std::vector<std::vector<double>> quad, da, slope;
    std::vector<double> peak, ratio;
    std::vector<std::vector<double>> inertial;
    double inertial_per_metre = 0.0;
    double i_at_d_min = NAN, i_at_d_max = NAN;
    double ratio_per_metre = 0.0, i_min = INFINITY, i_max = 0.0, d_min = INFINITY, d_max = 0.0;
    double p_min = INFINITY, p_max = 0.0, p_at_d_min = NAN, p_at_d_max = NAN;
    for (const ScaleRun* r : ok) {
      const double d = r->diameter;
      quad.push_back({d * d, d, 1.0});
      da.push_back(on ? std::vector<double>{1.0, r->self_weight_ratio} : std::vector<double>{1.0});
      slope.push_back({1.0, d});
      const double i = r->max_inertial_number;
      inertial.push_back({1.0, i, i * i});
      inertial_per_metre += i / d / ok.size();
      peak.push_back(r->peak_axial_stress);
      ratio.push_back(r->peak_axial_stress / s3);
      ratio_per_metre += r->self_weight_ratio / d / ok.size();
      i_min = std::min(i_min, r->max_inertial_number),
      i_max = std::max(i_max, r->max_inertial_number);
      if (d < d_min) d_min = d, p_at_d_min = r->peak_axial_stress, i_at_d_min = i;
      if (d > d_max) d_max = d, p_at_d_max = r->peak_axial_stress, i_at_d_max = i;
      p_min = std::min(p_min, r->peak_axial_stress), p_max = std::max(p_max, r->peak_axial_stress);
    }
    const Fit q = fit(quad, peak), a = fit(da, ratio), s = fit(slope, peak);
    nlohmann::json g;
    g["runs"] = ok.size();
    g["published_form"] = coefficients_json(q, {"a_Pa_per_m2", "b_Pa_per_m", "c_Pa"});
    g["dimensional_form"] = coefficients_json(
        a, on ? std::vector<std::string>{"A", "B"} : std::vector<std::string>{"A"});
    g["dimensional_form"]["form"] = on ? "sigma_peak / sigma_3 = A + B rho_bulk g H / sigma_3"
                                       : "sigma_peak / sigma_3 = A (no length scale left)";
    g["peak_against_d"] = coefficients_json(s, {"intercept_Pa", "slope_Pa_per_m"});
    const double spread = (p_max - p_min) / calibrate::mean(peak);
    g["peak_spread"] = spread;
    g["max_inertial_number_range"] = {i_min, i_max};
    nlohmann::json at_2mm = nlohmann::json::object();
    if (q.ok)
      at_2mm["published_form"] = extrapolation_json(
          predict(q, {reference_diameter * reference_diameter, reference_diameter, 1.0}));
    const bool rate_varies = i_max > 2 * i_min;
    if (a.ok && (on || !rate_varies)) {
      auto p = predict(a, on ? std::vector<double>{1.0, ratio_per_metre * reference_diameter}
                             : std::vector<double>{1.0});
      at_2mm["dimensional_form"] = extrapolation_json({s3 * p.first, s3 * p.second});
    }
    if (rate_varies && !on)  // a constant does not describe a peak that follows I
      g["dimensional_form"] = {{"form",
                                "not applicable: the inertial number changes with d (see "
                                "inertial_form)"}};
    // The loading rate: when the inertial number changes with d (a fixed strain rate makes it
    // grow in proportion to d), the dimensional form is a function of I.
    Fit in;
    if (rate_varies && !on) {
      in = fit(inertial, ratio);
      g["inertial_form"] = coefficients_json(in, {"A", "B", "C"});
      g["inertial_form"]["form"] = "sigma_peak / sigma_3 = A + B I + C I^2, I the run's maximum";
      if (in.ok) {
        const double i0 = inertial_per_metre * reference_diameter;
        auto p = predict(in, {1.0, i0, i0 * i0});
        at_2mm["inertial_form"] = extrapolation_json({s3 * p.first, s3 * p.second});
        at_2mm["inertial_form"]["inertial_number"] = i0;
      }
    }
    g["extrapolated_to_2mm"] = at_2mm;
    fits[on ? "gravity_on" : "gravity_off"] = g;

    if (!on && rate_varies) {
      off_text = fmt::format(
          "Without gravity the peak axial stress goes from {:.4g} kPa at d = {:g} m to {:.4g} kPa "
          "at {:g} m while the maximum inertial number goes from {:.2g} to {:.2g} ({}).",
          1e-3 * p_at_d_min, d_min, 1e-3 * p_at_d_max, d_max, i_at_d_min, i_at_d_max, f.loading);
      if (in.ok)
        off_text += fmt::format(
            " sigma_peak / sigma_3 = {:.4g} {:+.4g} I {:+.4g} I^2 (R^2 {:.4f}): the loading rate "
            "makes the peak grow; with the strain rate fixed, I grows in proportion to d, and "
            "the peak with it.",
            in.f.coefficients[0], in.f.coefficients[1], in.f.coefficients[2], in.r2);
      if (q.ok)
        off_text += fmt::format(
            " The published form fitted to these runs: sigma = {:.4g} d^2 {:+.4g} d {:+.4g} (d in "
            "m, sigma in MPa; R^2 {:.4f}), against the published 0.4469 d^2 + 5.311 d + 0.3033.",
            1e-6 * q.f.coefficients[0], 1e-6 * q.f.coefficients[1], 1e-6 * q.f.coefficients[2],
            q.r2);
    } else if (!on) {
      off_text = fmt::format(
          "Without gravity the peak axial stress is {:.1f} kPa (sigma_peak / sigma_3 = {:.3f}) "
          "at every diameter from {:g} to {:g} m: the {} runs spread by {:.2f} %{}, with the "
          "maximum inertial number between {:.2g} and {:.2g}.",
          1e-3 * calibrate::mean(peak), calibrate::mean(ratio), d_min, d_max, ok.size(),
          100 * spread,
          s.ok ? fmt::format(" (slope against d {:+.3g} +- {:.2g} kPa/m)",
                             1e-3 * s.f.coefficients[1], 1e-3 * s.f.standard_error(1))
               : "",
          i_min, i_max);
      // Scale-free: the peaks within 2 % of each other, or no significant trend against d (the
      // slope within two standard errors of 0); the scatter left is rounding amplified by the
      // packing's chaos (sizes a power of two apart scale exactly in floating point and give the
      // same peak, so a few runs can show a "significant" slope of a fraction of a percent).
      const bool scale_free =
          spread < 0.02 || (s.ok && std::abs(s.f.coefficients[1]) < 2 * s.f.standard_error(1));
      off_text += scale_free
                      ? " No trend with d: the test is scale-free, as dimensional analysis says it "
                        "must be when the stiffness scales with d and the inertial number is "
                        "held; the scatter is rounding amplified by the packing's chaos."
                      : " The peak changes with d although the inertial number does not: "
                        "look at the runs (preparation, re-equilibration) before reading a "
                        "trend.";
    } else if (ok.size() >= 2) {
      on_text = fmt::format(
          " With gravity the peak goes from {:.1f} kPa at d = {:g} m to {:.1f} kPa at {:g} m, "
          "where the self-weight ratio rho g H / sigma_3 reaches {:.3g}",
          1e-3 * p_at_d_min, d_min, 1e-3 * p_at_d_max, d_max, ratio_per_metre * d_max);
      if (a.ok)
        on_text += fmt::format(
            "; sigma_peak / sigma_3 = {:.3f} {:+.3f} rho g H / sigma_3 (+- {:.2g}, R^2 {:.4f}): "
            "{}",
            a.f.coefficients[0], a.f.coefficients[1], a.f.standard_error(1), a.r2,
            a.f.coefficients[1] > 2 * a.f.standard_error(1)
                ? "self-weight raises the peak."
                : (a.f.coefficients[1] < -2 * a.f.standard_error(1)
                       ? "self-weight lowers the peak."
                       : "self-weight does not change the peak measurably."));
      else
        on_text += ".";
    }
  }
  // The published fit against our largest size that gave a peak.
  const ScaleRun* largest = nullptr;
  for (const ScaleRun& r : runs)
    if (r.status == "ok" && (!largest || r.diameter > largest->diameter)) largest = &r;
  if (largest && largest->diameter >= 0.1)
    published_text = fmt::format(
        " The published fit (d in m, sigma in MPa) gives {:.4g} MPa at d = {:g} m, {:.3g} times "
        "our peak there ({:.1f} kPa, gravity {}; sigma_3 = {:.0f} kPa, {}).",
        1e-6 * published_fit_Pa(largest->diameter), largest->diameter,
        published_fit_Pa(largest->diameter) / largest->peak_axial_stress,
        1e-3 * largest->peak_axial_stress, largest->gravity > 0 ? "on" : "off", 1e-3 * s3,
        f.loading);
  j["fits"] = fits;
  const std::string explanation = off_text + on_text + slump_text + published_text;
  j["explanation"] = explanation;
  write_file_atomically(dir + "/summary.json", j.dump(2) + "\n");
  return explanation;
}

}  // namespace grainlab
