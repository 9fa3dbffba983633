#include "lab/scale_study.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/simulation.hpp"
#include "io/config_error.hpp"
#include "io/interrupt.hpp"
#include "io/output_files.hpp"
#include "io/python_script.hpp"
#include "io/summary_header.hpp"
#include "lab/lab_config.hpp"
#include "lab/lab_test.hpp"
#include "lab/scale_study_report.hpp"

namespace grainlab {
namespace fs = std::filesystem;

namespace {

constexpr const char* stored_config_name = "scale_study.toml";

// A length in SI with its unit, round-trip exact, for a generated config.
std::string metres(double v) {
  return exact(v) + " m";
}

std::vector<double> read_diameters(TableReader& t) {
  if (!t.has("diameters")) return default_scale_study_diameters();
  const toml::array* list = t.node("diameters")->as_array();
  if (!list || list->empty())
    t.fail("diameters", "expected a non-empty list of bead diameters, e.g. [\"2 mm\", \"1 m\"]");
  std::vector<double> out;
  for (const toml::node& n : *list) {
    double d = NAN;
    if (auto text = n.value<std::string>()) {
      try {
        d = parse_quantity(*text, Quantity::length);
      } catch (const std::invalid_argument& e) {
        t.fail("diameters", e.what());
      }
    } else if (auto v = n.value<double>()) {
      d = *v;
    }
    if (!(std::isfinite(d) && d > 0 && d <= 1000))
      t.fail("diameters", "expected diameters > 0 and at most 1000 m (a length with its unit)");
    for (double e : out)
      if (e == d) t.fail("diameters", fmt::format("the diameter {} m is listed twice", d));
    out.push_back(d);
  }
  return out;
}

std::vector<bool> read_gravity_settings(TableReader& t) {
  if (!t.has("gravity_settings")) return {false, true};
  const toml::array* list = t.node("gravity_settings")->as_array();
  if (!list || list->empty())
    t.fail("gravity_settings", "expected a non-empty list of \"off\" and \"on\"");
  std::vector<bool> out;
  for (const toml::node& n : *list) {
    const auto v = n.value<std::string>();
    if (!v || (*v != "off" && *v != "on"))
      t.fail("gravity_settings", "expected a list of \"off\" and \"on\"");
    for (bool e : out)
      if (e == (*v == "on")) t.fail("gravity_settings", fmt::format("\"{}\" is listed twice", *v));
    out.push_back(*v == "on");
  }
  return out;
}

// The run of diameter d with gravity on or off: its subdirectory's name.
std::string run_name(double d, bool gravity_on) {
  return fmt::format("d{:g}m-gravity-{}", d, gravity_on ? "on" : "off");
}

}  // namespace

std::vector<double> default_scale_study_diameters() {
  return {0.002, 1, 2, 4, 8, 10, 12, 14, 16, 18};
}

ScaleStudyConfig read_scale_study_config(const std::string& path, const toml::table& root) {
  ScaleStudyConfig c;
  TableReader t = test_table_reader(path, root);  // the study's own keys; the rest: plane strain
  c.diameters = read_diameters(t);
  c.gravity_settings = read_gravity_settings(t);
  c.gravity = t.number_or("gravity", Quantity::acceleration, c.gravity);
  if (!(c.gravity > 0 && c.gravity <= 1e3))
    t.fail("gravity", "expected the acceleration of the runs with gravity on, in (0, 1000] m/s^2");
  const std::string loading = t.string_or("loading", "inertial");
  c.base_root = root;
  toml::table& test = *c.base_root["test"].as_table();
  for (const char* key : {"diameters", "gravity_settings", "gravity", "strain_rate"})
    test.erase(key);
  test.insert_or_assign("type", "plane_strain");
  if (loading == "strain_rate") {
    c.loading = ScaleLoading::strain_rate;
    c.strain_rate = t.number("strain_rate", Quantity::dimensionless);
    if (!(c.strain_rate > 0 && c.strain_rate <= 1e3))
      t.fail("strain_rate", "expected an axial strain rate in (0, 1000] 1/s");
    // Placeholder: every run's platen speed is set from its own height.
    test.insert_or_assign("loading", "speed");
    test.insert_or_assign("platen_speed", "1 m/s");
  } else {
    c.loading = loading == "inertial" ? ScaleLoading::inertial : ScaleLoading::platen_speed;
    if (t.has("strain_rate")) t.fail("strain_rate", "only read with loading = \"strain_rate\"");
  }
  c.base = read_plane_strain_config(path, c.base_root);
  return c;
}

namespace {

// The prepared specimen scaled by `factor`: positions, radii and box.
Specimen scaled_specimen(const Specimen& s, double factor, double density) {
  Specimen out;
  const ParticleStore& p = s.particles;
  for (size_t i = 0; i < p.size(); ++i)
    out.particles.add(p.id[i], p.material[i], factor * p.radius[i], density, factor * p.position[i],
                      {}, {}, false);
  out.low = factor * s.low;
  out.high = factor * s.high;
  return out;
}

class ScaleStudy {
 public:
  ScaleStudy(ScaleStudyConfig c, std::string stored_path, const RunOptions& options)
      : c_(std::move(c)), stored_path_(std::move(stored_path)), options_(options) {}

