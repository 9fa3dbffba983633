#include "core/simulation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/team_limit.hpp"

namespace grainlab {

Simulation::Simulation(ParticleStore particles, std::vector<Wall> walls, PairTable table,
                       SimulationSettings settings)
    : particles_(std::move(particles)),
      walls_(std::move(walls)),
      table_(std::move(table)),
      settings_(settings),
      pieces_(table_.pieces()),
      neighbors_(settings.skin, settings.skin * settings.list_skin_fraction) {
  if (!(settings_.time_step > 0.0)) throw std::invalid_argument("time step must be > 0");
  if (!(settings_.skin > 0.0)) throw std::invalid_argument("Verlet skin must be > 0");
  if (!(settings_.list_skin_fraction > 0.0 && settings_.list_skin_fraction <= 1.0))
    throw std::invalid_argument("the list skin fraction must be in (0, 1]");
  rebuild_neighbors();
  compute_forces(0.0, false);
}

void Simulation::rebuild_neighbors() {
  entry_owners_ = {}, wall_entry_owners_ = {};  // made anew below: not held through the rebuild
  neighbors_.rebuild(particles_, walls_, pairs_, wall_contacts_, pieces_);
  index_entry_owners(true);
}

void Simulation::refresh_active_pairs() {
  // (entry_owners_ is written anew in place; the wall contacts stay as they are)
  neighbors_.refresh(particles_, pairs_, pieces_);
  index_entry_owners(false);
}

void Simulation::step() {
  const bool timed = phase_times_.on();  // (core/step_phase_times.hpp)
  const double step_start = timed ? StepPhaseTimes::now() : 0.0;
  double update_seconds = 0.0;
  phase_regions_ = 0.0;
  // (the automatic gather walk is chosen by the steps' times: core/gather_walk_trial.hpp)
  const bool walk_timed = gather_walk_ == GatherWalk::automatic;
  const double walk_start = walk_timed ? StepPhaseTimes::now() : 0.0;
  follow_step_team_limit();  // (the team may change between steps: core/team_limit.hpp)
  for (StepListener* l : listeners_) l->before_step(*this);
  drift_walls();
  if (one_sweep_possible()) {
    sweep_step();
  } else {
    // In stages. The drift writes the kernel's velocity records on its way; a rebuild reorders
    // the particles, and then the force region writes them again.
    bool records_written = false;
    ListUpdate update = kick_and_drift(records_written);
    // A particle that moved half the list skin may also have moved half the skin this very step
    // (kick_and_drift tests that only where it could happen before a refresh): decide as every
    // step would have.
    if (update == ListUpdate::refresh && neighbors_.needs_rebuild(particles_, walls_))
      update = ListUpdate::rebuild;
    const double update_start = timed ? StepPhaseTimes::now() : 0.0;
    if (update == ListUpdate::rebuild) {
      rebuild_neighbors();
      records_written = false;
      for (StepListener* l : listeners_) l->after_rebuild(*this);
    } else if (update == ListUpdate::refresh) {
      // The particles keep their order; the records are written again only because whether the
      // kernel runs depends on the list not being empty.
      refresh_active_pairs();
      records_written = false;
    }
    if (update != ListUpdate::none) list_displacement2_ = 0.0;  // selected where they are now
    if (timed) update_seconds = StepPhaseTimes::now() - update_start;
    compute_forces(settings_.time_step, true, records_written);
  }
  partition_.update();
  time_ += settings_.time_step;
  ++step_count_;
  if (flat_gather_) ++flat_gather_steps_;
  if (walk_timed && times_gather_walks())
    gather_walk_trial_.step_took(StepPhaseTimes::now() - walk_start);
  check_health();
  for (StepListener* l : listeners_) l->after_step(*this);
  if (timed)
    phase_times_.step_done(StepPhaseTimes::now() - step_start, phase_regions_, update_seconds);
}

void Simulation::scale_positions(const Vec3& centre, double factor) {
  ParticleStore& p = particles_;
  const long n = static_cast<long>(p.size());
  // Where steps may run as one sweep, the largest move widens the bound of one_sweep_possible
  // (the distance from the list's selection grows by at most the move).
  const bool bound = one_sweep_wanted_;
  double moved2 = 0.0, scale2 = 0.0;
#pragma omp parallel for schedule(static) reduction(max \
                                                    : moved2, scale2) if (n > parallel_threshold)
  for (long i = 0; i < n; ++i) {
    const Vec3 x = centre + factor * (p.position[i] - centre);
    if (bound) {
      moved2 = std::max(moved2, norm2(x - p.position[i]));
      scale2 = std::max(scale2, norm2(x));
    }
    p.position[i] = x;
  }
  if (bound) {
    const double reach = std::sqrt(list_displacement2_) + std::sqrt(moved2);
    list_displacement2_ = reach * reach;
    position_scale2_ = std::max(position_scale2_, scale2);
  } else {
    list_displacement2_ = position_scale2_ = INFINITY;
  }
}

