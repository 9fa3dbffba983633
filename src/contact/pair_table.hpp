// The symmetric material-pair table: every constant of the contact law that does not depend on
// the size of the bodies in contact is derived here once, at set-up. Per contact only the
// geometric factors remain: k_n = stiffness_per_radius * r*, c_n = 2 zeta sqrt(k_n m*).
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "contact/material.hpp"

namespace grainlab {

struct PairParams {
  double stiffness_per_radius = 0.0;    // pi E, Pa (k_n = pi E r*, Eq. 4)
  double damping_ratio = 0.0;           // zeta used (returns e exactly with the clamp)
  double textbook_damping_ratio = 0.0;  // zeta of Eq. 7, reported only
  double rns = 0.5, rzs = 0.0;
  double friction = 0.0;
  double arf = 0.0;
  double rolling_damping_ratio = 0.0;  // eta_theta
  double twisting_friction = 0.0;
  double rolling_force_stiffness_ratio = 0.0;
  double rolling_force_friction = 0.0;
  double youngs_modulus = 0.0;  // E used for this pair, Pa
  double restitution = 1.0;
  bool defined = false;
};

struct ContactPieces {
  bool rolling = false, twisting = false, rolling_force = false;
  friend bool operator==(const ContactPieces&, const ContactPieces&) = default;
};

class PairTable {
 public:
  explicit PairTable(std::vector<Material> materials);

  // Derives the constants of one pair; throws std::invalid_argument naming what is wrong.
  void set(int a, int b, const PairProperties& properties);

  const PairParams& operator()(int a, int b) const { return table_[a * count_ + b]; }
  int material_count() const { return count_; }
  const Material& material(int i) const { return materials_[i]; }
  int find(const std::string& name) const;  // -1 if unknown

  // The derived constants of every pair (checkpoints).
  const std::vector<PairParams>& entries() const { return table_; }
  void restore_entries(const std::vector<PairParams>& entries) { table_ = entries; }

  // Which optional pieces some pair switches on (the force loop is compiled per combination).
  ContactPieces pieces() const;

 private:
  std::vector<Material> materials_;
  int count_;
  std::vector<PairParams> table_;
};

}  // namespace grainlab
