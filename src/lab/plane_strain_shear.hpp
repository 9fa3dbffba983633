// The loading stage of the plane strain test: the membrane holds the two lateral faces at the
// confining pressure, the front and back walls stay fixed (zero strain through the thickness), the
// platens are driven; a curve.csv row every output strain interval with the stresses averaged
// over the interval, the running peak, membrane error and escaped-bead count. Everything carried
// from step to step is in PlaneStrainProgress plus the membrane's bead set (saved by id), which a
// checkpoint holds.
#pragma once

#include <array>
#include <string>

#include "control/membrane.hpp"
#include "control/plane_strain_box.hpp"
#include "lab/element_test.hpp"

namespace grainlab {

struct PlaneStrainProgress {  // plain values, saved as they are
  long step = 0, total_steps = 0, next_output = 0;
  double platen_speed = 0, strain_rate = 0, confining_stress = 0, diameter = 0, density = 0;
  double output_strain_interval = 0;
  Vec3 size0;  // width (membrane), thickness, height at the start of the loading
  double peak_axial = 0, peak_strain = 0, peak_deviator = 0, peak_lateral = 0, max_inertial = 0;
  // Over the rows past 0.5 % axial strain (the start-up transient of the platens):
  //   membrane error: the particles' (Love-Weber) lateral stress against the boundary-average
  //     lateral stress (membrane forces and every wall contact, measure/specimen_state.hpp),
  //     RMS and worst;
  //   the share of the lateral stress the friction of the fixed walls and the platens adds to
  //     the membrane's pressure (boundary-average / applied - 1), summed for its mean.
  double membrane_error2 = 0, max_membrane_error = 0, wall_friction_share_sum = 0;
  double max_applied_error = 0;  // |particles / applied - 1|, worst
  long membrane_samples = 0, max_escaped = 0;
  double max_out_of_plane_strain = 0, last_axial = 0, last_strain = 0;
  double vtk_strain_interval = 0;  // 0: no snapshots
  long next_vtk = 0;
  // Averages over the current output interval: walls and membrane every step, the particles'
  // stress every `plane_strain_sample_steps` steps.
  std::array<double, 4> wall_sum{};
  std::array<double, 2> applied_sum{};
  long wall_samples = 0;
  std::array<double, 3> particle_sum{}, boundary_sum{};
  long particle_samples = 0;
};

inline constexpr long plane_strain_sample_steps = 50;

class PlaneStrainShear : public LoadingStage {
 public:
  // A fresh stage, or (with `membrane_state`, from restore) the one a checkpoint holds.
  PlaneStrainShear(ElementRun& run, const PlaneStrainProgress& progress, const std::string& dir,
                   const std::string* membrane_state = nullptr);
  // The progress values and the membrane's state of a checkpoint.
  static PlaneStrainProgress restore(const ElementRun& run, std::string& membrane_state);

  const char* curve_header() const override;
  void observe(ElementRun& run, Progress& progress) override;
  bool finished(const ElementRun&) const override { return p_.step == p_.total_steps; }
  void after_step(ElementRun& run) override;
  long step() const override { return p_.step; }
  std::string position() const override;
  void save(ElementRun& run) const override;
  const PlaneStrainProgress& progress() const { return p_; }
  const Membrane& membrane() const { return membrane_; }

 private:
  void add_sample(const Simulation& sim, bool specimen);
  void record(ElementRun& run);
  void snapshot(ElementRun& run);

  PlaneStrainProgress p_;
  double axial_strain_ = 0.0;  // at the last observe
  std::string dir_;
  Membrane membrane_;
  PlaneStrainControl control_;
  ScopedListener membrane_attached_, control_attached_;
};

}  // namespace grainlab
