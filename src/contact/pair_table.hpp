// The symmetric material-pair table: every constant of the contact law that does not depend on
// the size of the bodies in contact is derived here once, at set-up. Per contact only the
// geometric factors remain: k_n = stiffness_per_radius * r*, c_n = 2 zeta sqrt(k_n m*).
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "contact/material.hpp"
#include "contact/pair_params.hpp"

namespace grainlab {

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
