// `[test] type = "sliding_friction"`: reads the test, runs it (and the inverse search for the
// input friction that reproduces a measured apparent one), writes the results.
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "contact/time_step.hpp"
#include "grainlab/version.hpp"
#include "io/config_error.hpp"
#include "io/interrupt.hpp"
#include "io/output_files.hpp"
#include "io/progress.hpp"
#include "io/scene_builder.hpp"
#include "io/summary_header.hpp"
#include "io/toml_reader.hpp"
#include "lab/lab_config.hpp"
#include "lab/lab_test.hpp"
#include "lab/sliding_friction.hpp"
#include "lab/sliding_friction_checkpoint.hpp"

namespace grainlab {
namespace {

std::vector<double> read_loads(TableReader& t) {
  const toml::node* n = t.node("loads");
  if (!n) return SlidingFrictionSettings{}.loads;
  const toml::array* a = n->as_array();
  if (!a || a->empty())
    t.fail("loads", "expected a list of normal loads, e.g. [\"0.1 N\", \"0.2 N\"]");
  std::vector<double> loads;
  for (const toml::node& item : *a) {
    double v = 0.0;
    if (auto x = item.value<double>())
      v = *x;
    else if (auto s = item.value<std::string>()) {
      try {
        v = parse_quantity(*s, Quantity::force);
      } catch (const std::invalid_argument& e) {
        t.fail("loads", e.what());
      }
    }
    if (!(v > 0.0)) t.fail("loads", "expected normal loads > 0 N");
    loads.push_back(v);
  }
  return loads;
}

nlohmann::json result_json(const SlidingFrictionResult& r) {
  nlohmann::json runs = nlohmann::json::array();
  for (const LoadRun& run : r.runs)
    runs.push_back({{"normal_load_N", run.load},
                    {"mean_sliding_force_N", run.mean_force},
                    {"sliding_force_sd_N", run.force_sd},
                    {"ratio_F_over_P", run.mean_force / run.load}});
  return {{"friction_input", r.friction_input},
          {"friction_apparent", r.friction_apparent},
          {"friction_apparent_standard_error", r.friction_apparent_se},
          {"r_squared", r.r_squared},
          {"bead_count", r.bead_count},
          {"bed_height_m", r.bed_height},
          {"time_step_s", r.time_step},
          {"loads", runs}};
}

// Below this, an F-P fit is no measurement of the friction.
constexpr double min_r_squared = 0.9;

}  // namespace

void run_sliding_friction(const std::string& path, const toml::table& root,
                          const RunOptions& options) {
  const SceneConfig c = read_lab_materials(path, root);
  TableReader t = test_table_reader(path, root);
  SlidingFrictionSettings s;
  s.bead_material = t.string_or("bead_material", "glass");
  s.slider_material = t.string("slider_material");
  s.diameter = t.number_or("diameter", Quantity::length, s.diameter);
  s.bed_length = t.number_or("bed_length", Quantity::length, s.bed_length);
  s.bed_width = t.number_or("bed_width", Quantity::length, s.bed_width);
  s.slider_length = t.number_or("slider_length", Quantity::length, s.slider_length);
  // Without a slider_length the slider covers the bed (the interface shear test, the default).
  s.slider_covers_bed = t.boolean_or("slider_covers_bed", !t.has("slider_length"));
  if (s.slider_covers_bed && t.has("slider_length"))
    t.fail("slider_length", "not with slider_covers_bed = true (the length is then derived)");
  s.slider_side_gap = t.number_or("slider_side_gap", Quantity::length, s.slider_side_gap);
  s.layers = static_cast<int>(t.integer_or("layers", s.layers));
  s.loads = read_loads(t);
  s.speed = t.number_or("speed", Quantity::velocity, s.speed);
  s.slide_distance = t.number_or("slide_distance", Quantity::length, s.slide_distance);
  s.spring_stiffness = t.number_or("spring_stiffness", Quantity::dimensionless, s.spring_stiffness);
  s.slider_mass = t.number_or("slider_mass", Quantity::mass, s.slider_mass);
  s.fixed_bed = t.boolean_or("fixed_bed", false);
  s.dt_fraction = t.number_or("dt_fraction", Quantity::dimensionless, s.dt_fraction);
  s.gravity = t.number_or("gravity", Quantity::acceleration, s.gravity);
  s.seed = static_cast<unsigned long>(t.integer_or("seed", 1));
  const std::optional<double> target =
      t.optional_number("target_friction", Quantity::dimensionless);
  const double tolerance = t.number_or("target_tolerance", Quantity::dimensionless, 0.002);
  if (!(s.diameter > 0)) t.fail("diameter", "expected a bead diameter > 0 m");
  if (!(s.bed_length >= 8 * s.diameter && s.bed_width >= 4 * s.diameter))
    t.fail("bed_length", "the bed must be at least 8 bead diameters long and 4 wide");
  if (s.slider_side_gap >= 0.5 * 0.99 * s.diameter)
    t.fail("slider_side_gap",
           "expected a clearance below a bead radius (a bead could wedge between the slider and "
           "the side wall)");
  if (s.layers < 1 || s.layers > 20) t.fail("layers", "expected 1 to 20 layers");
  if (!(s.speed > 0)) t.fail("speed", "expected a pulling speed > 0 m/s");
  if (!(s.slider_length >= 2 * s.diameter))
    t.fail("slider_length", "expected at least two bead diameters");
  if (s.slider_covers_bed) s.slider_length = s.bed_length + s.slide_distance + 2 * s.diameter;
  if (!(s.slide_distance > 0 &&
        (s.slider_covers_bed ||
         s.slider_length + s.slide_distance + 2 * s.diameter <= s.bed_length)))
    t.fail(
        "slide_distance",
        "expected a distance > 0 with slider_length + slide_distance + 2 diameters <= bed_length");
  if (!(s.spring_stiffness > 0)) t.fail("spring_stiffness", "expected a rope stiffness > 0 N/m");
  if (!(s.slider_mass > 0)) t.fail("slider_mass", "expected a slider mass > 0 kg");
  if (!(s.dt_fraction > 0 && s.dt_fraction <= 0.3))
    t.fail("dt_fraction", "expected a fraction of t_c in (0, 0.3]");
  if (target && !(*target > 0 && *target < 2))
    t.fail("target_friction", "expected an apparent friction in (0, 2)");
  if (target && s.loads.size() < 2) t.fail("loads", "the inverse mode needs at least two loads");
  PairTable table = build_pair_table(c);
  const int bead = lab_material(t, table, "bead_material", s.bead_material);
  const int slider = lab_material(t, table, "slider_material", s.slider_material);
  if (!c.materials[bead].density) t.fail("bead_material", "the bead material needs a density");
  require_pair(t, table, "bead_material", bead, bead);
  require_pair(t, table, "slider_material", bead, slider);
  const double pull_steps =
      s.slide_distance / s.speed / sliding_time_step(s, table, *c.materials[bead].density);
  if (!(pull_steps <= max_steps_per_run))
    t.fail("speed", fmt::format("a pull of slide_distance / speed would take {:.3g} steps, more "
                                "than grainlab runs ({:.0e})",
                                pull_steps, max_steps_per_run));
  const double checkpoint_interval =
      t.number_or("checkpoint_interval", Quantity::time, default_checkpoint_interval_s);
  if (!(checkpoint_interval > 0))
    t.fail("checkpoint_interval", "expected a wall-time interval > 0 s");
  t.finish();

  // Checkpoints (DIR/checkpoint.bin) every checkpoint_interval and on Ctrl-C; a resumed run
  // takes what was done from them.
  const std::string checkpoint_path = options.out_dir + "/checkpoint.bin";
  const bool resuming = !options.resumed_config.empty();
  if (resuming)
    continue_in_output_dir(options.out_dir);
  else
    prepare_output_dir(options.out_dir, options.overwrite);
  SlidingFrictionCheckpoints checkpoints =
      resuming
          ? SlidingFrictionCheckpoints::resume(checkpoint_path, checkpoint_interval, bead, table)
          : SlidingFrictionCheckpoints(checkpoint_path, {"sliding_friction", path, read_file(path)},
                                       checkpoint_interval);
  if (resuming && !options.quiet)
    fmt::print(stderr, "sliding friction: resuming from {}: {}\n", checkpoint_path,
               checkpoints.describe());
  install_interrupt_handler();
  const double density = *c.materials[bead].density;
  Progress progress("sliding friction", options.quiet, 2.0);
  SlidingFrictionResult r = simulate_sliding_friction(s, table, density, &progress, &checkpoints);

  nlohmann::json j = summary_header(path);
  j.update(result_json(r));
  j["test"] = "sliding_friction";
  j["pulling_speed_m_per_s"] = s.speed;
  j["fixed_bed"] = s.fixed_bed;
  std::string csv = "normal_load_N,t_s,pulled_m,rope_force_N,slider_z_m\n";
  for (const LoadRun& run : r.runs)
    for (const auto& row : run.record)
      csv += fmt::format("{},{},{},{},{}\n", run.load, exact(row[0]), exact(row[1]), exact(row[2]),
                         exact(row[3]));

  if (target) {
    // Inverse mode: find the input mu_s whose apparent friction is the measured one. The
    // apparent friction grows with mu_s; the bracket is widened until it holds the target, then
    // narrowed by regula falsi, each evaluation a full set of loads on the same bed.
    nlohmann::json iterations = nlohmann::json::array();
    // Each trial's apparent friction carries the standard error of its F-P fit: the search stops
    // once a trial is within `target_tolerance` or within two of its own standard errors (a
    // closer answer is not resolved by the simulated test's scatter).
    double last_se = 0.0;
    auto record = [&](double mu, const SlidingFrictionResult& tr) {
      iterations.push_back({{"friction_input", mu},
                            {"friction_apparent", tr.friction_apparent},
                            {"friction_apparent_standard_error", tr.friction_apparent_se},
                            {"r_squared", tr.r_squared}});
      last_se = tr.friction_apparent_se;
      if (!options.quiet)
        fmt::print(stderr, "inverse: mu_s = {:.4f} -> apparent {:.4f} +- {:.4f}\n", mu,
                   tr.friction_apparent, tr.friction_apparent_se);
      return tr.friction_apparent - *target;
    };
    auto apparent_for = [&](double mu) {
      PairProperties p;
      const PairParams& q = table(bead, slider);
      p.restitution = q.restitution;
      p.friction = mu;
      p.rns = q.rns;
      p.rzs = q.rzs;
      p.arf = q.arf;
      PairTable trial = table;
      trial.set(bead, slider, p);
      return record(mu, simulate_sliding_friction(s, trial, density, nullptr, &checkpoints));
    };
    // The lower end is not run: at mu_s = 0 the face carries no tangential force, and the little
    // the slider's edge adds is taken as zero.
    double lo = 0.0, f_lo = -*target;
    double hi = r.friction_input, f_hi = record(hi, r);
    double best = hi, best_f = std::abs(f_hi), best_se = last_se;
    auto resolved = [&] { return best_f <= std::max(tolerance, 2.0 * best_se); };
    while (f_hi < 0 && hi < 1.5) {
      lo = hi, f_lo = f_hi;
      hi = std::min(1.5, 2.0 * hi + 0.05);
      f_hi = apparent_for(hi);
      if (std::abs(f_hi) < best_f) best = hi, best_f = std::abs(f_hi), best_se = last_se;
    }
    const bool reached = f_hi >= 0;
    // Regula falsi, Illinois variant: when the same end of the bracket is kept twice, its value is
    // halved so the next point moves towards it (exact in one step for a linear mapping).
    int kept = 0;  // -1: lo was replaced last, +1: hi was replaced last
    for (int it = 0; reached && it < 12 && !resolved(); ++it) {
      const double mid = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
      const double f = apparent_for(mid);
      if (std::abs(f) < best_f) best = mid, best_f = std::abs(f), best_se = last_se;
      if (f < 0) {
        lo = mid, f_lo = f;
        if (kept == -1) f_hi *= 0.5;
        kept = -1;
      } else {
        hi = mid, f_hi = f;
        if (kept == 1) f_lo *= 0.5;
        kept = 1;
      }
    }
    j["inverse"] = {{"target_friction_apparent", *target},
                    {"tolerance", tolerance},
                    {"reached", reached && resolved()},
                    {"friction_input_found", best},
                    {"apparent_error", best_f},
                    {"apparent_standard_error", best_se},
                    {"iterations", iterations}};
    if (!options.quiet)
      fmt::print(
          "inverse: input friction {:.4f} reproduces the apparent friction {:.4f} (off by {:.4f}, "
          "standard error {:.4f}){}\n",
          best, *target, best_f, best_se,
          reached ? "" : " -- target not reachable below mu_s = 1.5");
  }
  // The apparent friction is the test's whole point: a fit that explains little of F against P,
  // or a slope <= 0, is no measurement (the bed too small or the pull too short for steady
  // sliding). Written with a warning, and the run fails.
  const bool unreliable = !(r.r_squared >= min_r_squared && r.friction_apparent > 0);
  if (unreliable)
    j["warning"] =
        fmt::format("unreliable: the F-P fit has R^2 = {:.3g} (below {}) or a slope <= 0 ({:.3g})",
                    r.r_squared, min_r_squared, r.friction_apparent);
  j["wall_time_s"] = checkpoints.wall_time();
  write_file_atomically(options.out_dir + "/force_time.csv", csv);
  write_file_atomically(options.out_dir + "/summary.json", j.dump(2) + "\n");
  // A finished run has nothing to resume.
  std::error_code ec;
  std::filesystem::remove(checkpoint_path, ec);
  if (unreliable)
    throw UnreliableResult(fmt::format(
        "{}: the apparent friction {:.4g} is not a measurement: its F-P fit has R^2 = {:.3g} "
        "(needs >= {}) and the slope must be > 0. The slider did not reach steady sliding: use a "
        "longer test.slide_distance, more test.layers or a larger bed (results written, with this "
        "warning in summary.json)",
        path, r.friction_apparent, r.r_squared, min_r_squared));
  progress.finish(fmt::format("{} beads, {} loads", r.bead_count, r.runs.size()));
  if (!options.quiet) {
    fmt::print(
        "sliding friction {} on a {} bed: input mu_s = {:.4f}, apparent = {:.4f} +- {:.4f} (R^2 = "
        "{:.4f})\n",
        s.slider_material, s.bead_material, r.friction_input, r.friction_apparent,
        r.friction_apparent_se, r.r_squared);
    for (const LoadRun& run : r.runs)
      fmt::print("  P = {:.4g} N   F = {:.4g} N (sd {:.2g})   F/P = {:.4f}\n", run.load,
                 run.mean_force, run.force_sd, run.mean_force / run.load);
  }
}

}  // namespace grainlab
