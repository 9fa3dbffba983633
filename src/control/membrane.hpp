// A flexible membrane on the two faces of a specimen normal to one axis (the lateral faces of a
// plane strain specimen): the confining pressure acts directly on the outermost particles, so the
// faces can bulge and a shear band can cross them, as through the laboratory's rubber membrane.
//
// Method (a grid of tributary areas):
//   - The face is spanned by walls along the two other axes (front/back walls and platens); their
//     positions give the face's current extent, divided into n_b x n_c cells about one diameter
//     wide (`cell_size`) when the membrane is first laid; the grid then stretches with the face.
//   - At every neighbour-list rebuild (and when first attached) the membrane bead of each cell is
//     the particle whose centre lies in the cell's column and whose surface reaches furthest out
//     (x - r smallest on the low face, x + r largest on the high face). Between rebuilds no
//     particle moves more than half the Verlet skin, so the set stays valid.
//   - Every step each membrane bead gets the force p A_cell along the face's inward normal, so
//     each face carries p x (current face area) in total; cells left without a bead (none in
//     practice) have their share spread over the others. (Tilting each force by the local slope
//     of the bead surface was tried: on a specimen at rest, with the walls held at p, it biased
//     the in-plane stresses by 1.3-2.2 %, the moment of the rough surface's edges; the faces'
//     slopes stay small while shearing, so the normal force is the better approximation.)
// A force through a sphere's centre exerts no torque, as a pressure on its surface does not.
// Cost: one pass over the particles per rebuild, and O(cells) per step (2 x 2,500 cells at the
// reference scale against 88,000 particles in the contact loop).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/state_io.hpp"
#include "core/step_listener.hpp"
#include "core/vec3.hpp"

namespace grainlab {

class Simulation;

struct MembraneSettings {
  int axis = 0;            // the faces are normal to this axis
  double pressure = 0.0;   // Pa, compressive
  double cell_size = 0.0;  // m, target side of a grid cell (about one bead diameter)
  // Walls bounding the face: low and high along axis b = (axis + 1) % 3, then along
  // c = (axis + 2) % 3 (their `point`s give the face's extent).
  std::array<int, 4> span_walls{};
};

// What the membrane measures on the faces (from the current particle positions).
struct MembraneFaces {
  std::array<double, 2> surface{};         // m: mean outer surface coordinate, low and high face
  double width = 0.0;                      // m: surface[1] - surface[0]
  double face_area = 0.0;                  // m^2: current extent b x c
  std::array<double, 2> applied_stress{};  // Pa: force along the axis / face area, per face
  long beads = 0;                          // membrane beads on both faces
  long escaped = 0;  // particles more than one cell beyond the membrane (must be 0)
};

class Membrane : public StepListener {
 public:
  explicit Membrane(const MembraneSettings& settings);

  // Identifies the membrane beads and sets their forces now (otherwise done at the first step).
  void start(Simulation& sim);
  // Identifies the membrane beads without applying forces (to measure a specimen's faces).
  void locate(const Simulation& sim) { identify(sim); }
  void before_step(Simulation& sim) override;
  void after_rebuild(Simulation& sim) override;

  // Removes the membrane's forces from the simulation (before detaching it for good).
  void release(Simulation& sim);

  MembraneFaces measure(const Simulation& sim) const;  // one pass over the particles
  // Mean outer surface coordinate of the faces (O(cells)): the specimen's width is
  // surface(1) - surface(0).
  double surface(const Simulation& sim, int side) const;
  double width(const Simulation& sim) const { return surface(sim, 1) - surface(sim, 0); }
  // The force along the axis the membrane applies to one face over the face's area, Pa (O(1): the
  // sum is kept as the forces are set).
  double applied_stress(const Simulation& sim, int side) const;
  const MembraneSettings& settings() const { return s_; }
  double pressure() const { return s_.pressure; }
  void set_pressure(double p) { s_.pressure = p; }

  // The membrane beads by particle id, for checkpoints: a resumed run goes on with the same set.
  void save(StateWriter& out, const Simulation& sim) const;
  void restore(StateReader& in, const Simulation& sim);

 private:
  void identify(const Simulation& sim);
  void apply(Simulation& sim);
  struct Extent {
    double lo_b, hi_b, lo_c, hi_c;
  };
  Extent extent(const Simulation& sim) const;
  // Outer surface coordinate of each cell of `side` (NaN where the cell is empty).
  std::vector<double> heights(const Simulation& sim, int side) const;
  // Outer surface coordinate of particle i on `side` (x - r on the low face, x + r on the high):
  // what heights() and surface() read, so that the two agree bit for bit.
  double height(const Simulation& sim, uint32_t i, int side) const;
  // applied_force_ from the particles' external forces now (after an identification or a
  // restore; apply() sets it as it applies them).
  void read_applied_forces(const Simulation& sim);

  static constexpr uint32_t none = UINT32_MAX;
  MembraneSettings s_;
  int b_ = 1, c_ = 2;
  int n_b_ = 0, n_c_ = 0;                      // 0: not laid yet
  std::array<std::vector<uint32_t>, 2> bead_;  // storage index per cell (none: empty)
  bool identified_ = false;
  // N: the sum over each face's beads of their external force along the axis, in cell order:
  // what applied_stress reports over the face area. The plane strain test's sample reads it every
  // step, where reading it back from 2 x 2,500 scattered particles had cost about 50 us. Kept, not
  // read: the membrane must be the only writer of its simulation's external forces (as in the
  // plane strain test); a second writer would leave the sum stale.
  std::array<double, 2> applied_force_{};
};

}  // namespace grainlab
