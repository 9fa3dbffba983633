// A step as one sweep over the particles (docs/performance.md sec. 27). In stages, a step makes
// three passes over every particle and every pair entry: the drift (and the kernel's velocity
// records), the forces (pair rows and wall contacts), the gather with the closing half kick.
// Each pass streams the whole packing through the caches, so in a large one every pass reads
// from memory what the pass before wrote (the lab's 88,400-bead specimen touches about 1.5 KiB
// per bead and step). In one sweep each particle is drifted, its row computed and its sums
// gathered within a few hundred particles of each other:
//
//   - the rows of particles [first, end) read the records and positions of their partners,
//     which lie after them, at most partner_reach_.farthest further on (the neighbour list's cell
//     order): the drift runs that far ahead of the rows;
//   - a particle's sums need its own row and the entries where it is second, whose rows come
//     before it: it is gathered and kicked right after its own row.
//
// The results are those of the stages bit for bit: every particle and every contact is the same
// arithmetic on the same values, only earlier or later in the step.
//
// What makes it possible: the stages decide after the drift whether the neighbour lists need a
// new selection or a rebuild, before any force is computed. The sweep computes forces before the
// last particle has moved, so it runs only where no update can follow the drift: the list was not
// built with a rebuild in view before the next selection (rebuild_possible_before_refresh), no
// wall has moved half a skin, and no particle can move half the list skin. The last is a bound:
// the largest displacement since the selection (after the last drift) plus dt times the largest
// speed the drift will give (formed by the last half kick as the drift will form it). A command
// between steps that moves particles or sets a velocity forgets the bound. In a dense packing the
// bound holds in all but about the last step before each selection.
//
// Threads: each takes its block of the partition (core/thread_partition.hpp) and sweeps it, all
// but its tail (the last 1 / tail_share of it), which the threads share.
//   1. It drifts the head of its block, the particles the rows of the blocks before it may reach
//      (partner_reach_.farthest), and takes chunks of the tails' drift (core/chunk_queue.hpp),
//      and waits for the others.
//   2. It sweeps its block up to the tail. A particle that is second in an entry of an earlier
//      block is "late": its sums are not complete until the other thread's rows are, and that
//      thread's scalar law may read its velocity and force until then; it is left for stage 4.
//      Late particles lie within `ahead` of the block's start (in its tail too, where the
//      block is that short).
//   3. Without waiting, it takes chunks of the tails' rows and wall contacts: its own tail's from
//      the front, the others' from their backs. A block that takes longer in this step (the
//      threads' speeds vary from step to step) thus hands part of its tail over.
//   4. After a second barrier, it gathers and kicks its late particles, and takes chunks of the
//      tails' sums and kicks.
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/simulation.hpp"

