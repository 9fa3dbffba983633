// The per-particle passes of velocity Verlet, vectorised across particles: the first half kick
// and drift (with the neighbour lists' displacement tests), the gather of each particle's force
// and torque from the contact stores, and the closing half kick (with the speeds the health
// check and the one-sweep bound read). In a packing at rest these passes stream every bead's
// arrays once per step each, and written one particle at a time (the drift took about 130 scalar
// instructions a bead) they were a quarter of the reference shear's step and two fifths of the
// preparation (docs/performance.md sec. 28).
//
// Every value is the scalar loop's, bit for bit: each component is the same IEEE product and
// sum (the objects are compiled with -ffp-contract=off), a squared length is summed x, y, z in
// that order, and a largest value is an exact maximum that skips NaN as std::max(largest, x)
// does. So the results do not depend on the instruction set, the thread count or where a
// range starts (tests/core/test_particle_passes_simd.cpp).
//
// Compiled once per instruction set with the pair kernel (src/core/CMakeLists.txt): the AVX-512
// object takes 8 particles (24 doubles of each Vec3 array) per iteration, the AVX2 object 4
// (12 doubles); the SSE2 object runs the particle loop as written. Chosen with the pair kernel (GRAINLAB_SIMD; "off",
// which turns the pair kernel off, keeps the SSE2 passes: the same arithmetic). Plain data only,
// as core/pair_kernel_simd.hpp.
#pragma once

#include <cstdint>

namespace grainlab {

// Views of the particle store (Vec3 fields as consecutive x, y, z doubles; SI units).
struct ParticlePassInput {
  double* position;
  double* velocity;
  double* angular_velocity;
  double* rotation;
  const double* force;
  const double* torque;
  const double* inverse_mass;
  const double* inverse_inertia;
  // The neighbour lists' positions at the active list's selection and at the last build; null:
  // the drift does not test them.
  const double* position_at_refresh;
  const double* position_at_build;
  double half_list_skin2;  // m^2: a particle beyond it from position_at_refresh is stale
  double half_skin2;       // m^2: beyond it from position_at_build, the list must be rebuilt
  double time_step;        // s
};

// What the drift found over the particles it moved: some particle beyond half the list skin
// (stale) or half the skin (moved), and, where asked (bound), the largest squared displacement
// from position_at_refresh and the largest squared distance from the origin (m^2). Each call
// raises them; start from zeros.
struct DriftTally {
  int stale = 0, moved = 0;
  double displacement2 = 0.0, scale2 = 0.0;
};

// v += dt/2 F/m, w += dt/2 T/I, x += dt v, rotation += dt w for particles [first, end), with the
// tests position_at_refresh and position_at_build ask for.
using SimdKickAndDrift = void (*)(const ParticlePassInput& in, long first, long end, bool bound,
                                  DriftTally& tally);
// v += dt/2 F/m, w += dt/2 T/I for particles [first, end). Raises max_speed2 to the largest |v|^2
// (NaN counts as infinite) and, with next_speed2, that to the largest |v + dt/2 F/m|^2: the speed
// the next drift will give.
using SimdHalfKick = void (*)(const ParticlePassInput& in, long first, long end, double& max_speed2,
                              double* next_speed2);

// Views of the contact stores (core/contact_store.hpp) for the gather of the reference law's
// sums (no rolling or twisting moments): per particle, in this order, its weight m g, the
// entries of its row (the force on the first body, the lever times the torque arm), the entries
// where it is second (the opposite force, its lever times the arm), its wall contacts and its
// external force.
struct GatherInput {
  const uint32_t* row_start;        // pair entries per particle, where it is first (N + 1)
  const uint32_t* col_start;        // where it is second (N + 1) ...
  const uint32_t* col_pair;         // ... and those entries' numbers
  const double* result;             // per pair entry a PairResult: 8 doubles
  const uint32_t* wall_row_start;   // wall entries per particle (N + 1)
  const double* force_on_particle;  // per wall entry, Vec3
  const double* torque_on_particle;
  const double* radius;
  const double* inverse_mass;
  const double* external_force;  // per particle, Vec3; null: none
  double gravity[3];             // m/s^2
  double* force;                 // out, per particle, Vec3
  double* torque;
  // Each pair entry's first particle (its row's) and second (its partner), and each wall
  // entry's particle; null (the default): the gather takes the particles one by one. With the
  // first two (and the third wherever there are wall entries: it is read only for them), the
  // AVX-512 and AVX2 gathers walk each block of gather_flat_block particles' entries flat
  // instead (the SSE2 object ignores them); the sums are the same either way.
  const uint32_t* row_owner = nullptr;
  const uint32_t* partner = nullptr;
  const uint32_t* wall_owner = nullptr;
};
// The flat walk: within a block of particles, first all their row entries in entry order,
// then all their column entries in column order, then all their wall entries, each added to
// its particle's running sum, so that no loop ends where a particle's entries end. One particle
// at a time, each of its row and column loops ends after 0 to 8 rounds, at random from one
// particle to the next. The sequence is the same in every step between selections of the list;
// on the development VM's Zen 5 the gather one particle at a time cost 8.4 ns a particle with
// 5,818 particles a thread and 20 ns with 11,636, which we read as the branch predictor
// remembering where the loops end for the first and not for the second; the flat walk cost 14.5
// ns with 11,636 (docs/performance.md sec. 40).
constexpr long gather_flat_block = 128;
// The sums of particles [first, end).
using SimdGather = void (*)(const GatherInput& in, long first, long end);

namespace simd_sse2 {
void kick_and_drift(const ParticlePassInput&, long, long, bool, DriftTally&);
void half_kick(const ParticlePassInput&, long, long, double&, double*);
void gather(const GatherInput&, long, long);
}  // namespace simd_sse2
namespace simd_avx2 {
void kick_and_drift(const ParticlePassInput&, long, long, bool, DriftTally&);
void half_kick(const ParticlePassInput&, long, long, double&, double*);
void gather(const GatherInput&, long, long);
}  // namespace simd_avx2
namespace simd_avx512 {
void kick_and_drift(const ParticlePassInput&, long, long, bool, DriftTally&);
void half_kick(const ParticlePassInput&, long, long, double&, double*);
void gather(const GatherInput&, long, long);
}  // namespace simd_avx512

struct SimdParticlePasses {
  SimdKickAndDrift kick_and_drift = nullptr;
  SimdHalfKick half_kick = nullptr;
  SimdGather gather = nullptr;
  const char* name = "";  // "sse2", "avx2" or "avx512"
};

// The passes of the instruction set the pair kernel runs (select_simd_pair_kernel), SSE2 where
// it is off. Throws as select_simd_pair_kernel.
SimdParticlePasses select_simd_particle_passes();

}  // namespace grainlab
