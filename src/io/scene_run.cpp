#include "io/scene_run.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "contact/time_step.hpp"
#include "core/simulation.hpp"
#include "grainlab/version.hpp"
#include "io/config_error.hpp"
#include "io/derived_report.hpp"
#include "io/output_files.hpp"
#include "io/progress.hpp"
#include "io/scene_builder.hpp"
#include "io/summary_header.hpp"
#include "io/wall_control.hpp"

namespace grainlab {

namespace {}  // namespace

void run_scene(const std::string& config_path, const RunOptions& options) {
  // Everything that can be wrong with the input is found before anything is written.
  const SceneConfig config = load_scene(config_path);
  PairTable table = build_pair_table(config);
  ParticleStore particles = build_particles(config);
  const std::vector<DerivedPair> derived = derive_pairs(config, table, particles);
  const TimeStepChoice dt = choose_time_step(config, derived);
  const SimulationSettings settings = simulation_settings(config, dt, particles);
  const double steps_needed = config.duration / dt.time_step;
  if (!(steps_needed <= max_steps_per_run))
    throw ConfigError(fmt::format(
        "{}: simulation.duration: {:.4g} s at dt = {:.4g} s needs {:.3g} steps, more than grainlab "
        "runs ({:.0e}); shorten the duration, or check the materials' E and density, which set "
        "the time step",
        config_path, config.duration, dt.time_step, steps_needed, max_steps_per_run));
  for (uint32_t id : config.output.trace_ids)
    if (id >= particles.size())
      throw ConfigError(fmt::format("{}: output.trace: particle id {} does not exist (ids 0..{})",
                                    config_path, id, particles.size() - 1));
  prepare_output_dir(options.out_dir, options.overwrite);

  const auto wall_start = std::chrono::steady_clock::now();
  Simulation sim(std::move(particles), config.walls, std::move(table), settings);
  WallStressControl wall_servos(config.wall_loads);
  if (!wall_servos.empty()) sim.attach(wall_servos);
  const std::string dir = options.out_dir;
  const long total_steps = static_cast<long>(std::ceil(config.duration / dt.time_step - 1e-9));
  if (!options.quiet)
    fmt::print(stderr,
               "grainlab run: {} particles, {} walls, dt = {:.4g} s ({:.3g} t_c, t_c = {:.4g} s), "
               "{} steps\n",
               sim.particles().size(), sim.walls().size(), dt.time_step, dt.dt_fraction,
               dt.collision_duration, total_steps);
  if (!options.quiet && dt.limited_by_stability)
    fmt::print(stderr, "grainlab run: note: dt lowered below dt_fraction * t_c to keep {} stable\n",
               dt.stable_limit_set_by);

  std::vector<uint32_t> traced = config.output.trace_ids;
  if (config.output.trace_all)
    for (uint32_t i = 0; i < sim.particles().size(); ++i) traced.push_back(i);
  CsvStream trace(dir + "/trace.csv", trace_header);
  std::vector<std::optional<double>> wall_areas;
  for (const WallLoad& load : config.wall_loads) wall_areas.push_back(load.area);
  std::optional<CsvStream> walls_csv;
  if (!sim.walls().empty()) walls_csv.emplace(dir + "/walls.csv", walls_header(sim.walls()));
  std::vector<std::pair<double, std::string>> snapshots;
  if (config.output.vtk) std::filesystem::create_directories(dir + "/vtk");

  auto write_outputs = [&](long step, bool trace_due, bool vtk_due) {
    const ParticleStore& p = sim.particles();
    if (trace_due && !traced.empty()) {
      const std::vector<size_t> where = indices_by_id(p);
      std::string rows;
      for (uint32_t id : traced) rows += trace_row(sim.time(), p, where[id]);
      trace.write(rows);
    }
    if (trace_due && walls_csv) walls_csv->write(walls_row(sim.time(), sim.walls(), wall_areas));
    if (vtk_due) {
      const std::string name = fmt::format("vtk/particles_{:08d}.vtu", step);
      write_file_atomically(dir + "/" + name, particles_vtu(p));
      snapshots.push_back({sim.time(), name});
      if (snapshots.size() == 1 && !sim.walls().empty()) {
        double extent = 0.0;
        for (const Vec3& x : p.position)
          extent = std::max({extent, std::abs(x.x), std::abs(x.y), std::abs(x.z)});
        write_file_atomically(dir + "/vtk/walls.vtu", walls_vtu(sim.walls(), 2.5 * extent + 1e-3));
      }
      write_file_atomically(dir + "/particles.pvd", pvd_index(snapshots));
    }
  };

  Progress progress("grainlab run", options.quiet);
  long next_trace = 0, next_vtk = 0;  // output numbers
  for (long step = 0;; ++step) {
    // Output k is due at the first step whose time reaches k * interval.
    const double t = step * dt.time_step;
    const bool trace_due = t >= next_trace * config.output.interval - 0.5 * dt.time_step;
    const bool vtk_due =
        config.output.vtk && t >= next_vtk * config.output.vtk_interval - 0.5 * dt.time_step;
    if (trace_due) ++next_trace;
    if (vtk_due) ++next_vtk;
    if (trace_due || vtk_due) write_outputs(step, trace_due, vtk_due);
    if (step == total_steps) break;
    sim.step();
    if ((step & 1023) == 0)
      progress.update(static_cast<double>(step) / total_steps,
                      fmt::format("t = {:.4g} s", sim.time()));
  }
  trace.close();
  if (walls_csv) walls_csv->close();
  const double wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  write_file_atomically(dir + "/final.csv", final_table(sim.particles()));

  nlohmann::json summary = summary_header(config_path, &config.source);
  summary["derived"] = derived_pairs_json(derived, dt);
  summary["derived"]["verlet_skin_m"] = settings.skin;
  summary["particles"] = sim.particles().size();
  summary["walls"] = sim.walls().size();
  summary["steps"] = sim.step_count();
  summary["simulated_time_s"] = sim.time();
  summary["neighbor_rebuilds"] = sim.rebuild_count();
  summary["kinetic_energy_final_J"] = sim.kinetic_energy();
  summary["touching_contacts_final"] = sim.touching_pair_count();
  summary["threads"] = omp_get_max_threads();
  summary["wall_time_s"] = wall_time;
  summary["particle_steps_per_s"] =
      wall_time > 0 ? sim.particles().size() * sim.step_count() / wall_time : 0.0;
  write_file_atomically(dir + "/summary.json", summary.dump(2) + "\n");
  progress.finish(
      fmt::format("{} steps, {} neighbour-list rebuilds", sim.step_count(), sim.rebuild_count()));
}

}  // namespace grainlab
