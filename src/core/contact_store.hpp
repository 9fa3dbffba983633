// Contact storage, in neighbour-list order.
//
// PairContacts is the half Verlet list in CSR form: the partners of particle i are
// partner[row_start[i] .. row_start[i+1]), all with index > i. Each entry carries its contact
// history (present whether or not the spheres touch now; zero when they do not) and what the
// last step computed for it (PairResult). The transpose (col_start/col_pair) lists, for each
// particle, the entries in which it is the second body, so that forces are gathered per
// particle in a fixed order: no atomics, identical sums for any thread count.
// Optional histories (rolling, twisting, rolling force) are empty unless a pair uses them.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "core/uninitialized_allocator.hpp"
#include "core/vec3.hpp"

namespace grainlab {

// For a CSR row index (row_start, N + 1 values): the row each entry lies in, i.e. its particle,
// written into `row` (its storage kept where it suffices), the rows shared among the threads
// (core/contact_store.cpp).
void index_rows_of_entries(const std::vector<uint32_t>& row_start, std::vector<uint32_t>& row);

// A CSR index (rows', columns' or cells' starts) from counts to their running sums: starts[k + 1]
// holds the count of row k, starts[0] = 0. Each thread sums its own part, then adds the totals of
// the parts before it. Integer sums: the same for any thread count (core/contact_store.cpp).
void sum_counts(std::vector<uint32_t>& starts);

// What the last force evaluation of one pair entry left for the gather, in one cache line. The
// gather reads each entry twice, once for each body, and the second read lies in another
// particle's row: out of the caches that costs a line per entry, where force and torques in
// separate arrays cost two (docs/performance.md sec. 14). The torques are not stored: the torque
// of the tangential force on a body is lever × torque_arm, its lever the body's radius less half
// the overlap (the contact point lies halfway through the overlap), the same product the law
// forms. A pair with rolling or twisting pieces adds a moment (PairContacts::moment).
struct alignas(64) PairResult {
  Vec3 force_on_first;  // N (the second body receives the opposite)
  Vec3 torque_arm;      // n x F_t, N: torque per metre of lever
  double overlap;       // m (0 when not touching)
  double normal_force;  // N (0 when not touching)
};
static_assert(sizeof(PairResult) == 64);

// The lever of a body of radius r in a contact of this overlap: the distance from its centre to
// the contact point, halfway through the overlap (the scalar pair loop and the gather use it).
inline double contact_lever(double radius, double overlap) {
  return radius - 0.5 * overlap;
}

struct PairContacts {
  std::vector<uint32_t> row_start;  // N + 1
  std::vector<uint32_t> partner;    // per entry: second particle
  std::vector<uint32_t> col_start;  // N + 1
  std::vector<uint32_t> col_pair;   // entries where the particle is second
  // history (m, rad); the sliding springs sized without zeroing (select_active writes each)
  std::vector<Vec3, UninitializedAllocator<Vec3>> sliding_spring;
  std::vector<Vec3> rolling_angle;
  std::vector<double> twisting_angle;
  std::vector<Vec3> rolling_force_displacement;
  // results of the last force computation (sized without zeroing: NeighborSearch::allocate_results
  // zeroes them in parallel)
  std::vector<PairResult, UninitializedAllocator<PairResult>> result;
  std::vector<Vec3> moment;  // N m, rolling + twisting moment on the first body (the second gets
                             // the opposite); empty unless a pair has those pieces

  size_t size() const { return partner.size(); }
  template <class Io>
  void for_each_field(Io&& io) {
    io(row_start), io(partner), io(col_start), io(col_pair), io(sliding_spring), io(rolling_angle),
        io(twisting_angle), io(rolling_force_displacement), io(result), io(moment);
  }
};

// The history fields of `store`, moved out (the rest stays behind, to be freed with `store`).
template <class Store>
Store histories_of(Store&& store) {
  Store h;
  h.sliding_spring = std::move(store.sliding_spring);
  h.rolling_angle = std::move(store.rolling_angle);
  h.twisting_angle = std::move(store.twisting_angle);
  h.rolling_force_displacement = std::move(store.rolling_force_displacement);
  return h;
}

// Whether entry e of a pair or wall store holds a history (a spring or an angle not zero): one
// that a rebuild must carry, and that the active pair list must keep.
template <class Store>
bool entry_has_history(const Store& s, size_t e) {
  return norm2(s.sliding_spring[e]) != 0.0 ||
         (!s.rolling_angle.empty() && norm2(s.rolling_angle[e]) != 0.0) ||
         (!s.twisting_angle.empty() && s.twisting_angle[e] != 0.0) ||
         (!s.rolling_force_displacement.empty() && norm2(s.rolling_force_displacement[e]) != 0.0);
}

// Particle-wall candidates, CSR by particle: walls wall[row_start[i] .. row_start[i+1]).
struct WallContacts {
  std::vector<uint32_t> row_start;
  std::vector<uint16_t> wall;
  std::vector<Vec3> sliding_spring;
  std::vector<Vec3> rolling_angle;
  std::vector<double> twisting_angle;
  std::vector<Vec3> rolling_force_displacement;
  std::vector<Vec3> force_on_particle;   // N
  std::vector<Vec3> torque_on_particle;  // N m
  std::vector<double> normal_stiffness;  // N/m (0 when not touching)
  std::vector<double> normal_force;      // N

  size_t size() const { return wall.size(); }
  template <class Io>
  void for_each_field(Io&& io) {
    io(row_start), io(wall), io(sliding_spring), io(rolling_angle), io(twisting_angle),
        io(rolling_force_displacement), io(force_on_particle), io(torque_on_particle),
        io(normal_stiffness), io(normal_force);
  }
};

}  // namespace grainlab
