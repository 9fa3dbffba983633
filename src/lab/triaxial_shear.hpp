// The loading stage of the triaxial test: the lateral boundary held at sigma_3 and the platens
// driven (control/box_controller.hpp), a curve.csv row every output strain interval with the
// stresses averaged over the interval, the running peaks and errors. Everything it carries from
// step to step is in ShearProgress, which a checkpoint saves whole (ElementRun::test_state).
#pragma once

#include <array>
#include <string>

#include "control/box_controller.hpp"
#include "lab/element_test.hpp"
#include "measure/interval_stresses.hpp"

namespace grainlab {

struct ShearProgress {  // plain values, saved as they are
  long step = 0, total_steps = 0, next_output = 0, lateral_samples = 0;
  double platen_speed = 0, strain_rate = 0, confining_stress = 0, diameter = 0, density = 0;
  double output_strain_interval = 0;
  Vec3 size0;
  double peak_axial = 0, peak_strain = 0, peak_deviator = 0, peak_ratio = 0, max_inertial = 0;
  double lateral_error2 = 0, max_lateral_error = 0, last_axial = 0, last_strain = 0;
  // Once quasi-static (axial strain > 0.5 %): largest |particle - boundary| / boundary over the
  // three axes, and the running sum of platen stress / boundary axial stress - 1 (the share of
  // the axial load the lateral walls' friction carries).
  double worst_agreement = 0, platen_excess_sum = 0;
  long platen_excess_rows = 0;
  double vtk_strain_interval = 0;  // 0: no snapshots
  long next_vtk = 0;
  std::array<double, 6> servo_integral{};
  // Averages over the current output interval: wall stresses every step, the specimen's
  // stresses every `stress_sample_steps` steps.
  IntervalStresses interval;
};

inline constexpr long stress_sample_steps = 50;

class TriaxialShear : public LoadingStage {
 public:
  // A fresh stage (progress set up by the caller) or one restored from run.test_state.
  TriaxialShear(ElementRun& run, const ShearProgress& progress, const std::string& dir);
  static ShearProgress restore(const ElementRun& run);

  const char* curve_header() const override;
  void observe(ElementRun& run, Progress& progress) override;
  bool finished(const ElementRun&) const override { return p_.step == p_.total_steps; }
  void after_step(ElementRun& run) override;
  long step() const override { return p_.step; }
  std::string position() const override;
  void save(ElementRun& run) const override;
  const ShearProgress& progress() const { return p_; }

 private:
  void record(ElementRun& run);
  void snapshot(ElementRun& run);

  ShearProgress p_;
  double axial_strain_ = 0.0;  // at the last observe
  std::string dir_;
  BoxController control_;
  ScopedListener attached_;
};

}  // namespace grainlab
