// The step loop. One step of velocity Verlet (kick-drift-kick) for translation and rotation of
// spheres, read top-down as named stages:
//   move walls -> half kick + drift -> neighbour list (if stale) -> pair forces -> wall forces
//   -> gather per particle -> half kick -> health check,
// as stages (each a pass over all particles) or, where no list update can follow the drift in a
// large packing, as one sweep that takes each particle through them in turn (core/one_sweep.cpp).
// The core knows nothing of laboratory tests; controllers change wall velocities between steps.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "contact/pair_table.hpp"
#include "core/chunk_queue.hpp"
#include "core/contact_store.hpp"
#include "core/gather_walk_trial.hpp"
#include "core/neighbor_search.hpp"
#include "core/pair_kernel_simd.hpp"
#include "core/particle_passes_simd.hpp"
#include "core/particles.hpp"
#include "core/state_io.hpp"
#include "core/step_listener.hpp"
#include "core/step_phase_times.hpp"
#include "core/thread_partition.hpp"
#include "geometry/wall.hpp"

namespace grainlab {

struct SimulationSettings {
  double time_step = 0.0;    // dt, s
  double dt_fraction = 0.0;  // dt / t_c when dt was derived (0 when given explicitly)
  Vec3 gravity;              // m/s^2
  double skin = 0.0;         // Verlet skin, m
  // The active pair list's skin as a fraction of `skin`, in (0, 1]; 1 keeps every candidate.
  // Results do not depend on it (core/neighbor_search.hpp).
  double list_skin_fraction = default_list_skin_fraction;
  double max_speed = 100.0;            // m/s; a faster particle means the run has blown up
  double max_overlap_fraction = 0.05;  // of the smaller radius
  // Whether the vectorised distance pass prefetches the entries ahead: automatic where the
  // partners lie far ahead in memory (prefetch_pays, core/pair_kernel_simd.hpp). Results do not
  // depend on it.
  enum class Prefetch { automatic, always, never } prefetch = Prefetch::automatic;
  // The config key that sets the time step, named in the advice of a BlowUpError.
  enum class StepKey { scene, lab_test } step_key = StepKey::scene;
};

// Thrown when the integration has become unphysical; the message says what and how to fix it.
class BlowUpError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Simulation {
 public:
  Simulation(ParticleStore particles, std::vector<Wall> walls, PairTable table,
             SimulationSettings settings);

  // Restores a simulation saved by save_state; `table` must have the same materials.
  Simulation(StateReader& state, PairTable table);
  void save_state(StateWriter& state) const;

  void step();
  void advance(long steps) {
    for (long s = 0; s < steps; ++s) step();
  }

  // Listeners are called in the order attached; the Simulation does not own them.
  void attach(StepListener& listener) { listeners_.push_back(&listener); }
  void detach(StepListener& listener) { std::erase(listeners_, &listener); }

  // Commands, between steps (from a listener's before_step or from the driving loop). Particle
  // indices are storage indices, which change at each neighbour-list rebuild (see particles().id).
  void set_wall_velocity(size_t wall, const Vec3& velocity) { walls_[wall].velocity = velocity; }
  void set_wall_point(size_t wall, const Vec3& point) { walls_[wall].point = point; }
  // A wall that changes shape or turns: its geometry (point, normal, axes, sizes, radius) from
  // `geometry`; its velocity, mass and forces are kept.
  void set_wall_geometry(size_t wall, const Wall& geometry);
  void set_wall_external_force(size_t wall, const Vec3& force) {
    walls_[wall].external_force = force;
  }
  void set_particle_velocity(size_t particle, const Vec3& velocity) {
    particles_.velocity[particle] = velocity;
    next_speed2_ = INFINITY;  // the next drift's bound (one_sweep_possible) is not known
  }
  // The per-particle external force source (a membrane): kept until changed or cleared.
  void set_external_force(size_t particle, const Vec3& force) {
    particles_.external_force[particle] = force;
    external_forces_ = true;
  }
  void clear_external_forces();
  // Moves every particle centre toward `centre` to centre + factor (x - centre): a homogeneous,
  // isotropic strain increment 1 - factor (the affine compaction of a specimen). Velocities are
  // kept; the neighbour list sees the move as displacement (and so does the bound of a step as
  // one sweep).
  void scale_positions(const Vec3& centre, double factor);
  // Replaces the material-pair constants (e.g. the friction while compacting); the table must
  // have the same materials and the same optional pieces of the contact law as the one given at
  // construction (std::invalid_argument otherwise).
  void set_pair_table(PairTable table);

