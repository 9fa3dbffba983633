#include "lab/plane_strain.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "control/plane_strain_box.hpp"
#include "io/output_files.hpp"
#include "io/output_manifest.hpp"
#include "io/python_script.hpp"
#include "lab/lab_config.hpp"
#include "lab/lab_test.hpp"
#include "lab/plane_strain_band.hpp"
#include "lab/plane_strain_shear.hpp"
#include "measure/boundary.hpp"
#include "measure/specimen_state.hpp"

namespace grainlab {
namespace {

constexpr double degrees = 180.0 / M_PI;

// The plane strain box of the specimen now, its lateral faces where a membrane finds them.
PlaneStrainBox located_box(const Simulation& sim, const SpecimenSettings& sp) {
  Membrane membrane(plane_strain_membrane(sp.confining_stress, sp.diameter));
  membrane.locate(sim);
  return plane_strain_box(sim, membrane);
}

}  // namespace

double specimen_weight(const Simulation& sim) {
  const ParticleStore& p = sim.particles();
  double mass = 0.0;
  for (size_t i = 0; i < p.size(); ++i)
    if (p.inverse_mass[i] > 0) mass += 1.0 / p.inverse_mass[i];
  return -sim.settings().gravity.z * mass;
}

// The lateral faces closed by the membrane at the confining stress, front/back walls and platens
// servo-held at it (under gravity the bottom platen at it plus the specimen's weight over its
// area), until every wall's stress, and the particles' lateral stress against the boundary's, is
// within the preparation's tolerance and the unbalanced force ratio is below 1e-3 (at most
// re_equilibration_max_time).
SpecimenMount plane_strain_mount(const ElementTestSettings& s) {
  const SpecimenSettings& sp = s.specimen;
  const double max_time = s.re_equilibration_max_time;
  SpecimenMount m;
  m.walls = [sp](const Specimen& s) {
    return plane_strain_walls(s.low, s.high, sp.lateral_material, sp.platen_material);
  };
  m.equilibrate = [sp, max_time](Simulation& sim,
                                 const std::function<bool(const HoldState&)>& on_check) {
    const double p = sp.confining_stress;
    // At rest under a constant pressure on two faces the specimen breathes, and with the glass's
    // e = 0.926 the 88,400-bead specimen rang for minutes (unbalanced force ratio cycling between
    // 0.007 and 0.03); damped contacts bring it to rest, then the measured ones are restored.
    const PairTable measured = sim.pair_table();
    sim.set_pair_table(resting_contacts(sp, measured, sim.settings().time_step,
                                        sim.particles().smallest_radius()));
    Membrane membrane(plane_strain_membrane(p, sp.diameter));
    membrane.start(sim);
    const AxisControl held{AxisMode::stress, p};
    PlaneStrainControl control(membrane, {held, held}, ServoRegime::compaction, sp.max_strain_rate);
    const double weight = specimen_weight(sim);
    control.set_bottom_platen_load(weight);
    HoldState state;
    {
      const ScopedListener m_attached(sim, membrane), c_attached(sim, control);
      const double t_end = sim.time() + max_time;
      while (sim.time() < t_end) {
        sim.advance(200);
        const PlaneStrainBox box = plane_strain_box(sim, membrane);
        state.solid_fraction = solid_fraction(sim.particles(), box.volume());
        // The walls at p, and the particles' lateral stress at the boundary's (the membrane's p
        // plus what the walls' and platens' friction adds).
        state.max_stress_error =
            std::abs(love_weber_stress(sim, box.volume())[0][0] /
                         boundary_stress(sim, box.centre(), box.volume())[0][0] -
                     1.0);
        for (int k = 0; k < 4; ++k) {
          const double target =
              p + (k == bottom_platen ? weight / (box.size().x * box.size().y) : 0.0);
          state.max_stress_error =
              std::max(state.max_stress_error,
                       std::abs(plane_strain_wall_stress(sim, box, k) / target - 1.0));
        }
        state.unbalanced = unbalanced_force_ratio(sim);
        if (on_check(state) && state.max_stress_error < sp.stress_tolerance &&
            state.unbalanced < 1e-3) {
          state.reached = true;
          break;
        }
      }
    }
    stop_walls(sim);
    membrane.release(sim);
    sim.set_pair_table(measured);
    return state;
  };
  m.volume = [sp](const Simulation& sim) { return located_box(sim, sp).volume(); };
  return m;
}

namespace {

void plot(const std::string& dir) {
  try {
    for (const char* f : {"curve.png", "curve.png.tmp.png", "band.png", "band.png.tmp.png"})
      record_output(dir + "/" + f);
    run_python_script("plot_plane_strain.py", {dir});
  } catch (const std::runtime_error& e) {
    fmt::print(stderr, "grainlab: warning: no curve.png / band.png: {}\n", e.what());
  }
}

void finish(const ElementRun& run, const PlaneStrainProgress& p, const ElementTestSettings& s,
            const std::string& dir, bool quiet) {
  nlohmann::json j = nlohmann::json::parse(run.run_info);
  const double s1 = p.peak_axial, s3 = p.peak_lateral;
  const double phi = std::asin((s1 - s3) / (s1 + s3)) * degrees;
  // Dilatancy at the peak: rates of volumetric and lateral strain per axial strain over +-1 %
  // around it, sin psi = -d(eps_v) / (d(eps_1) - d(eps_3)) (compression positive, eps_2 = 0).
  const std::vector<std::vector<double>> rows = curve_values(run.curve_rows);
  enum { axial = 1, lateral = 2, volumetric = 4 };
  auto near_peak = [&](const std::vector<double>& r) {
    return std::abs(r[axial] - p.peak_strain) <= 0.01;
  };
  const double dv = curve_slope(rows, axial, volumetric, near_peak);
  const double d3 = curve_slope(rows, axial, lateral, near_peak);
  const double psi = std::asin(std::clamp(-dv / (1.0 - d3), -1.0, 1.0)) * degrees;
  j["max_inertial_number"] = p.max_inertial;
  j["quasi_static_flag"] =
      p.max_inertial > 1e-3 ? "I exceeded 1e-3: not quasi-static" : "ok (I <= 1e-3)";
  j["peak_axial_stress_Pa"] = s1;
  j["axial_strain_at_peak"] = p.peak_strain;
  j["peak_deviator_stress_Pa"] = p.peak_deviator;
  j["peak_friction_angle_deg"] = phi;
  j["peak_friction_angle_rule"] = "plane strain: sin(phi) = (s1 - s3) / (s1 + s3) at the peak";
  j["dilatancy_angle_deg"] = psi;
  j["dilatancy_angle_rule"] =
      "sin(psi) = -d(eps_v) / (d(eps_1) - d(eps_3)), rates fitted over +-1 % axial strain around "
      "the peak";
  j["residual_axial_stress_Pa"] = p.last_axial;
  j["final_axial_strain"] = p.last_strain;
  const double rms = p.membrane_samples ? std::sqrt(p.membrane_error2 / p.membrane_samples) : 0.0;
  j["membrane"] = {
      {"method",
       "pressure on the outermost bead of each cell (about 1 d x 1 d) of the lateral faces, along "
       "the face normal, total = p x face area; re-identified at every neighbour-list rebuild"},
      {"lateral_stress_particles_vs_boundary_rms", rms},
      {"lateral_stress_particles_vs_boundary_max", p.max_membrane_error},
      {"within_2_percent", p.max_membrane_error <= 0.02},
      {"lateral_stress_particles_vs_applied_max", p.max_applied_error},
      {"wall_friction_share_of_lateral_stress",
       p.membrane_samples ? p.wall_friction_share_sum / p.membrane_samples : 0.0},
      {"comparison",
       "particles: Love-Weber average over the specimen; boundary: the average-stress theorem "
       "over the membrane's forces (at the beads' surface) and the contacts of the fixed walls "
       "and the platens, whose friction adds to the membrane's pressure (share reported); "
       "applied: the membrane's pressure"},
      {"max_escaped_beads", p.max_escaped}};
  j["max_out_of_plane_strain"] = p.max_out_of_plane_strain;
  const BandAnalysis band = analyse_shear_band(run.sim.particles(), p.diameter);
  write_band_map(dir + "/band_map.csv", band.map);
  j["shear_band"] = band_json(band.band, p.diameter, phi, psi);
  j["shear_band"]["map_low_m"] = {band.map.low_a, band.map.low_b};
  j["shear_band"]["offset_m"] = band.band.offset;
  j["steps"] = run.sim.step_count();
  j["neighbor_rebuilds"] = run.sim.rebuild_count();
  j["neighbor_list_refreshes"] = run.sim.list_refresh_count();
  j["shearing_wall_time_s"] = run.wall_time_before;
  j["wall_time_s"] = j["preparation_wall_time_s"].get<double>() + run.wall_time_before;
  const LaboratoryComparison lab = compare_with_laboratory(s.laboratory, s1, p.peak_strain);
  if (s.laboratory) j["reference"] = lab.json;
  write_file_atomically(dir + "/summary.json", j.dump(2) + "\n");
  plot(dir);
  if (!quiet)
    fmt::print(
        "plane strain: peak axial stress {:.1f} kPa at {:.2f} % axial strain{}; phi {:.1f} deg, "
        "psi {:.1f} "
        "deg; lateral stress of the particles vs the boundary within {:.2f} % (RMS {:.2f} %), {} "
        "escaped beads; band at "
        "{:.1f} deg (Mohr-Coulomb {:.1f}, Roscoe {:.1f}, Arthur {:.1f}), {:.1f} d thick; wall "
        "time {:.0f} s\n",
        1e-3 * s1, 100 * p.peak_strain, lab.text, phi, psi, 100 * p.max_membrane_error, 100 * rms,
        p.max_escaped, band.band.inclination_deg, 45 + phi / 2, 45 + psi / 2, 45 + (phi + psi) / 4,
        band.band.thickness / p.diameter, j["wall_time_s"].get<double>());
  if (p.max_escaped > 0)
    throw UnreliableResult(fmt::format(
        "{} beads escaped through the membrane: the results are not those of a confined "
        "specimen; use more beads across the width or a slower loading",
        p.max_escaped));
}

void shear_and_finish(ElementRun& run, const PlaneStrainProgress& start, const PlaneStrainConfig& c,
                      const RunOptions& options, const std::string* membrane_state) {
  PlaneStrainShear stage(run, start, options.out_dir, membrane_state);
  load_to_end(run, stage, c.settings.checkpoint_interval, options);
  finish(run, stage.progress(), c.settings, options.out_dir, options.quiet);
}

}  // namespace

PlaneStrainConfig read_plane_strain_config(const std::string& path, const toml::table& root) {
  TableReader t = test_table_reader(path, root);
  ElementTestSettings defaults;
  SpecimenSettings& sp = defaults.specimen;
  sp.count = 88400;
  sp.nominal_box = {0.060, 0.100, 0.100};  // width (membrane, x), thickness (y), height (z)
  sp.target_solid_fraction = 0.617;
  // 100 mm of beads: compacted walls-first they jam all at once and the walls overshoot many
  // times over (control/affine_compaction.hpp).
  sp.compaction = Compaction::affine;
  sp.max_strain_rate = 40.0;
  defaults.output_strain_interval = 0.002;
  PlaneStrainConfig c{read_element_test_keys(path, root, t, defaults)};
  const SpecimenSettings& s = c.settings.specimen;
  const std::string membrane = t.string_or("membrane_faces", "x");
  const std::string fixed = t.string_or("fixed_faces", "y");
  if (membrane == fixed)
    t.fail("membrane_faces",
           fmt::format("the membrane cannot be on the faces normal to {}: they have the fixed "
                       "walls (fixed_faces)",
                       fixed));
  if (membrane != "x")
    t.fail("membrane_faces",
           "expected \"x\": the membrane closes the faces normal to x (orient the box as box = "
           "[width, thickness, height])");
  if (fixed != "y")
    t.fail("fixed_faces", "expected \"y\": the fixed front and back walls are normal to y");
  const double across = s.nominal_box.x / s.diameter;
  if (across < 8.0)
    t.fail("box",
           fmt::format("the width holds {:.1f} bead diameters; the membrane needs at least 8 "
                       "across the width",
                       across));
  c.settings.gravity = t.number_or("gravity", Quantity::acceleration, 0.0);
  if (!(c.settings.gravity >= 0 && c.settings.gravity <= 1e3))
    t.fail("gravity", "expected an acceleration in [0, 1000] m/s^2 (acting along -z)");
  c.max_axial_strain = read_max_axial_strain(c, c.max_axial_strain, 1, t);
  t.finish();
  return c;
}

void run_plane_strain(const std::string& path, const toml::table& root, const RunOptions& options) {
  const PlaneStrainConfig c = read_plane_strain_config(path, root);
  const ElementTestSettings& s = c.settings;
  const SpecimenSettings& sp = s.specimen;
  ElementRun run =
      begin_element_test("plane_strain", path, root, c, options, plane_strain_mount(s));
  PlaneStrainProgress p;
  plan_shear_loading(p, run, s, located_box(run.sim, sp).size(), c.max_axial_strain);
  if (!options.quiet)
    fmt::print(stderr,
               "plane strain: {} particles, {:.2f} wide x {:.2f} thick x {:.2f} high mm; platens "
               "at {:.4g} m/s each (strain rate {:.3g} 1/s, {}), dt = {:.3g} s, {} steps\n",
               run.sim.particles().size(), 1e3 * p.size0.x, 1e3 * p.size0.y, 1e3 * p.size0.z,
               p.platen_speed, p.strain_rate,
               s.platen_speed ? "given" : "from the inertial-number bound",
               run.sim.settings().time_step, p.total_steps);
  nlohmann::json j = nlohmann::json::parse(run.run_info);
  j["initial_size_m"] = {{"width", p.size0.x}, {"thickness", p.size0.y}, {"height", p.size0.z}};
  // Self-weight: the weight over the platen area, the vertical stress it adds at the bottom
  // (rho_bulk g H); the mean over the height is half of it.
  j["gravity_m_per_s2"] = s.gravity;
  j["self_weight_stress_Pa"] = specimen_weight(run.sim) / (p.size0.x * p.size0.y);
  j["self_weight_over_confining_stress"] =
      j["self_weight_stress_Pa"].get<double>() / sp.confining_stress;
  run.run_info = j.dump();
  shear_and_finish(run, p, c, options, nullptr);
}

void resume_plane_strain(ElementRun run, const toml::table& root, const RunOptions& options) {
  const PlaneStrainConfig c = read_plane_strain_config(run.config_path, root);
  std::string membrane_state;
  const PlaneStrainProgress p = PlaneStrainShear::restore(run, membrane_state);
  if (!options.quiet)
    fmt::print(stderr, "plane strain: resuming {} at step {} of {}\n", run.config_path, p.step,
               p.total_steps);
  shear_and_finish(run, p, c, options, &membrane_state);
}

}  // namespace grainlab
