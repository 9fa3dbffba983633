// Specimen preparation (lab/specimen.hpp): placement on a jittered lattice, compaction to the
// confining stress (by the walls or by an affine strain), the friction steered toward a target
// solid fraction, the walls' hold to equilibrium; with periodic checkpoints (preparation.bin) that
// `grainlab run --resume DIR` continues bit-identically.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <random>

#include "contact/stability.hpp"
#include "contact/time_step.hpp"
#include "control/affine_compaction.hpp"
#include "control/box_controller.hpp"
#include "core/random_insertion.hpp"
#include "core/simulation.hpp"
#include "geometry/cuboid_box.hpp"
#include "io/checkpoint_clock.hpp"
#include "io/checkpoint_file.hpp"
#include "io/config_error.hpp"
#include "io/output_files.hpp"
#include "io/progress.hpp"
#include "lab/specimen.hpp"
#include "measure/boundary.hpp"
#include "measure/specimen_state.hpp"

namespace grainlab {
namespace {

struct Placement {
  std::vector<Sphere> spheres;
  Vec3 low, high;
};

Placement place_on_jittered_lattice(const SpecimenSettings& s) {
  std::mt19937_64 rng(s.seed);
  const double d_max = s.diameter + s.diameter_tolerance;
  const double spacing = 1.1 * d_max;
  // The lattice of the nominal box, grown in its aspect ratio until it has enough sites. A nominal
  // box with far more sites than beads (it only sets the aspect ratio: "1e9 mm" is legal) starts
  // from the size that just holds them instead, so the lattice stays about `count` sites.
  const double nominal_sites =
      (s.nominal_box.x / spacing) * (s.nominal_box.y / spacing) * (s.nominal_box.z / spacing);
  const double start = nominal_sites > 8.0 * s.count ? std::cbrt(s.count / nominal_sites) : 1.0;
  int n[3];
  for (double scale = start;; scale *= 1.01) {
    double sites = 1;
    for (int a = 0; a < 3; ++a) {
      n[a] = std::max(1, static_cast<int>(std::floor(scale * s.nominal_box[a] / spacing)));
      sites *= n[a];
    }
    if (sites >= s.count) break;
  }
  std::vector<long> sites(static_cast<size_t>(n[0]) * n[1] * n[2]);
  for (size_t k = 0; k < sites.size(); ++k) sites[k] = static_cast<long>(k);
  // Fisher-Yates with our own uniform draw (same on every platform).
  for (size_t k = sites.size() - 1; k > 0; --k)
    std::swap(sites[k], sites[static_cast<size_t>(uniform01(rng) * (k + 1))]);
  Placement p;
  p.low = {0, 0, 0};
  p.high = {n[0] * spacing, n[1] * spacing, n[2] * spacing};
  for (long k = 0; k < s.count; ++k) {
    const long site = sites[k];
    const int i = site % n[0], j = (site / n[0]) % n[1], l = site / (n[0] * n[1]);
    const double r = 0.5 * (s.diameter + s.diameter_tolerance * (2.0 * uniform01(rng) - 1.0));
    const double room = 0.5 * spacing - r;  // jitter that keeps the sphere inside its cell
    Vec3 c{(i + 0.5) * spacing, (j + 0.5) * spacing, (l + 0.5) * spacing};
    for (int a = 0; a < 3; ++a) c[a] += room * (2.0 * uniform01(rng) - 1.0);
    p.spheres.push_back({c, r});
  }
  return p;
}

// The contacts while preparing: bead-bead friction `bead_friction`, bead-wall friction at most
// `wall_friction`, restitution at most `e` (each < 0: the measured value). Only the packing's
// final static state is kept, which does not depend on e, so compaction may dissipate faster
// than the beads do.
void set_compaction_contacts(PairTable& table, const PairTable& original, const SpecimenSettings& s,
                             double bead_friction, double wall_friction, double e) {
  for (int other : {s.bead_material, s.lateral_material, s.platen_material}) {
    const PairParams& q = original(s.bead_material, other);
    if (!q.defined) continue;
    PairProperties p;
    p.restitution = e < 0 ? q.restitution : std::min(e, q.restitution);
    if (other == s.bead_material)  // may exceed the measured friction: a looser packing
      p.friction = bead_friction < 0 ? q.friction : bead_friction;
    else
      p.friction = wall_friction < 0 ? q.friction : std::min(wall_friction, q.friction);
    p.rns = q.rns;
    p.rzs = q.rzs;
    p.arf = q.arf;
    p.rolling_damping_ratio = q.rolling_damping_ratio;
    p.twisting_friction = q.twisting_friction;
    p.rolling_force_stiffness_ratio = q.rolling_force_stiffness_ratio;
    p.rolling_force_friction = q.rolling_force_friction;
    p.youngs_modulus = q.youngs_modulus;
    table.set(s.bead_material, other, p);
  }
}

// The state of an isotropically held cuboid specimen, as hold_isotropic checks it.
HoldState measure_hold_state(const Simulation& sim, double confining_stress) {
  HoldState state;
  state.solid_fraction = solid_fraction(sim.particles(), box_volume(sim.walls()));
  state.max_stress_error = 0.0;
  for (int k = 0; k < 6; ++k)
    state.max_stress_error = std::max(
        state.max_stress_error, std::abs(wall_stress(sim.walls(), k) / confining_stress - 1.0));
  state.unbalanced = unbalanced_force_ratio(sim);
  return state;
}

// "grnlpre2": the second layout of PrepState (the compaction plateau); a file of the first is
// refused as not a preparation checkpoint.
constexpr uint64_t preparation_magic = 0x67726e6c70726532;
constexpr const char* preparation_kind = "preparation checkpoint";

// Where a preparation stands: what a checkpoint holds besides the Simulation.
enum class PrepStage : int32_t { compacting = 0, holding = 1, done = 2 };
struct PrepState {
  PrepStage stage = PrepStage::compacting;
  double stage_end = 0.0;  // s simulated: the stage's bound (its start + max_time)
  bool friction_restored = false;
  bool target_reached = true;
  double affine_mean_stress = 0.0;    // Pa, the affine compaction's averaged wall stress
  std::array<double, 6> integrals{};  // the walls' servo integrals while holding, m/s
  double wall_time_before = 0.0;      // s, earlier sessions
  HoldState held;                     // the hold's last check (stage done)
  // The compaction plateau: the solid fraction the packing has stayed within
  // plateau_solid_fraction_band of for plateau_checks checks in a row.
  double plateau_solid_fraction = 0.0;
  int32_t plateau_checks = 0;
};

// A steered compaction has packed when its solid fraction has stayed within this band for
// plateau_checks_to_switch checks (200 steps each) with the wall stresses within
// plateau_stress_error of the target. A frictionless or very frictional packing can take far
// longer than that to meet the hold's unbalanced-force criterion (1e-4): near jamming the walls'
// servo keeps it breathing (unbalanced 0.02-0.08 at a constant solid fraction), but its density,
// which is all the compaction friction steers, no longer changes.
constexpr double plateau_solid_fraction_band = 2e-4;
constexpr int plateau_checks_to_switch = 25;
constexpr double plateau_stress_error = 0.10;

void save_preparation(const PreparationCheckpoints& cp, const PrepState& st,
                      const Simulation& sim) {
  StateWriter out;
  write_checkpoint_header(out, preparation_magic, cp.header);
  out.value(st);
  sim.save_state(out);
  write_sealed(out, cp.path);
}

}  // namespace

PairTable resting_contacts(const SpecimenSettings& s, const PairTable& measured, double time_step,
                           double min_radius) {
  const double e_measured = measured(s.bead_material, s.bead_material).restitution;
  for (double e = s.compaction_restitution; e < e_measured; e += 0.05) {
    PairTable damped = measured;
    set_compaction_contacts(damped, measured, s, -1.0, -1.0, e);
    if (stable_time_step(time_step, damped, s.bead_material, min_radius).time_step >= time_step)
      return damped;
  }
  return measured;
}

namespace {

// The walls' hold (isotropic stress servo, compaction regime) until `on_check` allows a stop and
// the criteria are met, or the simulated time reaches t_end. `after_check` runs after every check
// that did not stop the hold (checkpoints).
HoldState hold_loop(Simulation& sim, BoxController& servo, const HoldCriteria& c, double t_end,
                    const std::function<bool(const HoldState&)>& on_check,
                    const std::function<void()>& after_check) {
  const ScopedListener attached(sim, servo);
  HoldState state;
  while (sim.time() < t_end) {
    sim.advance(200);
    state = measure_hold_state(sim, c.confining_stress);
    const bool may_stop = on_check(state);
    if (may_stop && state.max_stress_error < c.stress_tolerance &&
        state.unbalanced < c.unbalanced_tolerance) {
      state.reached = true;
      break;
    }
    after_check();
  }
  stop_walls(sim);
  return state;
}

BoxController isotropic_servo(const HoldCriteria& c) {
  const AxisControl held{AxisMode::stress, c.confining_stress};
  return BoxController(
      BoxControlSettings{{held, held, held}, ServoRegime::compaction, 0.0, c.max_strain_rate});
}

}  // namespace

HoldState hold_isotropic(Simulation& sim, const HoldCriteria& c,
                         const std::function<bool(const HoldState&)>& on_check) {
  BoxController servo = isotropic_servo(c);
  return hold_loop(sim, servo, c, sim.time() + c.max_time, on_check, [] {});
}

CheckpointHeader peek_preparation_checkpoint(const std::string& path) {
  CheckpointHeader header;
  open_checkpoint(path, preparation_magic, preparation_kind, header);
  return header;
}

Specimen prepare_cuboid_specimen(const SpecimenSettings& s, PairTable table, Progress* progress,
                                 const PreparationCheckpoints* checkpoints) {
  const PairTable original = table;
  const Placement placement = place_on_jittered_lattice(s);
  ParticleStore particles;
  for (size_t i = 0; i < placement.spheres.size(); ++i)
    particles.add(static_cast<uint32_t>(i), s.bead_material, placement.spheres[i].radius, s.density,
                  placement.spheres[i].centre, {}, {}, false);
  Specimen out;
  out.inserted_box = placement.high - placement.low;
  out.inserted_solid_fraction =
      solid_fraction(particles, out.inserted_box.x * out.inserted_box.y * out.inserted_box.z);

  const double r_min = s.min_radius();
  const PairParams& glass = original(s.bead_material, s.bead_material);
  // Steering: compact with the compaction friction (frictionless by default when there is a
  // target) until the target solid fraction is reached or the packing has settled, then switch
  // the measured friction on so the packing locks in; without either, the beads' own friction.
  // The walls are frictionless while compacting toward a target, and for the whole preparation
  // unless wall_friction_while_preparing.
  const bool steered = s.target_solid_fraction || s.compaction_friction;
  const double bead_friction =
      s.compaction_friction ? *s.compaction_friction : (s.target_solid_fraction ? 0.0 : -1.0);
  const double hold_wall_friction = s.wall_friction_while_preparing ? -1.0 : 0.0;
  out.compaction_friction = bead_friction < 0 ? glass.friction : bead_friction;
  out.compaction_restitution = std::min(s.compaction_restitution, glass.restitution);
  out.wall_friction_while_preparing = s.wall_friction_while_preparing;
  set_compaction_contacts(table, original, s, bead_friction,
                          s.target_solid_fraction ? 0.0 : hold_wall_friction,
                          s.compaction_restitution);
  // The step must be stable for the compaction contacts (more damped) and the measured ones
  // (restored at the end), by the one rule of contact/stability.hpp.
  SimulationSettings settings;
  const MaterialTimeStep step = specimen_time_step(s, original, r_min);
  PairTable measured_friction = table;
  set_compaction_contacts(measured_friction, original, s, -1.0, hold_wall_friction,
                          s.compaction_restitution);
  settings.time_step = std::min(
      {step.time_step, stable_time_step(step.time_step, table, s.bead_material, r_min).time_step,
       stable_time_step(step.time_step, measured_friction, s.bead_material, r_min).time_step});
  // below s.dt_fraction if stability lowered it
  settings.dt_fraction = settings.time_step / step.collision_duration;
  settings.skin = verlet_skin(s.diameter);
  settings.step_key = SimulationSettings::StepKey::lab_test;

  PrepState st;
  st.friction_restored = !steered;
  st.stage = s.compaction == Compaction::affine ? PrepStage::compacting : PrepStage::holding;
  st.stage_end = s.max_time;
  std::optional<Simulation> resumed;
  double earlier_wall_time = 0.0;
  if (checkpoints && checkpoints->resume) {
    // Continue from the last checkpoint: the stage, the steering and the controllers' state,
    // and the simulation with the contact table it had then.
    CheckpointHeader header;  // read before, to find the config
    StateReader in =
        open_checkpoint(checkpoints->path, preparation_magic, preparation_kind, header);
    try {
      st = in.value<PrepState>();
      earlier_wall_time = st.wall_time_before;
      resumed.emplace(in, st.friction_restored ? measured_friction : table);
      if (!in.at_end()) throw std::runtime_error("trailing data");
      if (progress)
        progress->message(
            fmt::format("resuming the preparation from {} at t = {:.4g} s simulated ({})",
                        checkpoints->path, resumed->time(),
                        st.stage == PrepStage::compacting
                            ? "compacting"
                            : (st.stage == PrepStage::holding ? "holding" : "done")));
    } catch (const std::runtime_error& e) {
      throw unresumable_checkpoint(checkpoints->path, e);
    }
  }
  Simulation sim = resumed ? std::move(*resumed)
                           : Simulation(std::move(particles),
                                        cuboid_walls(placement.low, placement.high,
                                                     s.lateral_material, s.platen_material),
                                        table, settings);
  out.target_reached = st.target_reached;

  // Checkpoints every interval of wall time, and on Ctrl-C (then Interrupted).
  CheckpointClock clock(checkpoints ? checkpoints->interval_s
                                    : std::numeric_limits<double>::infinity());
  const auto save = [&] {
    if (!checkpoints) return;
    PrepState now = st;
    now.wall_time_before += clock.session_time();
    save_preparation(*checkpoints, now, sim);
  };
  const auto after_check = [&] {
    clock.poll(save, [&] {
      return checkpoints ? "interrupted while preparing the specimen: saved; grainlab run --resume "
                           "DIR continues"
                         : "interrupted while preparing the specimen: nothing was saved";
    });
  };

  const char* stage = st.stage == PrepStage::compacting ? "compacting" : "preparing";
  const auto steer = [&](const HoldState& state) {
    const bool settled =
        state.max_stress_error < s.stress_tolerance && state.unbalanced < s.unbalanced_tolerance;
    const bool at_target =
        s.target_solid_fraction && state.solid_fraction >= *s.target_solid_fraction;
    if (std::abs(state.solid_fraction - st.plateau_solid_fraction) > plateau_solid_fraction_band) {
      st.plateau_solid_fraction = state.solid_fraction;
      st.plateau_checks = 0;
    } else {
      ++st.plateau_checks;
    }
    const bool packed = st.plateau_checks >= plateau_checks_to_switch &&
                        state.max_stress_error < plateau_stress_error;
    bool switched = false;
    if (!st.friction_restored && (at_target || settled || packed)) {
      // Target reached, or the packing settled or stopped compacting (below the target: it
      // cannot get denser at this stress and friction, so the target is out of reach, reported).
      if (s.target_solid_fraction)
        st.target_reached = state.solid_fraction >= *s.target_solid_fraction - 0.005;
      sim.set_pair_table(measured_friction);
      st.friction_restored = true;
      switched = true;  // not a stop yet: the packing must come to rest with the measured friction
    }
    if (progress) {
      // The preparation stops on criteria (the target, then equilibrium), long before its time
      // limit s.max_time: only the affine compaction toward a target solid fraction can say how
      // far it is; the holds show their state without a percentage or an ETA.
      double fraction = Progress::unknown_fraction;
      if (st.stage == PrepStage::compacting && s.target_solid_fraction)
        fraction = std::clamp((state.solid_fraction - out.inserted_solid_fraction) /
                                  (*s.target_solid_fraction - out.inserted_solid_fraction),
                              0.0, 1.0);
      progress->update(
          fraction,
          fmt::format("{}: phi = {:.4f}, wall stress error {:.2f} %, unbalanced {:.1e}", stage,
                      state.solid_fraction, 100 * state.max_stress_error, state.unbalanced));
    }
    return st.friction_restored && !switched;
  };
  const HoldCriteria criteria{s.confining_stress, s.max_strain_rate, s.stress_tolerance,
                              s.unbalanced_tolerance, s.max_time};
  if (st.stage == PrepStage::compacting) {
    // Affine compaction (control/affine_compaction.hpp) until the mean wall stress has come
    // within 2 % of the confining stress; the walls' servos then take over.
    AffineCompaction compaction(s.confining_stress, s.max_strain_rate);
    compaction.set_mean_stress(st.affine_mean_stress);
    {
      const ScopedListener attached(sim, compaction);
      while (sim.time() < st.stage_end) {
        sim.advance(200);
        steer(measure_hold_state(sim, s.confining_stress));
        if (compaction.stress_error() > -0.02) break;
        st.affine_mean_stress = compaction.mean_stress();
        after_check();
      }
    }
    stop_walls(sim);
    st.stage = PrepStage::holding;
    st.stage_end = sim.time() + s.max_time;
  }
  if (st.stage == PrepStage::holding) {
    stage = s.compaction == Compaction::affine ? "holding" : "preparing";
    BoxController servo = isotropic_servo(criteria);
    servo.set_integrals(st.integrals);
    st.held = hold_loop(sim, servo, criteria, st.stage_end, steer, [&] {
      st.integrals = servo.integrals();
      after_check();
    });
    st.stage = PrepStage::done;
    save();  // a resume after this point goes straight to the specimen
  }
  if (s.target_solid_fraction && !st.friction_restored)  // ran out of time before either
    st.target_reached = solid_fraction(sim.particles(), box_volume(sim.walls())) >=
                        *s.target_solid_fraction - 0.005;
  out.target_reached = st.target_reached;
  out.equilibrium_reached = st.held.reached;
  out.earlier_wall_time = earlier_wall_time;
  out.low = box_low(sim.walls());
  out.high = box_high(sim.walls());
  out.solid_fraction = solid_fraction(sim.particles(), box_volume(sim.walls()));
  out.coordination_number = coordination_number(sim);
  out.unbalanced_force_ratio = unbalanced_force_ratio(sim);
  const Tensor3 lw = love_weber_stress(sim, box_volume(sim.walls()));
  out.love_weber_diagonal = std::array<double, 3>{lw[0][0], lw[1][1], lw[2][2]};
  out.max_stress_error = st.held.max_stress_error;
  out.simulated_time = sim.time();
  out.time_step = sim.settings().time_step;
  out.steps = sim.step_count();
  // Particles in id order, at rest (velocities dropped: the specimen is in equilibrium).
  const ParticleStore& p = sim.particles();
  for (size_t i : indices_by_id(p))
    out.particles.add(p.id[i], p.material[i], p.radius[i], s.density, p.position[i], {}, {}, false);
  return out;
}

}  // namespace grainlab