  double time() const { return time_; }
  long step_count() const { return step_count_; }
  const SimulationSettings& settings() const { return settings_; }
  // Read-only views.
  const ParticleStore& particles() const { return particles_; }
  const std::vector<Wall>& walls() const { return walls_; }
  const PairTable& pair_table() const { return table_; }
  const PairContacts& pair_contacts() const { return pairs_; }
  const WallContacts& wall_contacts() const { return wall_contacts_; }
  long rebuild_count() const { return neighbors_.rebuild_count(); }
  // Whether the vectorised rows prefetch (SimulationSettings::prefetch), as last chosen.
  bool rows_prefetch() const { return prefetch_ahead_; }
  // Selections of the active pair list: one per rebuild, and the refreshes between them.
  long list_refresh_count() const { return neighbors_.refresh_count(); }
  // Selects the active pair list again now, from the same candidates, as a step does when a
  // particle has moved half the list skin (for benchmarks of the refresh; the results do not
  // change: core/neighbor_search.hpp).
  void refresh_pair_list() {
    refresh_active_pairs();
    list_displacement2_ = 0.0;  // selected where they are now
  }
  // Builds the neighbour lists again now, as a step does when a particle has moved half the skin
  // (for benchmarks of the rebuild): the particles are sorted into cell order again, so storage
  // indices may change (listeners hear after_rebuild); the results do not.
  void rebuild_pair_list() {
    rebuild_neighbors();
    list_displacement2_ = 0.0;
    for (StepListener* l : listeners_) l->after_rebuild(*this);
  }
  // Whether a step runs as one sweep (core/one_sweep.cpp): automatic where it pays (the drift's
  // lead fits in the L3; on up to 2 threads where the partners lie beyond the L2, on one where
  // they lie inside it: one_sweep_team), always where it can, or never (in stages). The results
  // are the same. Not saved with the state.
  enum class OneSweep { automatic, always, never };
  void set_one_sweep(OneSweep choice) {
    one_sweep_choice_ = choice;
    choose_one_sweep();
  }
  long one_sweep_steps() const { return one_sweep_steps_; }  // steps run as one sweep
  // The chunks at the back of each thread's block in the force stages (core/chunk_queue.hpp;
  // the same results either way).
  void set_chunk_tail(ChunkQueue::Tail tail) { chunk_tail_ = tail; }
  // Whether the drift's particles go through a chunk queue (core/chunk_queue.hpp: a thread that
  // is done takes the last chunks of one that lags) or each thread drifts its own block whole:
  // automatic shares them on teams of shared_drift_team threads or more, always, or never. On 16
  // threads it halves the wait at the drift's end; the step moved by 0.98-1.03 (docs/performance.md
  // sec. 34): it is there for a thread held up in the drift, which no one else could relieve. The
  // results are the same. Not saved with the state.
  enum class DriftSharing { automatic, always, never };
  void set_drift_sharing(DriftSharing choice) { drift_sharing_ = choice; }
  static constexpr int shared_drift_team = 4;
  // Whether the gather walks each block of particles' entries flat (core/particle_passes_simd.hpp,
  // GatherInput::row_owner) or takes the particles one by one: automatic, flat, or one by one.
  // Automatic times the step's own steps with each walk and keeps the faster
  // (core/gather_walk_trial.hpp); before its first trial ends, and where only one walk exists
  // (the SSE2 object, the scalar law), it walks flat where a thread of the step's team has at
  // least flat_gather_share particles. Which walk is faster depends on the core: on the
  // development VM's Zen 5 one by one with 5,818 particles a thread (the branch predictor
  // remembers where each particle's entries end) and flat with 11,636 or more
  // (docs/performance.md sec. 40), on its Intel Xeon flat with both (sec. 53). The flat walk
  // needs the kernel's entry owners; without them the gather goes one by one. The results are
  // the same. Not saved with the state.
  enum class GatherWalk { automatic, flat, one_by_one };
  void set_gather_walk(GatherWalk choice) { gather_walk_ = choice; }
  static constexpr long flat_gather_share = 10000;
  static constexpr bool walks_gather_flat_automatically(long n, int team) {
    return n >= flat_gather_share * team;
  }
  // steps whose gather was to walk flat (the walk chosen; without the kernel's owners it went
  // one by one all the same)
  long flat_gather_steps() const { return flat_gather_steps_; }
  // How the stages in a step's regions share their chunks (core/chunk_queue.hpp): about
  // `chunks_per_thread` chunks of each block (at most 1,024 particles each), and whether a block's
  // last untaken chunk stays with its owner. Automatic (the default): 8 chunks and the owner keeps
  // its last on teams of fewer than fine_chunk_team threads, 16 chunks and it need not on larger
  // ones (docs/performance.md sec. 34). The tails of a swept step (core/one_sweep.cpp, automatic
  // on 2 threads only) keep 8 chunks and the owner's last. The results are the same. Not saved
  // with the state.
  struct ChunkSharing {
    long chunks_per_thread = 8;
    bool owner_keeps_last = true;
  };
  static constexpr int fine_chunk_team = 8;
  void set_chunk_sharing(std::optional<ChunkSharing> choice) {  // nullopt: automatic
    chunk_sharing_ = choice;
    if (chunk_sharing_)
      chunk_sharing_->chunks_per_thread =
          std::clamp(chunk_sharing_->chunks_per_thread, 1L, 1L << 20);
  }
  ChunkSharing chunk_sharing(int team) const {
    if (chunk_sharing_) return *chunk_sharing_;
    return team >= fine_chunk_team ? ChunkSharing{16, false} : ChunkSharing{8, true};
  }
  // Steps whose drift was planned through the queue (a region whose team is not the planned one
  // falls back to blocks: core/chunk_queue.hpp).
  long shared_drift_steps() const { return shared_drift_steps_; }
  // Per-thread times of the step's stages and waits, from now on (zeroed) or no more
  // (core/step_phase_times.hpp; the same results either way).
  void time_step_phases(bool on) {
    phase_times_.switch_on(on, std::max(omp_get_max_threads(), omp_get_num_procs()));
  }
  const StepPhaseTimes& step_phase_times() const { return phase_times_; }

