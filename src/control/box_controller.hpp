// The one controller of a cuboid box's six walls (geometry/cuboid_box.hpp), used by every element
// test: per axis, the two walls of that axis
//   hold a stress      (servo, control/stress_servo.hpp: the lateral boundary held at sigma_3),
//   move at a speed    (each wall inward at `inward_speed`, m/s: the platens of a strain-
//                       controlled test; negative moves them apart),
//   or stay fixed      (zero strain: an oedometer's lateral walls, a plane-strain test's front
//                       and back).
// It is a StepListener: attached to the Simulation it sets the wall velocities before every step.
// The servo state (the integral terms) is part of a checkpoint.
#pragma once

#include <array>

#include "control/stress_servo.hpp"
#include "core/step_listener.hpp"

namespace grainlab {

enum class AxisMode { fixed, stress, speed };

struct AxisControl {
  AxisMode mode = AxisMode::fixed;
  double stress = 0.0;        // Pa, compressive positive (mode stress)
  double inward_speed = 0.0;  // m/s, each wall of the axis (mode speed)
};

// Speed cap of the stress-held walls: a fixed speed (max_speed > 0), or the strain rate
// max_strain_rate applied to the current box (each wall at most rate x half the box size).
struct BoxControlSettings {
  std::array<AxisControl, 3> axes;  // x, y, z
  ServoRegime regime = ServoRegime::holding;
  double max_speed = 0.0;        // m/s
  double max_strain_rate = 0.0;  // 1/s, used when max_speed = 0
};

class BoxController : public StepListener {
 public:
  explicit BoxController(const BoxControlSettings& settings);

  void before_step(Simulation& sim) override;

  // Changes what one axis does (e.g. unloading: reverse the platens) keeping the servo state.
  void set_axis(int axis, const AxisControl& control) { s_.axes[axis] = control; }
  const AxisControl& axis(int a) const { return s_.axes[a]; }

  // Servo integrals of the six walls, m/s (for checkpoints).
  std::array<double, 6> integrals() const;
  void set_integrals(const std::array<double, 6>& v);

 private:
  BoxControlSettings s_;
  std::array<StressServo, 6> servos_;
};

// Sets every wall of the simulation to rest (the end of a controlled stage).
void stop_walls(Simulation& sim);

}  // namespace grainlab
