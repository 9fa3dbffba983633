#include "lab/triaxial.hpp"

#include <fmt/format.h>

#include <array>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "contact/time_step.hpp"
#include "control/stress_servo.hpp"
#include "core/simulation.hpp"
#include "grainlab/version.hpp"
#include "io/output_files.hpp"
#include "io/progress.hpp"
#include "io/toml_reader.hpp"
#include "lab/cuboid_box.hpp"
#include "lab/triaxial_config.hpp"
#include "lab/triaxial_plot.hpp"
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

Specimen obtain_specimen(const TriaxialConfig& c, const RunOptions& options, Progress& progress) {
  if (c.settings.specimen_file) {
    std::string file = *c.settings.specimen_file;
    if (std::filesystem::is_directory(file)) file += "/specimen.csv";
    return load_specimen(file, c.settings.specimen.density);
  }
  (void)options;
  return prepare_cuboid_specimen(c.settings.specimen, c.table, &progress);
}

}  // namespace

void run_prepare(const std::string& path, const RunOptions& options) {
  const toml::table root = parse_toml_file(path);
  const TriaxialConfig c = read_triaxial_config(path, root);
  prepare_output_dir(options.out_dir, options.overwrite);
  const auto start = std::chrono::steady_clock::now();
  Progress progress("grainlab prepare", options.quiet);
  const Specimen s = prepare_cuboid_specimen(c.settings.specimen, c.table, &progress);
  save_specimen(options.out_dir + "/specimen.csv", s);
  nlohmann::json j = specimen_json(s);
  j["grainlab_version"] = version_string;
  j["config_file"] = path;
  j["confining_stress_Pa"] = c.settings.specimen.confining_stress;
  j["wall_time_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  write_file_atomically(options.out_dir + "/specimen.json", j.dump(2) + "\n");
  progress.finish(fmt::format("solid fraction {:.4f}, box {:.2f} x {:.2f} x {:.2f} mm", s.solid_fraction,
                              1e3 * (s.high.x - s.low.x), 1e3 * (s.high.y - s.low.y), 1e3 * (s.high.z - s.low.z)));
}

void run_triaxial(const std::string& path, const toml::table& root, const RunOptions& options) {
  const TriaxialConfig c = read_triaxial_config(path, root);
  const TriaxialSettings& s = c.settings;
  const SpecimenSettings& sp = s.specimen;
  if (s.specimen_file && !std::filesystem::exists(*s.specimen_file))
    throw ConfigError(fmt::format("{}: test.specimen: {} does not exist (make one with grainlab prepare)", path,
                                  *s.specimen_file));
  prepare_output_dir(options.out_dir, options.overwrite);
  const auto wall_start = std::chrono::steady_clock::now();
  Progress progress("grainlab triaxial", options.quiet);
  const Specimen specimen = obtain_specimen(c, options, progress);
  const double prep_wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  if (!s.specimen_file) save_specimen(options.out_dir + "/specimen.csv", specimen);

  // Shearing: no gravity; lateral walls servo-held at the confining stress; platens driven.
  const PairParams& glass = c.table(sp.bead_material, sp.bead_material);
  double r_min = 1e300;
  for (double r : specimen.particles.radius) r_min = std::min(r_min, r);
  SimulationSettings settings;
  settings.time_step = sp.dt_fraction * collision_duration(r_min, sp.density, glass.youngs_modulus, glass.restitution);
  settings.dt_fraction = sp.dt_fraction;
  settings.skin = 0.1 * sp.diameter;
  Simulation sim(specimen.particles, cuboid_walls(specimen.low, specimen.high, sp.lateral_material, sp.platen_material),
                 c.table, settings);
  // A specimen is stored without contact history (tangential springs), so it is first brought
  // back to equilibrium under the confining stress before the platens move.
  const HoldState held = hold_isotropic(
      sim, HoldCriteria{sp.confining_stress, sp.max_strain_rate, sp.stress_tolerance, 1e-3, 0.02},
      [&](const HoldState& state) {
        progress.update(0.0, fmt::format("re-equilibrating: wall stress error {:.2f} %, unbalanced {:.1e}",
                                         100 * state.max_stress_error, state.unbalanced));
        return true;
      });
  const Vec3 size0 = box_high(sim.walls()) - box_low(sim.walls());
  const double volume0 = size0.x * size0.y * size0.z;
  const double height0 = size0.z;
  // Platen speed: given, or the fastest whose inertial number at the confining stress is the bound
  // (the mean stress only grows while shearing, so I stays below it).
  const double rate_bound = s.max_inertial_number / (sp.diameter * std::sqrt(sp.density / sp.confining_stress));
  const double platen_speed = s.platen_speed ? *s.platen_speed : 0.5 * rate_bound * height0;
  const double strain_rate = 2.0 * platen_speed / height0;
  const double dt = settings.time_step;
  const long total_steps = static_cast<long>(std::ceil(s.max_axial_strain * height0 / (2.0 * platen_speed) / dt));
  if (!options.quiet)
    fmt::print(stderr,
               "triaxial: {} particles, box {:.2f} x {:.2f} x {:.2f} mm, solid fraction {:.4f}; platens at {:.4g} m/s "
               "each (strain rate {:.3g} 1/s, {}), dt = {:.3g} s, {} steps\n",
               specimen.particles.size(), 1e3 * size0.x, 1e3 * size0.y, 1e3 * size0.z,
               solid_fraction(sim.particles(), size0.x * size0.y * size0.z),
               platen_speed, strain_rate, s.platen_speed ? "given" : "from the inertial-number bound", dt, total_steps);

  CsvStream curve(options.out_dir + "/curve.csv",
                  "time_s,axial_strain,lateral_strain_x,lateral_strain_y,volumetric_strain,"
                  "axial_stress_walls_Pa,lateral_stress_x_walls_Pa,lateral_stress_y_walls_Pa,"
                  "axial_stress_particles_Pa,lateral_stress_x_particles_Pa,lateral_stress_y_particles_Pa,"
                  "deviator_stress_Pa,mean_stress_Pa,stress_ratio,solid_fraction,coordination_number,"
                  "inertial_number,unbalanced_force_ratio");
  double peak_axial = 0, peak_strain = 0, peak_deviator = 0, peak_ratio = 0, max_inertial = 0;
  double lateral_error2 = 0;
  long lateral_samples = 0;
  double worst_agreement = 0;  // largest |wall - particle| / wall axial stress once quasi-static
  double last_axial = 0, last_strain = 0;
  long next_output = 0;
  // Lateral walls may move as fast as the platens (the specimen cannot dilate faster).
  std::array<StressServo, 4> servos;
  for (StressServo& servo : servos) servo = StressServo(ServoSettings{sp.confining_stress, 2.0 * platen_speed});
  for (long step = 0;; ++step) {
    const Vec3 lo = box_low(sim.walls()), hi = box_high(sim.walls());
    const Vec3 size = hi - lo;
    const double axial_strain = (height0 - size.z) / height0;
    if (axial_strain >= next_output * s.output_strain_interval - 1e-12 || step == total_steps) {
      ++next_output;
      const double volume = size.x * size.y * size.z;
      const Tensor3 sigma = love_weber_stress(sim, volume);
      const double sa = 0.5 * (wall_stress(sim.walls(), bottom) + wall_stress(sim.walls(), top));
      const double sx = 0.5 * (wall_stress(sim.walls(), x_low) + wall_stress(sim.walls(), x_high));
      const double sy = 0.5 * (wall_stress(sim.walls(), y_low) + wall_stress(sim.walls(), y_high));
      const double deviator = sa - 0.5 * (sx + sy), mean = (sa + sx + sy) / 3.0;
      const double inertial = inertial_number(strain_rate, sp.diameter, sp.density, mean);
      const double unbalanced = unbalanced_force_ratio(sim);
      curve.write(fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", exact(sim.time()),
                              exact(axial_strain), exact((size0.x - size.x) / size0.x),
                              exact((size0.y - size.y) / size0.y), exact(1.0 - volume / volume0), exact(sa), exact(sx),
                              exact(sy), exact(sigma[2][2]), exact(sigma[0][0]), exact(sigma[1][1]), exact(deviator),
                              exact(mean), exact(deviator / mean), exact(solid_fraction(sim.particles(), volume)),
                              exact(coordination_number(sim)), exact(inertial), exact(unbalanced)));
      if (step > 0) {
        max_inertial = std::max(max_inertial, inertial);
        for (int k = 0; k < 4; ++k) {
          const double e = wall_stress(sim.walls(), k) / sp.confining_stress - 1.0;
          lateral_error2 += e * e;
          ++lateral_samples;
        }
        if (axial_strain > 0.005) worst_agreement = std::max(worst_agreement, std::abs(sigma[2][2] - sa) / sa);
      }
      if (sa > peak_axial) peak_axial = sa, peak_strain = axial_strain;
      peak_deviator = std::max(peak_deviator, deviator);
      peak_ratio = std::max(peak_ratio, deviator / mean);
      last_axial = sa;
      last_strain = axial_strain;
      progress.update(static_cast<double>(step) / total_steps,
                      fmt::format("axial strain {:.2f} %, axial stress {:.1f} kPa", 100 * axial_strain, 1e-3 * sa));
    }
    if (step == total_steps) break;
    for (int k = 0; k < 4; ++k)
      set_inward_speed(sim.walls(), k,
                       servos[k].update(wall_stress(sim.walls(), k), wall_area(sim.walls(), k),
                                        sim.walls()[k].contact_stiffness, dt));
    set_inward_speed(sim.walls(), bottom, platen_speed);
    set_inward_speed(sim.walls(), top, platen_speed);
    sim.step();
  }
  curve.close();
  const double wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  const double sigma3 = sp.confining_stress;
  const double phi_peak = std::asin(peak_deviator / (peak_deviator + 2.0 * sigma3)) * 180.0 / M_PI;

  nlohmann::json j;
  j["grainlab_version"] = version_string;
  j["config_file"] = path;
  j["inputs"] = nlohmann::json::parse([&] {
    std::ostringstream o;
    o << toml::json_formatter{root};
    return o.str();
  }());
  j["specimen"] = specimen_json(specimen);
  j["specimen"]["source"] = s.specimen_file ? *s.specimen_file : std::string("prepared in this run");
  j["time_step_s"] = dt;
  j["dt_fraction"] = sp.dt_fraction;
  j["collision_duration_s"] = dt / sp.dt_fraction;
  j["loading"] = {{"platen_speed_m_per_s", platen_speed},
                  {"strain_rate_per_s", strain_rate},
                  {"rule", s.platen_speed ? "platen speed given (paper: 0.01 m/s)" : "fastest rate with I <= max_inertial_number"},
                  {"max_inertial_number_bound", s.max_inertial_number}};
  j["max_inertial_number"] = max_inertial;
  j["quasi_static_flag"] = max_inertial > 1e-3 ? "I exceeded 1e-3: not quasi-static" : "ok (I <= 1e-3)";
  j["initial_solid_fraction"] = solid_fraction(specimen.particles, volume0);
  j["re_equilibration"] = {{"unbalanced_force_ratio", held.unbalanced}, {"max_wall_stress_error", held.max_stress_error},
                           {"reached", held.reached}};
  j["peak_axial_stress_Pa"] = peak_axial;
  j["axial_strain_at_peak"] = peak_strain;
  j["peak_deviator_stress_Pa"] = peak_deviator;
  j["peak_stress_ratio_q_over_p"] = peak_ratio;
  j["peak_friction_angle_deg"] = phi_peak;
  j["residual_axial_stress_Pa"] = last_axial;
  j["final_axial_strain"] = last_strain;
  j["lateral_stress_rms_error"] = lateral_samples ? std::sqrt(lateral_error2 / lateral_samples) : 0.0;
  j["wall_particle_axial_stress_max_difference"] = worst_agreement;
  j["steps"] = sim.step_count();
  j["neighbor_rebuilds"] = sim.rebuild_count();
  j["wall_time_s"] = wall_time;
  j["preparation_wall_time_s"] = prep_wall_time;
  j["reference"] = {{"laboratory_peak_axial_stress_Pa", lab_peak_axial_stress},
                    {"laboratory_axial_strain_at_peak", lab_axial_strain_at_peak},
                    {"published_dem_peak_axial_stress_Pa", published_dem_peak_axial_stress},
                    {"difference_to_laboratory", peak_axial / lab_peak_axial_stress - 1.0},
                    {"difference_to_published_dem", peak_axial / published_dem_peak_axial_stress - 1.0}};
  write_file_atomically(options.out_dir + "/summary.json", j.dump(2) + "\n");
  plot_triaxial_curve(options.out_dir);
  progress.finish(fmt::format("{} steps", sim.step_count()));
  if (!options.quiet)
    fmt::print("triaxial: peak axial stress {:.1f} kPa at {:.2f} % axial strain; laboratory 342.4 kPa at 5.11 % ({:+.1f} %), "
               "published DEM 320.25 kPa ({:+.1f} %); lateral stress RMS error {:.3f} %; wall time {:.0f} s\n",
               1e-3 * peak_axial, 100 * peak_strain, 100 * (peak_axial / lab_peak_axial_stress - 1.0),
               100 * (peak_axial / published_dem_peak_axial_stress - 1.0),
               100 * j["lateral_stress_rms_error"].get<double>(), wall_time);
}

}  // namespace grainlab