namespace grainlab {

// On more than one thread the last 1 / tail_share of each block is shared among the threads: its
// drift in stage 1, its rows in stage 3 and its sums and kicks in stage 4 (sweep_step).
constexpr long tail_share = 8;

void Simulation::choose_one_sweep() {
  // (automatic: only on the thread counts it was measured on, where it paid there. On a 16-core
  // Xeon the sweep ran at 0.84 to 0.97 of the stages' speed at 8 and 16 threads, in every
  // workload from 11.6k to 745k beads (docs/performance.md sec. 31): there the stages share
  // their chunks, and the sweep's blocks were fixed; it shares only their tails since sec. 33,
  // not measured on 16 cores)
  one_sweep_automatic_team_ = one_sweep_team(partner_reach_.mean, partner_reach_.farthest,
                                             l2_cache_bytes(), l3_cache_bytes());
  one_sweep_wanted_ = uses_pair_kernel() && !entry_owners_.empty() &&
                      (one_sweep_choice_ == OneSweep::always ||
                       (one_sweep_choice_ == OneSweep::automatic && one_sweep_automatic_team_ > 0));
  // (next_speed2_, the bound of the next drift's speeds, stays: the kernel reads it too)
  if (!one_sweep_wanted_) list_displacement2_ = position_scale2_ = INFINITY;
}

bool Simulation::one_sweep_possible() {
  if (!one_sweep_wanted_) return false;
  const size_t n = particles_.size();
  // (automatic: only on the teams one_sweep_team allows)
  if (one_sweep_choice_ == OneSweep::automatic &&
      step_team(static_cast<long>(n)) > one_sweep_automatic_team_)
    return false;
  if (!neighbors_.built_for(n) || neighbors_.rebuild_possible_before_refresh() ||
      !neighbors_.walls_and_count_allow(n, walls_))
    return false;
  // The farthest any particle can be from its place at the selection after this step's drift:
  // its distance before it plus dt times its speed, each widened for the rounding of the
  // computed squares (relative 1e-9) and of the positions themselves (a few units in the last
  // place of the largest coordinate).
  const double reach = (1.0 + 1e-9) * (std::sqrt(list_displacement2_) +
                                       settings_.time_step * std::sqrt(next_speed2_)) +
                       1e-15 * std::sqrt(position_scale2_);
  return reach * reach < neighbors_.half_list_skin2();  // false where a bound is infinite or NaN
}

void Simulation::close_particles(long first, long end, long block_first, bool late,
                                 double& max_speed2, double& next_speed2) {
  const PairContacts& c = pairs_;
  // second in an entry whose first particle lies before the block (col_pair is in entry order,
  // so its first entry has the lowest first particle)
  const auto is_late = [&](long i) {
    return c.col_start[i] < c.col_start[i + 1] &&
           entry_owners_[c.col_pair[c.col_start[i]]] < static_cast<uint32_t>(block_first);
  };
  for (long i = first; i < end;) {
    const bool this_late = block_first > 0 && is_late(i);
    long j = i + 1;
    while (j < end && (block_first > 0 && is_late(j)) == this_late) ++j;
    if (this_late == late) {
      gather_particles({i, j});
      max_speed2 = std::max(max_speed2, half_kick_particles({i, j}, &next_speed2));
    }
    i = j;
  }
}

void Simulation::sweep_step() {
  const double dt = settings_.time_step;
  const long n = static_cast<long>(particles_.size());
  const long ahead = partner_reach_.farthest;
  const ParticlePassInput pass = particle_pass_input(true, false);
  constexpr long force_tile = 1024;  // particles per call to the rows, walls and gather
  prepare_pair_forces();
  prepare_wall_lanes();
  const int team = step_team(n);
  flat_gather_ = walks_gather_flat(n, team);
  partition_.plan(n, team);
  // The blocks' tails (the last 1 / tail_share of each), shared in stages 1, 3 and 4.
  const auto tail_of = [&](const IndexBlock& b) {
    return IndexBlock{b.end - (b.end - b.first) / tail_share, b.end};
  };
  if (team > 1) {
    const auto tail_of_thread = [&](int t) { return tail_of(partition_.block(t)); };
    const long chunk = stage_chunk(n / tail_share, team);
    record_chunks_.plan_ranges(n, team, chunk, chunk_tail_, tail_of_thread);
    contact_chunks_.plan_ranges(n, team, chunk, chunk_tail_, tail_of_thread);
    particle_chunks_.plan_ranges(n, team, chunk, chunk_tail_, tail_of_thread);
  }
  int stale = 0;
  double displacement2 = 0.0, scale2 = 0.0, max_fraction = 0.0, max_speed2 = 0.0, next_speed2 = 0.0;
  long handed_back = 0, walls_handed_back = 0;
  StepPhaseTimes& timer = phase_times_;
  const bool timed = timer.on();
  if (timed) timer.region_begins();
#pragma omp parallel reduction(| : stale) \
    reduction(max : displacement2, scale2, max_fraction, max_speed2, next_speed2) \
    reduction(+ : handed_back, walls_handed_back) if (team > 1)
  {
    const IndexBlock block = partition_.thread_block_of(n);
    // (the tails only where the team is the one they were planned for: a region may have fewer
    // threads than asked for)
    const bool tails = team > 1 && omp_get_num_threads() == partition_.team();
    const long tail_first = tails ? tail_of(block).first : block.end;
    // `busy`: the time on its own particles (a thread's speed, core/thread_partition.hpp), the
    // others' chunks and the barriers left out; `since`: when the current stage began.
    double busy = 0.0, since = timed ? timer.thread_begins() : omp_get_wtime();
    const auto own_work_since = [&](double start) { busy += omp_get_wtime() - start; };
    // The first half kick and the drift of the particles up to `target` (kick_and_drift's
    // arithmetic and its list test), with their records.
    long drifted = block.first;
    DriftTally tally;
    const auto drift_to = [&](long target) {
      if (drifted >= target) return;
      drift_particles(pass, {drifted, target}, true, true, tally);
      drifted = target;
    };
    // 1. the head, which the rows of the blocks before this one may reach, and the tails, whose
    // rows any thread may compute from stage 2 on (shared: core/chunk_queue.hpp)
    drift_to(std::min(tail_first, block.first + ahead));
    own_work_since(since);
    ChunkQueue::OwnWork own_drift, own_rows, own_sums;
    if (tails)
      own_drift = record_chunks_.drain([&](long first, long end) {
        drift_particles(pass, {first, end}, true, true, tally);
      });
    timer.barrier_after(StepPhaseTimes::sweep_head, since);
    // 2. the sweep: the drift `ahead` particles in front of the rows, each particle's sums and
    // half kick right after its row
    for (long first = block.first; first < tail_first; first += force_tile) {
      const long end = std::min(tail_first, first + force_tile);
      drift_to(std::min(tail_first, end + ahead));
      max_fraction = std::max({max_fraction, compute_pair_forces(dt, {first, end}, handed_back),
                               compute_wall_forces(dt, {first, end}, walls_handed_back)});
      close_particles(first, end, block.first, false, max_speed2, next_speed2);
    }
    const double core_done = omp_get_wtime();
    busy += core_done - since;
    // 3. the tails' rows and wall contacts, each thread from its own and then from the others'
    // backs (core/chunk_queue.hpp), without waiting for the others' blocks: how long a block
    // takes varies from step to step, and the blocks alone had left one thread waiting for the
    // other 3 to 6 % of the step on 2 threads (docs/performance.md sec. 33). A tail's rows read
    // particles up to `ahead` further on: of the tails and of later blocks' heads, all drifted in
    // stage 1, and none of them kicked before stage 4 (the heads' particles they reach are
    // late). The particles of a tail are second in entries of the tail and of the rows before
    // it, so all their sums wait for stage 4.
    if (tails) {
      if (timed) timer.add(StepPhaseTimes::sweep_block, core_done - since);
      since = core_done;
      own_rows = contact_chunks_.drain([&](long first, long end) {
        max_fraction = std::max({max_fraction, compute_pair_forces(dt, {first, end}, handed_back),
                                 compute_wall_forces(dt, {first, end}, walls_handed_back)});
      });
      timer.barrier_after(StepPhaseTimes::sweep_tails, since);
    } else {
      timer.barrier_after(StepPhaseTimes::sweep_block, since);
    }
    // The walls' totals, serial in entry order (their bits), by the first thread, whose block has
    // no late particles, while the others sum theirs. After the region they had cost 41 µs per
    // step of 139,632 beads (docs/performance.md sec. 33).
    // (not a thread's own work: left out of its speed)
    if (omp_get_thread_num() == 0) gather_walls();
    // 4. the late particles, now that every row is done, and the tails' sums and half kicks
    const double late_start = omp_get_wtime();
    close_particles(block.first, std::min(tail_first, block.first + ahead), block.first, true,
                    max_speed2, next_speed2);
    own_work_since(late_start);
    if (tails)
      own_sums = particle_chunks_.drain([&](long first, long end) {
        close_particles(first, end, 0, false, max_speed2, next_speed2);
      });
    if (timed) timer.last_work(StepPhaseTimes::sweep_late, since);
    // (the particles a thread carried through the step: its core, and its share of the tails'
    // three stages, counted a third each)
    const long own_tail = (own_drift.count + own_rows.count + own_sums.count) / 3;
    partition_.record(omp_get_thread_num(), (tail_first - block.first) + own_tail,
                      busy + own_drift.seconds + own_rows.seconds + own_sums.seconds);
    stale |= tally.stale;
    displacement2 = std::max(displacement2, tally.displacement2);
    scale2 = std::max(scale2, tally.scale2);
  }
  if (timed) phase_regions_ += timer.region_ends(StepPhaseTimes::sweep_late_wait);
  if (stale != 0)  // one_sweep_possible's bound excludes it: a bug, not a physical state
    throw std::logic_error("a particle moved half the list skin in a step run as one sweep");
  list_displacement2_ = displacement2;
  position_scale2_ = scale2;
  max_overlap_fraction_ = max_fraction;
  pairs_handed_to_scalar_law_ = handed_back;
  walls_handed_to_scalar_law_ = walls_handed_back;
  max_speed2_ = max_speed2;
  next_speed2_ = next_speed2;
  half_kick_walls();
  ++one_sweep_steps_;
}

}  // namespace grainlab
