// The machinery every element test on a cuboid specimen shares (triaxial, oedometer, plane
// strain), so that a test is one file of what is its own: which axis is held how
// (control/box_controller.hpp, control/plane_strain_box.hpp), when it records and what, and its
// summary.
//
//   ElementTestSettings     the [test] keys every element test reads (specimen, loading rate,
//                           outputs, checkpoints)  -> read_element_test_keys
//   start_element_test      specimen prepared (or loaded), the Simulation built with the one
//                           time-step rule, re-equilibrated at the confining stress
//   LoadingStage            a test's loading, driven step by step by run_loading, which also
//                           writes the curve, the periodic and the Ctrl-C checkpoints, progress
//   ElementRun              everything a checkpoint holds; `grainlab run --resume DIR` finds
//                           the test by its type in the registry (lab/registry.cpp)
#pragma once

#include <fmt/format.h>
#include <toml++/toml.h>

#include <cmath>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "contact/pair_table.hpp"
#include "core/simulation.hpp"
#include "io/progress.hpp"
#include "io/scene_config.hpp"
#include "io/scene_run.hpp"
#include "io/toml_reader.hpp"
#include "lab/laboratory.hpp"
#include "lab/specimen.hpp"

namespace grainlab {

struct ElementTestSettings {
  SpecimenSettings specimen;
  std::optional<std::string> specimen_file;  // a prepared specimen to reuse
  std::optional<double> platen_speed;        // m/s each platen; empty: from the inertial number
  double max_inertial_number = 1e-3;
  double output_strain_interval = 0.001;
  bool vtk = false;
  double vtk_strain_interval = 0.01;
  double checkpoint_interval = default_checkpoint_interval_s;  // s of wall time
  // s simulated, at most, for the re-equilibration under the confining stress before the loading
  double re_equilibration_max_time = 0.02;
  // m/s^2 along -z from the re-equilibration on (the specimen is prepared without it); only the
  // plane strain test reads the key, whose mount carries the weight on the bottom platen
  double gravity = 0.0;
  std::optional<LaboratoryValues> laboratory;
};

// A test config read: materials and pairs, the pair table and the shared settings.
struct ElementTestConfig {
  SceneConfig scene;
  PairTable table{{}};
  ElementTestSettings settings;
};

// Reads the shared keys of [test] (materials, specimen, loading, outputs) with the test's own
// defaults; the caller reads its own keys from `t` and calls t.finish() (element_test_keys.cpp).
ElementTestConfig read_element_test_keys(const std::string& path, const toml::table& root,
                                         TableReader& t, const ElementTestSettings& defaults = {});

// test.max_axial_strain (default `fallback`) in (0, 0.5), and the step budget of a loading to it
// (check_step_budget).
double read_max_axial_strain(const ElementTestConfig& c, double fallback, int passes,
                             TableReader& t);

// ConfigError naming the loading key unless the loading to `max_axial_strain` (both ways when
// `passes` = 2) fits in max_steps_per_run steps, estimated from the nominal box and beads.
void check_step_budget(const ElementTestConfig& c, double max_axial_strain, int passes,
                       const TableReader& t);

// The loaded specimen file or a freshly prepared specimen.
Specimen obtain_specimen(const ElementTestConfig& c, Progress& progress,
                         const PreparationCheckpoints* checkpoints = nullptr);
nlohmann::json specimen_json(const Specimen& s);

// The time step of a test on this specimen: dt_fraction * t_c of the smallest bead, lowered
// where a spring-dashpot in use needs it (contact/stability.hpp).
struct ElementTimeStep {
  SimulationSettings settings;
  double collision_duration = 0.0;  // s, of the smallest bead pair
  std::string limited_by;
};
ElementTimeStep element_time_step(const SpecimenSettings& sp, const PairTable& table,
                                  const ParticleStore& particles);

// ConfigError unless test.specimen (when given) exists.
void check_specimen_file(const std::string& config_path, const ElementTestSettings& s);

// The platens' speed: given, or the fastest whose inertial number at the confining stress is the
// bound (the mean stress only grows while loading, so I stays below it).
struct LoadingRate {
  double platen_speed = 0.0;  // m/s, each platen
  double strain_rate = 0.0;   // 1/s, 2 v / H0
};
LoadingRate loading_rate(const ElementTestSettings& s, double height0);
nlohmann::json loading_json(const LoadingRate& rate, const ElementTestSettings& s);

// Everything a checkpoint holds.
struct ElementRun {
  Simulation sim;
  std::string type;                      // test.type
  std::string config_path, config_text;  // to rebuild the pair table on resume
  std::string run_info;           // JSON text of what the summary needs from before the loading
  std::string curve_rows;         // curve.csv rows so far (without header)
  std::string vtk_index;          // <DataSet> lines of particles.pvd so far
  std::string test_state;         // the test's own progress values (LoadingStage::save)
  double wall_time_before = 0.0;  // s spent in earlier sessions of this run
};

// The start of a shear test's loading (triaxial, plane strain): the platens' rate, the steps to
// max_axial_strain and the constants every curve row needs, written into the test's progress
// values (`P`, plain values carrying these names); run_info gets the "loading" entry.
template <class P>
LoadingRate plan_shear_loading(P& p, ElementRun& run, const ElementTestSettings& s,
                               const Vec3& size0, double max_axial_strain) {
  const SpecimenSettings& sp = s.specimen;
  const LoadingRate rate = loading_rate(s, size0.z);
  p.size0 = size0;
  p.platen_speed = rate.platen_speed;
  p.strain_rate = rate.strain_rate;
  p.confining_stress = sp.confining_stress;
  p.diameter = sp.diameter;
  p.density = sp.density;
  p.output_strain_interval = s.output_strain_interval;
  p.vtk_strain_interval = s.vtk ? s.vtk_strain_interval : 0.0;
  // Each platen moves at the platen speed: the height closes at twice it.
  p.total_steps = static_cast<long>(std::ceil(max_axial_strain * size0.z / (2.0 * p.platen_speed) /
                                              run.sim.settings().time_step));
  nlohmann::json j = nlohmann::json::parse(run.run_info);
  j["loading"] = loading_json(rate, s);
  run.run_info = j.dump();
  return rate;
}

// How a test holds its prepared specimen: the walls its Simulation is built with, the
// re-equilibration under the confining stress before the loading, and the specimen's volume.
// The default (an empty mount): the six walls of the preparation box, held isotropically by servo
// (hold_isotropic). The plane strain test replaces the lateral walls by a membrane.
struct SpecimenMount {
  std::function<std::vector<Wall>(const Specimen&)> walls;
  // Brings the simulation to rest at the confining stress; `on_check` as in hold_isotropic.
  std::function<HoldState(Simulation&, const std::function<bool(const HoldState&)>& on_check)>
      equilibrate;
  std::function<double(const Simulation&)> volume;
};

// Specimen obtained, simulation built, re-equilibrated under the confining stress (a specimen
// file carries no contact history); run_info holds the specimen, time step and preparation.
ElementRun start_element_test(const std::string& type, const std::string& config_path,
                              const toml::table& root, const ElementTestConfig& c,
                              const std::string& out_dir, Progress& progress,
                              const SpecimenMount& mount = {},
                              const std::string& resumed_config = {});

// The first steps of every element test's run: the specimen file checked, the output directory
// prepared, Ctrl-C handled, then start_element_test.
ElementRun begin_element_test(const std::string& type, const std::string& config_path,
                              const toml::table& root, const ElementTestConfig& c,
                              const RunOptions& options, const SpecimenMount& mount = {});

// A stage's own state (plain values) into a checkpoint and back.
template <class T>
void store_test_state(ElementRun& run, const T& state) {
  StateWriter out;
  out.value(state);
  run.test_state = out.bytes();
}
template <class T>
T restored_test_state(const ElementRun& run) {
  StateReader in(run.test_state);
  return in.value<T>();
}

// One test's loading. run_loading calls, per step: observe (record outputs when due), then,
// unless finished, Simulation::step (the test's controller is attached to the simulation) and
// after_step (accumulate).
class LoadingStage {
 public:
  virtual ~LoadingStage() = default;
  virtual const char* curve_header() const = 0;
  virtual void observe(ElementRun& run, Progress& progress) = 0;
  virtual bool finished(const ElementRun& run) const = 0;
  virtual void after_step(ElementRun& run) = 0;
  virtual long step() const = 0;                 // steps of this stage so far
  virtual std::string position() const = 0;      // where an interrupted run stopped, for the user
  virtual void save(ElementRun& run) const = 0;  // its state into run.test_state
};

// Runs the stage to its end in DIR: DIR/checkpoint.bin every `checkpoint_interval_s` of wall
// time and on Ctrl-C / SIGTERM (then throws Interrupted); curve.csv at the end.
void run_loading(ElementRun& run, LoadingStage& stage, const std::string& dir,
                 double checkpoint_interval_s, Progress& progress);
// run_loading into options.out_dir with a progress line "grainlab TYPE".
void load_to_end(ElementRun& run, LoadingStage& stage, double checkpoint_interval_s,
                 const RunOptions& options);

void save_checkpoint(const ElementRun& run, const std::string& path);
// The test type and config stored in a checkpoint (to rebuild the pair table before loading it).
CheckpointHeader peek_checkpoint(const std::string& path);
// Throws ConfigError for a missing or damaged checkpoint.
ElementRun load_checkpoint(const std::string& path, PairTable table);

// The rows of a curve.csv text as numbers (for summaries computed from the curve).
std::vector<std::vector<double>> curve_values(const std::string& rows);

// Least-squares slope of column y against column x over the rows where `use` holds (NaN below
// 3 rows).
double curve_slope(const std::vector<std::vector<double>>& rows, int x, int y,
                   const std::function<bool(const std::vector<double>&)>& use);

// Whether the next output of a series every `interval` of axial strain is due (the strain reached
// next x interval, or it is the loading's last step); advances `next` when it is.
inline bool output_due(double axial_strain, long& next, double interval, bool last_step) {
  if (!(axial_strain >= next * interval - 1e-12 || last_step)) return false;
  ++next;
  return true;
}

// The outputs of a loading driven by axial strain (progress values `P` as in
// plan_shear_loading, plus step, next_output, next_vtk and last_axial): a curve row (`record`)
// and the progress line every output strain interval, a snapshot every vtk strain interval (none
// when 0), each also at the loading's last step.
template <class P, class Record, class Snapshot>
void strain_outputs(P& p, double axial_strain, Progress& progress, Record&& record,
                    Snapshot&& snapshot) {
  const bool last = p.step == p.total_steps;
  if (output_due(axial_strain, p.next_output, p.output_strain_interval, last)) {
    record();
    progress.update(static_cast<double>(p.step) / p.total_steps,
                    fmt::format("axial strain {:.2f} %, axial stress {:.1f} kPa",
                                100 * axial_strain, 1e-3 * p.last_axial));
  }
  if (p.vtk_strain_interval > 0 &&
      output_due(axial_strain, p.next_vtk, p.vtk_strain_interval, last))
    snapshot();
}

// A ParaView snapshot in DIR/vtk: the particles' and the walls' .vtu texts at `step`, added to the
// run's DIR/particles.pvd index.
void add_vtk_snapshot(ElementRun& run, const std::string& dir, long step,
                      const std::string& particles_vtu, const std::string& walls_vtu);

}  // namespace grainlab
