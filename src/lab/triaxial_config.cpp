#include "lab/triaxial_config.hpp"

#include <fmt/format.h>

#include "io/config_error.hpp"
#include "io/scene_builder.hpp"
#include "io/toml_reader.hpp"
#include "lab/lab_config.hpp"

namespace grainlab {

TriaxialConfig read_triaxial_config(const std::string& path, const toml::table& root) {
  TriaxialConfig c;
  c.scene = read_lab_materials(path, root);
  TableReader t = test_table_reader(path, root);
  TriaxialSettings& s = c.settings;
  SpecimenSettings& p = s.specimen;
  c.table = build_pair_table(c.scene);
  auto material = [&](const char* key, const char* fallback) {
    return lab_material(t, c.table, key, t.string_or(key, fallback));
  };
  p.bead_material = material("bead_material", "glass");
  p.lateral_material = material("lateral_material", "rubber_membrane");
  p.platen_material = material("platen_material", "porous_stone");
  const Material& bead = c.scene.materials[p.bead_material];
  if (!bead.density) t.fail("bead_material", "the bead material needs a density");
  p.density = *bead.density;
  for (int other : {p.bead_material, p.lateral_material, p.platen_material})
    require_pair(t, c.table, "bead_material", p.bead_material, other);
  p.count = t.integer_or("count", p.count);
  if (p.count < 8) t.fail("count", "expected at least 8 particles");
  if (p.count > 20'000'000)
    t.fail("count", "more particles than grainlab places in one specimen (20 million)");
  p.diameter = t.number_or("diameter", Quantity::length, p.diameter);
  p.diameter_tolerance = t.number_or("diameter_tolerance", Quantity::length, p.diameter_tolerance);
  if (!(p.diameter > 0)) t.fail("diameter", "expected a diameter > 0 m");
  if (!(p.diameter_tolerance >= 0 && p.diameter_tolerance < 0.5 * p.diameter))
    t.fail("diameter_tolerance", "expected 0 <= tolerance < half the diameter");
  if (t.has("box")) {
    const auto box = t.numbers("box", Quantity::length, 3);
    p.nominal_box = {box[0], box[1], box[2]};
  }
  for (int a = 0; a < 3; ++a)
    if (!(p.nominal_box[a] >= 2.0 * (p.diameter + p.diameter_tolerance)))
      t.fail("box", "every side of the box must hold at least two particle diameters");
  // The beads must fit in the nominal box below random close packing (solid fraction 0.64).
  const double bead_volume = p.count * (M_PI / 6.0) * p.diameter * p.diameter * p.diameter;
  const double needed = bead_volume / (p.nominal_box.x * p.nominal_box.y * p.nominal_box.z);
  if (needed > 0.64)
    t.fail("count",
           fmt::format(
               "more particles than fit in the box: they would fill {:.2f} of it, above random "
               "close packing (0.64)",
               needed));
  p.confining_stress = t.number_or("confining_stress", Quantity::pressure, p.confining_stress);
  if (!(p.confining_stress > 0)) t.fail("confining_stress", "expected a confining stress > 0 Pa");
  if (auto phi = t.optional_number("target_solid_fraction", Quantity::dimensionless)) {
    if (!(*phi > 0.45 && *phi < 0.66))
      t.fail("target_solid_fraction", "expected a solid fraction in (0.45, 0.66)");
    p.target_solid_fraction = *phi;
  }
  p.dt_fraction = t.number_or("dt_fraction", Quantity::dimensionless, p.dt_fraction);
  if (!(p.dt_fraction > 0 && p.dt_fraction <= 0.3))
    t.fail("dt_fraction", "expected a fraction of t_c in (0, 0.3]");
  p.max_strain_rate =
      t.number_or("compaction_strain_rate", Quantity::dimensionless, p.max_strain_rate);
  p.max_time = t.number_or("preparation_max_time", Quantity::time, p.max_time);
  p.compaction_restitution =
      t.number_or("compaction_restitution", Quantity::dimensionless, p.compaction_restitution);
  if (!(p.compaction_restitution > 0 && p.compaction_restitution <= 1))
    t.fail("compaction_restitution", "expected a restitution coefficient in (0, 1]");
  p.seed = static_cast<uint64_t>(t.integer_or("seed", 1));
  if (t.has("specimen")) s.specimen_file = t.string("specimen");
  const std::string loading = t.string_or("loading", "inertial");
  if (loading == "paper") {
    s.platen_speed = 0.01;
  } else if (loading == "speed") {
    s.platen_speed = t.number("platen_speed", Quantity::velocity);
    if (!(*s.platen_speed > 0)) t.fail("platen_speed", "expected a platen speed > 0 m/s");
  } else if (loading != "inertial") {
    t.fail("loading",
           "expected \"inertial\" (fastest rate with I below max_inertial_number), \"paper\" (0.01 "
           "m/s) or \"speed\"");
  }
  s.max_inertial_number =
      t.number_or("max_inertial_number", Quantity::dimensionless, s.max_inertial_number);
  if (!(s.max_inertial_number > 0)) t.fail("max_inertial_number", "expected a bound > 0");
  s.max_axial_strain = t.number_or("max_axial_strain", Quantity::dimensionless, s.max_axial_strain);
  if (!(s.max_axial_strain > 0 && s.max_axial_strain < 0.5))
    t.fail("max_axial_strain", "expected a strain in (0, 0.5)");
  s.output_strain_interval =
      t.number_or("output_strain_interval", Quantity::dimensionless, s.output_strain_interval);
  if (!(s.output_strain_interval > 0))
    t.fail("output_strain_interval", "expected a strain interval > 0");
  s.checkpoint_interval = t.number_or("checkpoint_interval", Quantity::time, s.checkpoint_interval);
  if (!(s.checkpoint_interval > 0))
    t.fail("checkpoint_interval", "expected a wall-time interval > 0 s");
  s.vtk = t.boolean_or("vtk", false);
  s.vtk_strain_interval =
      t.number_or("vtk_strain_interval", Quantity::dimensionless, s.vtk_strain_interval);
  if (!(s.vtk_strain_interval > 0))
    t.fail("vtk_strain_interval", "expected an axial-strain interval > 0");
  t.finish();
  return c;
}

}  // namespace grainlab
