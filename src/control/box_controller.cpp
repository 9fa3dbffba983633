#include "control/box_controller.hpp"

#include "core/simulation.hpp"
#include "measure/boundary.hpp"

namespace grainlab {

BoxController::BoxController(const BoxControlSettings& settings) : s_(settings) {
  for (int k = 0; k < 6; ++k)
    servos_[k] = StressServo(
        ServoSettings{s_.axes[k / 2].stress, s_.max_speed, proportional_gain(s_.regime)});
}

void BoxController::before_step(Simulation& sim) {
  const std::vector<Wall>& walls = sim.walls();
  const double dt = sim.settings().time_step;
  const Vec3 size = box_size(walls);
  for (int k = 0; k < 6; ++k) {
    const AxisControl& a = s_.axes[k / 2];
    switch (a.mode) {
      case AxisMode::fixed:
        sim.set_wall_velocity(k, {});
        break;
      case AxisMode::speed:
        sim.set_wall_velocity(k, a.inward_speed * walls[k].normal);
        break;
      case AxisMode::stress: {
        StressServo& servo = servos_[k];
        servo.set_target(a.stress);
        servo.set_max_speed(s_.max_speed > 0.0 ? s_.max_speed
                                               : s_.max_strain_rate * 0.5 * size[k / 2]);
        const double inward = servo.update(wall_stress(walls, k), wall_area(walls, k),
                                           walls[k].contact_stiffness, dt);
        sim.set_wall_velocity(k, inward * walls[k].normal);
        break;
      }
    }
  }
}

std::array<double, 6> BoxController::integrals() const {
  std::array<double, 6> v;
  for (int k = 0; k < 6; ++k) v[k] = servos_[k].integral();
  return v;
}

void BoxController::set_integrals(const std::array<double, 6>& v) {
  for (int k = 0; k < 6; ++k) servos_[k].set_integral(v[k]);
}

void stop_walls(Simulation& sim) {
  for (size_t k = 0; k < sim.walls().size(); ++k) sim.set_wall_velocity(k, {});
}

}  // namespace grainlab
