#include "lab/element_test.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "calibrate/least_squares.hpp"
#include "contact/stability.hpp"
#include "contact/time_step.hpp"
#include "grainlab/version.hpp"
#include "io/checkpoint_clock.hpp"
#include "io/config_error.hpp"
#include "io/interrupt.hpp"
#include "io/output_files.hpp"
#include "io/output_manifest.hpp"
#include "io/scene_builder.hpp"
#include "io/summary_header.hpp"
#include "lab/lab_config.hpp"
#include "measure/boundary.hpp"
#include "measure/solid_fraction.hpp"
#include "measure/specimen_state.hpp"

namespace grainlab {

nlohmann::json specimen_json(const Specimen& s) {
  // The bulk solid fraction includes the loose layer along the walls: also the interior value,
  // three mean diameters from every wall (where that leaves at least 4 diameters), and the profile
  // across each axis in slabs about one diameter thick (measure/solid_fraction.hpp).
  double mean_radius = 0.0;
  for (double r : s.particles.radius) mean_radius += r / s.particles.size();
  const double d = 2.0 * mean_radius;
  nlohmann::json profile;
  std::vector<double> widths;
  for (int a = 0; a < 3; ++a) {
    const int bins = std::max(1, static_cast<int>(std::lround((s.high[a] - s.low[a]) / d)));
    widths.push_back((s.high[a] - s.low[a]) / bins);
    profile[std::string(1, "xyz"[a])] = solid_fraction_profile(s.particles, s.low, s.high, a, bins);
  }
  profile["bin_width_m"] = widths;
  // null when the specimen has no interior at least 4 diameters across in every direction.
  nlohmann::json interior = nullptr;
  bool room = true;
  for (int a = 0; a < 3; ++a) room = room && s.high[a] - s.low[a] - 6 * d >= 4 * d;
  if (room) interior = interior_solid_fraction(s.particles, s.low, s.high, 3 * d);
  return {
      {"particles", s.particles.size()},
      {"interior_solid_fraction", interior},
      {"interior_margin_m", 3 * d},
      {"solid_fraction_profile", profile},
      {"inserted_box_m", {s.inserted_box.x, s.inserted_box.y, s.inserted_box.z}},
      {"inserted_solid_fraction", s.inserted_solid_fraction},
      {"final_box_m", {s.high.x - s.low.x, s.high.y - s.low.y, s.high.z - s.low.z}},
      {"solid_fraction", s.solid_fraction},
      {"coordination_number", s.coordination_number},
      {"unbalanced_force_ratio", s.unbalanced_force_ratio},
      {"max_wall_stress_error", s.max_stress_error},
      {"compaction_friction", s.compaction_friction},
      {"wall_friction_while_preparing", s.wall_friction_while_preparing},
      {"love_weber_stress_diagonal_Pa",  // null: read from a file (no contact forces)
       s.love_weber_diagonal ? nlohmann::json(*s.love_weber_diagonal) : nlohmann::json(nullptr)},
      {"compaction_restitution", s.compaction_restitution},
      {"equilibrium_reached", s.equilibrium_reached},
      {"target_solid_fraction_reached", s.target_reached},
      {"simulated_time_s", s.simulated_time},
      // the preparation's step and step count (null: the specimen was read from a file)
      {"time_step_s", s.time_step > 0 ? nlohmann::json(s.time_step) : nlohmann::json(nullptr)},
      {"steps", s.time_step > 0 ? nlohmann::json(s.steps) : nlohmann::json(nullptr)}};
}

Specimen obtain_specimen(const ElementTestConfig& c, Progress& progress,
                         const PreparationCheckpoints* checkpoints) {
  if (c.settings.specimen_file) {
    std::string file = *c.settings.specimen_file;
    if (std::filesystem::is_directory(file)) file += "/specimen.csv";
    return load_specimen(file, c.settings.specimen.density, c.settings.specimen.bead_material);
  }
  return prepare_cuboid_specimen(c.settings.specimen, c.table, &progress, checkpoints);
}

ElementTimeStep element_time_step(const SpecimenSettings& sp, const PairTable& table,
                                  const ParticleStore& particles) {
  const MaterialTimeStep step = specimen_time_step(sp, table, particles.smallest_radius());
  ElementTimeStep out;
  out.collision_duration = step.collision_duration;
  out.limited_by = step.limited_by;
  out.settings.time_step = step.time_step;
  out.settings.dt_fraction = step.dt_fraction;
  out.settings.skin = verlet_skin(sp.diameter);
  out.settings.step_key = SimulationSettings::StepKey::lab_test;
  return out;
}

std::vector<std::vector<double>> curve_values(const std::string& rows) {
  std::vector<std::vector<double>> out;
  std::istringstream lines(rows);
  for (std::string line; std::getline(lines, line);) {
    std::vector<double> r;
    std::istringstream fields(line);
    for (std::string f; std::getline(fields, f, ',');) r.push_back(std::stod(f));
    out.push_back(std::move(r));
  }
  return out;
}

double curve_slope(const std::vector<std::vector<double>>& rows, int x, int y,
                   const std::function<bool(const std::vector<double>&)>& use) {
  std::vector<std::vector<double>> design;
  std::vector<double> values;
  for (const auto& r : rows)
    if (use(r)) design.push_back({1.0, r[x]}), values.push_back(r[y]);
  return design.size() >= 3 ? calibrate::least_squares(design, values).coefficients[1] : NAN;
}

void add_vtk_snapshot(ElementRun& run, const std::string& dir, long step,
                      const std::string& particles_vtu, const std::string& walls_vtu) {
  std::filesystem::create_directories(dir + "/vtk");
  const std::string particles = fmt::format("vtk/particles_{:08d}.vtu", step);
  const std::string walls = fmt::format("vtk/walls_{:08d}.vtu", step);
  write_file_atomically(dir + "/" + particles, particles_vtu);
  write_file_atomically(dir + "/" + walls, walls_vtu);
  const double t = run.sim.time();
  run.vtk_index +=
      fmt::format("    <DataSet timestep=\"{:.9g}\" part=\"0\" file=\"{}\"/>\n", t, particles);
  run.vtk_index +=
      fmt::format("    <DataSet timestep=\"{:.9g}\" part=\"1\" file=\"{}\"/>\n", t, walls);
  write_file_atomically(
      dir + "/particles.pvd",
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\">\n  <Collection>\n" +
          run.vtk_index + "  </Collection>\n</VTKFile>\n");
}

double read_max_axial_strain(const ElementTestConfig& c, double fallback, int passes,
                             TableReader& t) {
  const double strain = t.number_or("max_axial_strain", Quantity::dimensionless, fallback);
  if (!(strain > 0 && strain < 0.5)) t.fail("max_axial_strain", "expected a strain in (0, 0.5)");
  check_step_budget(c, strain, passes, t);
  return strain;
}

void check_step_budget(const ElementTestConfig& c, double max_axial_strain, int passes,
                       const TableReader& t) {
  const SpecimenSettings& sp = c.settings.specimen;
  const double dt = specimen_time_step(sp, c.table, sp.min_radius()).time_step;
  const double height = sp.nominal_box.z;
  const double speed = loading_rate(c.settings, height).platen_speed;
  const double steps = passes * max_axial_strain * height / (2.0 * speed) / dt;
  // The re-equilibration's bound in steps (its time scales with the beads, as the step does).
  const double hold_steps = c.settings.re_equilibration_max_time / dt;
  if (!(hold_steps <= max_steps_per_run))
    t.fail("re_equilibration_max_time",
           fmt::format("the re-equilibration could take {:.3g} steps (dt = {:.3g} s), more than "
                       "grainlab runs ({:.0e})",
                       hold_steps, dt, max_steps_per_run));
  if (!(steps <= max_steps_per_run))
    t.fail(c.settings.platen_speed ? "platen_speed" : "max_inertial_number",
           fmt::format("the loading would take about {:.3g} steps (dt = {:.3g} s), more than "
                       "grainlab runs ({:.0e}); load faster",
                       steps, dt, max_steps_per_run));
}

void check_specimen_file(const std::string& path, const ElementTestSettings& s) {
  if (s.specimen_file && !std::filesystem::exists(*s.specimen_file))
    throw ConfigError(
        fmt::format("{}: test.specimen: {} does not exist (make one with grainlab prepare)", path,
                    *s.specimen_file));
}

LoadingRate loading_rate(const ElementTestSettings& s, double height0) {
  const SpecimenSettings& sp = s.specimen;
  const double rate_bound =
      s.max_inertial_number / (sp.diameter * std::sqrt(sp.density / sp.confining_stress));
  LoadingRate r;
  r.platen_speed = s.platen_speed ? *s.platen_speed : 0.5 * rate_bound * height0;
  r.strain_rate = 2.0 * r.platen_speed / height0;
  return r;
}

nlohmann::json loading_json(const LoadingRate& rate, const ElementTestSettings& s) {
  return {{"platen_speed_m_per_s", rate.platen_speed},
          {"strain_rate_per_s", rate.strain_rate},
          {"rule", s.platen_speed ? "platen speed given (paper: 0.01 m/s)"
                                  : "fastest rate with I <= max_inertial_number"},
          {"max_inertial_number_bound", s.max_inertial_number}};
}

ElementRun start_element_test(const std::string& type, const std::string& path,
                              const toml::table& root, const ElementTestConfig& c,
                              const std::string& out_dir, Progress& progress,
                              const SpecimenMount& mount, const std::string& resumed_config) {
  const ElementTestSettings& s = c.settings;
  const SpecimenSettings& sp = s.specimen;
  const auto wall_start = std::chrono::steady_clock::now();
  // The preparation checkpoints every checkpoint_interval (preparation.bin), and a resumed run
  // continues it with the config text stored there.
  const std::string config_text = resumed_config.empty() ? read_file(path) : resumed_config;
  const PreparationCheckpoints checkpoints{out_dir + "/preparation.bin",
                                           s.checkpoint_interval,
                                           {type, path, config_text},
                                           !resumed_config.empty()};
  const Specimen specimen = obtain_specimen(c, progress, &checkpoints);
  if (!s.specimen_file) save_specimen(out_dir + "/specimen.csv", specimen);
  ElementTimeStep step = element_time_step(sp, c.table, specimen.particles);
  step.settings.gravity = {0.0, 0.0, -s.gravity};
  // The speed above which the run is taken to have blown up: 100 m/s, or ten times the speed of
  // a fall through the specimen's height where gravity makes that larger (a scale study's
  // metre-sized beads), so that only a blow-up trips it.
  step.settings.max_speed =
      std::max(step.settings.max_speed,
               10.0 * std::sqrt(2.0 * s.gravity * (specimen.high.z - specimen.low.z)));
  ElementRun run{Simulation(specimen.particles,
                            mount.walls ? mount.walls(specimen)
                                        : cuboid_walls(specimen.low, specimen.high,
                                                       sp.lateral_material, sp.platen_material),
                            c.table, step.settings),
                 type,
                 path,
                 config_text,
                 /*run_info=*/{},
                 /*curve_rows=*/{},
                 /*vtk_index=*/{},
                 /*test_state=*/{},
                 /*wall_time_before=*/0.0};
  // A specimen is stored without contact history (tangential springs), so it is first brought
  // back to equilibrium under the confining stress before the loading starts.
  const auto on_check = [&](const HoldState& state) {
    if (interrupt_requested())
      throw Interrupted("interrupted before the loading began: nothing to resume");
    progress.update(Progress::unknown_fraction,
                    fmt::format("re-equilibrating: wall stress error {:.2f} %, unbalanced {:.1e}",
                                100 * state.max_stress_error, state.unbalanced));
    return true;
  };
  const HoldState held =
      mount.equilibrate
          ? mount.equilibrate(run.sim, on_check)
          : hold_isotropic(run.sim,
                           HoldCriteria{sp.confining_stress, sp.max_strain_rate,
                                        sp.stress_tolerance, 1e-3, s.re_equilibration_max_time},
                           on_check);
  nlohmann::json j = summary_header(path, &root);
  j["specimen"] = specimen_json(specimen);
  j["specimen"]["source"] =
      s.specimen_file ? *s.specimen_file : std::string("prepared in this run");
  const double dt = step.settings.time_step;
  j["time_step_s"] = dt;
  j["dt_fraction"] = dt / step.collision_duration;
  j["collision_duration_s"] = step.collision_duration;
  j["time_step_limited_by"] = step.limited_by;
  if (!mount.equilibrate) {  // the box held isotropically: its stress state at the start
    const Tensor3 lw = love_weber_stress(run.sim, box_volume(run.sim.walls()));
    j["initial_love_weber_stress_Pa"] = {{lw[0][0], lw[0][1], lw[0][2]},
                                         {lw[1][0], lw[1][1], lw[1][2]},
                                         {lw[2][0], lw[2][1], lw[2][2]}};
  }
  j["initial_solid_fraction"] = solid_fraction(
      run.sim.particles(), mount.volume ? mount.volume(run.sim) : box_volume(run.sim.walls()));
  j["re_equilibration"] = {{"unbalanced_force_ratio", held.unbalanced},
                           {"max_wall_stress_error", held.max_stress_error},
                           {"reached", held.reached}};
  j["preparation_wall_time_s"] =  // with the sessions before a resumed preparation
      specimen.earlier_wall_time +
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  run.run_info = j.dump();
  return run;
}

ElementRun begin_element_test(const std::string& type, const std::string& path,
                              const toml::table& root, const ElementTestConfig& c,
                              const RunOptions& options, const SpecimenMount& mount) {
  check_specimen_file(path, c.settings);
  if (options.resumed_config.empty())
    prepare_output_dir(options.out_dir, options.overwrite);
  else
    continue_in_output_dir(options.out_dir);
  install_interrupt_handler();
  Progress preparing("grainlab " + type, options.quiet);
  return start_element_test(type, path, root, c, options.out_dir, preparing, mount,
                            options.resumed_config);
}

void load_to_end(ElementRun& run, LoadingStage& stage, double checkpoint_interval_s,
                 const RunOptions& options) {
  Progress progress("grainlab " + run.type, options.quiet);
  run_loading(run, stage, options.out_dir, checkpoint_interval_s, progress);
  progress.finish(fmt::format("{} steps", run.sim.step_count()));
}

void run_loading(ElementRun& run, LoadingStage& stage, const std::string& dir,
                 double checkpoint_interval_s, Progress& progress) {
  // The interrupt flag is looked at every step, the wall clock every 1000.
  CheckpointClock clock(checkpoint_interval_s, 1000);
  // The curve is written as curve.csv.partial and renamed at the end: the manifest lists its
  // final name (--overwrite removes it with its .partial sibling).
  record_output(dir + "/curve.csv");
  auto write_curve = [&] {
    write_file_atomically(dir + "/curve.csv.partial",
                          std::string(stage.curve_header()) + "\n" + run.curve_rows);
  };
  auto checkpoint = [&] {
    stage.save(run);
    const double before = run.wall_time_before;
    run.wall_time_before += clock.session_time();
    write_curve();
    save_checkpoint(run, dir + "/checkpoint.bin");
    run.wall_time_before = before;
  };
  for (;;) {
    stage.observe(run, progress);
    if (stage.finished(run)) break;
    clock.poll(checkpoint, [&] {
      return fmt::format(
          "interrupted at {}; checkpoint written, continue with: "
          "grainlab run --resume {}",
          stage.position(), dir);
    });
    run.sim.step();
    stage.after_step(run);
  }
  run.wall_time_before += clock.session_time();
  stage.save(run);
  write_curve();
  std::filesystem::rename(dir + "/curve.csv.partial", dir + "/curve.csv");
  std::error_code ec;
  std::filesystem::remove(dir + "/checkpoint.bin", ec);
  // A finished run has nothing to resume: --resume on it is refused, not a rerun.
  std::filesystem::remove(dir + "/preparation.bin", ec);
}

}  // namespace grainlab
