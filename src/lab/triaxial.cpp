#include "lab/triaxial.hpp"

#include <fmt/format.h>

#include <array>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "contact/stability.hpp"
#include "contact/time_step.hpp"
#include "control/stress_servo.hpp"
#include "core/simulation.hpp"
#include "grainlab/version.hpp"
#include "io/config_error.hpp"
#include "io/output_files.hpp"
#include "io/progress.hpp"
#include "io/toml_reader.hpp"
#include "measure/boundary.hpp"
#include "lab/interrupt.hpp"
#include "lab/triaxial_config.hpp"
#include "lab/triaxial_plot.hpp"
#include "lab/triaxial_shear.hpp"
#include "measure/specimen_state.hpp"

namespace grainlab {
namespace {

// Laboratory and published DEM peaks of the reference case (DESIGN.md sec. 5).
constexpr double lab_peak_axial_stress = 342.4e3, lab_axial_strain_at_peak = 0.0511;
constexpr double published_dem_peak_axial_stress = 320.25e3;

nlohmann::json specimen_json(const Specimen& s) {
  return {{"particles", s.particles.size()},
          {"inserted_box_m", {s.inserted_box.x, s.inserted_box.y, s.inserted_box.z}},
          {"inserted_solid_fraction", s.inserted_solid_fraction},
          {"final_box_m", {s.high.x - s.low.x, s.high.y - s.low.y, s.high.z - s.low.z}},
          {"solid_fraction", s.solid_fraction},
          {"coordination_number", s.coordination_number},
          {"unbalanced_force_ratio", s.unbalanced_force_ratio},
          {"max_wall_stress_error", s.max_stress_error},
          {"compaction_friction", s.compaction_friction},
          {"compaction_restitution", s.compaction_restitution},
          {"equilibrium_reached", s.equilibrium_reached},
          {"target_solid_fraction_reached", s.target_reached},
          {"simulated_time_s", s.simulated_time}};
}

Specimen obtain_specimen(const TriaxialConfig& c, Progress& progress) {
  if (c.settings.specimen_file) {
    std::string file = *c.settings.specimen_file;
    if (std::filesystem::is_directory(file)) file += "/specimen.csv";
    return load_specimen(file, c.settings.specimen.density);
  }
  return prepare_cuboid_specimen(c.settings.specimen, c.table, &progress);
}

}  // namespace

void run_prepare(const std::string& path, const RunOptions& options) {
  const toml::table root = parse_toml_file(path);
  const TriaxialConfig c = read_triaxial_config(path, root);
  prepare_output_dir(options.out_dir, options.overwrite);
  install_interrupt_handler();
  const auto start = std::chrono::steady_clock::now();
  Progress progress("grainlab prepare", options.quiet);
  const Specimen s = prepare_cuboid_specimen(c.settings.specimen, c.table, &progress);
  save_specimen(options.out_dir + "/specimen.csv", s);
  nlohmann::json j = specimen_json(s);
  j["grainlab_version"] = version_string;
  j["config_file"] = path;
  j["confining_stress_Pa"] = c.settings.specimen.confining_stress;
  j["wall_time_s"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  write_file_atomically(options.out_dir + "/specimen.json", j.dump(2) + "\n");
  progress.finish(fmt::format("solid fraction {:.4f}, box {:.2f} x {:.2f} x {:.2f} mm",
                              s.solid_fraction, 1e3 * (s.high.x - s.low.x),
                              1e3 * (s.high.y - s.low.y), 1e3 * (s.high.z - s.low.z)));
}

namespace {

void finish_triaxial(const ShearRun& run, const std::string& dir, bool quiet) {
  const ShearProgress& p = run.progress;
  const double sigma3 = p.confining_stress;
  const double phi_peak =
      std::asin(p.peak_deviator / (p.peak_deviator + 2.0 * sigma3)) * 180.0 / M_PI;
  nlohmann::json j = nlohmann::json::parse(run.run_info);
  j["max_inertial_number"] = p.max_inertial;
  j["quasi_static_flag"] =
      p.max_inertial > 1e-3 ? "I exceeded 1e-3: not quasi-static" : "ok (I <= 1e-3)";
  j["peak_axial_stress_Pa"] = p.peak_axial;
  j["axial_strain_at_peak"] = p.peak_strain;
  j["peak_deviator_stress_Pa"] = p.peak_deviator;
  j["peak_stress_ratio_q_over_p"] = p.peak_ratio;
  j["peak_friction_angle_deg"] = phi_peak;
  j["residual_axial_stress_Pa"] = p.last_axial;
  j["final_axial_strain"] = p.last_strain;
  const double rms = p.lateral_samples ? std::sqrt(p.lateral_error2 / p.lateral_samples) : 0.0;
  j["lateral_stress_rms_error"] = rms;
  j["lateral_stress_max_error"] = p.max_lateral_error;
  // Walls vs particles: the boundary-average stress (platens and lateral walls, with the moment of
  // the wall friction) against the Love-Weber average, worst axis and output interval once past
  // 0.5 % axial strain; and how far the platen stress F/A exceeds the specimen's average axial
  // stress because the lateral walls' friction carries part of the load.
  j["wall_particle_stress_max_difference"] = p.worst_agreement;
  j["platen_over_average_axial_stress"] =
      p.platen_excess_rows ? p.platen_excess_sum / p.platen_excess_rows : 0.0;
  j["steps"] = run.sim.step_count();
  j["neighbor_rebuilds"] = run.sim.rebuild_count();
  j["shearing_wall_time_s"] = p.wall_time_before;
  j["wall_time_s"] = j["preparation_wall_time_s"].get<double>() + p.wall_time_before;
  j["reference"] = {
      {"laboratory_peak_axial_stress_Pa", lab_peak_axial_stress},
      {"laboratory_axial_strain_at_peak", lab_axial_strain_at_peak},
      {"published_dem_peak_axial_stress_Pa", published_dem_peak_axial_stress},
      {"difference_to_laboratory", p.peak_axial / lab_peak_axial_stress - 1.0},
      {"difference_to_published_dem", p.peak_axial / published_dem_peak_axial_stress - 1.0}};
  write_file_atomically(dir + "/summary.json", j.dump(2) + "\n");
  plot_triaxial_curve(dir);
  if (!quiet)
    fmt::print(
        "triaxial: peak axial stress {:.1f} kPa at {:.2f} % axial strain; laboratory 342.4 kPa at "
        "5.11 % ({:+.1f} %), "
        "published DEM 320.25 kPa ({:+.1f} %); lateral stress RMS error {:.2f} % (worst interval "
        "{:.2f} %); particle vs boundary stress within {:.2f} %; wall time {:.0f} s\n",
        1e-3 * p.peak_axial, 100 * p.peak_strain,
        100 * (p.peak_axial / lab_peak_axial_stress - 1.0),
        100 * (p.peak_axial / published_dem_peak_axial_stress - 1.0), 100 * rms,
        100 * p.max_lateral_error, 100 * p.worst_agreement, j["wall_time_s"].get<double>());
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

void run_triaxial(const std::string& path, const toml::table& root, const RunOptions& options) {
  const TriaxialConfig c = read_triaxial_config(path, root);
  const TriaxialSettings& s = c.settings;
  const SpecimenSettings& sp = s.specimen;
  if (s.specimen_file && !std::filesystem::exists(*s.specimen_file))
    throw ConfigError(
        fmt::format("{}: test.specimen: {} does not exist (make one with grainlab prepare)", path,
                    *s.specimen_file));
  prepare_output_dir(options.out_dir, options.overwrite);
  install_interrupt_handler();
  const auto wall_start = std::chrono::steady_clock::now();
  Progress progress("grainlab triaxial", options.quiet);
  const Specimen specimen = obtain_specimen(c, progress);
  if (!s.specimen_file) save_specimen(options.out_dir + "/specimen.csv", specimen);

  // Shearing: no gravity; lateral walls servo-held at the confining stress; platens driven.
  const PairParams& glass = c.table(sp.bead_material, sp.bead_material);
  double r_min = 1e300;
  for (double r : specimen.particles.radius) r_min = std::min(r_min, r);
  SimulationSettings settings;
  const double collision_duration_of_beads =
      collision_duration(r_min, sp.density, glass.youngs_modulus, glass.restitution);
  const TimeStepChoiceForMaterial step = stable_time_step(
      sp.dt_fraction * collision_duration_of_beads, c.table, sp.bead_material, r_min);
  const std::string time_step_limited_by = step.limited_by;
  settings.time_step = step.time_step;
  settings.dt_fraction = settings.time_step / collision_duration_of_beads;
  settings.skin = verlet_skin(sp.diameter);
  ShearRun run{
      Simulation(specimen.particles,
                 cuboid_walls(specimen.low, specimen.high, sp.lateral_material, sp.platen_material),
                 c.table, settings),
      {},
      {},
      {},
      {},
      path,
      read_text(path)};
  Simulation& sim = run.sim;
  // A specimen is stored without contact history (tangential springs), so it is first brought
  // back to equilibrium under the confining stress before the platens move.
  const HoldState held = hold_isotropic(
      sim, HoldCriteria{sp.confining_stress, sp.max_strain_rate, sp.stress_tolerance, 1e-3, 0.02},
      [&](const HoldState& state) {
        if (interrupt_requested())
          throw Interrupted("interrupted before shearing began: nothing to resume");
        progress.update(
            0.0, fmt::format("re-equilibrating: wall stress error {:.2f} %, unbalanced {:.1e}",
                             100 * state.max_stress_error, state.unbalanced));
        return true;
      });
  const double prep_wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  ShearProgress& p = run.progress;
  p.size0 = box_high(sim.walls()) - box_low(sim.walls());
  const double height0 = p.size0.z;
  // Platen speed: given, or the fastest whose inertial number at the confining stress is the bound
  // (the mean stress only grows while shearing, so I stays below it).
  const double rate_bound =
      s.max_inertial_number / (sp.diameter * std::sqrt(sp.density / sp.confining_stress));
  p.platen_speed = s.platen_speed ? *s.platen_speed : 0.5 * rate_bound * height0;
  p.strain_rate = 2.0 * p.platen_speed / height0;
  p.confining_stress = sp.confining_stress;
  p.diameter = sp.diameter;
  p.density = sp.density;
  p.output_strain_interval = s.output_strain_interval;
  p.vtk_strain_interval = s.vtk ? s.vtk_strain_interval : 0.0;
  const double dt = settings.time_step;
  p.total_steps =
      static_cast<long>(std::ceil(s.max_axial_strain * height0 / (2.0 * p.platen_speed) / dt));
  if (!options.quiet)
    fmt::print(stderr,
               "triaxial: {} particles, box {:.2f} x {:.2f} x {:.2f} mm, solid fraction {:.4f}; "
               "platens at {:.4g} m/s "
               "each (strain rate {:.3g} 1/s, {}), dt = {:.3g} s, {} steps\n",
               specimen.particles.size(), 1e3 * p.size0.x, 1e3 * p.size0.y, 1e3 * p.size0.z,
               solid_fraction(sim.particles(), p.size0.x * p.size0.y * p.size0.z), p.platen_speed,
               p.strain_rate, s.platen_speed ? "given" : "from the inertial-number bound", dt,
               p.total_steps);

  nlohmann::json j;
  j["grainlab_version"] = version_string;
  j["config_file"] = path;
  std::ostringstream inputs;
  inputs << toml::json_formatter{root};
  j["inputs"] = nlohmann::json::parse(inputs.str());
  j["specimen"] = specimen_json(specimen);
  j["specimen"]["source"] =
      s.specimen_file ? *s.specimen_file : std::string("prepared in this run");
  j["time_step_s"] = dt;
  j["dt_fraction"] = dt / collision_duration_of_beads;
  j["collision_duration_s"] = collision_duration_of_beads;
  j["time_step_limited_by"] = time_step_limited_by;
  j["loading"] = {{"platen_speed_m_per_s", p.platen_speed},
                  {"strain_rate_per_s", p.strain_rate},
                  {"rule", s.platen_speed ? "platen speed given (paper: 0.01 m/s)"
                                          : "fastest rate with I <= max_inertial_number"},
                  {"max_inertial_number_bound", s.max_inertial_number}};
  j["initial_solid_fraction"] = solid_fraction(sim.particles(), p.size0.x * p.size0.y * p.size0.z);
  j["re_equilibration"] = {{"unbalanced_force_ratio", held.unbalanced},
                           {"max_wall_stress_error", held.max_stress_error},
                           {"reached", held.reached}};
  j["preparation_wall_time_s"] = prep_wall_time;
  run.run_info = j.dump();
  shear(run, options.out_dir, s.checkpoint_interval, progress);
  progress.finish(fmt::format("{} steps", sim.step_count()));
  finish_triaxial(run, options.out_dir, options.quiet);
}

void resume_triaxial(const RunOptions& options) {
  const std::string checkpoint = options.out_dir + "/checkpoint.bin";
  std::string path, text;
  peek_checkpoint_config(checkpoint, path, text);
  toml::table root;
  try {
    root = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    throw ConfigError(fmt::format("{}: the stored configuration does not parse: {}", checkpoint,
                                  e.description()));
  }
  const TriaxialConfig c = read_triaxial_config(path, root);
  install_interrupt_handler();
  ShearRun run = load_checkpoint(checkpoint, c.table);
  if (!options.quiet)
    fmt::print(stderr, "triaxial: resuming {} at step {} of {}\n", path, run.progress.step,
               run.progress.total_steps);
  Progress progress("grainlab triaxial", options.quiet);
  shear(run, options.out_dir, c.settings.checkpoint_interval, progress);
  progress.finish(fmt::format("{} steps", run.sim.step_count()));
  finish_triaxial(run, options.out_dir, options.quiet);
}

}  // namespace grainlab
