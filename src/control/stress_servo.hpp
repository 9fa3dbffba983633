// Stress-controlled walls: a proportional-integral servo whose gains come from the summed
// contact stiffness on the wall and the time step, so the user never tunes them.
//
// The wall stress responds to the inward wall speed v as d(sigma)/dt = (k_sum / A) (v - v_req),
// where v_req is the speed at which the specimen itself moves (dilation, compaction). With
//   e = (sigma_target - sigma) A / (k_sum dt)        [m/s: the speed that cancels the error in one
//   step] v = alpha_p e + integral,   integral += alpha_i e   (each step)
// the closed loop is a damped oscillator with omega = sqrt(alpha_i)/dt and damping ratio
// alpha_p / (2 sqrt(alpha_i)); alpha_i = alpha_p^2 / 4 makes it critically damped (no overshoot)
// and leaves no steady error while the specimen dilates at a constant rate (the integral carries
// v_req).
//
// The integral term makes the servo act like a wall of mass m_eq = k_sum dt^2 / alpha_i pushed by
// the stress error: over any interval the mean stress error is m_eq dv / (A dt_interval), so a
// heavy equivalent wall cannot follow a dilating or collapsing specimen. In contact units,
// m_eq / (mass of the bead layer it touches) = (omega_n dt)^2 / alpha_i with omega_n dt ~ 0.3 at
// dt = 0.1 t_c. Two settings, for two regimes:
// - compaction of a loose assembly (the default, alpha_p = 0.02, time constant 100 steps): the
//   wall keeps losing and regaining contact with a light, mobile layer; a stiffer servo bounces off
//   it in a limit cycle (alpha_p = 0.2 left the 500-bead preparation oscillating at +-135 % stress
//   error), a gentle one compacts steadily.
// - holding a jammed specimen while it is sheared (`holding_proportional_gain` = 0.2, time
//   constant 10 steps, one collision duration): the equivalent wall is then about ten times
//   heavier than the bead layer it touches, heavy enough not to rattle it and light enough to
//   follow the specimen. Worst interval-averaged lateral stress error on the 500-bead triaxial test
//   sheared at I = 1e-3: 17 % with alpha_p = 0.02, 0.76 % with 0.1, 0.19 % with 0.2, 0.07 % with
//   0.3.
// Speeds are capped: approach speed when the wall has no contact, and a quasi-static bound set by
// the test.
#pragma once

#include <algorithm>

namespace grainlab {

inline constexpr double holding_proportional_gain = 0.2;
inline constexpr double compaction_proportional_gain = 0.02;

// The two regimes above; the gains are chosen here and nowhere else.
enum class ServoRegime { compaction, holding };
inline double proportional_gain(ServoRegime r) {
  return r == ServoRegime::holding ? holding_proportional_gain : compaction_proportional_gain;
}

struct ServoSettings {
  double target_stress = 0.0;                          // Pa, compressive positive
  double max_speed = 0.01;                             // m/s
  double proportional = compaction_proportional_gain;  // alpha_p
};

class StressServo {
 public:
  StressServo() = default;
  explicit StressServo(const ServoSettings& s) : s_(s) {}

  // Inward wall speed for the next step, m/s (negative: outward).
  double update(double stress, double area, double contact_stiffness, double dt) {
    if (contact_stiffness <= 0.0) {  // not touching: approach (or retreat) at the cap
      integral_ = 0.0;
      return s_.target_stress > stress ? s_.max_speed : -s_.max_speed;
    }
    const double e = (s_.target_stress - stress) * area / (contact_stiffness * dt);
    const double alpha_i = 0.25 * s_.proportional * s_.proportional;
    integral_ = std::clamp(integral_ + alpha_i * e, -s_.max_speed, s_.max_speed);
    return std::clamp(integral_ + s_.proportional * e, -s_.max_speed, s_.max_speed);
  }

  void set_max_speed(double v) { s_.max_speed = v; }
  void set_target(double stress) { s_.target_stress = stress; }
  double integral() const { return integral_; }
  void set_integral(double v) { integral_ = v; }  // for restarts

 private:
  ServoSettings s_;
  double integral_ = 0.0;  // m/s
};

}  // namespace grainlab
