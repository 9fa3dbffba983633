// Isotropic compaction of a cuboid specimen by a homogeneous (affine) strain: every step the six
// walls and every particle centre move toward the box centre by the same strain increment.
//
// Why: compacting by the walls alone builds the density from the walls inwards. At the scale of
// the plane strain test (88,400 beads, 100 mm) the walls approach at rate x half the box (0.5 m/s
// at 10 /s); when the dense layers they push meet, the packing jams all at once and the walls
// overshoot the confining stress many times over, then ring for minutes (a 100 mm specimen takes
// ~5,000 steps for an elastic wave to cross, against the servo's 100-step time constant). An
// affine strain compacts every part of the specimen at the same rate, so the stress builds
// everywhere at once and the walls read the bulk stress without waiting for a wave; its speed no
// longer grows with the specimen. The same idea as compaction by growing radii (YADE's internal
// compaction), but with the radii kept at their measured sizes.
//
// Rate law: strain rate = max_strain_rate x clamp(1 - sigma / target, -1, 1) on all three axes,
// with sigma the mean of the six wall stresses averaged (exponentially) over the last 100 steps,
// 10 collision times at dt = 0.1 t_c: full speed while the packing is loose, slowing to zero as
// the stress reaches the target, and expanding the box above it. The averaging matters: near
// jamming the wall stress of a small specimen spikes and drops from step to step, and the same
// law on the instantaneous stress reversed on every spike, unjammed the packing again and again
// and stalled 2,000 beads 2 % short of jamming. Isotropic scaling moves two beads in contact
// apart or together only along the line of their centres, so it adds nothing to the tangential
// springs. Velocities are kept: they are the beads' motion relative to the affine field.
#pragma once

#include "core/step_listener.hpp"

namespace grainlab {

class AffineCompaction : public StepListener {
 public:
  AffineCompaction(double target_stress, double max_strain_rate)
      : target_stress_(target_stress), max_strain_rate_(max_strain_rate) {}

  void before_step(Simulation& sim) override;

  // Mean wall stress (averaged as above) relative to the target, minus 1.
  double stress_error() const { return mean_stress_ / target_stress_ - 1.0; }
  double strain_rate() const { return strain_rate_; }  // 1/s, compressive positive, last step
  // The averaged mean wall stress, Pa (for checkpoints).
  double mean_stress() const { return mean_stress_; }
  void set_mean_stress(double v) { mean_stress_ = v; }

 private:
  double target_stress_;    // Pa
  double max_strain_rate_;  // 1/s
  double strain_rate_ = 0.0;
  double mean_stress_ = 0.0;  // Pa, the averaged mean wall stress
};

}  // namespace grainlab
