// What runs between the steps of a Simulation without being part of the physics of the step:
// controllers (a servo that sets a wall's velocity, a membrane that sets the external forces on
// boundary particles) and observers (a recorder that sums wall stresses). A listener is attached
// to a Simulation (Simulation::attach) and called once per step, never per contact, so a virtual
// call costs nothing measurable.
//
// Order within one Simulation::step():
//   before_step  (controllers: commands such as set_wall_velocity, set_external_force)
//   half kick + drift, walls move
//   neighbour list rebuilt if stale -> after_rebuild (e.g. re-identify the boundary particles;
//                                      particle storage indices change at a rebuild)
//   forces, half kick, health check
//   after_step   (observers: read-only views of the new state)
#pragma once

namespace grainlab {

class Simulation;

class StepListener {
 public:
  virtual ~StepListener() = default;
  virtual void before_step(Simulation&) {}
  virtual void after_rebuild(Simulation&) {}
  virtual void after_step(const Simulation&) {}
};

}  // namespace grainlab
