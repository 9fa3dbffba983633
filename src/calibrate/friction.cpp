#include "calibrate/friction.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <set>

#include "calibrate/input_error.hpp"
#include "calibrate/least_squares.hpp"

namespace grainlab::calibrate {
namespace {

std::string join_speeds(const std::vector<FrictionAtSpeed>& speeds) {
  std::vector<std::string> s;
  for (const auto& a : speeds) s.push_back(fmt::format("{:g}", a.speed_mm_per_min));
  return fmt::format("{}", fmt::join(s, ", "));
}

// Plausible ranges of a sliding-friction bench test: dry friction coefficients up to about 1.5
// (rubber on rough surfaces), loads and forces up to a few kN on a laboratory slider.
constexpr double max_plausible_friction = 1.5;
constexpr double max_plausible_force_n = 1e4;
constexpr double min_r_squared = 0.9;
constexpr size_t max_point_warnings = 5;

void add_plausibility_warnings(FrictionAnalysis& a) {
  size_t point_warnings = 0, more = 0;
  auto point_warning = [&](std::string w) {
    if (point_warnings++ < max_point_warnings)
      a.warnings.push_back(std::move(w));
    else
      ++more;
  };
  for (const FrictionMaterial& m : a.materials) {
    for (const FrictionAtSpeed& s : m.speeds) {
      for (const LoadPoint& p : s.points) {
        if (p.normal_load_n > max_plausible_force_n || p.friction_force_n > max_plausible_force_n)
          point_warning(fmt::format(
              "{} line {}: a load of {:.4g} N / a force of {:.4g} N is beyond a sliding-friction "
              "bench ({:g} N); are the units N?",
              a.source, p.line, p.normal_load_n, p.friction_force_n, max_plausible_force_n));
        else if (p.friction_force_n > max_plausible_friction * p.normal_load_n)
          point_warning(fmt::format(
              "{} line {}: F / P = {:.3g}, above any dry friction coefficient ({:g}); are F and "
              "P in the same unit and in the right columns?",
              a.source, p.line, p.friction_force_n / p.normal_load_n, max_plausible_friction));
      }
      if (!(s.origin.slope > 0 && s.origin.slope <= max_plausible_friction))
        a.warnings.push_back(fmt::format("{} at {:g} mm/min: mu = {:.4g} is outside (0, {:g}]",
                                         m.material, s.speed_mm_per_min, s.origin.slope,
                                         max_plausible_friction));
      if (!(s.origin.r_squared >= min_r_squared))
        a.warnings.push_back(fmt::format(
            "{} at {:g} mm/min: the F-P line explains little of the scatter (R^2 = {:.3g} < "
            "{:g}); mu is not reliable there",
            m.material, s.speed_mm_per_min, s.origin.r_squared, min_r_squared));
    }
    if (m.speed_fit && !(m.speed_fit->quasi_static.value > 0 &&
                         m.speed_fit->quasi_static.value <= max_plausible_friction))
      a.warnings.push_back(fmt::format("{}: the quasi-static mu = {:.4g} is outside (0, {:g}]",
                                       m.material, m.speed_fit->quasi_static.value,
                                       max_plausible_friction));
  }
  if (more) a.warnings.push_back(fmt::format("... and {} more lines like these", more));
}

}  // namespace

FrictionAnalysis analyse_friction(const CsvTable& table, const FrictionOptions& options) {
  if (!(options.breakpoint_mm_per_min > 0.0))
    throw InputError(fmt::format("the speed breakpoint must be positive (got {} mm/min)",
                                 options.breakpoint_mm_per_min));
  const std::size_t c_material = table.column("material");
  const std::size_t c_speed = table.column("speed_mm_per_min");
  const std::size_t c_load = table.column("normal_load_N");
  const std::size_t c_force = table.column("friction_force_N");

  FrictionAnalysis analysis;
  analysis.source = table.file_name();
  analysis.options = options;
  for (const CsvRecord& rec : table.records()) {
    std::string material = table.text(rec, c_material);
    if (auto it = options.rename.find(material); it != options.rename.end()) material = it->second;
    const LoadPoint p{rec.line, table.number(rec, c_speed), table.number(rec, c_load),
                      table.number(rec, c_force)};
    if (!(p.speed_mm_per_min > 0.0))
      throw InputError(fmt::format("{}: speed_mm_per_min = {} must be positive", table.where(rec),
                                   p.speed_mm_per_min));
    if (!(p.normal_load_n > 0.0))
      throw InputError(fmt::format("{}: normal_load_N = {} must be positive", table.where(rec),
                                   p.normal_load_n));
    if (p.friction_force_n < 0.0)
      throw InputError(fmt::format("{}: friction_force_N = {} is negative", table.where(rec),
                                   p.friction_force_n));
    auto m = std::find_if(analysis.materials.begin(), analysis.materials.end(),
                          [&](const FrictionMaterial& x) { return x.material == material; });
    if (m == analysis.materials.end()) {
      analysis.materials.push_back({material, {}, std::nullopt, {}});
      m = std::prev(analysis.materials.end());
    }
    auto s = std::find_if(m->speeds.begin(), m->speeds.end(), [&](const FrictionAtSpeed& x) {
      return x.speed_mm_per_min == p.speed_mm_per_min;
    });
    if (s == m->speeds.end()) {
      m->speeds.push_back({p.speed_mm_per_min, {}, {}, {}});
      s = std::prev(m->speeds.end());
    }
    s->points.push_back(p);
  }

  for (FrictionMaterial& m : analysis.materials) {
    std::sort(m.speeds.begin(), m.speeds.end(),
              [](const auto& a, const auto& b) { return a.speed_mm_per_min < b.speed_mm_per_min; });
    std::vector<LoadPoint> all;
    for (FrictionAtSpeed& s : m.speeds) {
      std::set<double> loads;
      for (const auto& p : s.points) loads.insert(p.normal_load_n);
      if (loads.size() < 2) {
        std::vector<std::size_t> lines;
        for (const auto& p : s.points) lines.push_back(p.line);
        throw InputError(fmt::format(
            "{} line {}: {} at {:g} mm/min has only one normal load (P = {:g} N, line{} {}); an "
            "F-P fit needs at least two different loads",
            table.file_name(), lines.front(), m.material, s.speed_mm_per_min, *loads.begin(),
            lines.size() > 1 ? "s" : "", fmt::join(lines, ", ")));
      }
      s.origin = fit_through_origin(s.points, options.level);
      s.free = fit_free_intercept(s.points, options.level);
      all.insert(all.end(), s.points.begin(), s.points.end());
    }
    try {
      m.speed_fit = fit_speed_curve(all, options.breakpoint_mm_per_min, options.level);
    } catch (const RankDeficient&) {
      m.speed_fit_note = fmt::format(
          "no speed fit: a curve quadratic below {0:g} mm/min and linear above needs at least "
          "three different speeds at or below {0:g} mm/min (or two below it and two above); "
          "{1} has {2} mm/min",
          options.breakpoint_mm_per_min, m.material, join_speeds(m.speeds));
    }
  }
  add_plausibility_warnings(analysis);
  return analysis;
}

}  // namespace grainlab::calibrate
