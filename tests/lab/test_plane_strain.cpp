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
#include <memory>

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

// A small specimen of the reference beads, prepared between rigid frictionless walls, in a
// simulation with the plane strain test's walls (not yet mounted: the lateral faces open).
struct Mounted {
  Mounted(long count, const Vec3& nominal_box) {
    SpecimenSettings& sp = test.specimen;
    sp.count = count;
    sp.nominal_box = nominal_box;
    sp.bead_material = 0, sp.lateral_material = 1, sp.platen_material = 2;
    const PairTable table = reference_pairs();
    const Specimen specimen = prepare_cuboid_specimen(sp, table, nullptr);
    mount = plane_strain_mount(test);
    SimulationSettings settings;
    settings.time_step = specimen_time_step(sp, table, sp.min_radius()).time_step;
    settings.skin = 0.1 * sp.diameter;
    sim = std::make_unique<Simulation>(specimen.particles, mount.walls(specimen), table, settings);
  }
  ElementTestSettings test;
  SpecimenMount mount;
  std::unique_ptr<Simulation> sim;
};
}  // namespace

TEST(Membrane, HoldsAStaticSpecimenAtTheIsotropicConfiningStress) {
  const Mounted m(800, {0.016, 0.016, 0.020});
  const SpecimenSettings& sp = m.test.specimen;
  Simulation& sim = *m.sim;
  const HoldState settled = m.mount.equilibrate(sim, [](const HoldState&) { return true; });
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

// The membrane keeps the sum of the forces it sets (control/membrane.hpp: applied_stress reads no
// particle). Checked against the forces themselves, read back from the particles here: after it
// is laid, after steps with neighbour rebuilds (each finds the beads anew), in a membrane restored
// from a save, and in one that only locates the beads another has just laid; zero once released.
TEST(Membrane, AppliedStressIsTheForcesItSetOverTheFaceArea) {
  const Mounted m(400, {0.012, 0.012, 0.016});
  const SpecimenSettings& sp = m.test.specimen;
  Simulation& sim = *m.sim;
  const double p = sp.confining_stress;
  const MembraneSettings laid = plane_strain_membrane(p, sp.diameter);

  // The x forces on each face, read from the particles (low face: pushed towards +x), over the
  // face area the membrane measures.
  const auto read_back = [&](const Membrane& m, int side) {
    double force = 0.0;
    for (const Vec3& f : sim.particles().external_force)
      if (side == 0 ? f.x > 0.0 : f.x < 0.0) force += std::abs(f.x);
    return force / m.measure(sim).face_area;
  };
  const auto expect_read_back = [&](const Membrane& m, const char* when) {
    for (int side = 0; side < 2; ++side) {
      const double expected = read_back(m, side);
      EXPECT_GT(expected, 0.5 * p) << when;
      EXPECT_NEAR(m.applied_stress(sim, side) / expected, 1.0, 1e-12) << when << " side " << side;
    }
  };

  Membrane membrane(laid);
  membrane.start(sim);
  expect_read_back(membrane, "laid");
  // (located in the same state: the same grid and beads as the membrane just laid)
  Membrane located(laid);
  located.locate(sim);
  expect_read_back(located, "located");
  {
    const ScopedListener attached(sim, membrane);
    // (a rebuild each time the top platen is moved out by a skin, more than the half skin that
    // calls for one)
    const long rebuilds = sim.rebuild_count();
    for (int k = 0; k < 2; ++k) {
      sim.set_wall_point(top_platen,
                         sim.walls()[top_platen].point + Vec3{0, 0, sim.settings().skin});
      sim.advance(20);
    }
    ASSERT_EQ(sim.rebuild_count(), rebuilds + 2);
    expect_read_back(membrane, "after rebuilds");
  }
  StateWriter out;
  membrane.save(out, sim);
  Membrane restored(laid);
  StateReader in(out.bytes());
  restored.restore(in, sim);
  expect_read_back(restored, "restored");
  membrane.release(sim);
  EXPECT_EQ(membrane.applied_stress(sim, 0), 0.0);
  EXPECT_EQ(membrane.applied_stress(sim, 1), 0.0);
}
