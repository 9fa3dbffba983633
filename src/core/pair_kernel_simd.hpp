// The particle-pair force loop for the reference contact law (sliding friction only: no rolling,
// twisting or rolling-force pieces), vectorised across contacts: 8 contacts per lane vector (4 in
// the AVX2 object's pair rows, core/simd_lanes.hpp), the branches of the law (the clamp of F_n,
// the turn of the spring into the tangent plane, the slip) as per-lane selects; and the same law
// for the particle-wall contacts (wall_law; for plane walls also the search for the touching
// candidates, plane_wall_rows, and the walls' totals, wall_totals: core/wall_kernel_simd.cpp).
//
// Each lane does exactly the arithmetic of the scalar loop (core/contact_forces.cpp with
// contact/contact_law.hpp), in the same order, with IEEE operations only (+ - * / and a
// correctly rounded sqrt; the kernel is compiled with -ffp-contract=off, so no multiply-add is
// fused). A contact's result therefore does not depend on which lane or vector it lands in, on
// the thread count, or on the instruction set: SSE2, AVX2 and AVX-512 give the same bits, and in
// the portable build the same bits as the scalar loop (tests/core/test_pair_kernel_simd.cpp).
//
// Contacts that may have begun during this step (the first-touch correction may apply; rare in
// a packing at rest) are not computed here: their entries are handed back to the caller, which
// runs the scalar law on them. The gathers and scatters of entry data use 32-bit offsets: the
// caller keeps the scalar loop for more than 2^31 / 3 entries (and, conservatively, particles).
//
// The kernel is compiled once per instruction set (core/pair_kernel_simd.cpp, see
// src/core/CMakeLists.txt) and chosen at run time from what the CPU supports; the environment
// variable GRAINLAB_SIMD = off | sse2 | avx2 | avx512 | auto (default) overrides the choice.
// This header holds only plain data, so the per-instruction-set objects share no inline code
// with the rest of the program.
#pragma once

#include <cstddef>
#include <cstdint>

