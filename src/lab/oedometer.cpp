#include "lab/oedometer.hpp"

#include <fmt/format.h>

#include <cmath>

#include "control/box_controller.hpp"
#include "io/config_error.hpp"
#include "io/output_files.hpp"
#include "lab/lab_config.hpp"
#include "measure/boundary.hpp"
#include "measure/interval_stresses.hpp"
#include "measure/specimen_state.hpp"

namespace grainlab {
namespace {

struct OedometerState {  // plain values, saved as they are
  long step = 0, steps_per_output = 1;
  int phase = 1;  // +1 loading, -1 unloading, 0 done
  double platen_speed = 0, max_axial_stress = 0, unload_stress = 0, max_axial_strain = 0;
  Vec3 size0;
  IntervalStresses interval;
};

constexpr const char* header =
    "time_s,phase,axial_strain,lateral_strain_x,lateral_strain_y,axial_stress_walls_Pa,"
    "lateral_stress_x_walls_Pa,lateral_stress_y_walls_Pa,axial_stress_particles_Pa,"
    "lateral_stress_x_particles_Pa,lateral_stress_y_particles_Pa,K0_walls,K0_particles,"
    "solid_fraction,coordination_number";

BoxControlSettings oedometer_control(double inward_speed) {  // lateral walls fixed
  return {{AxisControl{}, AxisControl{}, AxisControl{AxisMode::speed, 0.0, inward_speed}}};
}

class Compression : public LoadingStage {
 public:
  Compression(ElementRun& run, const OedometerState& s)
      : s_(s),
        control_(oedometer_control(s.phase * s.platen_speed)),
        attached_(run.sim, control_) {}
  const char* curve_header() const override { return header; }
  long step() const override { return s_.step; }
  bool finished(const ElementRun&) const override { return s_.phase == 0; }
  std::string position() const override { return fmt::format("step {}", s_.step); }
  void save(ElementRun& run) const override { store_test_state(run, s_); }

  void after_step(ElementRun& run) override {
    s_.interval.add_walls(run.sim);
    if (s_.step++ % 50 == 0) s_.interval.add_specimen(run.sim);  // a pass over all contacts
    if (s_.step % s_.steps_per_output != 0) return;
    // The turning points are decided on the interval averages (a step's wall force rattles).
    const double axial = record(run), strain = box_strain(s_.size0, box_size(run.sim.walls())).z;
    if (s_.phase == 1 && strain > s_.max_axial_strain)
      throw ConfigError(
          fmt::format("test.max_axial_stress: {:.4g} Pa not reached by axial strain "
                      "{:.3g} (test.max_axial_strain)",
                      s_.max_axial_stress, strain));
    if ((s_.phase == 1 && axial >= s_.max_axial_stress) ||
        (s_.phase == -1 && axial <= s_.unload_stress)) {
      s_.phase = s_.phase == 1 ? -1 : 0;
      control_.set_axis(2, {AxisMode::speed, 0.0, s_.phase * s_.platen_speed});
    }
  }

  void observe(ElementRun& run, Progress& progress) override {
    if (s_.step == 0) record(run);
    if (s_.step % 1000 == 0)
      progress.update(
          Progress::unknown_fraction,
          fmt::format("{}: axial strain {:.3f} %", s_.phase > 0 ? "loading" : "unloading",
                      100 * box_strain(s_.size0, box_size(run.sim.walls())).z));
  }

 private:
  // One curve row: stresses averaged since the last row (the state itself for the first);
  // returns the row's axial stress.
  double record(ElementRun& run) {
    const Simulation& sim = run.sim;
    const IntervalStresses::Averages averaged = s_.interval.take(sim);
    const std::array<double, 3>& particles = averaged.particle;
    std::array<double, 3> wall;
    for (int a = 0; a < 3; ++a) wall[a] = 0.5 * (averaged.wall[2 * a] + averaged.wall[2 * a + 1]);
    const Vec3 strain = box_strain(s_.size0, box_size(sim.walls()));
    run.curve_rows +=
        fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", exact(sim.time()), s_.phase,
                    exact(strain.z), exact(strain.x), exact(strain.y), exact(wall[2]),
                    exact(wall[0]), exact(wall[1]), exact(particles[2]), exact(particles[0]),
                    exact(particles[1]), exact(0.5 * (wall[0] + wall[1]) / wall[2]),
                    exact(0.5 * (particles[0] + particles[1]) / particles[2]),
                    exact(solid_fraction(sim.particles(), box_volume(sim.walls()))),
                    exact(coordination_number(sim)));
    return wall[2];
  }

