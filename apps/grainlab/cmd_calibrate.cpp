// `grainlab calibrate restitution|friction`: analysis of laboratory measurements
// (docs/calibration.md, src/calibrate/). Prints tables like the published Tables 3 and 4 (or JSON
// with
// --json), optionally plots them and writes the [[pair]] entries `grainlab run` reads.
#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "calibrate/csv_table.hpp"
#include "calibrate/friction.hpp"
#include "calibrate/input_error.hpp"
#include "calibrate/materials_out.hpp"
#include "calibrate/plot.hpp"
#include "calibrate/report.hpp"
#include "calibrate/restitution.hpp"
#include "calibrate/trajectory.hpp"
#include "command.hpp"

namespace grainlab::app {
namespace {

using namespace grainlab::calibrate;

// Options shared by both analyses.
struct CommonOptions {
  bool json = false;
  std::string plot_path;
  std::string materials_out;
  std::string bead_material = "glass";
  std::vector<std::string> rename;
  double level = 0.95;
};

struct RestitutionOptions {
  CommonOptions common;
  std::string throws_csv;
  std::string trajectory_csv;
  double plate_z_m = 0.0;
  std::optional<double> gravity;
  std::string material;  // trajectory mode: the plate material, for --materials-out
};

struct FrictionCliOptions {
  CommonOptions common;
  std::string slide_csv;
  double breakpoint_mm_per_min = 5.0;
  std::optional<double> at_speed_mm_per_min;
};

void add_common(CLI::App* sub, CommonOptions& o) {
  sub->add_flag("--json", o.json, "print the results as JSON instead of tables");
  sub->add_option("--plot", o.plot_path, "write a plot of the analysis (PNG, matplotlib)");
  sub->add_option("--materials-out", o.materials_out,
                  "write/merge the [[pair]] entries for `grainlab run` into this TOML file");
  sub->add_option("--bead-material", o.bead_material,
                  "the bead's material name in the [[pair]] entries")
      ->capture_default_str();
  sub->add_option("--rename", o.rename,
                  "FROM=TO: call the CSV material FROM by the scene's name TO (repeatable)")
      ->allow_extra_args(false);
  sub->add_option("--level", o.level, "confidence level of the intervals")
      ->capture_default_str()
      ->check(CLI::Range(0.5, 0.9999));
}

std::map<std::string, std::string> parse_renames(const std::vector<std::string>& items) {
  std::map<std::string, std::string> out;
  for (const auto& item : items) {
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == item.size())
      throw InputError(fmt::format("--rename {}: expected FROM=TO", item));
    out[item.substr(0, eq)] = item.substr(eq + 1);
  }
  return out;
}

std::string ci_text(const ConfidenceInterval& ci) {
  if (!std::isfinite(ci.low) || ci.low == ci.high) return "no CI";
  return fmt::format("{:g} % CI [{:.4f}, {:.4f}]", 100.0 * ci.level, ci.low, ci.high);
}

// Prints the report, writes the materials file, draws the plot: in that order, so a failing
// analysis writes nothing.
int finish(const CommonOptions& o, const std::string& text, const nlohmann::json& doc,
           const std::vector<PairUpdate>& updates) {
  if (o.json)
    std::cout << doc.dump(2) << "\n";
  else
    std::cout << text;
  std::cout.flush();
  if (!o.materials_out.empty() && updates.empty()) {
    fmt::print(stderr, "grainlab: warning: no calibrated value to write; {} not written\n",
               o.materials_out);
  } else if (!o.materials_out.empty()) {
    write_materials_toml(o.materials_out, updates);
    std::size_t n = 0;
    for (const auto& u : updates) n += u.values.size();
    fmt::print(stderr, "grainlab: wrote {} value{} to {}\n", n, n == 1 ? "" : "s", o.materials_out);
  }
  if (!o.plot_path.empty()) {
    plot_analysis(doc, o.plot_path);
    fmt::print(stderr, "grainlab: wrote the plot {}\n", o.plot_path);
  }
  return exit_ok;
}

int run_restitution(const RestitutionOptions& o) {
  const bool trajectory = !o.trajectory_csv.empty();
  if (trajectory == !o.throws_csv.empty())
    throw InputError("give either a throws table (THROWS.csv) or --trajectory TRACK.csv");
  if (trajectory && !o.common.materials_out.empty() && o.material.empty())
    throw InputError("--materials-out with --trajectory needs --material NAME (the plate's)");
  std::vector<PairUpdate> updates;
  if (trajectory) {
    const CsvTable table = CsvTable::read(o.trajectory_csv);
    TrajectoryOptions topt;
    topt.plate_z_m = o.plate_z_m;
    topt.gravity = o.gravity;
    topt.level = o.common.level;
    const TrajectoryResult r = analyse_trajectory(read_track(table), o.trajectory_csv, topt);
    for (const auto& w : r.warnings) fmt::print(stderr, "grainlab: warning: {}\n", w);
    if (!o.material.empty())
      updates.push_back(
          {o.common.bead_material,
           o.material,
           {{"restitution", r.e_velocity.value,
             fmt::format("e = -v_after/v_before from the tracked throw {} ({} + {} points, {})",
                         o.trajectory_csv, r.n_before, r.n_after, ci_text(r.e_velocity.ci))}}});
    return finish(o.common, trajectory_text(r), trajectory_json(r), updates);
  }
  const CsvTable table = CsvTable::read(o.throws_csv);
  const RestitutionAnalysis a =
      analyse_throws(table, parse_renames(o.common.rename), o.common.level);
  for (const auto& m : a.materials)
    updates.push_back({o.common.bead_material,
                       m.material,
                       {{"restitution", m.mean,
                         fmt::format("mean e = sqrt(h/H) of {} throws in {} (sd {:.4f}, {})", m.n,
                                     o.throws_csv, m.sd, ci_text(m.ci))}}});
  return finish(o.common, restitution_text(a), restitution_json(a), updates);
}

int run_friction(const FrictionCliOptions& o) {
  const CsvTable table = CsvTable::read(o.slide_csv);
  FrictionOptions fopt;
  fopt.breakpoint_mm_per_min = o.breakpoint_mm_per_min;
  fopt.level = o.common.level;
  fopt.rename = parse_renames(o.common.rename);
  const FrictionAnalysis a = analyse_friction(table, fopt);
  std::vector<PairUpdate> updates;
  for (const auto& m : a.materials) {
    if (o.at_speed_mm_per_min) {
      const FrictionAtSpeed* s = nullptr;
      for (const auto& x : m.speeds)
        if (std::abs(x.speed_mm_per_min - *o.at_speed_mm_per_min) <= 1e-9 * x.speed_mm_per_min)
          s = &x;
      if (!s)
        throw InputError(fmt::format("--at-speed {:g}: {} was not tested at that speed",
                                     *o.at_speed_mm_per_min, m.material));
      updates.push_back(
          {o.common.bead_material,
           m.material,
           {{"friction", s->origin.slope,
             fmt::format("F-P slope through the origin at {:g} mm/min in {} ({} points, {})",
                         s->speed_mm_per_min, o.slide_csv, s->origin.n, ci_text(s->origin.ci))}}});
      continue;
    }
    if (!m.speed_fit) {
      fmt::print(stderr, "grainlab: warning: {}\n", m.speed_fit_note);
      if (!o.common.materials_out.empty())
        fmt::print(stderr,
                   "grainlab: warning: no quasi-static friction for {}: not written to {} (use "
                   "--at-speed V to write the value at a tested speed)\n",
                   m.material, o.common.materials_out);
      continue;
    }
    const SpeedFit& f = *m.speed_fit;
    updates.push_back(
        {o.common.bead_material,
         m.material,
         {{"friction", f.quasi_static.value,
           fmt::format("quasi-static mu(V -> 0) of the speed fit to {} ({} points at {} speeds, "
                       "breakpoint {:g} mm/min, {})",
                       o.slide_csv, f.n, m.speeds.size(), f.breakpoint_mm_per_min,
                       ci_text(f.quasi_static.ci))}}});
  }
  return finish(o.common, friction_text(a), friction_json(a), updates);
}

// InputError (bad data or options) -> exit 2 with the message; the rest goes to main (exit 1).
template <class F>
int guarded(F&& f) {
  try {
    return f();
  } catch (const InputError& e) {
    fmt::print(stderr, "grainlab: error: {}\n", e.what());
    return exit_bad_input;
  }
}

}  // namespace

