#include "lab/triaxial.hpp"

#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "io/interrupt.hpp"
#include "io/output_files.hpp"
#include "lab/lab_config.hpp"
#include "lab/triaxial_plot.hpp"
#include "lab/triaxial_shear.hpp"
#include "measure/boundary.hpp"
#include "measure/specimen_state.hpp"

namespace grainlab {
namespace {

void finish_triaxial(const ElementRun& run, const ShearProgress& p, const ElementTestSettings& s,
                     const std::string& dir, bool quiet) {
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
  j["neighbor_list_refreshes"] = run.sim.list_refresh_count();
  j["shearing_wall_time_s"] = run.wall_time_before;
  j["wall_time_s"] = j["preparation_wall_time_s"].get<double>() + run.wall_time_before;
  const LaboratoryComparison lab =
      compare_with_laboratory(s.laboratory, p.peak_axial, p.peak_strain);
  if (s.laboratory) j["reference"] = lab.json;
  write_file_atomically(dir + "/summary.json", j.dump(2) + "\n");
  plot_triaxial_curve(dir);
  if (!quiet)
    fmt::print(
        "triaxial: peak axial stress {:.1f} kPa at {:.2f} % axial strain{}; lateral stress RMS "
        "error {:.2f} % (worst interval {:.2f} %); particle vs boundary stress within {:.2f} %; "
        "wall time {:.0f} s\n",
        1e-3 * p.peak_axial, 100 * p.peak_strain, lab.text, 100 * rms, 100 * p.max_lateral_error,
        100 * p.worst_agreement, j["wall_time_s"].get<double>());
}

void shear_and_finish(ElementRun& run, const ShearProgress& start, const TriaxialConfig& c,
                      const RunOptions& options) {
  TriaxialShear stage(run, start, options.out_dir);
  load_to_end(run, stage, c.settings.checkpoint_interval, options);
  finish_triaxial(run, stage.progress(), c.settings, options.out_dir, options.quiet);
}

}  // namespace

TriaxialConfig read_triaxial_config(const std::string& path, const toml::table& root) {
  TableReader t = test_table_reader(path, root);
  TriaxialConfig c{read_element_test_keys(path, root, t)};
  c.max_axial_strain = read_max_axial_strain(c, c.max_axial_strain, 1, t);
  t.finish();
  return c;
}

void run_triaxial(const std::string& path, const toml::table& root, const RunOptions& options) {
  const TriaxialConfig c = read_triaxial_config(path, root);
  const ElementTestSettings& s = c.settings;
  ElementRun run = begin_element_test("triaxial", path, root, c, options);
  ShearProgress p;
  plan_shear_loading(p, run, s, box_size(run.sim.walls()), c.max_axial_strain);
  if (!options.quiet)
    fmt::print(stderr,
               "triaxial: {} particles, box {:.2f} x {:.2f} x {:.2f} mm, solid fraction {:.4f}; "
               "platens at {:.4g} m/s each (strain rate {:.3g} 1/s, {}), dt = {:.3g} s, {} steps\n",
               run.sim.particles().size(), 1e3 * p.size0.x, 1e3 * p.size0.y, 1e3 * p.size0.z,
               solid_fraction(run.sim.particles(), box_volume(run.sim.walls())), p.platen_speed,
               p.strain_rate, s.platen_speed ? "given" : "from the inertial-number bound",
               run.sim.settings().time_step, p.total_steps);
  shear_and_finish(run, p, c, options);
}

void resume_triaxial(ElementRun run, const toml::table& root, const RunOptions& options) {
  const TriaxialConfig c = read_triaxial_config(run.config_path, root);
  const ShearProgress p = TriaxialShear::restore(run);
  if (!options.quiet)
    fmt::print(stderr, "triaxial: resuming {} at step {} of {}\n", run.config_path, p.step,
               p.total_steps);
  shear_and_finish(run, p, c, options);
}

}  // namespace grainlab
