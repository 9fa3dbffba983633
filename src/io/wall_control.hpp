// Walls of a scene held at a target normal stress (`[[wall]] target_stress`, docs/scene-schema.md).
// Before every step each such wall gets a velocity along its normal from a StressServo
// (control/stress_servo.hpp), fed with the normal stress the particles exerted on it in the last
// force evaluation, the area it loads and its summed contact stiffness. The servo holds a jammed
// specimen (holding_proportional_gain); its speed is capped by the wall's max_speed.
#pragma once

#include <vector>

#include "control/stress_servo.hpp"
#include "core/step_listener.hpp"
#include "geometry/wall.hpp"
#include "io/scene_config.hpp"

namespace grainlab {

// Compressive normal stress the particles exert on a plane or rectangle wall over `area_m2`, Pa:
// -(F . n) / A, positive when particles on the side the normal points to push on it.
double compressive_normal_stress(const Wall& wall, double area_m2);

class WallStressControl : public StepListener {
 public:
  // `loads` holds one entry per wall (SceneConfig::wall_loads); walls without target_stress are
  // left alone.
  explicit WallStressControl(const std::vector<WallLoad>& loads);

  bool empty() const { return held_.empty(); }
  void before_step(Simulation& sim) override;
  // The servos' integral terms, for checkpoints (one per held wall, in wall order).
  std::vector<double> integrals() const;
  void set_integrals(const std::vector<double>& v);

 private:
  struct HeldWall {
    size_t wall = 0;
    double area_m2 = 0.0;
    StressServo servo;
  };
  std::vector<HeldWall> held_;
};

}  // namespace grainlab