Command add_calibrate_command(CLI::App& app) {
  CLI::App* sub = app.add_subcommand(
      "calibrate",
      "analyse laboratory measurements (restitution, friction); see docs/calibration.md");
  sub->require_subcommand(1);

  auto ro = std::make_shared<RestitutionOptions>();
  CLI::App* rest = sub->add_subcommand(
      "restitution", "restitution coefficients from flat throws (material,H_m,h_m) or a track");
  rest->add_option("throws", ro->throws_csv, "CSV of throws: material,H_m,h_m (or H_mm,h_mm)");
  rest->add_option("--trajectory", ro->trajectory_csv,
                   "CSV of a camera-tracked throw: t_s,x_m,z_m (instead of a throws table)");
  rest->add_option("--plate-z", ro->plate_z_m, "height of the plate in the track (m)")
      ->capture_default_str();
  rest->add_option("--g", ro->gravity, "fix gravity (m/s^2) instead of fitting it");
  rest->add_option("--material", ro->material,
                   "with --trajectory: the plate's material name (for --materials-out)");
  add_common(rest, ro->common);

  auto fo = std::make_shared<FrictionCliOptions>();
  CLI::App* fric = sub->add_subcommand(
      "friction",
      "friction coefficients from material,speed_mm_per_min,normal_load_N,friction_force_N");
  fric->add_option("slide", fo->slide_csv, "CSV of the sliding-friction test")->required();
  fric->add_option("--breakpoint", fo->breakpoint_mm_per_min,
                   "speed (mm/min) where the speed fit turns from quadratic to linear")
      ->capture_default_str();
  fric->add_option("--at-speed", fo->at_speed_mm_per_min,
                   "write mu at this tested speed (mm/min) to --materials-out instead of the "
                   "quasi-static value");
  add_common(fric, fo->common);

  return {sub, [rest, fric, ro, fo]() -> int {
            if (rest->parsed()) return guarded([&] { return run_restitution(*ro); });
            if (fric->parsed()) return guarded([&] { return run_friction(*fo); });
            return exit_bad_input;
          }};
}

}  // namespace grainlab::app
