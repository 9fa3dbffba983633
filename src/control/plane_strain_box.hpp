// The plane strain box: rigid front and back walls (y) and platens (z) as plane walls, and the
// two lateral faces (x) closed by a flexible membrane (control/membrane.hpp) instead of walls.
// Its extent: width between the membrane surfaces, thickness between front and back, height
// between the platens. PlaneStrainControl sets the four walls each step: per axis (y, z) fixed,
// driven at a speed, or servo-held at a stress over the membrane-bounded face area.
#pragma once

#include <array>
#include <vector>

#include "control/box_controller.hpp"
#include "control/membrane.hpp"
#include "geometry/wall.hpp"

namespace grainlab {

enum PlaneStrainWall { front = 0, back = 1, bottom_platen = 2, top_platen = 3 };

// The four walls in PlaneStrainWall order, closing [lo, hi] along y and z.
std::vector<Wall> plane_strain_walls(const Vec3& lo, const Vec3& hi, int side_material,
                                     int platen_material);

// The membrane on the x faces, its grid one `diameter` wide, spanned by the four walls.
MembraneSettings plane_strain_membrane(double pressure, double diameter);

struct PlaneStrainBox {
  Vec3 low, high;  // x from the membrane surfaces, y and z from the walls
  Vec3 size() const { return high - low; }
  double volume() const {
    const Vec3 d = size();
    return d.x * d.y * d.z;
  }
  Vec3 centre() const { return 0.5 * (low + high); }
};
PlaneStrainBox plane_strain_box(const Simulation& sim, const Membrane& membrane);

// Compressive normal stress on wall k (F / A over the current face it closes), Pa.
double plane_strain_wall_stress(const Simulation& sim, const PlaneStrainBox& box, int k);

class PlaneStrainControl : public StepListener {
 public:
  // axes[0] for the front/back walls (y), axes[1] for the platens (z).
  PlaneStrainControl(const Membrane& membrane, const std::array<AxisControl, 2>& axes,
                     ServoRegime regime, double max_strain_rate);
  void before_step(Simulation& sim) override;
  void set_axis(int k, const AxisControl& c) { axes_[k] = c; }
  // The specimen's weight (N) under gravity along -z: a stress-held bottom platen is held at the
  // axis stress plus weight / area, so that a specimen at rest has the axis stress on top.
  void set_bottom_platen_load(double weight) { bottom_platen_load_ = weight; }
  std::array<double, 4> integrals() const;
  void set_integrals(const std::array<double, 4>& v);

 private:
  const Membrane& membrane_;
  std::array<AxisControl, 2> axes_;
  double max_strain_rate_;
  double bottom_platen_load_ = 0.0;  // N
  std::array<StressServo, 4> servos_;
};

}  // namespace grainlab
