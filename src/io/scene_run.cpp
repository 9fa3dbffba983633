#include "io/scene_run.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "contact/time_step.hpp"
#include "core/simulation.hpp"
#include "grainlab/version.hpp"
#include "io/checkpoint_clock.hpp"
#include "io/checkpoint_file.hpp"
#include "io/config_error.hpp"
#include "io/derived_report.hpp"
#include "io/interrupt.hpp"
#include "io/output_files.hpp"
#include "io/output_manifest.hpp"
#include "io/progress.hpp"
#include "io/scene_builder.hpp"
#include "io/summary_header.hpp"
#include "io/wall_control.hpp"

namespace grainlab {

namespace {

// "grnlscn1": a scene run's checkpoint, first layout.
constexpr uint64_t scene_magic = 0x67726e6c73636e31;
constexpr const char* scene_kind = "scene checkpoint";

// Where a scene run stands: what a checkpoint holds besides the snapshots' index, the walls'
// servo integrals and the Simulation. Plain values, saved as they are.
struct SceneProgress {
  long step = 0;                          // steps done
  long next_trace = 0;                    // number of the next trace / walls.csv output
  long next_vtk = 0;                      // number of the next snapshot
  double wall_time_before = 0.0;          // s, earlier sessions
  long trace_bytes = 0, walls_bytes = 0;  // lengths of the .partial CSVs at the checkpoint
};

// Everything a scene run builds from its config, checked before anything is written.
struct SceneSetup {
  SceneConfig config;
  PairTable table{{}};
  ParticleStore particles;
  std::vector<DerivedPair> derived;
  TimeStepChoice dt;
  SimulationSettings settings;
  long total_steps = 0;
};

SceneSetup set_up(const std::string& config_path) {
  SceneSetup s{.config = load_scene(config_path),
               .table = PairTable{{}},
               .particles = {},
               .derived = {},
               .dt = {},
               .settings = {},
               .total_steps = 0};
  const SceneConfig& config = s.config;
  s.table = build_pair_table(config);
  s.particles = build_particles(config);
  s.derived = derive_pairs(config, s.table, s.particles);
  s.dt = choose_time_step(config, s.derived);
  s.settings = simulation_settings(config, s.dt, s.particles);
  const double steps_needed = config.duration / s.dt.time_step;
  if (!(steps_needed <= max_steps_per_run))
    throw ConfigError(fmt::format(
        "{}: simulation.duration: {:.4g} s at dt = {:.4g} s needs {:.3g} steps, more than grainlab "
        "runs ({:.0e}); shorten the duration, or check the materials' E and density, which set "
        "the time step",
        config_path, config.duration, s.dt.time_step, steps_needed, max_steps_per_run));
  for (uint32_t id : config.output.trace_ids)
    if (id >= s.particles.size())
      throw ConfigError(fmt::format("{}: output.trace: particle id {} does not exist (ids 0..{})",
                                    config_path, id, s.particles.size() - 1));
  s.total_steps = static_cast<long>(std::ceil(config.duration / s.dt.time_step - 1e-9));
  return s;
}

// A scene run from its start or from a checkpoint (`resume`: the checkpoint's reader, positioned
// after its header).
void run(const std::string& config_path, const std::string& config_text, SceneSetup setup,
         const RunOptions& options, StateReader* resume) {
  const SceneConfig& config = setup.config;
  const TimeStepChoice& dt = setup.dt;
  const std::string dir = options.out_dir;
  SceneProgress p;
  std::vector<std::pair<double, std::string>> snapshots;
  std::vector<double> integrals;
  std::optional<Simulation> restored;
  if (resume) {
    try {
      p = resume->value<SceneProgress>();
      const auto n = resume->value<uint64_t>();
      if (n > static_cast<uint64_t>(setup.total_steps) + 1) throw std::runtime_error("snapshots");
      for (uint64_t k = 0; k < n; ++k) {
        const double t = resume->value<double>();
        snapshots.push_back({t, resume->text()});
      }
      resume->array(integrals);
      restored.emplace(*resume, setup.table);
      if (!resume->at_end()) throw std::runtime_error("trailing data");
      if (p.step < 0 || p.step > setup.total_steps || restored->step_count() != p.step)
        throw std::runtime_error("step out of range");
    } catch (const std::runtime_error& e) {
      throw unresumable_checkpoint(dir + "/checkpoint.bin", e);
    }
  }
  // The interrupt flag is looked at every step, the wall clock every 1024.
  CheckpointClock clock(config.output.checkpoint_interval, 1024);
  Simulation sim = restored ? std::move(*restored)
                            : Simulation(std::move(setup.particles), config.walls,
                                         std::move(setup.table), setup.settings);
  WallStressControl wall_servos(config.wall_loads);
  wall_servos.set_integrals(integrals);
  if (!wall_servos.empty()) sim.attach(wall_servos);
  const long total_steps = setup.total_steps;
  if (!options.quiet && resume)
    fmt::print(stderr, "grainlab run: resuming {} at step {} of {}\n", config_path, p.step,
               total_steps);
  else if (!options.quiet)
    fmt::print(stderr,
               "grainlab run: {} particles, {} walls, dt = {:.4g} s ({:.3g} t_c, t_c = {:.4g} s), "
               "{} steps\n",
               sim.particles().size(), sim.walls().size(), dt.time_step, dt.dt_fraction,
               dt.collision_duration, total_steps);
  if (!options.quiet && dt.limited_by_stability && !resume)
    fmt::print(stderr, "grainlab run: note: dt lowered below dt_fraction * t_c to keep {} stable\n",
               dt.stable_limit_set_by);

  std::vector<uint32_t> traced = config.output.trace_ids;
  if (config.output.trace_all)
    for (uint32_t i = 0; i < sim.particles().size(); ++i) traced.push_back(i);
  std::vector<std::optional<double>> wall_areas;
  for (const WallLoad& load : config.wall_loads) wall_areas.push_back(load.area);
  // The CSVs of an interrupted run are cut back to their length at the checkpoint and continued.
  CsvStream trace = resume ? CsvStream::resumed(dir + "/trace.csv", p.trace_bytes)
                           : CsvStream(dir + "/trace.csv", trace_header);
  std::optional<CsvStream> walls_csv;
  if (!sim.walls().empty())
    walls_csv.emplace(resume ? CsvStream::resumed(dir + "/walls.csv", p.walls_bytes)
                             : CsvStream(dir + "/walls.csv", walls_header(sim.walls())));
  if (config.output.vtk) std::filesystem::create_directories(dir + "/vtk");

  auto write_outputs = [&](long step, bool trace_due, bool vtk_due) {
    const ParticleStore& particles = sim.particles();
    if (trace_due && !traced.empty()) {
      const std::vector<size_t> where = indices_by_id(particles);
      std::string rows;
      for (uint32_t id : traced) rows += trace_row(sim.time(), particles, where[id]);
      trace.write(rows);
    }
    if (trace_due && walls_csv) walls_csv->write(walls_row(sim.time(), sim.walls(), wall_areas));
    if (vtk_due) {
      const std::string name = fmt::format("vtk/particles_{:08d}.vtu", step);
      write_file_atomically(dir + "/" + name, particles_vtu(particles));
      snapshots.push_back({sim.time(), name});
      if (snapshots.size() == 1 && !sim.walls().empty()) {
        double extent = 0.0;
        for (const Vec3& x : particles.position)
          extent = std::max({extent, std::abs(x.x), std::abs(x.y), std::abs(x.z)});
        write_file_atomically(dir + "/vtk/walls.vtu", walls_vtu(sim.walls(), 2.5 * extent + 1e-3));
      }
      write_file_atomically(dir + "/particles.pvd", pvd_index(snapshots));
    }
  };

  const auto checkpoint = [&] {
    SceneProgress now = p;
    now.wall_time_before += clock.session_time();
    now.trace_bytes = trace.flushed_bytes();
    now.walls_bytes = walls_csv ? walls_csv->flushed_bytes() : 0;
    StateWriter out;
    write_checkpoint_header(out, scene_magic, {"scene", config_path, config_text});
    out.value(now);
    out.value(static_cast<uint64_t>(snapshots.size()));
    for (const auto& [t, name] : snapshots) out.value(t), out.text(name);
    out.array(wall_servos.integrals());
    sim.save_state(out);
    write_sealed(out, dir + "/checkpoint.bin");
  };

  Progress progress("grainlab run", options.quiet);
  for (;; ++p.step) {
    // Output k is due at the first step whose time reaches k * interval.
    const double t = p.step * dt.time_step;
    const bool trace_due = t >= p.next_trace * config.output.interval - 0.5 * dt.time_step;
    const bool vtk_due =
        config.output.vtk && t >= p.next_vtk * config.output.vtk_interval - 0.5 * dt.time_step;
    if (trace_due) ++p.next_trace;
    if (vtk_due) ++p.next_vtk;
    if (trace_due || vtk_due) write_outputs(p.step, trace_due, vtk_due);
    if (p.step == total_steps) break;
    clock.poll(checkpoint, [&] {
      return fmt::format(
          "interrupted at t = {:.6g} s; checkpoint written, continue with: "
          "grainlab run --resume {}",
          sim.time(), dir);
    });
    if ((p.step & 1023) == 0) {
      progress.update(static_cast<double>(p.step) / total_steps,
                      fmt::format("t = {:.4g} s", sim.time()));
    }
    sim.step();
  }
  trace.close();
  if (walls_csv) walls_csv->close();
  const double wall_time = p.wall_time_before + clock.session_time();
  write_file_atomically(dir + "/final.csv", final_table(sim.particles()));

  nlohmann::json summary = summary_header(config_path, &config.source);
  summary["derived"] = derived_pairs_json(setup.derived, dt);
  summary["derived"]["verlet_skin_m"] = setup.settings.skin;
  summary["particles"] = sim.particles().size();
  summary["walls"] = sim.walls().size();
  summary["steps"] = sim.step_count();
  summary["simulated_time_s"] = sim.time();
  summary["neighbor_rebuilds"] = sim.rebuild_count();
  summary["neighbor_list_refreshes"] = sim.list_refresh_count();
  summary["kinetic_energy_final_J"] = sim.kinetic_energy();
  summary["touching_contacts_final"] = sim.touching_pair_count();
  summary["threads"] = omp_get_max_threads();
  summary["wall_time_s"] = wall_time;
  summary["particle_steps_per_s"] =
      wall_time > 0 ? sim.particles().size() * sim.step_count() / wall_time : 0.0;
  write_file_atomically(dir + "/summary.json", summary.dump(2) + "\n");
  std::error_code ec;
  std::filesystem::remove(dir + "/checkpoint.bin", ec);  // finished: nothing to resume
  progress.finish(
      fmt::format("{} steps, {} neighbour-list rebuilds", sim.step_count(), sim.rebuild_count()));
}

}  // namespace

void run_scene(const std::string& config_path, const RunOptions& options) {
  // Everything that can be wrong with the input is found before anything is written.
  SceneSetup setup = set_up(config_path);
  const std::string config_text = read_file(config_path);
  prepare_output_dir(options.out_dir, options.overwrite);
  install_interrupt_handler();
  run(config_path, config_text, std::move(setup), options, nullptr);
}

bool is_scene_checkpoint(const std::string& path) {
  return has_checkpoint_magic(path, scene_magic);
}

void resume_scene(const RunOptions& options) {
  const std::string file = options.out_dir + "/checkpoint.bin";
  CheckpointHeader header;
  StateReader in = open_checkpoint(file, scene_magic, scene_kind, header);
  // The run continues with the config it started from: a changed or missing file is refused.
  if (!std::filesystem::exists(header.config_path) ||
      read_file(header.config_path) != header.config_text)
    throw ConfigError(fmt::format(
        "{}: the run started from {}, which {}; resume needs the config it started from "
        "(restore it, or start a new run)",
        file, header.config_path,
        std::filesystem::exists(header.config_path) ? "has changed since" : "no longer exists"));
  SceneSetup setup = set_up(header.config_path);
  continue_in_output_dir(options.out_dir);
  install_interrupt_handler();
  run(header.config_path, header.config_text, std::move(setup), options, &in);
}

}  // namespace grainlab