// The walls' first half kick and drift (a wall with mass: v += dt/2 F/M), before the particles':
// the particles' drift does not read the walls.
void Simulation::drift_walls() {
  const double dt = settings_.time_step, half = 0.5 * dt;
  for (Wall& w : walls_) {
    if (w.mass > 0.0) w.velocity += (half / w.mass) * (w.force + w.external_force);
    w.point += dt * w.velocity;
  }
}

// First half of velocity Verlet for the particles: v(t + dt/2) = v(t) + dt/2 F/m, then
// x(t + dt) = x + dt v (the walls have moved already). Returns what the neighbour lists need: the
// checks of each particle's displacement since the last selection of the active list (and, where it
// could matter before the next one, since the last rebuild) are made in the same loop (one parallel
// region, not two). When the vectorised kernel runs, the same pass writes its velocity records
// (particle_records: the half-step velocities just made and the end-of-step estimates from the
// forces held), tile by tile while the tile's velocities and forces are still in the caches, and
// sets records_written; the force region then skips its own records stage.
Simulation::ListUpdate Simulation::kick_and_drift(bool& records_written) {
  const long n = static_cast<long>(particles_.size());
  // (the list's positions are only looked at when it was built for this many particles)
  const bool check_particles = neighbors_.built_for(particles_.size());
  // (the test against the build's positions only where it could come true before a refresh;
  // a refresh step makes it in full in step())
  const bool check_rebuild = check_particles && neighbors_.rebuild_possible_before_refresh();
  records_written = uses_pair_kernel();
  const ParticlePassInput pass = particle_pass_input(check_particles, check_rebuild);
  // (the bound of one_sweep_possible, where the next step may run as one sweep)
  const bool bound = check_particles && one_sweep_wanted_;
  int moved = 0, stale = 0;
  double displacement2 = 0.0, scale2 = 0.0;
  const int team = step_team(n);
  partition_.plan(n, team);
  // On many threads the drift's blocks, sized for the force stages, take unequal times, and a
  // thread that lags makes the others wait at the region's end (on 16 Xeon threads, 139,632 beads:
  // 93 us per step of a 167 us drift, docs/performance.md sec. 34): there the others take its last
  // chunks. That halved the wait; the step moved by 0.98 to 1.03, since a chunk taken over leaves
  // its particles in the taker's caches for the force stages. A particle's drift is the same
  // whichever thread makes it.
  const bool shared = shares_drift(team);
  if (shared) {
    const ChunkSharing sharing = chunk_sharing(team);
    drift_chunks_.plan(partition_, stage_chunk(n, team, sharing.chunks_per_thread), chunk_tail_,
                       sharing.owner_keeps_last);
    ++shared_drift_steps_;
  }
  StepPhaseTimes& timer = phase_times_;
  const bool timed = timer.on();
  if (timed) timer.region_begins();
#pragma omp parallel reduction(|               \
                               : moved, stale) \
    reduction(max                              \
              : displacement2, scale2) if (n > parallel_threshold)
  {
    // (the clock only where it is read: the timers, or the block's time for the partition)
    const double start = timed ? timer.thread_begins() : shared ? 0.0 : omp_get_wtime();
    DriftTally tally;
    const auto drift = [&](long first, long end) {
      drift_particles(pass, {first, end}, bound, records_written, tally);
    };
    if (shared) {
      const ChunkQueue::OwnWork own = drift_chunks_.drain(drift);
      partition_.record(omp_get_thread_num(), own.count, own.seconds);
    } else {
      const IndexBlock block = partition_.thread_block_of(n);
      drift(block.first, block.end);
      partition_.record(omp_get_thread_num(), block.end - block.first, omp_get_wtime() - start);
    }
    stale |= tally.stale, moved |= tally.moved;
    displacement2 = std::max(displacement2, tally.displacement2);
    scale2 = std::max(scale2, tally.scale2);
    if (timed) timer.last_work(StepPhaseTimes::drift, start);
  }
  if (timed) phase_regions_ += timer.region_ends(StepPhaseTimes::drift_wait);
  list_displacement2_ = bound ? displacement2 : INFINITY;
  position_scale2_ = bound ? scale2 : INFINITY;
  if (moved != 0 || !neighbors_.walls_and_count_allow(particles_.size(), walls_))
    return ListUpdate::rebuild;
  return stale != 0 ? ListUpdate::refresh : ListUpdate::none;
}