  double kinetic_energy() const;     // translational + rotational, J
  long touching_pair_count() const;  // particle-particle contacts with F_n > 0
  double max_overlap_fraction() const { return max_overlap_fraction_; }
  // Which pair force loop runs: "scalar", "sse2", "avx2" or "avx512" (core/pair_kernel_simd.hpp).
  const char* pair_kernel_name() const { return simd_pair_kernel_.name; }
  // Pair entries the kernel handed back to the scalar law in the last force evaluation (contacts
  // that may have begun within the step); 0 when the scalar loop ran.
  long pairs_handed_to_scalar_law() const { return pairs_handed_to_scalar_law_; }
  // The same for the wall contacts (the kernel's wall lanes).
  long walls_handed_to_scalar_law() const { return walls_handed_to_scalar_law_; }
  // Whether the kernel found the touching wall candidates itself in the last force evaluation
  // (every wall a plane, at most max_lane_walls; core/pair_kernel_simd.hpp, plane_wall_rows).
  bool walls_in_plane_lanes() const { return wall_planes_.count > 0; }

 private:
  // What the neighbour lists need after the drift: nothing, a new selection of the active list,
  // or a rebuild. records_written: whether it wrote the kernel's velocity records for the force
  // evaluation that follows.
  enum class ListUpdate { none, refresh, rebuild };
  void drift_walls();  // the walls' half kick and drift (before the particles')
  // Views of the particles for the passes of velocity Verlet (core/particle_passes_simd.hpp),
  // with the neighbour lists' positions for the drift's tests: against the selection's
  // (list_test) and against the build's (rebuild_test).
  ParticlePassInput particle_pass_input(bool list_test, bool rebuild_test);
  ListUpdate kick_and_drift(bool& records_written);
  // kick_and_drift's arithmetic for particles [range.first, range.end) (the lists' tests as
  // `pass` asks, `bound`: the sweep's bound too), in tiles of drift_tile particles, each tile's
  // velocity records written right after it where `records`, while its velocities and forces are
  // still in the caches. For the stages' drift and for a swept step's.
  static constexpr long drift_tile = 256;  // particles: 25 kB of velocities, forces and records
  void drift_particles(const ParticlePassInput& pass, IndexBlock range, bool bound, bool records,
                       DriftTally& tally);
  // The step as one sweep over the particles (core/one_sweep.cpp): where no particle can move
  // half the list skin in this step (from list_displacement2_ and next_speed2_), no list update
  // can follow the drift, so each particle's drift, forces, gather and half kick run together,
  // while its data is in the caches.
  bool one_sweep_possible();
  void choose_one_sweep();  // one_sweep_wanted_ from the choice and the list (index_entry_owners)
  void sweep_step();
  // The gather and half kick of the particles of [first, end) that are (late) or are not
  // (!late) second in an entry whose first particle lies before `block_first`.
  void close_particles(long first, long end, long block_first, bool late, double& max_speed2,
                       double& next_speed2);
  // drift: how long the positions moved since the last force evaluation (dt within step(); 0 for
  // the first evaluation of a fresh state, when no contact spring may advance). close_step: end
  // with the second half kick. records_written: the kernel's velocity records are those of the
  // current velocities and forces already (kick_and_drift wrote them, no rebuild since).
  void compute_forces(double drift, bool close_step, bool records_written = false);
  // The stages of compute_forces, each on a chunk of particles taken by the calling thread inside
  // its parallel region (the *_walls ones serial after it).
  void prepare_pair_forces();  // serial, before the region
  // views of the particles, the pair store and the records for the kernel (uses_pair_kernel())
  SimdPairInput kernel_input(double drift);
  // the kernel's velocity records (only when uses_pair_kernel()); the rows read them after a
  // barrier
  void write_particle_records(double drift, IndexBlock block);
  double compute_pair_forces(double drift, IndexBlock block, long& handed_back);
  // the walls as the kernel's lanes read them (only when the kernel runs)
  void prepare_wall_lanes();  // serial, before the region
  double compute_wall_forces(double drift, IndexBlock block, long& handed_back);
  void gather_particles(IndexBlock block);
  void gather_walls();
  // Returns the largest speed squared; with next_speed2, raises it to the largest speed squared
  // that the next step's first half kick will give (with the forces just summed).
  double half_kick_particles(IndexBlock block, double* next_speed2);
  void half_kick_walls();
  void rebuild_neighbors();
  void refresh_active_pairs();
  // Whether the pair forces go through the vectorised kernel (set by the table's pieces, the CPU
  // and the list's size; fixed between rebuilds).
  bool uses_pair_kernel() const;
  // entry_owners_, room for particle_records_ and one_material_, when the kernel runs; the
  // wall entries' owners too where the wall contacts changed (a rebuild, a restore)
  void index_entry_owners(bool walls_changed);
  void check_health() const;
  void check_restored_state() const;  // after loading a checkpoint; std::runtime_error
  const char* step_key() const;       // the config key of the time step, for advice