  OedometerState s_;
  BoxController control_;
  ScopedListener attached_;
};

void finish(const ElementRun& run, const std::string& dir, bool quiet) {
  const std::vector<std::vector<double>> rows = curve_values(run.curve_rows);
  enum { phase = 1, strain = 2, sv = 5, sh = 6, k0w = 11, k0p = 12 };
  size_t top = 0;
  for (size_t i = 0; i < rows.size(); ++i)
    if (rows[i][phase] == 1) top = i;  // the last loading row: the switch at max stress
  const double s0 = rows.front()[sv], smax = rows[top][sv];
  const double upper = s0 + 0.5 * (smax - s0);  // moduli on the upper half of each branch
  nlohmann::json j = nlohmann::json::parse(run.run_info);
  j["max_axial_stress_Pa"] = smax;
  j["axial_strain_at_max_stress"] = rows[top][strain];
  j["K0_walls_at_max_stress"] = rows[top][k0w];
  j["K0_particles_at_max_stress"] = rows[top][k0p];
  j["K0_walls_vs_particles"] = rows[top][k0w] / rows[top][k0p] - 1.0;
  j["K0_incremental_on_loading"] =
      curve_slope(rows, sv, sh, [&](const auto& r) { return r[phase] == 1 && r[sv] >= upper; });
  j["constrained_modulus_loading_Pa"] =
      curve_slope(rows, strain, sv, [&](const auto& r) { return r[phase] == 1 && r[sv] >= upper; });
  j["constrained_modulus_unloading_Pa"] = curve_slope(
      rows, strain, sv, [&](const auto& r) { return r[phase] == -1 && r[sv] >= upper; });
  j["residual_axial_strain"] = rows.back()[strain];
  j["lateral_strain_max"] = std::max(std::abs(rows.back()[3]), std::abs(rows.back()[4]));
  j["steps"] = run.sim.step_count();
  j["loading_wall_time_s"] = run.wall_time_before;
  write_file_atomically(dir + "/summary.json", j.dump(2) + "\n");
  if (!quiet)
    fmt::print(
        "oedometer: K0 = {:.4f} (walls) / {:.4f} (particles) at {:.0f} kPa; constrained "
        "modulus {:.1f} MPa loading, {:.1f} MPa unloading\n",
        rows[top][k0w], rows[top][k0p], 1e-3 * smax,
        1e-6 * j["constrained_modulus_loading_Pa"].get<double>(),
        1e-6 * j["constrained_modulus_unloading_Pa"].get<double>());
}

void load_and_finish(ElementRun& run, const OedometerState& s, const OedometerConfig& c,
                     const RunOptions& options) {
  Compression stage(run, s);
  load_to_end(run, stage, c.settings.checkpoint_interval, options);
  finish(run, options.out_dir, options.quiet);
}

}  // namespace

OedometerConfig read_oedometer_config(const std::string& path, const toml::table& root) {
  TableReader t = test_table_reader(path, root);
  // One-dimensional compression is stiff (M ~ GPa for glass beads at 150 kPa): the whole loading
  // spans ~1e-4 strain, so the platens move a hundred times slower than in a triaxial test to
  // keep the loading time ~100 elastic wave transits of the specimen, with rows every 2e-6.
  ElementTestSettings defaults;
  defaults.max_inertial_number = 1e-5;
  defaults.output_strain_interval = 2e-6;
  OedometerConfig c{read_element_test_keys(path, root, t, defaults)};
  const double sigma3 = c.settings.specimen.confining_stress;
  c.max_axial_stress = t.number_or("max_axial_stress", Quantity::pressure, c.max_axial_stress);
  if (!(c.max_axial_stress > sigma3))
    t.fail("max_axial_stress", "expected a stress above the confining stress");
  c.unload_stress = t.number_or("unload_stress", Quantity::pressure, sigma3);
  if (!(c.unload_stress > 0 && c.unload_stress < c.max_axial_stress))
    t.fail("unload_stress", "expected a stress in (0, max_axial_stress)");
  c.max_axial_strain = read_max_axial_strain(c, c.max_axial_strain, 2, t);
  // The oedometer has no peak to compare: laboratory values would be ignored without a word.
  if (c.settings.laboratory)
    t.fail("laboratory",
           "the oedometer test compares no result with laboratory values (a peak and its strain "
           "are compared by the triaxial and plane strain tests)");
  t.finish();
  return c;
}

void run_oedometer(const std::string& path, const toml::table& root, const RunOptions& options) {
  const OedometerConfig c = read_oedometer_config(path, root);
  ElementRun run = begin_element_test("oedometer", path, root, c, options);
  OedometerState s;
  s.size0 = box_size(run.sim.walls());
  const LoadingRate rate = loading_rate(c.settings, s.size0.z);
  s.platen_speed = rate.platen_speed;
  s.max_axial_stress = c.max_axial_stress;
  s.unload_stress = c.unload_stress;
  s.max_axial_strain = c.max_axial_strain;
  s.steps_per_output =
      std::max(1L, std::lround(c.settings.output_strain_interval * s.size0.z /
                               (2.0 * s.platen_speed) / run.sim.settings().time_step));
  nlohmann::json j = nlohmann::json::parse(run.run_info);
  j["loading"] = loading_json(rate, c.settings);
  run.run_info = j.dump();
  load_and_finish(run, s, c, options);
}

void resume_oedometer(ElementRun run, const toml::table& root, const RunOptions& options) {
  load_and_finish(run, restored_test_state<OedometerState>(run),
                  read_oedometer_config(run.config_path, root), options);
}

}  // namespace grainlab
