#include <fmt/format.h>

#include <chrono>
#include <filesystem>

#include "geometry/cuboid_box.hpp"
#include "grainlab/version.hpp"
#include "io/config_error.hpp"
#include "io/interrupt.hpp"
#include "io/output_files.hpp"
#include "io/summary_header.hpp"
#include "lab/flat_throw.hpp"
#include "lab/lab_test.hpp"
#include "lab/oedometer.hpp"
#include "lab/plane_strain.hpp"
#include "lab/scale_study.hpp"
#include "lab/sliding_friction.hpp"
#include "lab/sliding_friction_checkpoint.hpp"
#include "lab/triaxial.hpp"

namespace grainlab {

namespace {
template <class Config, Config (*read)(const std::string&, const toml::table&)>
ElementTestConfig element_config(const std::string& path, const toml::table& root) {
  return read(path, root);
}
}  // namespace

const std::vector<LabTestEntry>& lab_tests() {
  static const std::vector<LabTestEntry> table{
      {"flat_throw", "simulated flat-throw restitution test (docs/lab-tests.md)", run_flat_throw},
      {"sliding_friction", "simulated sliding-friction test, with inverse mode (docs/lab-tests.md)",
       run_sliding_friction},
      {"triaxial",
       "triaxial test of a cuboid specimen with servo-held lateral walls (docs/lab-tests.md)",
       run_triaxial, element_config<TriaxialConfig, read_triaxial_config>, resume_triaxial},
      {"oedometer",
       "one-dimensional compression between fixed lateral walls: constrained modulus and K0",
       run_oedometer, element_config<OedometerConfig, read_oedometer_config>, resume_oedometer},
      {"plane_strain",
       "plane strain test: lateral faces held by a flexible membrane, fixed front and back walls, "
       "and a map of the shear band",
       run_plane_strain, element_config<PlaneStrainConfig, read_plane_strain_config>,
       resume_plane_strain},
      {"scale_study",
       "the plane strain test repeated with the bead diameter and the model scaled together, "
       "with gravity off and on (each run resumable in its own subdirectory)",
       run_scale_study},
  };
  return table;
}

namespace {

const LabTestEntry& entry_for(const std::string& path, const toml::table& root) {
  const toml::node* test = root.get("test");
  std::string known;
  for (const LabTestEntry& e : lab_tests())
    known += (known.empty() ? "" : ", ") + std::string(e.type);
  const toml::table* t = test ? test->as_table() : nullptr;
  const toml::node* type = t ? t->get("type") : nullptr;
  if (!type || !type->is_string())
    throw ConfigError(fmt::format("{} line {}: test.type: missing; expected one of: {}", path,
                                  test ? test->source().begin.line : 0, known));
  for (const LabTestEntry& e : lab_tests())
    if (*type->value<std::string>() == e.type) return e;
  throw ConfigError(fmt::format("{} line {}: test.type: unknown test \"{}\"; expected one of: {}",
                                path, type->source().begin.line, *type->value<std::string>(),
                                known));
}

}  // namespace

void run_lab_test(const std::string& path, const toml::table& root, const RunOptions& options) {
  entry_for(path, root).run(path, root, options);
}

namespace {

// The config a checkpoint holds, parsed; ConfigError naming the checkpoint when it does not.
toml::table stored_config(const std::string& file, const CheckpointHeader& h) {
  try {
    return toml::parse(h.config_text, h.config_path);
  } catch (const toml::parse_error& e) {
    throw ConfigError(
        fmt::format("{}: the stored configuration does not parse: {}", file, e.description()));
  }
}

// Continues a run that picks its own checkpoint up (an element test's preparation.bin, a
// sliding-friction test's checkpoint.bin): the test named in `file`'s header is run again with
// the config stored there. ConfigError when that test cannot be resumed this way (`resumable`).
void replay_stored_run(const std::string& file, const CheckpointHeader& h, const char* kind,
                       bool (*resumable)(const LabTestEntry&), const RunOptions& options) {
  const toml::table root = stored_config(file, h);
  const LabTestEntry& e = entry_for(h.config_path, root);
  if (h.type != e.type || !resumable(e))
    throw ConfigError(fmt::format("{}: a {} {} cannot be resumed", file, h.type, kind));
  RunOptions resumed = options;
  resumed.resumed_config = h.config_text;
  e.run(h.config_path, root, resumed);
}

}  // namespace

void resume_lab_test(const RunOptions& options) {
  if (is_scale_study_dir(options.out_dir)) {
    resume_scale_study(options);
    return;
  }
  const std::string checkpoint = options.out_dir + "/checkpoint.bin";
  const std::string preparation = options.out_dir + "/preparation.bin";
  if (SlidingFrictionCheckpoints::is_one(checkpoint)) {
    // The test takes what was done from its checkpoint.
    replay_stored_run(
        checkpoint, SlidingFrictionCheckpoints::peek(checkpoint), "checkpoint",
        [](const LabTestEntry& e) { return e.run == run_sliding_friction; }, options);
    return;
  }
  if (!std::filesystem::exists(checkpoint) && std::filesystem::exists(preparation)) {
    // Killed before the loading's first checkpoint: the preparation continues, then the run.
    replay_stored_run(
        preparation, peek_preparation_checkpoint(preparation), "preparation",
        [](const LabTestEntry& e) { return e.element_config != nullptr; }, options);
    return;
  }
  const CheckpointHeader h = peek_checkpoint(checkpoint);
  const toml::table root = stored_config(checkpoint, h);
  const LabTestEntry& e = entry_for(h.config_path, root);
  if (h.type != e.type || !e.resume)
    throw ConfigError(fmt::format("{}: a {} checkpoint cannot be resumed", checkpoint, h.type));
  const ElementTestConfig c = e.element_config(h.config_path, root);
  install_interrupt_handler();
  continue_in_output_dir(options.out_dir);
  e.resume(load_checkpoint(checkpoint, c.table), root, options);
}

namespace {

// The config of an element test; ConfigError naming test.type, with `refusal` (a format with the
// test type), for a test without a specimen.
ElementTestConfig element_config_of(const std::string& path, const toml::table& root,
                                    const char* refusal) {
  const LabTestEntry& e = entry_for(path, root);
  if (!e.element_config)
    throw ConfigError(
        fmt::format("{}: test.type: {}", path, fmt::format(fmt::runtime(refusal), e.type)));
  return e.element_config(path, root);
}

}  // namespace

ElementTestScene element_test_scene(const std::string& path, const toml::table& root) {
  // A scale study's constants are those of its plane strain test at the base diameter (where
  // its specimen is prepared; every other run is that specimen scaled).
  const ElementTestConfig c =
      entry_for(path, root).type == std::string_view("scale_study")
          ? ElementTestConfig(read_scale_study_config(path, root).base)
          : element_config_of(path, root,
                              "grainlab params shows the constants of scenes, element tests "
                              "(triaxial, oedometer, plane_strain) and scale studies, "
                              "not of a {} test");
  const SpecimenSettings& sp = c.settings.specimen;
  ElementTestScene out{c.scene, {}};
  out.scene.dt_fraction = sp.dt_fraction;
  out.scene.walls = cuboid_walls({}, sp.nominal_box, sp.lateral_material, sp.platen_material);
  for (uint32_t id = 0; id < 2; ++id)
    out.particles.add(id, sp.bead_material, sp.min_radius(), sp.density, {}, {}, {}, false);
  return out;
}

void run_prepare(const std::string& path, const RunOptions& options) {
  const toml::table root = parse_toml_file(path);
  const ElementTestConfig c = element_config_of(
      path, root,
      "a {} test has no specimen to prepare (element tests: triaxial, oedometer, plane_strain)");
  prepare_output_dir(options.out_dir, options.overwrite);
  install_interrupt_handler();
  const auto start = std::chrono::steady_clock::now();
  Progress progress("grainlab prepare", options.quiet);
  const Specimen s = prepare_cuboid_specimen(c.settings.specimen, c.table, &progress);
  save_specimen(options.out_dir + "/specimen.csv", s);
  nlohmann::json j = summary_header(path);
  j.update(specimen_json(s));
  j["confining_stress_Pa"] = c.settings.specimen.confining_stress;
  j["wall_time_s"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  write_file_atomically(options.out_dir + "/specimen.json", j.dump(2) + "\n");
  progress.finish(fmt::format("solid fraction {:.4f}, box {:.2f} x {:.2f} x {:.2f} mm",
                              s.solid_fraction, 1e3 * (s.high.x - s.low.x),
                              1e3 * (s.high.y - s.low.y), 1e3 * (s.high.z - s.low.z)));
}

}  // namespace grainlab
