#include "contact/pair_table.hpp"

#include <numbers>

#include "contact/damping.hpp"

namespace grainlab {

PairTable::PairTable(std::vector<Material> materials)
    : materials_(std::move(materials)),
      count_(static_cast<int>(materials_.size())),
      table_(static_cast<size_t>(count_ * count_)) {}

int PairTable::find(const std::string& name) const {
  for (int i = 0; i < count_; ++i)
    if (materials_[i].name == name) return i;
  return -1;
}

void PairTable::set(int a, int b, const PairProperties& p) {
  if (!(p.restitution > 0.0 && p.restitution <= 1.0))
    throw std::invalid_argument("restitution must lie in (0, 1]");
  if (!(p.friction >= 0.0)) throw std::invalid_argument("friction must be >= 0");
  if (!(p.rns > 0.0)) throw std::invalid_argument("rns (k_s/k_n) must be > 0");
  if (!(p.rzs >= 0.0)) throw std::invalid_argument("rzs (c_s/c_n) must be >= 0");
  if (!(p.arf >= 0.0)) throw std::invalid_argument("arf must be >= 0");
  if (!(p.twisting_friction >= 0.0)) throw std::invalid_argument("twisting_friction must be >= 0");
  if (!(p.rolling_force_stiffness_ratio >= 0.0 && p.rolling_force_friction >= 0.0))
    throw std::invalid_argument("rolling force parameters must be >= 0");

  // Stiffness modulus: the pair's own E if given; otherwise the particles' E, combined as two
  // springs in series (2 E_a E_b / (E_a + E_b), which is E for equal materials). A material
  // without E (a wall) leaves the other's E.
  double e_modulus = 0.0;
  if (p.youngs_modulus) {
    e_modulus = *p.youngs_modulus;
  } else {
    const auto& ea = materials_[a].youngs_modulus;
    const auto& eb = materials_[b].youngs_modulus;
    if (ea && eb)
      e_modulus = 2.0 * *ea * *eb / (*ea + *eb);
    else if (ea)
      e_modulus = *ea;
    else if (eb)
      e_modulus = *eb;
  }
  if (!(e_modulus > 0.0))
    throw std::invalid_argument(
        "no Young's modulus: set youngs_modulus > 0 on a material or the pair");

  PairParams q;
  q.youngs_modulus = e_modulus;
  q.stiffness_per_radius = std::numbers::pi * e_modulus;
  q.restitution = p.restitution;
  q.damping_ratio = damping_ratio_for_restitution(p.restitution);
  q.textbook_damping_ratio = textbook_damping_ratio(p.restitution);
  q.rns = p.rns;
  q.rzs = p.rzs;
  q.friction = p.friction;
  q.arf = p.arf;
  q.rolling_damping_ratio =
      p.rolling_damping_ratio >= 0.0 ? p.rolling_damping_ratio : q.damping_ratio;
  q.twisting_friction = p.twisting_friction;
  q.rolling_force_stiffness_ratio = p.rolling_force_stiffness_ratio;
  q.rolling_force_friction = p.rolling_force_friction;
  q.defined = true;
  table_[a * count_ + b] = q;
  table_[b * count_ + a] = q;
}

ContactPieces PairTable::pieces() const {
  ContactPieces c;
  for (const PairParams& p : table_) {
    c.rolling = c.rolling || (p.defined && p.arf > 0.0);
    c.twisting = c.twisting || (p.defined && p.twisting_friction > 0.0);
    c.rolling_force = c.rolling_force || (p.defined && p.rolling_force_stiffness_ratio > 0.0);
  }
  return c;
}

}  // namespace grainlab
