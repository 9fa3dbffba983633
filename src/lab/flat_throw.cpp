#include "lab/flat_throw.hpp"

#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "contact/stability.hpp"
#include "contact/time_step.hpp"
#include "core/simulation.hpp"
#include "grainlab/version.hpp"
#include "io/config_error.hpp"
#include "io/output_files.hpp"
#include "io/scene_builder.hpp"
#include "io/summary_header.hpp"
#include "io/toml_reader.hpp"
#include "lab/lab_config.hpp"

namespace grainlab {

// The flight before and after the impact is ballistic (gravity only), which velocity Verlet
// integrates exactly; the test therefore places the bead analytically just above the target
// (a tenth of a radius) and runs the DEM step by step only through the contact, with the fine
// step that an impact needs. Camera frames of the flight are sampled from the same parabolas.
FlatThrowResult simulate_flat_throw(const FlatThrowSettings& s, const PairTable& table,
                                    double bead_density) {
  const double r = 0.5 * s.diameter, g = s.gravity;
  const int bead = table.find(s.bead_material), target = table.find(s.target_material);
  const PairParams& pair = table(bead, target);
  FlatThrowResult out;
  out.restitution_input = pair.restitution;

  // Target surface at z = 0. A fixed target bead sits with its top at z = 0 right below the
  // landing point, so the impact is central (normal vertical) as on a plate.
  const double approach_gap = 0.1 * r;
  const double fall = s.launch_height - approach_gap;  // until the bottom is approach_gap above
  const double t_approach = std::sqrt(2.0 * fall / g);
  const double vz0 = -g * t_approach;
  const double x_launch = 0.0, x_start = s.launch_speed * t_approach;
  const double x_impact =
      x_start + s.launch_speed * (approach_gap / -vz0);  // approx. landing point

  ParticleStore p;
  std::vector<Wall> walls;
  p.add(0, bead, r, bead_density, {x_start, 0.0, r + approach_gap}, {s.launch_speed, 0.0, vz0},
        {0.0, s.spin, 0.0}, false);
  if (s.target_is_bead) {
    p.add(1, target, r, bead_density, {x_impact, 0.0, -r}, {}, {}, true);
  } else {
    Wall w;
    w.shape = WallShape::plane;
    w.material = target;
    w.normal = {0, 0, 1};
    finish_wall_geometry(w);
    walls.push_back(w);
  }
  const MaterialTimeStep step =
      material_time_step(s.dt_fraction, table, bead, {target}, r, bead_density);
  SimulationSettings settings;
  settings.time_step = step.time_step;
  settings.dt_fraction = step.dt_fraction;
  settings.gravity = {0.0, 0.0, -g};
  settings.skin = verlet_skin(2.0 * r);
  settings.step_key = SimulationSettings::StepKey::lab_test;  // advice names test.dt_fraction
  Simulation sim(std::move(p), walls, table, settings);
  out.time_step = settings.time_step;
  out.dt_fraction = settings.dt_fraction;

  auto bead_index = [&] { return sim.particles().id[0] == 0 ? size_t{0} : size_t{1}; };
  auto bottom_height = [&] {  // lowest point of the thrown bead above the target surface
    return sim.particles().position[bead_index()].z - r;
  };
  double contact_start = -1.0, contact_end = -1.0, vz_before = 0.0;
  for (long step = 0; step < 100'000'000; ++step) {
    const double vz = sim.particles().velocity[bead_index()].z;
    sim.step();
    const bool touching = bottom_height() < 0.0 ||
                          (s.target_is_bead &&
                           norm(sim.particles().position[0] - sim.particles().position[1]) < 2 * r);
    if (touching && contact_start < 0) {
      contact_start = sim.time();
      vz_before = vz;
    }
    if (touching) ++out.contact_steps;
    if (!touching && contact_start >= 0 && contact_end < 0) contact_end = sim.time();
    if (contact_end >= 0 && bottom_height() >= approach_gap) break;
  }
  if (contact_end < 0) throw std::runtime_error("flat throw: the bead never left the target");
  const ParticleStore& q = sim.particles();
  const size_t b = bead_index();
  const double vz_after = q.velocity[b].z, z_after = bottom_height();
  out.contact_duration = contact_end - contact_start;
  // Measured like the laboratory: launch height and rebound apex of the bead's lowest point.
  out.launch_height = s.launch_height;
  out.rebound_height = z_after + vz_after * vz_after / (2.0 * g);
  out.restitution_simulated = std::sqrt(out.rebound_height / out.launch_height);
  out.restitution_velocity_ratio = -vz_after / vz_before;

  // Camera frames: before the impact from the launch parabola, after it from the rebound one
  // (centre heights; target surface at z = 0), up to the rebound apex and a little beyond.
  const double t_contact_end_abs = t_approach + sim.time();
  const double x_after = q.position[b].x, vx_after = q.velocity[b].x;
  const double t_apex_after = t_contact_end_abs + vz_after / g;
  const double frame = 1.0 / s.frame_rate;
  for (double t = 0.0; t <= t_apex_after + 0.5 * (t_apex_after - t_contact_end_abs); t += frame) {
    if (t <= t_approach) {
      out.trajectory.push_back(
          {t, x_launch + s.launch_speed * t, r + s.launch_height - 0.5 * g * t * t});
    } else if (t >= t_contact_end_abs) {
      const double tau = t - t_contact_end_abs;
      out.trajectory.push_back(
          {t, x_after + vx_after * tau, r + z_after + vz_after * tau - 0.5 * g * tau * tau});
    }  // frames during the ~10 microseconds of contact are not seen by a camera
  }
  return out;
}

void run_flat_throw(const std::string& path, const toml::table& root, const RunOptions& options) {
  const SceneConfig c = read_lab_materials(path, root);
  TableReader t = test_table_reader(path, root);
  FlatThrowSettings s;
  s.bead_material = t.string_or("bead_material", "glass");
  s.target_material = t.string("target_material");
  s.diameter = t.number_or("diameter", Quantity::length, 2e-3);
  s.launch_height = t.number_or("launch_height", Quantity::length, 0.1);
  s.launch_speed = t.number_or("launch_speed", Quantity::velocity, 0.2);
  if (t.has("spin")) {
    s.spin = t.number("spin", Quantity::angular_velocity);
  } else {
    s.spin = s.launch_speed / (0.5 * s.diameter);  // rolling off the launch table, about +y
  }
  s.dt_fraction = t.number_or("dt_fraction", Quantity::dimensionless, 0.002);
  s.gravity = t.number_or("gravity", Quantity::acceleration, 9.81);
  s.frame_rate = t.number_or("frame_rate", Quantity::dimensionless, 1000.0);
  if (!(s.diameter > 0)) t.fail("diameter", "expected a bead diameter > 0 m");
  if (!(s.launch_height > 0.1 * s.diameter))
    t.fail("launch_height", "expected H > a tenth of the bead diameter");
  if (!(s.dt_fraction > 0 && s.dt_fraction <= 0.1))
    t.fail("dt_fraction", "expected a fraction of t_c in (0, 0.1]");
  if (!(s.gravity > 0)) t.fail("gravity", "expected g > 0 m/s^2");
  if (!(s.frame_rate > 0)) t.fail("frame_rate", "expected frames per second > 0");
  PairTable table = build_pair_table(c);
  const int bead = lab_material(t, table, "bead_material", s.bead_material);
  const int target = lab_material(t, table, "target_material", s.target_material);
  if (!c.materials[bead].density) t.fail("bead_material", "the bead material needs a density");
  require_pair(t, table, "target_material", bead, target);
  s.target_is_bead = t.boolean_or("target_is_bead", bead == target);
  t.finish();

  prepare_output_dir(options.out_dir, options.overwrite);
  const FlatThrowResult r = simulate_flat_throw(s, table, *c.materials[bead].density);
  std::string csv = "t_s,x_m,z_m\n";
  for (const auto& f : r.trajectory)
    csv += fmt::format("{},{},{}\n", exact(f.t), exact(f.x), exact(f.z));
  write_file_atomically(options.out_dir + "/trajectory.csv", csv);
  nlohmann::json j = summary_header(path);
  j["test"] = "flat_throw";
  j["bead_material"] = s.bead_material;
  j["target_material"] = s.target_material;
  j["target_is_fixed_bead"] = s.target_is_bead;
  j["launch_height_m"] = r.launch_height;
  j["rebound_height_m"] = r.rebound_height;
  j["launch_speed_m_per_s"] = s.launch_speed;
  j["spin_rad_per_s"] = s.spin;
  j["restitution_input"] = r.restitution_input;
  j["restitution_simulated"] = r.restitution_simulated;
  j["restitution_velocity_ratio"] = r.restitution_velocity_ratio;
  j["restitution_error"] = r.restitution_simulated - r.restitution_input;
  j["contact_duration_s"] = r.contact_duration;
  j["time_step_s"] = r.time_step;
  j["dt_fraction"] = r.dt_fraction;
  j["trajectory_note"] = "trajectory.csv: bead centre, target surface at z = 0 (use --plate-z 0)";
  write_file_atomically(options.out_dir + "/summary.json", j.dump(2) + "\n");
  if (!options.quiet)
    fmt::print(
        "flat throw {} on {}: e_input = {:.4f}, e_sim = sqrt(h/H) = {:.4f} (H = {:.4g} m, h = "
        "{:.4g} m), "
        "velocity ratio {:.4f}\n",
        s.bead_material, s.target_material, r.restitution_input, r.restitution_simulated,
        r.launch_height, r.rebound_height, r.restitution_velocity_ratio);
}

}  // namespace grainlab