void Simulation::drift_particles(const ParticlePassInput& pass, IndexBlock range, bool bound,
                                 bool records, DriftTally& tally) {
  for (long first = range.first; first < range.end; first += drift_tile) {
    const long end = std::min(range.end, first + drift_tile);
    particle_passes_.kick_and_drift(pass, first, end, bound, tally);
    if (records) write_particle_records(settings_.time_step, {first, end});
  }
}

// Second half of velocity Verlet for particles [b.first, b.end), with the forces just summed:
// v(t + dt) = v(t + dt/2) + dt/2 F/m. Returns the largest speed squared (NaN as infinite);
// next_speed2 is raised to that of the velocity the next step's drift will move a particle at, as
// it will form it, unless a command changes the velocity first.
double Simulation::half_kick_particles(IndexBlock b, double* next_speed2) {
  double max_speed2 = 0.0;
  particle_passes_.half_kick(particle_pass_input(false, false), b.first, b.end, max_speed2,
                             next_speed2);
  return max_speed2;
}

ParticlePassInput Simulation::particle_pass_input(bool list_test, bool rebuild_test) {
  ParticleStore& p = particles_;
  return {components(p.position),
          components(p.velocity),
          components(p.angular_velocity),
          components(p.rotation),
          components(p.force),
          components(p.torque),
          p.inverse_mass.data(),
          p.inverse_inertia.data(),
          list_test ? components(neighbors_.position_at_refresh()) : nullptr,
          rebuild_test ? components(neighbors_.position_at_build()) : nullptr,
          neighbors_.half_list_skin2(),
          neighbors_.half_skin2(),
          settings_.time_step};
}

void Simulation::half_kick_walls() {
  const double half = 0.5 * settings_.time_step;
  for (Wall& w : walls_)
    if (w.mass > 0.0) w.velocity += (half / w.mass) * (w.force + w.external_force);
}

void Simulation::set_wall_geometry(size_t k, const Wall& g) {
  Wall& w = walls_[k];
  if (g.shape != w.shape)
    throw std::invalid_argument("set_wall_geometry: the shape must not change");
  w.point = g.point, w.normal = g.normal, w.axis_u = g.axis_u, w.axis_v = g.axis_v;
  w.half_u = g.half_u, w.half_v = g.half_v, w.axis = g.axis, w.radius = g.radius;
}

void Simulation::clear_external_forces() {
  std::fill(particles_.external_force.begin(), particles_.external_force.end(), Vec3{});
  external_forces_ = false;
}

void Simulation::set_pair_table(PairTable table) {
  if (table.material_count() != table_.material_count() || !(table.pieces() == pieces_))
    throw std::invalid_argument(
        "set_pair_table: the materials and the pieces of the contact law must not change");
  table_ = std::move(table);
}

