#include "io/wall_control.hpp"

#include "core/simulation.hpp"

namespace grainlab {

double compressive_normal_stress(const Wall& wall, double area_m2) {
  return 0.0 - dot(wall.force, wall.normal) / area_m2;  // 0 - : no -0 in walls.csv
}

WallStressControl::WallStressControl(const std::vector<WallLoad>& loads) {
  for (size_t k = 0; k < loads.size(); ++k) {
    if (!loads[k].target_stress) continue;
    held_.push_back({k, *loads[k].area,
                     StressServo(ServoSettings{*loads[k].target_stress, loads[k].max_speed,
                                               proportional_gain(ServoRegime::holding)})});
  }
}

void WallStressControl::before_step(Simulation& sim) {
  const double dt = sim.settings().time_step;
  for (HeldWall& h : held_) {
    const Wall& w = sim.walls()[h.wall];
    const double inward_speed =
        h.servo.update(compressive_normal_stress(w, h.area_m2), h.area_m2, w.contact_stiffness, dt);
    sim.set_wall_velocity(h.wall, inward_speed * w.normal);
  }
}

std::vector<double> WallStressControl::integrals() const {
  std::vector<double> v;
  for (const HeldWall& h : held_) v.push_back(h.servo.integral());
  return v;
}

void WallStressControl::set_integrals(const std::vector<double>& v) {
  for (size_t k = 0; k < held_.size() && k < v.size(); ++k) held_[k].servo.set_integral(v[k]);
}

}  // namespace grainlab