  void run() {
    install_interrupt_handler();
    const Specimen base = base_specimen();
    const auto start = std::chrono::steady_clock::now();
    std::vector<ScaleRun> runs;
    const size_t total = c_.diameters.size() * c_.gravity_settings.size();
    for (double d : c_.diameters)
      for (bool gravity_on : c_.gravity_settings) {
        if (!options_.quiet)
          fmt::print(
              stderr, "scale study: run {} of {}: d = {:g} m, gravity {} ({:.0f} s so far)\n",
              runs.size() + 1, total, d, gravity_on ? "on" : "off",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        runs.push_back(run_one(base, d, gravity_on));
        continue_in_output_dir(options_.out_dir);
      }
    const SpecimenSettings& sp = c_.base.settings.specimen;
    nlohmann::json header = summary_header(stored_path_);
    header["base_specimen"] = specimen_json(base);
    header["base_diameter_m"] = sp.diameter;
    const std::string explanation = write_scale_study_report(
        runs, {sp.confining_stress, loading_words()}, options_.out_dir, header);
    try {
      for (const char* f : {"scale.png", "scale.png.tmp.png"})
        record_output(options_.out_dir + "/" + f);
      run_python_script("plot_scale_study.py", {options_.out_dir});
    } catch (const std::runtime_error& e) {
      fmt::print(stderr, "grainlab: warning: no scale.png: {}\n", e.what());
    }
    if (!options_.quiet) fmt::print("scale study: {}\n", explanation);
    // A trend needs two sizes that gave a peak: a warning for a gravity setting without them,
    // a failed study when no setting has them.
    bool any_trend = false;
    for (bool gravity_on : c_.gravity_settings) {
      int usable = 0;
      for (const ScaleRun& r : runs) usable += (r.gravity > 0) == gravity_on && r.status == "ok";
      any_trend |= usable >= 2;
      if (usable < 2)
        fmt::print(stderr,
                   "grainlab: warning: fewer than two runs with gravity {} gave a peak: no trend "
                   "can be read there (see the status column of {}/scale.csv)\n",
                   gravity_on ? "on" : "off", options_.out_dir);
    }
    if (!any_trend)
      throw UnreliableResult(fmt::format(
          "no gravity setting has two runs that gave a peak: the study shows no trend (see the "
          "status column of {}/scale.csv)",
          options_.out_dir));
  }

 private:
  std::string dir(const std::string& name) const { return options_.out_dir + "/" + name; }

  std::string loading_words() const {
    switch (c_.loading) {
      case ScaleLoading::inertial:
        return fmt::format("the fastest rate with inertial number I <= {:g} at every d",
                           c_.base.settings.max_inertial_number);
      case ScaleLoading::platen_speed:
        return fmt::format("a fixed platen speed of {:g} m/s at every d",
                           *c_.base.settings.platen_speed);
      case ScaleLoading::strain_rate:
        return fmt::format("a fixed axial strain rate of {:g} 1/s at every d", c_.strain_rate);
    }
    return {};
  }

  // The specimen of the base diameter: the config's own specimen file, or prepared once (without
  // gravity, with preparation checkpoints) in DIR/specimen.
  Specimen base_specimen() {
    const ElementTestSettings& s = c_.base.settings;
    const SpecimenSettings& sp = s.specimen;
    if (s.specimen_file) {
      std::string file = *s.specimen_file;
      if (fs::is_directory(file)) file += "/specimen.csv";
      base_file_ = fs::absolute(file).string();
      return load_specimen(base_file_, sp.density, sp.bead_material);
    }
    const std::string specimen_dir = dir("specimen");
    base_file_ = fs::absolute(specimen_dir + "/specimen.csv").string();
    if (fs::exists(base_file_)) return load_specimen(base_file_, sp.density, sp.bead_material);
    fs::create_directories(specimen_dir);
    const PreparationCheckpoints checkpoints{specimen_dir + "/preparation.bin",
                                             s.checkpoint_interval,
                                             {"scale_study", stored_path_, read_file(stored_path_)},
                                             fs::exists(specimen_dir + "/preparation.bin")};
    Progress progress("grainlab scale study: preparing", options_.quiet);
    const Specimen prepared = prepare_cuboid_specimen(sp, c_.base.table, &progress, &checkpoints);
    save_specimen(base_file_, prepared);
    write_file_atomically(specimen_dir + "/specimen.json", specimen_json(prepared).dump(2) + "\n");
    std::error_code ec;
    fs::remove(specimen_dir + "/preparation.bin", ec);
    progress.finish(fmt::format("solid fraction {:.4f}", prepared.solid_fraction));
    return load_specimen(base_file_, sp.density, sp.bead_material);
  }

  // The config of one run: the base config with every length scaled by d / d_base, times with
  // it and rates against it, the scaled specimen, gravity when on.
  std::string run_config(const Specimen& base, double d, bool gravity_on, const std::string& name) {
    const ElementTestSettings& s = c_.base.settings;
    const SpecimenSettings& sp = s.specimen;
    const double factor = d / sp.diameter;
    std::string specimen = base_file_;
    if (factor != 1.0) {
      specimen = fs::absolute(dir("specimen") + fmt::format("/d{:g}m.csv", d)).string();
      if (!fs::exists(specimen)) {
        fs::create_directories(dir("specimen"));
        save_specimen(specimen, scaled_specimen(base, factor, sp.density));
      }
    }
    toml::table root = c_.base_root;
    toml::table& t = *root["test"].as_table();
    t.insert_or_assign("diameter", metres(d));
    t.insert_or_assign("diameter_tolerance", metres(factor * sp.diameter_tolerance));
    t.insert_or_assign(
        "box", toml::array{metres(factor * sp.nominal_box.x), metres(factor * sp.nominal_box.y),
                           metres(factor * sp.nominal_box.z)});
    t.insert_or_assign("specimen", specimen);
    t.insert_or_assign("re_equilibration_max_time",
                       exact(factor * s.re_equilibration_max_time) + " s");
    t.insert_or_assign("compaction_strain_rate", sp.max_strain_rate / factor);
    if (gravity_on) t.insert_or_assign("gravity", exact(c_.gravity) + " m/s^2");
    if (c_.loading == ScaleLoading::strain_rate) {
      const double height = factor * (base.high.z - base.low.z);
      t.insert_or_assign("platen_speed", exact(0.5 * c_.strain_rate * height) + " m/s");
    }
    std::ostringstream text;
    text << "# grainlab scale study: run " << name << " (d = " << fmt::format("{:g}", d)
         << " m, gravity " << (gravity_on ? "on" : "off") << "), generated from " << stored_path_
         << "\n"
         << root << "\n";
    return text.str();
  }

  ScaleRun run_one(const Specimen& base, double d, bool gravity_on) {
    const std::string name = run_name(d, gravity_on);
    const std::string run_dir = dir(name);
    ScaleRun r;
    r.name = name;
    r.diameter = d;
    r.gravity = gravity_on ? c_.gravity : 0.0;
    // A run that failed before (its cause in failure.txt) is not run again: it would fail the same
    // way (the runs are deterministic).
    const std::string failure = run_dir + "/failure.txt";
    if (!fs::exists(run_dir + "/summary.json") && fs::exists(failure)) {
      r.status = read_file(failure);
    } else if (!fs::exists(run_dir + "/summary.json")) {
      RunOptions sub = options_;
      sub.out_dir = run_dir;
      sub.overwrite = false;
      try {
        if (fs::exists(run_dir + "/checkpoint.bin")) {
          resume_lab_test(sub);
        } else {
          const std::string config = dir(name + ".toml");
          write_file_atomically(config, run_config(base, d, gravity_on, name));
          // A run killed before its first checkpoint starts again (only its own files go).
          if (fs::exists(run_dir)) prepare_output_dir(run_dir, true);
          run_lab_test(config, parse_toml_file(config), sub);
        }
      } catch (const UnreliableResult& e) {
        r.status = e.what();
      } catch (const BlowUpError& e) {
        r.status = e.what();
        write_file_atomically(failure, r.status);
      }
    }
    read_run(run_dir + "/summary.json", r);
    return r;
  }

  static void read_run(const std::string& file, ScaleRun& r) {
    if (!fs::exists(file)) {
      if (r.status.empty()) r.status = "no summary.json";
      return;
    }
    const nlohmann::json j = nlohmann::json::parse(read_file(file));
    r.particles = j["specimen"]["particles"].get<long>();
    const auto& size = j["initial_size_m"];
    r.size = {size["width"].get<double>(), size["thickness"].get<double>(),
              size["height"].get<double>()};
    r.peak_axial_stress = j["peak_axial_stress_Pa"].get<double>();
    r.axial_strain_at_peak = j["axial_strain_at_peak"].get<double>();
    r.self_weight_ratio = j["self_weight_over_confining_stress"].get<double>();
    r.max_inertial_number = j["max_inertial_number"].get<double>();
    r.wall_time = j["wall_time_s"].get<double>();
    if (r.status.empty()) {
      const long escaped = j["membrane"]["max_escaped_beads"].get<long>();
      if (escaped > 0)
        r.status = fmt::format("{} beads escaped through the membrane", escaped);
      else if (!j["re_equilibration"]["reached"].get<bool>())
        r.status =
            r.gravity > 0
                ? "not at rest before the loading: the specimen was still settling under its "
                  "own weight when the re-equilibration's time ran out"
                : "not at rest before the loading: the re-equilibration did not converge";
      else
        r.status = "ok";
    }
  }

  ScaleStudyConfig c_;
  std::string stored_path_;
  RunOptions options_;
  std::string base_file_;
};

// Removes the results of the runs a study made in DIR (each run's own recorded files), for
// --overwrite; a subdirectory without grainlab's manifest is the user's and is left alone.
void clear_study_runs(const std::string& dir) {
  if (!fs::is_directory(dir)) return;
  for (const fs::directory_entry& e : fs::directory_iterator(dir))
    if (e.is_directory() && fs::exists(e.path() / manifest_name))
      prepare_output_dir(e.path().string(), true);
}

}  // namespace

void run_scale_study(const std::string& path, const toml::table& root, const RunOptions& options) {
  const ScaleStudyConfig c = read_scale_study_config(path, root);
  check_specimen_file(path, c.base.settings);
  if (options.overwrite) clear_study_runs(options.out_dir);
  prepare_output_dir(options.out_dir, options.overwrite);
  // The config is kept with the results: a resume needs nothing else.
  const std::string stored = options.out_dir + "/" + stored_config_name;
  write_file_atomically(stored, read_file(path));
  ScaleStudy(c, stored, options).run();
}

bool is_scale_study_dir(const std::string& dir) {
  return fs::exists(dir + "/" + stored_config_name);
}

void resume_scale_study(const RunOptions& options) {
  if (fs::exists(options.out_dir + "/summary.json"))
    throw ConfigError(fmt::format(
        "{}: this scale study has finished (summary.json); nothing to resume", options.out_dir));
  const std::string stored = options.out_dir + "/" + stored_config_name;
  const toml::table root = parse_toml_file(stored);
  const ScaleStudyConfig c = read_scale_study_config(stored, root);
  continue_in_output_dir(options.out_dir);
  ScaleStudy(c, stored, options).run();
}

}  // namespace grainlab