// The force sources, in the order they are summed: pair contacts, wall contacts, then (in
// gather) gravity and the per-particle external forces; then, closing a step, the second half
// kick. Every sum and every contact is the same arithmetic whatever the thread count and
// whichever thread takes it.
void Simulation::compute_forces(double drift, bool close_step, bool records_written) {
  const long n = static_cast<long>(particles_.size());
  prepare_pair_forces();
  prepare_wall_lanes();
  const bool parallel = n > parallel_threshold;
  const int team = step_team(n);
  const ChunkSharing sharing = chunk_sharing(team);
  const long chunk = stage_chunk(n, team, sharing.chunks_per_thread);
  const bool records = uses_pair_kernel() && !records_written;
  flat_gather_ = walks_gather_flat(n, team);
  partition_.plan(n, team);  // (the drift's blocks, unless this is a fresh state)
  if (records) record_chunks_.plan(partition_, chunk, chunk_tail_, sharing.owner_keeps_last);
  contact_chunks_.plan(partition_, chunk, chunk_tail_, sharing.owner_keeps_last);
  particle_chunks_.plan(partition_, chunk, chunk_tail_, sharing.owner_keeps_last);
  double max_fraction = 0.0, max_speed2 = 0.0, next_speed2 = 0.0;
  long handed_back = 0, walls_handed_back = 0;
  // (for one_sweep_possible and the kernel's test for contacts begun in the next step)
  const bool next_bound = close_step && (one_sweep_wanted_ || uses_pair_kernel());
  // One region, up to three stages, a barrier after each but the last: the pair rows and wall
  // contacts read every particle's record, the gather reads every entry's result. The records
  // stage runs only where kick_and_drift has not written them (after a rebuild, on a fresh
  // state): within a run of steps the region has two stages and one barrier. Each stage shares
  // its chunks (core/chunk_queue.hpp).
  StepPhaseTimes& timer = phase_times_;
  const bool timed = timer.on();
  if (timed) timer.region_begins();
#pragma omp parallel reduction(max : max_fraction, max_speed2, next_speed2) \
    reduction(+ : handed_back, walls_handed_back) if (parallel)
  {
    double since = timed ? timer.thread_begins() : 0.0;
    if (records) {
      record_chunks_.drain([&](long first, long end) {
        write_particle_records(drift, {first, end});
      });
      timer.barrier_after(StepPhaseTimes::records, since);
    }
    const ChunkQueue::OwnWork contacts = contact_chunks_.drain([&](long first, long end) {
      max_fraction = std::max({max_fraction, compute_pair_forces(drift, {first, end}, handed_back),
                               compute_wall_forces(drift, {first, end}, walls_handed_back)});
    });
    timer.barrier_after(StepPhaseTimes::contacts, since);
    // The walls' totals, serial in entry order (their bits), by one thread while the others
    // start on the particles' sums: they take its chunks (core/chunk_queue.hpp). After the
    // region, every thread had waited for them: on 16 Xeon threads, 139,632 beads, the step's
    // serial part was 102 us of about 1.5 ms, 60 us with them here (docs/performance.md sec. 31).
    if (omp_get_thread_num() == 0) gather_walls();
    const ChunkQueue::OwnWork gathered = particle_chunks_.drain([&](long first, long end) {
      gather_particles({first, end});
      if (close_step)
        max_speed2 = std::max(
            max_speed2, half_kick_particles({first, end}, next_bound ? &next_speed2 : nullptr));
    });
    partition_.record(omp_get_thread_num(), contacts.count + gathered.count,
                      contacts.seconds + gathered.seconds);
    if (timed) timer.last_work(StepPhaseTimes::gather, since);
  }
  if (timed) phase_regions_ += timer.region_ends(StepPhaseTimes::gather_wait);
  max_overlap_fraction_ = max_fraction;
  pairs_handed_to_scalar_law_ = handed_back;
  walls_handed_to_scalar_law_ = walls_handed_back;
  next_speed2_ = next_bound ? next_speed2 : INFINITY;
  if (close_step) {
    max_speed2_ = max_speed2;
    half_kick_walls();
  }
}

const char* Simulation::step_key() const {
  return settings_.step_key == SimulationSettings::StepKey::scene ? "simulation.dt_fraction (or dt)"
                                                                  : "test.dt_fraction";
}

void Simulation::check_health() const {
  const double max_speed = settings_.max_speed;
  if (!(max_speed2_ <= max_speed * max_speed)) {
    const bool nan = std::isinf(max_speed2_) || std::isnan(max_speed2_);
    const bool scene = settings_.step_key == SimulationSettings::StepKey::scene;
    throw BlowUpError(fmt::format(
        "the run blew up at t = {:.6g} s (step {}): {}. Either the time step ({:.3g} s) is too "
        "large for the contact stiffness (lower {}), or the particles were driven that fast: "
        "check the initial velocities, the wall speeds and loads, and gravity{}.",
        time_, step_count_,
        nan ? std::string("a particle velocity became NaN")
            : fmt::format("a particle reached {:.3g} m/s, above {} = {:.3g} m/s",
                          std::sqrt(max_speed2_),
                          scene ? "simulation.max_speed" : "the test's speed limit", max_speed),
        settings_.time_step, step_key(),
        scene ? " (or raise simulation.max_speed if such speeds are real)" : ""));
  }
  if (max_overlap_fraction_ > settings_.max_overlap_fraction) {
    throw BlowUpError(fmt::format(
        "the run blew up at t = {:.6g} s (step {}): two bodies overlap by {:.2f} % of a radius "
        "(limit {:.2f} %). The contacts are too soft for the load or the time step ({:.3g} s) is "
        "too "
        "large; lower {}, slow the walls, or raise the stiffness.",
        time_, step_count_, 100.0 * max_overlap_fraction_, 100.0 * settings_.max_overlap_fraction,
        settings_.time_step, step_key()));
  }
}

double Simulation::kinetic_energy() const {
  const ParticleStore& p = particles_;
  double e = 0.0;
  for (size_t i = 0; i < p.size(); ++i) {
    if (p.inverse_mass[i] == 0.0) continue;
    e += 0.5 * norm2(p.velocity[i]) / p.inverse_mass[i] +
         0.5 * norm2(p.angular_velocity[i]) / p.inverse_inertia[i];
  }
  return e;
}

long Simulation::touching_pair_count() const {
  return std::count_if(pairs_.result.begin(), pairs_.result.end(),
                       [](const PairResult& r) { return r.normal_force > 0.0; });
}

}  // namespace grainlab
