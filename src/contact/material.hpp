// Materials and the measured quantities of each material pair (docs/contact-model.md), as read
// from a configuration. Units: Pa, kg/m^3, dimensionless coefficients.
#pragma once

#include <optional>
#include <string>

namespace grainlab {

struct Material {
  std::string name;
  std::optional<double> youngs_modulus;  // E, Pa (walls may omit it)
  std::optional<double> poisson_ratio;   // nu, - (recorded; the linear model does not use it)
  std::optional<double> density;         // rho, kg/m^3 (walls may omit it)
};

// What the laboratory measures (or the user chooses) for one pair of materials.
struct PairProperties {
  double restitution = 1.0;                    // e, in (0, 1]
  double friction = 0.0;                       // mu_s >= 0
  double rns = 0.5;                            // k_s / k_n
  double rzs = 0.0;                            // c_s / c_n
  double arf = 0.0;                            // rolling friction: mu_theta = arf * a
  double rolling_damping_ratio = -1.0;         // eta_theta; < 0 means "use the normal zeta"
  double twisting_friction = 0.0;              // mu_t = twisting_friction * a; 0 = off
  double rolling_force_stiffness_ratio = 0.0;  // k_r / k_n; 0 = off
  double rolling_force_friction = 0.0;         // mu_r
  std::optional<double> youngs_modulus;        // overrides the particles' E for this pair, Pa
};

}  // namespace grainlab