  ParticleStore particles_;
  std::vector<Wall> walls_;
  PairTable table_;
  SimulationSettings settings_;
  ContactPieces pieces_;
  NeighborSearch neighbors_;
  PairContacts pairs_;
  WallContacts wall_contacts_;
  double time_ = 0.0;
  long step_count_ = 0;
  double max_overlap_fraction_ = 0.0;
  double max_speed2_ = 0.0;
  bool external_forces_ = false;  // some particle has a non-zero external force
  // For one_sweep_possible: the largest displacement since the active list's selection, squared
  // (m^2, after the last drift; 0 after a refresh), the largest squared distance of a particle
  // from the origin then (m^2, for the rounding of positions), and the largest squared speed the
  // next drift will move a particle at (m^2/s^2, from the last half kick). Infinite: not known.
  double list_displacement2_ = INFINITY, position_scale2_ = INFINITY, next_speed2_ = INFINITY;
  OneSweep one_sweep_choice_ = OneSweep::automatic;
  bool one_sweep_wanted_ = false;     // the choice for this list: the drift and kick form the bound
  int one_sweep_automatic_team_ = 0;  // most threads it sweeps on if automatic (one_sweep_team)
  long one_sweep_steps_ = 0;
  StepPhaseTimes phase_times_;
  double phase_regions_ = 0.0;  // s: this step's parallel regions, while the timers are on
  // How far ahead of their rows the list's partners lie (index_entry_owners): the mean decides
  // the rows' prefetch and the sweep, the farthest how far ahead of a row the sweep's drift must
  // have written its partners' records.
  PartnerReach partner_reach_;
  // The vectorised pair loop for the reference law (no rolling, twisting or rolling-force piece),
  // the first particle of each entry, and room for the entries the kernel hands back (first
  // touch in the step), one slot per entry.
  SimdPairKernel simd_pair_kernel_ = select_simd_pair_kernel();
  // The first half kick and drift, the gather and the closing half kick, across particles
  SimdParticlePasses particle_passes_ = select_simd_particle_passes();
  std::vector<uint32_t> deferred_pairs_;
  std::vector<uint32_t> entry_owners_;       // per pair entry: its first particle (for the kernel)
  std::vector<double> particle_records_;     // the kernel's per-particle velocity records
  std::vector<uint32_t> wall_entry_owners_;  // per wall entry: its particle (for the kernel)
  std::vector<SimdWallState> wall_lane_state_;  // per wall, for the kernel's wall lanes
  // Where every wall is a plane (at most max_lane_walls): the planes as the kernel's
  // plane_wall_rows reads them (count 0 otherwise), and room for the wall entries it hands back.
  SimdPlanes wall_planes_;
  std::vector<uint32_t> deferred_walls_;
  int one_material_ = -1;        // the material of every particle, or -1 where they differ (kernel)
  bool prefetch_ahead_ = false;  // whether the kernel's rows prefetch (index_entry_owners)
  long pairs_handed_to_scalar_law_ = 0, walls_handed_to_scalar_law_ = 0;
  // Who takes which particles in compute_forces' three stages (records; pair rows and wall
  // contacts; gather and half kick): planned afresh at each call.
  ChunkQueue record_chunks_, contact_chunks_, particle_chunks_;
  ChunkQueue::Tail chunk_tail_ = ChunkQueue::Tail::even;
  // The drift's chunks, where it shares them (set_drift_sharing).
  ChunkQueue drift_chunks_;
  DriftSharing drift_sharing_ = DriftSharing::automatic;
  std::optional<ChunkSharing> chunk_sharing_;  // (set_chunk_sharing; nullopt: automatic)
  long shared_drift_steps_ = 0;
  GatherWalk gather_walk_ = GatherWalk::automatic;
  bool flat_gather_ = false;           // for this step's gather (walks_gather_flat of its team)
  GatherWalkTrial gather_walk_trial_;  // (automatic, where both walks exist)
  long flat_gather_steps_ = 0;
  // whether the automatic walk is chosen by timing the steps (both walks exist)
  bool times_gather_walks() const;
  bool walks_gather_flat(long n, int team) {
    if (gather_walk_ != GatherWalk::automatic) return gather_walk_ == GatherWalk::flat;
    const bool rule = walks_gather_flat_automatically(n, team);
    return times_gather_walks() ? gather_walk_trial_.flat(n, team, rule) : rule;
  }
  bool shares_drift(int team) const {
    return team > 1 && (drift_sharing_ == DriftSharing::always ||
                        (drift_sharing_ == DriftSharing::automatic && team >= shared_drift_team));
  }
  // The block each thread starts from in every stage, sized by the threads' measured speeds
  // (planned in kick_and_drift and compute_forces, updated after each step).
  ThreadPartition partition_;
  // The team the step's regions run with (1 below parallel_threshold particles).
  int step_team(long n) const { return n > parallel_threshold ? omp_get_max_threads() : 1; }
  std::vector<StepListener*> listeners_;
};

// Attaches a listener for the lifetime of this object (also when an exception leaves the scope).
class ScopedListener {
 public:
  ScopedListener(Simulation& sim, StepListener& listener) : sim_(sim), listener_(listener) {
    sim_.attach(listener_);
  }
  ~ScopedListener() { sim_.detach(listener_); }
  ScopedListener(const ScopedListener&) = delete;
  ScopedListener& operator=(const ScopedListener&) = delete;

 private:
  Simulation& sim_;
  StepListener& listener_;
};

}  // namespace grainlab
