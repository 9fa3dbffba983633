#include "calibrate/restitution.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

#include "calibrate/input_error.hpp"

namespace grainlab::calibrate {

RestitutionResult summarise_throws(std::string material, std::vector<Throw> throws, double level) {
  RestitutionResult r;
  r.material = std::move(material);
  r.throws = std::move(throws);
  r.n = r.throws.size();
  std::vector<double> e;
  for (const Throw& t : r.throws) e.push_back(t.restitution);
  r.mean = calibrate::mean(e);
  if (r.n >= 2) {
    r.sd = sample_sd(e);
    r.standard_error = r.sd / std::sqrt(static_cast<double>(r.n));
    // The mean of n throws: t interval with n - 1 degrees of freedom.
    r.ci = t_interval(r.mean, r.standard_error, static_cast<double>(r.n - 1), level);
  } else {
    r.sd = std::numeric_limits<double>::quiet_NaN();
    r.standard_error = std::numeric_limits<double>::quiet_NaN();
    r.ci = {level, r.mean, r.mean};
  }
  return r;
}

RestitutionAnalysis analyse_throws(const CsvTable& table,
                                   const std::map<std::string, std::string>& rename, double level) {
  const std::size_t c_material = table.column("material");
  // Heights in metres (H_m, h_m) or in millimetres (H_mm, h_mm).
  const bool in_mm = !table.find_column("H_m") && !table.find_column("h_m") &&
                     (table.find_column("H_mm") || table.find_column("h_mm"));
  const double scale = in_mm ? 1e-3 : 1.0;
  const std::string launch_name = in_mm ? "H_mm" : "H_m";
  const std::string rebound_name = in_mm ? "h_mm" : "h_m";
  const std::size_t c_launch = table.column(launch_name);
  const std::size_t c_rebound = table.column(rebound_name);

  RestitutionAnalysis analysis;
  analysis.source = table.file_name();
  std::vector<std::pair<std::string, std::vector<Throw>>> groups;
  for (const CsvRecord& rec : table.records()) {
    std::string material = table.text(rec, c_material);
    if (auto it = rename.find(material); it != rename.end()) material = it->second;
    const double launch = table.number(rec, c_launch);
    const double rebound = table.number(rec, c_rebound);
    if (!(launch > 0.0))
      throw InputError(
          fmt::format("{}: {} = {} must be positive", table.where(rec), launch_name, launch));
    if (!(rebound > 0.0))
      throw InputError(
          fmt::format("{}: {} = {} must be positive (a throw without a rebound "
                      "cannot be analysed; leave it out)",
                      table.where(rec), rebound_name, rebound));
    if (rebound > launch)
      throw InputError(
          fmt::format("{}: {} = {} is larger than {} = {} (a rebound cannot exceed the drop)",
                      table.where(rec), rebound_name, rebound, launch_name, launch));
    Throw t{rec.line, launch * scale, rebound * scale, std::sqrt(rebound / launch)};
    auto g = std::find_if(groups.begin(), groups.end(),
                          [&](const auto& grp) { return grp.first == material; });
    if (g == groups.end()) {
      groups.push_back({material, {}});
      g = std::prev(groups.end());
    }
    g->second.push_back(t);
  }
  for (auto& [material, throws] : groups)
    analysis.materials.push_back(summarise_throws(material, std::move(throws), level));
  return analysis;
}

}  // namespace grainlab::calibrate
