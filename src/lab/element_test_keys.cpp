// The keys every element test shares ([test] table: the specimen, its preparation, the loading
// rate, outputs, checkpoints, laboratory values), read and checked (lab/element_test.hpp).
#include <fmt/format.h>

#include <cmath>

#include "io/config_error.hpp"
#include "io/scene_builder.hpp"
#include "lab/element_test.hpp"
#include "lab/lab_config.hpp"
#include "lab/laboratory.hpp"

namespace grainlab {

ElementTestConfig read_element_test_keys(const std::string& path, const toml::table& root,
                                         TableReader& t, const ElementTestSettings& defaults) {
  ElementTestConfig c;
  c.settings = defaults;
  c.scene = read_lab_materials(path, root);
  ElementTestSettings& s = c.settings;
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
  // The box is the specimen's size; beads that fill a tiny part of it would be compacted over
  // many box lengths, the walls driven at a speed in proportion (a 1e9 mm box blew up at
  // 1.8 km/s).
  if (needed < 0.1)
    t.fail(
        "box",
        fmt::format("the {} beads fill only {:.2g} of this box; expected at least 0.1 (the box is "
                    "the specimen's size: a packing fills 0.55-0.64 of it)",
                    p.count, needed));
  p.confining_stress = t.number_or("confining_stress", Quantity::pressure, p.confining_stress);
  if (!(p.confining_stress > 0)) t.fail("confining_stress", "expected a confining stress > 0 Pa");
  const toml::node* target =
      t.has("target_solid_fraction") ? t.node("target_solid_fraction") : nullptr;
  if (target && target->value<std::string>() == "none") {
    p.target_solid_fraction.reset();  // compact with the beads' own friction, no target
  } else if (auto phi = t.optional_number("target_solid_fraction", Quantity::dimensionless)) {
    if (!(*phi > 0.45 && *phi < 0.66))
      t.fail("target_solid_fraction", "expected a solid fraction in (0.45, 0.66)");
    p.target_solid_fraction = *phi;
  }
  if (auto mu = t.optional_number("compaction_friction", Quantity::dimensionless)) {
    if (!(*mu >= 0 && *mu <= 1))
      t.fail("compaction_friction",
             "expected a bead-bead friction coefficient in [0, 1] (below the measured one packs "
             "denser, above it looser)");
    p.compaction_friction = *mu;
  }
  p.wall_friction_while_preparing =
      t.boolean_or("wall_friction_while_preparing", p.wall_friction_while_preparing);
  p.dt_fraction = t.number_or("dt_fraction", Quantity::dimensionless, p.dt_fraction);
  if (!(p.dt_fraction > 0 && p.dt_fraction <= 0.3))
    t.fail("dt_fraction", "expected a fraction of t_c in (0, 0.3]");
  p.max_strain_rate =
      t.number_or("compaction_strain_rate", Quantity::dimensionless, p.max_strain_rate);
  if (!(p.max_strain_rate > 0 && p.max_strain_rate <= 1e3))
    t.fail("compaction_strain_rate", "expected a strain rate in (0, 1000] 1/s");
  p.max_time = t.number_or("preparation_max_time", Quantity::time, p.max_time);
  if (!(p.max_time > 0 && p.max_time <= 100))
    t.fail("preparation_max_time", "expected a simulated time in (0, 100] s");
  p.unbalanced_tolerance = t.number_or("preparation_unbalanced_tolerance", Quantity::dimensionless,
                                       p.unbalanced_tolerance);
  if (!(p.unbalanced_tolerance > 0 && p.unbalanced_tolerance <= 0.1))
    t.fail("preparation_unbalanced_tolerance",
           "expected a ratio of mean unbalanced to mean contact force in (0, 0.1]");
  const std::string compaction =
      t.string_or("compaction", p.compaction == Compaction::affine ? "affine" : "walls");
  if (compaction == "affine")
    p.compaction = Compaction::affine;
  else if (compaction == "walls")
    p.compaction = Compaction::walls;
  else
    t.fail("compaction",
           "expected \"walls\" (the walls' servos compact the specimen) or \"affine\" (the whole "
           "box is strained homogeneously, then held by the walls)");
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
  s.output_strain_interval =
      t.number_or("output_strain_interval", Quantity::dimensionless, s.output_strain_interval);
  if (!(s.output_strain_interval > 0))
    t.fail("output_strain_interval", "expected a strain interval > 0");
  s.checkpoint_interval = t.number_or("checkpoint_interval", Quantity::time, s.checkpoint_interval);
  if (!(s.checkpoint_interval > 0))
    t.fail("checkpoint_interval", "expected a wall-time interval > 0 s");
  s.laboratory = read_laboratory_values(path, t);
  s.re_equilibration_max_time =
      t.number_or("re_equilibration_max_time", Quantity::time, s.re_equilibration_max_time);
  if (!(s.re_equilibration_max_time > 0 && std::isfinite(s.re_equilibration_max_time)))
    t.fail("re_equilibration_max_time", "expected a simulated time > 0 s");
  s.vtk = t.boolean_or("vtk", false);
  s.vtk_strain_interval =
      t.number_or("vtk_strain_interval", Quantity::dimensionless, s.vtk_strain_interval);
  if (!(s.vtk_strain_interval > 0))
    t.fail("vtk_strain_interval", "expected an axial-strain interval > 0");
  return c;
}

}  // namespace grainlab