namespace grainlab {

struct PairParams;

// Per particle, the velocities the pair law reads, side by side (particle_record_size doubles,
// written by the kernel's `records` stage at each evaluation): the half-step v and omega, then
// the end-of-step estimates v + dt/2 F/m and omega + dt/2 T/I. A lane then loads a particle's
// twelve values with two plain loads, where gathering them (with AVX-512 one gather instruction
// per value, 28 per batch of 8 contacts) had been the kernel's largest cost
// (docs/performance.md sec. 12).
constexpr int particle_record_size = 12;
// Doubles per PairResult (core/contact_store.hpp): force on the first body, torque arm, overlap,
// normal force.
constexpr int pair_result_size = 8;

// Raw views of the particle store and the pair contact store (SI units, Vec3 fields as
// consecutive x, y, z doubles).
struct SimdPairInput {
  const double* position;
  const double* velocity;          // half-step, v(t + dt/2)
  const double* angular_velocity;  // half-step
  const double* force;             // of the previous evaluation (end-of-step velocity estimate)
  const double* torque;
  const double* radius;
  const double* inverse_mass;
  const double* inverse_inertia;
  const int32_t* material;
  double* particle_record;  // particle_record_size per particle: written by records, read by rows
  const PairParams* pair_params;  // material_count x material_count, row-major
  int32_t material_count;
  // The constants of every pair when all particles are of one material (then the lanes take
  // them by broadcast instead of one lookup per lane and value); null otherwise.
  const PairParams* one_pair;
  const uint32_t* row_start;
  const uint32_t* partner;
  const uint32_t* owner;   // per entry: its first particle (the row it lies in)
  double* sliding_spring;  // per entry, in/out
  double* result;          // per entry, out: a PairResult (pair_result_size doubles)
  double time_step;        // s
  double drift;            // s: time the positions last drifted over (0 on a fresh state)
  // Whether the rows ask the caches ahead for the entries' results, springs and partners'
  // records (prefetch_pays); the results are the same either way.
  bool prefetch_ahead;
  // m: a bound B with |s_t|^2 / (2 D) <= B / D for every pair, where s is the pair's relative
  // drift over the step (begun_curvature_bound); infinite where none is known. Lanes whose overlap
  // exceeds twice the normal increment plus B / D cannot have begun in the step, and their batch
  // skips pair_entry's test (the same decisions: the test runs wherever a lane might pass it).
  double curvature_bound = __builtin_inf();
};

// The bound of SimdPairInput::curvature_bound from the largest speed squared any particle drifts
// at in the step (formed as the drift forms the velocities; infinite where unknown):
// |s| = drift |v_j - v_i| <= 2 drift V, so |s|^2 / (2 D) <= 2 drift^2 V^2 / D. Widened by 1e-12
// (relative) for the rounding of V^2, of the bound's own product and of the lanes' s, |s|^2 and
// quotient (about 20 units of 1.1e-16), and at least 1e-300 m^2 where those round to subnormals.
inline double begun_curvature_bound(double drift, double next_speed2) {
  const double bound = 2.0 * drift * drift * next_speed2 * (1.0 + 1e-12);
  if (bound != bound) return __builtin_inf();  // (no bound)
  return bound > 1e-300 ? bound : 1e-300;
}

// The wall contacts through the same lanes (the law of contact/contact_law.hpp with body B a
// wall: lever 0, no spin, m* from the particle and the wall's mass). The caller finds the
// touching candidates (the gap to a wall of any shape, core/wall_forces.cpp; plane walls:
// plane_wall_rows below) and hands them over in batches of 8; the lanes read the particle's
// velocities from its record, so the records must have been written, as for the pair rows.
//
// One wall as the lanes read it, prepared before the force region from core/wall.hpp's Wall.
struct SimdWallState {
  double velocity[3];         // m/s, half-step (a wall with mass) or prescribed
  double velocity_at_end[3];  // m/s, end-of-step estimate for the dashpots (= velocity if fixed)
  double inverse_mass;        // 1/kg, 0 for a wall whose motion is prescribed
  int32_t material;
};
// Views of the wall contact store (core/contact_store.hpp, WallContacts; Vec3 fields as x, y, z).
struct SimdWallInput {
  const SimdWallState* walls;
  double* sliding_spring;      // per entry, in/out
  double* force_on_particle;   // per entry, out
  double* torque_on_particle;  // per entry, out
  double* normal_stiffness;    // per entry, out
  double* normal_force;        // per entry, out
};
constexpr int wall_batch_lanes = 8;
// Up to 8 touching wall contacts (lanes count .. 7 unused): the contact normal (unit, from the
// particle's centre towards the wall), the gap from the centre to the wall surface (the lever),
// the overlap r - gap and the particle's radius.
struct SimdWallBatch {
  alignas(64) double normal_x[wall_batch_lanes], normal_y[wall_batch_lanes],
      normal_z[wall_batch_lanes], gap[wall_batch_lanes], overlap[wall_batch_lanes],
      radius[wall_batch_lanes];
  uint32_t particle[wall_batch_lanes], entry[wall_batch_lanes], wall[wall_batch_lanes];
  int count = 0;
};
// Runs the law on the batch's contacts and stores their results and springs, except for
// contacts that may have begun in this step (first touch), which it leaves untouched: returns
// them as a bit mask of lanes for the caller's scalar law. Reads `pairs` for the particle data,
// the records, the pair constants, time_step and drift. May overwrite the unused lanes.
using SimdWallLaw = unsigned (*)(const SimdPairInput& pairs, const SimdWallInput& in,
                                 SimdWallBatch& batch);

// Where every wall is a plane, and there are at most max_lane_walls of them (a cuboid box), the
// kernel also finds the touching candidates itself: the gap of 8 candidates at a time, as
// geometry/wall.hpp's wall_gap gives it for a plane (d = x - point, gap = d . normal, contact
// normal -normal), apart ones cleared as the scalar loop clears them.
constexpr int max_lane_walls = 8;
struct SimdPlanes {  // per wall k < count: a point on the plane, m, and its unit normal
  double point_x[max_lane_walls], point_y[max_lane_walls], point_z[max_lane_walls];
  double normal_x[max_lane_walls], normal_y[max_lane_walls], normal_z[max_lane_walls];
  int count = 0;
};
struct SimdWallCandidates {
  const uint32_t* owner;  // per wall entry: its particle
  const uint16_t* wall;   // per wall entry: its wall (< planes->count)
  const SimdPlanes* planes;
};
// Per wall k < count (at most max_lane_walls), what Simulation::gather_walls sums over the
// touching wall entries (normal stiffness not 0), in entry order: the force on the wall (the
// opposite of each force on a particle), the contacts' normal stiffnesses, and their count.
struct SimdWallTotals {
  double force_x[max_lane_walls], force_y[max_lane_walls], force_z[max_lane_walls];
  double stiffness[max_lane_walls];  // N/m
  long count[max_lane_walls];
};
// The totals over wall entries [0, entries), given per entry the force on the particle (x, y, z),
// the normal stiffness and the wall (< wall_count <= max_lane_walls).
using SimdWallTotalsOf = void (*)(const double* force_on_particle, const double* normal_stiffness,
                                  const uint16_t* wall, uint32_t entries, int wall_count,
                                  SimdWallTotals& totals);

// The wall entries [first_entry, end_entry): each apart from its plane (or a fixed particle on a
// fixed wall) gets zero force, torque, stiffness and normal force and forgets its spring; the
// touching ones go through the law's lanes as wall_law runs them, in entry order, except those
// that may have begun in this step, which are written to deferred[0 .. deferred_count) for the
// caller's scalar law (room for every entry of the range). Returns the largest overlap / r of the
// touching ones, 0 if none. The particle records must have been written.
using SimdPlaneWallRows = double (*)(const SimdPairInput& pairs, const SimdWallInput& in,
                                     const SimdWallCandidates& candidates, uint32_t first_entry,
                                     uint32_t end_entry, uint32_t* deferred, long& deferred_count);

// Computes the entries of rows [first_row, end_row). Entries left to the caller (first touch in
// this step) are written to deferred[0 .. deferred_count), which must have room for every entry
// of those rows. Returns the largest overlap / min(r_i, r_j) among the touching contacts, 0 if
// none.
// Reads particle_record of every particle the entries name: all particles' records must have been
// written (by particle_records) before any thread runs its rows.
using SimdPairRows = double (*)(const SimdPairInput& in, long first_row, long end_row,
                                uint32_t* deferred, long& deferred_count);
// Writes the particle records of particles [first, end) from the velocities, forces and torques.
using SimdParticleRecords = void (*)(const SimdPairInput& in, long first, long end);

namespace simd_sse2 {
double pair_rows(const SimdPairInput&, long, long, uint32_t*, long&);
void particle_records(const SimdPairInput&, long, long);
unsigned wall_law(const SimdPairInput&, const SimdWallInput&, SimdWallBatch&);
double plane_wall_rows(const SimdPairInput&, const SimdWallInput&, const SimdWallCandidates&,
                       uint32_t, uint32_t, uint32_t*, long&);
void wall_totals(const double*, const double*, const uint16_t*, uint32_t, int, SimdWallTotals&);
}  // namespace simd_sse2
namespace simd_avx2 {
double pair_rows(const SimdPairInput&, long, long, uint32_t*, long&);
void particle_records(const SimdPairInput&, long, long);
unsigned wall_law(const SimdPairInput&, const SimdWallInput&, SimdWallBatch&);
double plane_wall_rows(const SimdPairInput&, const SimdWallInput&, const SimdWallCandidates&,
                       uint32_t, uint32_t, uint32_t*, long&);
void wall_totals(const double*, const double*, const uint16_t*, uint32_t, int, SimdWallTotals&);
}  // namespace simd_avx2
namespace simd_avx512 {
double pair_rows(const SimdPairInput&, long, long, uint32_t*, long&);
void particle_records(const SimdPairInput&, long, long);
unsigned wall_law(const SimdPairInput&, const SimdWallInput&, SimdWallBatch&);
double plane_wall_rows(const SimdPairInput&, const SimdWallInput&, const SimdWallCandidates&,
                       uint32_t, uint32_t, uint32_t*, long&);
void wall_totals(const double*, const double*, const uint16_t*, uint32_t, int, SimdWallTotals&);
}  // namespace simd_avx512

struct SimdPairKernel {
  SimdPairRows rows = nullptr;  // null: the scalar loop
  SimdParticleRecords records = nullptr;
  SimdWallLaw walls = nullptr;
  SimdPlaneWallRows plane_walls = nullptr;
  SimdWallTotalsOf wall_totals = nullptr;
  const char* name = "scalar";  // "scalar", "sse2", "avx2" or "avx512"
};

// The best kernel this CPU runs, or the one GRAINLAB_SIMD names. Throws std::runtime_error
// naming the variable for an unknown value or an instruction set the CPU lacks.
SimdPairKernel select_simd_pair_kernel();

// Whether the rows' prefetch pays (docs/performance.md sec. 26). partner_reach: how many beads
// further on in the particle order a row's farthest partner lies, on average over the rows
// (about one layer of the neighbour grid's cells). Where the beads in between (at about 1.5 KiB
// each of what a step touches: the bead's arrays and records, its entries' results and springs)
// outgrow the L2 cache, a partner's record has left it before the lanes read it. Measured on a
// 1 MiB L2 (the switch at 683 beads): a reach of 255 and 506 beads level, of 997 to 1,475 beads
// 1.2-1.3x faster.
bool prefetch_pays(double partner_reach, long l2_cache_bytes);
// How far ahead a CSR pair list's partners lie in the particle order: the mean over the rows of
// the farthest partner's distance (the partner_reach of prefetch_pays; rows without entries left
// out), and the farthest over all rows (one_sweep_team's max_partner_ahead). 0 when all are empty.
struct PartnerReach {
  double mean = 0.0;
  long farthest = 0;
};
PartnerReach partner_reach(const uint32_t* row_start, const uint32_t* partner, size_t rows);
// This CPU's L2 data cache per core, bytes (1 MiB where the system does not say).
long l2_cache_bytes();
// The largest team a step runs as one sweep with automatically (core/one_sweep.cpp,
// docs/performance.md sec. 27, 37 and 45); 0: none. Only where what a step touches of the beads
// the drift runs ahead of the rows (max_partner_ahead: the farthest partner's distance in the
// particle order) fits in half the L3, so that the records and results a sweep writes are still
// cached when it reads them; then on up to 2 threads where the rows' prefetch pays (the partners
// lie beyond the L2), and on one thread where they lie inside it. Measured on the 2-core VM
// (1 MiB L2, 32 MiB L3): 88,400 beads (reach 1,475, ahead 2,952: 4.3 MiB) 1.11-1.14x faster on
// 1 thread, 1.075x on 2; 46,544 (997 and 2,029: 3.0 MiB) 1.00-1.03x on 1; 744,704 in a cube
// (ahead 7,933: 11.6 MiB) 0.96x in sec. 27, 1.10-1.22x on 1 thread and 1.05-1.16x on 2 in
// sec. 45; in flatter tiles (sec. 45) ahead 12,367 (18.1 MiB) 1.06-1.15x and 1.08-1.12x, ahead
// 17,853 (26.2 MiB) 0.98-1.08x and 0.97-0.99x, ahead 31,683 (46 MiB) 0.92-1.08x and 0.90-0.93x.
// 11,636 (sec. 37): 1.05x on 1 thread; on 2 threads from 0.96 to 1.05x idle, and 8 % slower
// where another process takes slices of one core (the sweep's blocks are fixed where the stages
// share their chunks), so 2 threads keep the stages there. At more than 2 threads the stages
// share their chunks and were faster on a 16-core Xeon (sec. 31).
int one_sweep_team(double partner_reach, long max_partner_ahead, long l2_cache_bytes,
                   long l3_cache_bytes);
// This CPU's L3 cache, bytes (8 MiB where the system does not say).
long l3_cache_bytes();

}  // namespace grainlab
