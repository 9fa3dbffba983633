// Normal damping of the linear spring-dashpot, chosen from the restitution coefficient e.
//
// Textbook (published Eq. 7, with its sign and logarithm corrected):
//   zeta = -ln e / sqrt(pi^2 + ln^2 e),  c_n = 2 zeta sqrt(k_n m*).
// That zeta returns e exactly only if the dashpot may pull the bodies together at the end of
// the contact. grainlab never lets the normal force become tensile, so the contact ends when
// k_n U_n + c_n dU_n/dt first reaches zero, slightly before U_n does, and the bodies leave
// faster: with the textbook zeta, e = 0.5 rebounds near 0.55. grainlab therefore inverts the
// closed-form restitution of the clamped contact (Schwager & Poeschel, Granular Matter 9, 2007,
// derived again in docs/contact-model.md) once per material pair at set-up.
// All times below are in units of 1/omega_0, omega_0 = sqrt(k_n / m*).
#pragma once

namespace grainlab {

// zeta of the published Eq. 7 (ln form), for 0 < e <= 1.
double textbook_damping_ratio(double restitution);

// Restitution of a head-on contact with damping ratio zeta >= 0 whose force is clamped at zero.
double clamped_restitution(double damping_ratio);

// Time from first touch until the clamped force returns to zero, in units of 1/omega_0.
double clamped_force_duration(double damping_ratio);

// Time from first touch until the overlap returns to zero (the bodies separate at constant
// speed once the force has vanished), in units of 1/omega_0.
double clamped_overlap_duration(double damping_ratio);

// zeta for which the clamped contact returns `restitution` exactly (0 < e <= 1), to 1e-13.
double damping_ratio_for_restitution(double restitution);

}  // namespace grainlab
