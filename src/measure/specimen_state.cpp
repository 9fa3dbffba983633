#include "measure/specimen_state.hpp"

#include <numbers>

namespace grainlab {
namespace {
Tensor3 symmetric_over_volume(const Tensor3& s, double volume) {
  Tensor3 out{};
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) out[a][b] = 0.5 * (s[a][b] + s[b][a]) / volume;
  return out;
}
// An external force (a membrane's pressure) is a load on the particle's surface where the pushing
// body touches it: the point opposite the force's direction, -r F/|F| from the centre. (Zero for
// a particle without one.)
Vec3 external_load_arm(const ParticleStore& p, size_t i) {
  const double f = norm(p.external_force[i]);
  return f > 0.0 ? (-p.radius[i] / f) * p.external_force[i] : Vec3{};
}
}  // namespace

Tensor3 love_weber_stress(const Simulation& sim, double volume) {
  const ParticleStore& p = sim.particles();
  const PairContacts& c = sim.pair_contacts();
  const WallContacts& wc = sim.wall_contacts();
  Tensor3 s{};
  // Serial, in storage order: deterministic.
  for (size_t i = 0; i < p.size(); ++i) {
    for (uint32_t e = c.row_start[i]; e < c.row_start[i + 1]; ++e) {
      const PairResult& r = c.result[e];
      if (r.normal_force == 0.0 && norm2(r.force_on_first) == 0.0) continue;
      const Vec3 f = -1.0 * r.force_on_first;  // on the second particle
      const Vec3 l = p.position[c.partner[e]] - p.position[i];
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) s[a][b] += f[a] * l[b];
    }
    for (uint32_t e = wc.row_start[i]; e < wc.row_start[i + 1]; ++e) {
      if (wc.normal_stiffness[e] == 0.0) continue;
      const Vec3 f = -1.0 * wc.force_on_particle[e];  // on the wall
      const WallGap g = wall_gap(sim.walls()[wc.wall[e]], p.position[i]);
      const Vec3 l = g.gap * g.normal;  // centre -> contact point
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) s[a][b] += f[a] * l[b];
    }
    if (const Vec3 l = external_load_arm(p, i); norm2(l) > 0.0) {
      const Vec3 f = -1.0 * p.external_force[i];  // on the membrane
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) s[a][b] += f[a] * l[b];
    }
  }
  // Compressive positive: a contact pushing the bodies apart (f along l) is compression.
  return symmetric_over_volume(s, volume);
}

Tensor3 boundary_stress(const Simulation& sim, const Vec3& centre, double volume) {
  const ParticleStore& p = sim.particles();
  const WallContacts& wc = sim.wall_contacts();
  Tensor3 s{};
  for (size_t i = 0; i < p.size(); ++i)
    for (uint32_t e = wc.row_start[i]; e < wc.row_start[i + 1]; ++e) {
      if (wc.normal_stiffness[e] == 0.0) continue;
      const Vec3 f = -1.0 * wc.force_on_particle[e];  // on the wall
      const WallGap g = wall_gap(sim.walls()[wc.wall[e]], p.position[i]);
      const Vec3 x = p.position[i] + g.gap * g.normal - centre;  // contact point from x_0
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) s[a][b] += f[a] * x[b];
    }
  for (size_t i = 0; i < p.size(); ++i)
    if (const Vec3 l = external_load_arm(p, i); norm2(l) > 0.0) {
      const Vec3 f = -1.0 * p.external_force[i];
      const Vec3 x = p.position[i] + l - centre;
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) s[a][b] += f[a] * x[b];
    }
  return symmetric_over_volume(s, volume);
}

double solid_fraction(const ParticleStore& p, double volume) {
  double v = 0.0;
  for (double r : p.radius) v += 4.0 / 3.0 * std::numbers::pi * r * r * r;
  return v / volume;
}

double coordination_number(const Simulation& sim) {
  long pp = sim.touching_pair_count(), pw = 0;
  for (double k : sim.wall_contacts().normal_stiffness) pw += k > 0.0;
  return sim.particles().size() ? (2.0 * pp + pw) / sim.particles().size() : 0.0;
}

std::vector<int> contacts_per_particle(const Simulation& sim) {
  const ParticleStore& p = sim.particles();
  const PairContacts& c = sim.pair_contacts();
  const WallContacts& wc = sim.wall_contacts();
  std::vector<int> count(p.size(), 0);
  for (size_t i = 0; i < p.size(); ++i) {
    for (uint32_t e = c.row_start[i]; e < c.row_start[i + 1]; ++e)
      if (c.result[e].normal_force > 0.0) ++count[i], ++count[c.partner[e]];
    for (uint32_t e = wc.row_start[i]; e < wc.row_start[i + 1]; ++e)
      count[i] += wc.normal_force[e] > 0.0;
  }
  return count;
}

double unbalanced_force_ratio(const Simulation& sim) {
  const ParticleStore& p = sim.particles();
  double net = 0.0;
  long free = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    if (p.inverse_mass[i] == 0.0) continue;
    net += norm(p.force[i]);  // includes gravity: at rest under gravity it is balanced too
    ++free;
  }
  double contact = 0.0;
  long n = 0;
  for (const PairResult& r : sim.pair_contacts().result)
    if (r.normal_force > 0.0) contact += r.normal_force, ++n;
  for (double f : sim.wall_contacts().normal_force)
    if (f > 0.0) contact += f, ++n;
  if (n == 0 || free == 0) return 1.0;
  return (net / free) / (contact / n);
}

}  // namespace grainlab
