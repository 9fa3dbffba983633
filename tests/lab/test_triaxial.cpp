// Specimen preparation on a small cuboid specimen (500 beads of the reference glass): the
// solid-fraction target is hit and the servo holds the confining stress at rest; and the three
// stress measures on an exactly known static state. The sheared specimen (lateral stress held,
// stresses agreeing, a peak against the published DEM) is checked end to end in lab_checks.py
// (triaxial_small_specimen_shear).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "contact/stability.hpp"
#include "lab/specimen.hpp"
#include "measure/boundary.hpp"
#include "measure/specimen_state.hpp"
#include "support/scenes.hpp"

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
  t.set(0, 0, test::pair_properties(0.926, 0.16));
  t.set(0, 1, test::pair_properties(0.58, 0.21));
  t.set(0, 2, test::pair_properties(0.73, 0.18));
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

TEST(SpecimenPreparation, CompactionFrictionSteersTheDensityBothWays) {
  // Compacted with less bead friction than the measured 0.16 the packing gets denser, with more
  // it gets looser; every specimen ends in equilibrium with the measured friction switched on.
  // (The loose packing settles further once its friction drops to 0.16: compacted at 0.6 it
  // ended 0.008 below the measured friction's specimen in this box, at 1.0 further.)
  double solid_fraction[3];
  const double compaction_friction[3] = {0.0, -1.0, 1.0};  // -1: the measured friction
  for (int k = 0; k < 3; ++k) {
    SpecimenSettings settings = small_specimen();
    if (compaction_friction[k] >= 0) settings.compaction_friction = compaction_friction[k];
    const Specimen s = prepare_cuboid_specimen(settings, reference_pairs(), nullptr);
    EXPECT_TRUE(s.equilibrium_reached) << k;
    EXPECT_DOUBLE_EQ(s.compaction_friction, k == 1 ? 0.16 : compaction_friction[k]);
    solid_fraction[k] = s.solid_fraction;
  }
  EXPECT_GT(solid_fraction[0], solid_fraction[1] + 0.01);
  EXPECT_LT(solid_fraction[2], solid_fraction[1] - 0.01);
}

TEST(SpecimenPreparation, FrictionlessWallsLeaveTheSpecimenIsotropic) {
  // With frictionless walls the walls carry no shear, so the specimen's own (Love-Weber) stress
  // is the walls' normal stress: the confining stress on every axis within the hold's 0.5 %
  // (plus the unbalanced force's share). With the measured wall friction the preparation locks
  // shear into the wall contacts and the axes differ by more.
  double spread[2];
  for (int walls = 0; walls < 2; ++walls) {
    SpecimenSettings settings = small_specimen();
    settings.wall_friction_while_preparing = walls == 1;
    const Specimen s = prepare_cuboid_specimen(settings, reference_pairs(), nullptr);
    ASSERT_TRUE(s.equilibrium_reached);
    ASSERT_TRUE(s.love_weber_diagonal);
    double lo = 1e300, hi = -1e300;
    for (double sigma : *s.love_weber_diagonal) lo = std::min(lo, sigma), hi = std::max(hi, sigma);
    spread[walls] = (hi - lo) / settings.confining_stress;
    if (walls == 0) {
      for (double sigma : *s.love_weber_diagonal)
        EXPECT_NEAR(sigma / settings.confining_stress, 1.0, 0.01);
    }
  }
  EXPECT_GT(spread[1], 2.0 * spread[0]);
}

