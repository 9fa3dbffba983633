#include "control/membrane.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

#include "core/simulation.hpp"

namespace grainlab {

Membrane::Membrane(const MembraneSettings& settings)
    : s_(settings), b_((settings.axis + 1) % 3), c_((settings.axis + 2) % 3) {
  if (!(s_.cell_size > 0)) throw std::invalid_argument("membrane: cell size must be > 0");
}

Membrane::Extent Membrane::extent(const Simulation& sim) const {
  const std::vector<Wall>& w = sim.walls();
  return {w[s_.span_walls[0]].point[b_], w[s_.span_walls[1]].point[b_],
          w[s_.span_walls[2]].point[c_], w[s_.span_walls[3]].point[c_]};
}

namespace {
// The membrane's beads lie scattered through the particles' arrays (one per cell column on each
// face), and a step's passes have moved their lines out of the caches by the time the membrane
// reads them: the per-step loops ask for the bead this many cells ahead (none past the end).
constexpr size_t prefetch_cells = 16;
uint32_t ahead(const std::vector<uint32_t>& beads, size_t k) {
  return k + prefetch_cells < beads.size() ? beads[k + prefetch_cells] : UINT32_MAX;  // (none)
}

int cell_index(double x, double lo, double width, int n) {
  return std::clamp(static_cast<int>(std::floor((x - lo) / width)), 0, n - 1);
}
}  // namespace

// The outermost particle of every cell column on each face (serial, storage order: the same set
// whatever the thread count).
void Membrane::identify(const Simulation& sim) {
  const ParticleStore& p = sim.particles();
  const Extent e = extent(sim);
  // The grid is laid once (the first identification) and then stretches with the face: a cell
  // count that changed as the platens advance would shift the measured surface by a jump.
  if (n_b_ == 0) {
    n_b_ = std::max(1, static_cast<int>(std::lround((e.hi_b - e.lo_b) / s_.cell_size)));
    n_c_ = std::max(1, static_cast<int>(std::lround((e.hi_c - e.lo_c) / s_.cell_size)));
  }
  const double db = (e.hi_b - e.lo_b) / n_b_, dc = (e.hi_c - e.lo_c) / n_c_;
  const size_t cells = static_cast<size_t>(n_b_) * n_c_;
  std::array<std::vector<double>, 2> reach;
  for (int side = 0; side < 2; ++side) {
    bead_[side].assign(cells, none);
    reach[side].assign(cells, -INFINITY);
  }
  const int a = s_.axis;
  for (size_t i = 0; i < p.size(); ++i) {
    if (p.inverse_mass[i] == 0.0) continue;
    const size_t cell =
        static_cast<size_t>(cell_index(p.position[i][c_], e.lo_c, dc, n_c_)) * n_b_ +
        cell_index(p.position[i][b_], e.lo_b, db, n_b_);
    // How far out the particle's surface reaches on each face.
    const double out[2] = {-(p.position[i][a] - p.radius[i]), p.position[i][a] + p.radius[i]};
    for (int side = 0; side < 2; ++side)
      if (out[side] > reach[side][cell]) {
        reach[side][cell] = out[side];
        bead_[side][cell] = static_cast<uint32_t>(i);
      }
  }
  identified_ = true;
  read_applied_forces(sim);
}

void Membrane::read_applied_forces(const Simulation& sim) {
  for (int side = 0; side < 2; ++side) {
    double force = 0.0;
    for (uint32_t i : bead_[side])
      if (i != none) force += std::abs(sim.particles().external_force[i][s_.axis]);
    applied_force_[side] = force;
  }
}

double Membrane::height(const Simulation& sim, uint32_t i, int side) const {
  const ParticleStore& p = sim.particles();
  return p.position[i][s_.axis] + (side == 0 ? -1.0 : 1.0) * p.radius[i];
}

std::vector<double> Membrane::heights(const Simulation& sim, int side) const {
  std::vector<double> h(bead_[side].size(), NAN);
  for (size_t k = 0; k < h.size(); ++k)
    if (const uint32_t i = bead_[side][k]; i != none) h[k] = height(sim, i, side);
  return h;
}

void Membrane::apply(Simulation& sim) {
  const Extent e = extent(sim);
  const double cell_area = (e.hi_b - e.lo_b) / n_b_ * (e.hi_c - e.lo_c) / n_c_;
  for (int side = 0; side < 2; ++side) {
    long occupied = 0;
    for (uint32_t i : bead_[side]) occupied += i != none;
    if (occupied == 0) {
      applied_force_[side] = 0.0;
      continue;
    }
    // Each cell's share of p x face area, pushing inward along the axis; empty cells' shares go
    // to the occupied ones.
    Vec3 inward{};
    inward[s_.axis] = (side == 0 ? 1.0 : -1.0) * s_.pressure * cell_area *
                      static_cast<double>(bead_[side].size()) / occupied;
    // (the sum applied_stress reports, formed as reading the forces back would form it)
    double force = 0.0;
    const std::vector<uint32_t>& beads = bead_[side];
    for (size_t k = 0; k < beads.size(); ++k) {
      if (const uint32_t j = ahead(beads, k); j != none)
        __builtin_prefetch(&sim.particles().external_force[j], 1);
      if (const uint32_t i = beads[k]; i != none)
        sim.set_external_force(i, inward), force += std::abs(inward[s_.axis]);
    }
    applied_force_[side] = force;
  }
}

void Membrane::start(Simulation& sim) {
  sim.clear_external_forces();
  identify(sim);
  apply(sim);
}

double Membrane::applied_stress(const Simulation& sim, int side) const {
  if (!identified_) return 0.0;
  const Extent e = extent(sim);
  return applied_force_[side] / ((e.hi_b - e.lo_b) * (e.hi_c - e.lo_c));
}

void Membrane::before_step(Simulation& sim) {
  if (!identified_) {
    sim.clear_external_forces();
    identify(sim);
  }
  apply(sim);
}

void Membrane::after_rebuild(Simulation& sim) {
  // Storage indices changed: find the outermost particles again, and move the forces to them.
  sim.clear_external_forces();
  identify(sim);
  apply(sim);
}

void Membrane::release(Simulation& sim) {
  sim.clear_external_forces();
  identified_ = false;
}

// heights() summed as measure() sums them, without the vector: the plane strain test's sample
// asks for both faces after every step (and a servo-held control before it).
double Membrane::surface(const Simulation& sim, int side) const {
  if (!identified_) return NAN;
  const ParticleStore& p = sim.particles();
  double sum = 0.0;
  long n = 0;
  const std::vector<uint32_t>& beads = bead_[side];
  for (size_t k = 0; k < beads.size(); ++k) {
    if (const uint32_t j = ahead(beads, k); j != none)
      __builtin_prefetch(&p.position[j]), __builtin_prefetch(&p.radius[j]);
    const uint32_t i = beads[k];
    if (i == none) continue;
    const double v = height(sim, i, side);
    if (!std::isnan(v)) sum += v, ++n;
  }
  return n ? sum / n : NAN;
}

MembraneFaces Membrane::measure(const Simulation& sim) const {
  MembraneFaces m;
  if (!identified_) return m;
  const ParticleStore& p = sim.particles();
  const Extent e = extent(sim);
  const double db = (e.hi_b - e.lo_b) / n_b_, dc = (e.hi_c - e.lo_c) / n_c_;
  m.face_area = (e.hi_b - e.lo_b) * (e.hi_c - e.lo_c);
  std::array<std::vector<double>, 2> h{heights(sim, 0), heights(sim, 1)};
  for (int side = 0; side < 2; ++side) {
    double sum = 0.0;
    long n = 0;
    for (size_t k = 0; k < h[side].size(); ++k)
      if (!std::isnan(h[side][k])) sum += h[side][k], ++n;
    m.surface[side] = n ? sum / n : NAN;
    m.applied_stress[side] = applied_stress(sim, side);
    m.beads += n;
  }
  m.width = m.surface[1] - m.surface[0];
  // Escaped: beyond its cell's membrane surface by more than a cell, or outside the spanning
  // walls by more than its radius.
  for (size_t i = 0; i < p.size(); ++i) {
    const Vec3& x = p.position[i];
    const double r = p.radius[i];
    if (x[b_] < e.lo_b - r || x[b_] > e.hi_b + r || x[c_] < e.lo_c - r || x[c_] > e.hi_c + r) {
      ++m.escaped;
      continue;
    }
    // The membrane's furthest reach around the particle's cell (3 x 3 cells: the surface is
    // rough at the bead scale, and a particle may have moved into a neighbouring column).
    const int jb = cell_index(x[b_], e.lo_b, db, n_b_), jc = cell_index(x[c_], e.lo_c, dc, n_c_);
    double reach[2] = {INFINITY, -INFINITY};
    for (int kc = std::max(0, jc - 1); kc <= std::min(n_c_ - 1, jc + 1); ++kc)
      for (int kb = std::max(0, jb - 1); kb <= std::min(n_b_ - 1, jb + 1); ++kb) {
        const size_t cell = static_cast<size_t>(kc) * n_b_ + kb;
        if (!std::isnan(h[0][cell])) reach[0] = std::min(reach[0], h[0][cell]);
        if (!std::isnan(h[1][cell])) reach[1] = std::max(reach[1], h[1][cell]);
      }
    const double cell_size = std::max(db, dc);
    if (reach[0] - (x[s_.axis] - r) > cell_size || (x[s_.axis] + r) - reach[1] > cell_size)
      ++m.escaped;
  }
  return m;
}

void Membrane::save(StateWriter& out, const Simulation& sim) const {
  out.value(identified_), out.value(n_b_), out.value(n_c_);
  const ParticleStore& p = sim.particles();
  for (int side = 0; side < 2; ++side) {
    std::vector<uint32_t> ids(bead_[side].size(), none);
    for (size_t k = 0; k < ids.size(); ++k)
      if (bead_[side][k] != none) ids[k] = p.id[bead_[side][k]];
    out.array(ids);
  }
}

void Membrane::restore(StateReader& in, const Simulation& sim) {
  identified_ = in.value<bool>();
  n_b_ = in.value<int>(), n_c_ = in.value<int>();
  const ParticleStore& p = sim.particles();
  std::unordered_map<uint32_t, uint32_t> index;
  for (size_t i = 0; i < p.size(); ++i) index[p.id[i]] = static_cast<uint32_t>(i);
  for (int side = 0; side < 2; ++side) {
    std::vector<uint32_t> ids;
    in.array(ids);
    if (identified_ && (n_b_ < 1 || n_c_ < 1 ||
                        ids.size() != static_cast<size_t>(n_b_) * static_cast<size_t>(n_c_)))
      throw std::runtime_error("membrane grid does not match");
    bead_[side].assign(ids.size(), none);
    for (size_t k = 0; k < ids.size(); ++k) {
      if (ids[k] == none) continue;
      const auto found = index.find(ids[k]);
      if (found == index.end()) throw std::runtime_error("membrane bead id out of range");
      bead_[side][k] = found->second;
    }
  }
  read_applied_forces(sim);  // the forces are the restored simulation's
}

}  // namespace grainlab
