#include "control/plane_strain_box.hpp"

#include "core/simulation.hpp"
#include "geometry/cuboid_box.hpp"

namespace grainlab {

std::vector<Wall> plane_strain_walls(const Vec3& lo, const Vec3& hi, int side_material,
                                     int platen_material) {
  std::vector<Wall> box = cuboid_walls(lo, hi, side_material, platen_material);
  box[y_low].name = "front", box[y_high].name = "back";
  return {box[y_low], box[y_high], box[bottom], box[top]};
}

MembraneSettings plane_strain_membrane(double pressure, double diameter) {
  return {0, pressure, diameter, {front, back, bottom_platen, top_platen}};
}

PlaneStrainBox plane_strain_box(const Simulation& sim, const Membrane& membrane) {
  const std::vector<Wall>& w = sim.walls();
  return {{membrane.surface(sim, 0), w[front].point.y, w[bottom_platen].point.z},
          {membrane.surface(sim, 1), w[back].point.y, w[top_platen].point.z}};
}

double plane_strain_wall_stress(const Simulation& sim, const PlaneStrainBox& box, int k) {
  const Wall& w = sim.walls()[k];
  const Vec3 d = box.size();
  const double area = k < bottom_platen ? d.x * d.z : d.x * d.y;
  return -dot(w.force, w.normal) / area;
}

PlaneStrainControl::PlaneStrainControl(const Membrane& membrane,
                                       const std::array<AxisControl, 2>& axes, ServoRegime regime,
                                       double max_strain_rate)
    : membrane_(membrane), axes_(axes), max_strain_rate_(max_strain_rate) {
  for (int k = 0; k < 4; ++k)
    servos_[k] = StressServo(ServoSettings{axes_[k / 2].stress, 0.0, proportional_gain(regime)});
}

void PlaneStrainControl::before_step(Simulation& sim) {
  // The box (the membrane's surfaces: a pass over its beads) only where a servo needs it: not
  // while the walls are fixed or driven, as in the shearing.
  const bool servo = axes_[0].mode == AxisMode::stress || axes_[1].mode == AxisMode::stress;
  const PlaneStrainBox box = servo ? plane_strain_box(sim, membrane_) : PlaneStrainBox{};
  const Vec3 size = box.size();
  const double dt = sim.settings().time_step;
  for (int k = 0; k < 4; ++k) {
    const AxisControl& a = axes_[k / 2];
    const Wall& w = sim.walls()[k];
    switch (a.mode) {
      case AxisMode::fixed:
        sim.set_wall_velocity(k, {});
        break;
      case AxisMode::speed:
        sim.set_wall_velocity(k, a.inward_speed * w.normal);
        break;
      case AxisMode::stress: {
        StressServo& servo = servos_[k];
        const double area = k < bottom_platen ? size.x * size.z : size.x * size.y;
        servo.set_target(a.stress + (k == bottom_platen ? bottom_platen_load_ / area : 0.0));
        servo.set_max_speed(max_strain_rate_ * 0.5 * size[1 + k / 2]);
        const double inward =
            servo.update(plane_strain_wall_stress(sim, box, k), area, w.contact_stiffness, dt);
        sim.set_wall_velocity(k, inward * w.normal);
        break;
      }
    }
  }
}

std::array<double, 4> PlaneStrainControl::integrals() const {
  std::array<double, 4> v;
  for (int k = 0; k < 4; ++k) v[k] = servos_[k].integral();
  return v;
}

void PlaneStrainControl::set_integrals(const std::array<double, 4>& v) {
  for (int k = 0; k < 4; ++k) servos_[k].set_integral(v[k]);
}

}  // namespace grainlab