TEST(SpecimenPreparation, ReferenceCompactionRestitutionKeepsTheTestsStep) {
  // The reference config (examples/triaxial/reference.toml) compacts with restitution 0.4: the
  // most damped of 0.3, 0.35, 0.4, ... whose contacts the stability rule (contact/stability.hpp)
  // keeps stable at the test's own step, so that its preparation runs at 0.1 t_c; the default
  // 0.3 lowers the preparation's step.
  const SpecimenSettings s = small_specimen();
  const PairTable measured = reference_pairs();
  const double r_min = s.min_radius();
  const double step = specimen_time_step(s, measured, r_min).time_step;
  // every bead contact (with beads and walls) at restitution min(e, measured), as while compacting
  const auto stable_at = [&](double e) {
    PairTable t = measured;
    t.set(0, 0, test::pair_properties(std::min(e, 0.926), 0.16));
    t.set(0, 1, test::pair_properties(std::min(e, 0.58), 0.21));
    t.set(0, 2, test::pair_properties(std::min(e, 0.73), 0.18));
    return stable_time_step(step, t, 0, r_min).time_step >= step;
  };
  EXPECT_TRUE(stable_at(0.4));
  EXPECT_FALSE(stable_at(0.35));
  EXPECT_FALSE(stable_at(s.compaction_restitution));  // the default, 0.3
  // and a preparation with 0.4 runs at that step
  SpecimenSettings with_04 = s;
  with_04.compaction_restitution = 0.4;
  with_04.count = 100;  // the step, not the packing, is checked here
  const Specimen prepared = prepare_cuboid_specimen(with_04, measured, nullptr);
  EXPECT_EQ(prepared.time_step, step);
  EXPECT_GT(prepared.steps, 0);
  EXPECT_NEAR(prepared.steps * prepared.time_step, prepared.simulated_time,
              1e-9 * prepared.simulated_time);
}

TEST(SpecimenPreparation, SavedSpecimenReloadsExactly) {
  SpecimenSettings settings = small_specimen();
  settings.count = 60;
  settings.nominal_box = {0.008, 0.008, 0.012};
  settings.max_time = 0.005;
  const Specimen s = prepare_cuboid_specimen(settings, reference_pairs(), nullptr);
  const std::string path = ::testing::TempDir() + "/specimen.csv";
  save_specimen(path, s);
  const Specimen back = load_specimen(path, 2500.0, 0);
  ASSERT_EQ(back.particles.size(), s.particles.size());
  EXPECT_EQ(back.particles.position, s.particles.position);
  EXPECT_EQ(back.particles.radius, s.particles.radius);
  EXPECT_EQ(back.low, s.low);
  EXPECT_EQ(back.high, s.high);
}

// One bead pressed by the six walls of a box slightly smaller than it, with different overlaps
// across and along: in this static state the stress is known exactly. Each wall pushes with
// F = k_n * overlap, the contact points lie on the walls, and the average stress over the box is
// F / (face area) on each axis (the average-stress theorem), with no shear. The wall stress, the
// Love-Weber average and the boundary average must all give it.
TEST(SpecimenStresses, BeadSqueezedInABoxGivesWallForceOverArea) {
  const double r = 1e-3, overlap_x = 2e-7, overlap_z = 5e-7;
  const Vec3 half{r - overlap_x, r - overlap_x, r - overlap_z};
  ParticleStore p;
  p.add(0, 0, r, 2500.0, {0, 0, 0}, {}, {}, false);
  SimulationSettings settings;
  settings.time_step = 1e-9;
  settings.skin = 1e-4;
  Simulation sim(std::move(p), cuboid_walls(-1.0 * half, half, 1, 2), reference_pairs(), settings);
  sim.step();  // forces of the static state (the bead does not move: they cancel)
  const double volume = box_volume(sim.walls());
  const Tensor3 lw = love_weber_stress(sim, volume);
  const Tensor3 boundary = boundary_stress(sim, {0, 0, 0}, volume);
  const double area_x = 4 * half.y * half.z, area_z = 4 * half.x * half.y;
  const double fx = norm(sim.walls()[x_low].force), fz = norm(sim.walls()[top].force);
  ASSERT_GT(fx, 0.0);
  // k_n = pi E r* with r* = r on a wall (docs/contact-model.md); the bead is at rest, so no
  // damping.
  EXPECT_NEAR(fz, M_PI * 46.2e9 * r * overlap_z, 1e-6 * fz);
  EXPECT_NEAR(fx, M_PI * 46.2e9 * r * overlap_x, 1e-6 * fx);
  for (const Tensor3& s : {lw, boundary}) {
    EXPECT_NEAR(s[0][0], fx / area_x, 1e-9 * fx / area_x);
    EXPECT_NEAR(s[1][1], fx / area_x, 1e-9 * fx / area_x);
    EXPECT_NEAR(s[2][2], fz / area_z, 1e-9 * fz / area_z);
    EXPECT_NEAR(s[0][2], 0.0, 1e-9 * fz / area_z);
  }
  EXPECT_NEAR(wall_stress(sim.walls(), top), fz / area_z, 1e-9 * fz / area_z);
  EXPECT_NEAR(wall_stress(sim.walls(), x_high), fx / area_x, 1e-9 * fx / area_x);
}
