// The flexible membrane (control/membrane.hpp) on its own: a small specimen of the reference glass
// beads, prepared between rigid frictionless walls, then its lateral walls replaced by the membrane
// at 150 kPa (the plane strain test's re-equilibration, lab/plane_strain.hpp) and held at rest, the
// front/back walls and platens servo-held at the same stress. In static equilibrium the average
// stress the particles carry (Love-Weber, with the membrane's forces as boundary loads at the
// beads' surface) must be the isotropic confining stress: checked averaged over 4,000 further
// steps, every diagonal within 1 %, the shear components below 1 % of p; the membrane's forces
// along x add up to p x face area on each face; no bead leaves.
#include <gtest/gtest.h>

#include <cmath>

#include "control/plane_strain_box.hpp"
#include "lab/plane_strain.hpp"
#include "lab/specimen.hpp"
#include "measure/specimen_state.hpp"
#include "support/scenes.hpp"

using namespace grainlab;

namespace {
PairTable reference_pairs() {
  PairTable t({Material{"glass", 46.2e9, 0.245, 2500.0}, Material{"rubber_membrane", {}, {}, {}},
               Material{"porous_stone", {}, {}, {}}});
  t.set(0, 0, test::pair_properties(0.926, 0.16));
  // Frictionless (lubricated) walls: the only lateral load is the membrane's.
  t.set(0, 1, test::pair_properties(0.58, 0.0));
  t.set(0, 2, test::pair_properties(0.73, 0.0));
  return t;
}
}  // namespace

TEST(Membrane, HoldsAStaticSpecimenAtTheIsotropicConfiningStress) {
  ElementTestSettings settings_of_test;
  SpecimenSettings& sp = settings_of_test.specimen;
  sp.count = 800;
  sp.nominal_box = {0.016, 0.016, 0.020};
  sp.bead_material = 0, sp.lateral_material = 1, sp.platen_material = 2;
  const PairTable table = reference_pairs();
  const Specimen specimen = prepare_cuboid_specimen(sp, table, nullptr);
  const SpecimenMount mount = plane_strain_mount(settings_of_test);
  SimulationSettings settings;
  settings.time_step = specimen_time_step(sp, table, sp.min_radius()).time_step;
  settings.skin = 0.1 * sp.diameter;
  Simulation sim(specimen.particles, mount.walls(specimen), table, settings);
  const HoldState settled = mount.equilibrate(sim, [](const HoldState&) { return true; });
  ASSERT_TRUE(settled.reached) << settled.max_stress_error << " " << settled.unbalanced;

  // Held further: the membrane at p on the x faces, the four walls servo-held at p.
  const double p = sp.confining_stress;
  Membrane membrane(plane_strain_membrane(p, sp.diameter));
  membrane.start(sim);
  const AxisControl held{AxisMode::stress, p};
  PlaneStrainControl walls(membrane, {held, held}, ServoRegime::holding, sp.max_strain_rate);
  const ScopedListener attached(sim, membrane), servo(sim, walls);
  Tensor3 mean{};
  const int samples = 40;
  for (int k = 0; k < samples; ++k) {
    sim.advance(100);
    const PlaneStrainBox box = plane_strain_box(sim, membrane);
    const Tensor3 s = love_weber_stress(sim, box.volume());
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) mean[a][b] += s[a][b] / samples;
  }
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(mean[a][a] / p, 1.0, 0.01) << "axis " << a;
    for (int b = a + 1; b < 3; ++b) EXPECT_LT(std::abs(mean[a][b]) / p, 0.01) << a << b;
  }
  const MembraneFaces faces = membrane.measure(sim);
  // p x face area, the area at the step's start (the servo moved the walls by one step since:
  // a few 1e-8 of the area).
  EXPECT_NEAR(faces.applied_stress[0] / p, 1.0, 1e-6);
  EXPECT_NEAR(faces.applied_stress[1] / p, 1.0, 1e-6);
  EXPECT_EQ(faces.escaped, 0);
  // One membrane bead per cell on each face: 8 x 10 cells of about one diameter.
  EXPECT_GT(faces.beads, 2 * 0.9 * (0.016 / 0.002) * (0.020 / 0.002));
}
