#include "lab/specimen.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <random>
#include <sstream>

#include "contact/stability.hpp"
#include "contact/time_step.hpp"
#include "control/affine_compaction.hpp"
#include "control/box_controller.hpp"
#include "core/random_insertion.hpp"
#include "core/simulation.hpp"
#include "io/config_error.hpp"
#include "io/output_files.hpp"
#include "io/progress.hpp"
#include "lab/interrupt.hpp"
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
  // Smallest lattice of the nominal aspect ratio with enough sites.
  int n[3];
  for (double scale = 1.0;; scale *= 1.01) {
    long sites = 1;
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

// Contact constants while compacting: friction mu (< 0: the measured one) and restitution e
// (< 0: the measured one). Only the packing's final static state is kept, which does not
// depend on e, so compaction may dissipate faster than the beads do.
void set_compaction_contacts(PairTable& table, const PairTable& original, const SpecimenSettings& s,
                             double mu, double e) {
  for (int other : {s.bead_material, s.lateral_material, s.platen_material}) {
    const PairParams& q = original(s.bead_material, other);
    if (!q.defined) continue;
    PairProperties p;
    p.restitution = e < 0 ? q.restitution : std::min(e, q.restitution);
    p.friction = mu < 0 ? q.friction : std::min(mu, q.friction);
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

}  // namespace

PairTable resting_contacts(const SpecimenSettings& s, const PairTable& measured, double time_step,
                           double min_radius) {
  const double e_measured = measured(s.bead_material, s.bead_material).restitution;
  for (double e = s.compaction_restitution; e < e_measured; e += 0.05) {
    PairTable damped = measured;
    set_compaction_contacts(damped, measured, s, -1.0, e);
    if (stable_time_step(time_step, damped, s.bead_material, min_radius).time_step >= time_step)
      return damped;
  }
  return measured;
}

MaterialTimeStep specimen_time_step(const SpecimenSettings& s, const PairTable& table,
                                    double min_radius) {
  return material_time_step(s.dt_fraction, table, s.bead_material,
                            {s.bead_material, s.lateral_material, s.platen_material}, min_radius,
                            s.density);
}

namespace {

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

// Affine compaction (control/affine_compaction.hpp) until the mean wall stress has come within
// 2 % of the confining stress; the walls' servos then take over (and `on_check` goes on steering
// the friction there). `on_check` runs every 200 steps.
void compact_affinely(Simulation& sim, const HoldCriteria& c,
                      const std::function<bool(const HoldState&)>& on_check) {
  const double t_end = sim.time() + c.max_time;
  AffineCompaction compaction(c.confining_stress, c.max_strain_rate);
  const ScopedListener attached(sim, compaction);
  while (sim.time() < t_end) {
    sim.advance(200);
    on_check(measure_hold_state(sim, c.confining_stress));
    if (compaction.stress_error() > -0.02) break;
  }
  stop_walls(sim);
}

}  // namespace

HoldState hold_isotropic(Simulation& sim, const HoldCriteria& c,
                         const std::function<bool(const HoldState&)>& on_check) {
  const double t_end = sim.time() + c.max_time;
  const AxisControl held{AxisMode::stress, c.confining_stress};
  BoxController servo(
      BoxControlSettings{{held, held, held}, ServoRegime::compaction, 0.0, c.max_strain_rate});
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
  }
  stop_walls(sim);
  return state;
}

Specimen prepare_cuboid_specimen(const SpecimenSettings& s, PairTable table, Progress* progress) {
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
  // Steering: compact frictionless until the target solid fraction is reached, then switch the
  // measured friction on so the packing locks in; without a target, the particles' own friction.
  out.compaction_friction = s.target_solid_fraction ? 0.0 : glass.friction;
  out.compaction_restitution = std::min(s.compaction_restitution, glass.restitution);
  set_compaction_contacts(table, original, s, s.target_solid_fraction ? 0.0 : -1.0,
                          s.compaction_restitution);
  // The step must be stable for the compaction contacts (more damped) and the measured ones
  // (restored at the end), by the one rule of contact/stability.hpp.
  SimulationSettings settings;
  const MaterialTimeStep step = specimen_time_step(s, original, r_min);
  PairTable measured_friction = table;
  set_compaction_contacts(measured_friction, original, s, -1.0, s.compaction_restitution);
  settings.time_step = std::min(
      {step.time_step, stable_time_step(step.time_step, table, s.bead_material, r_min).time_step,
       stable_time_step(step.time_step, measured_friction, s.bead_material, r_min).time_step});
  // below s.dt_fraction if stability lowered it
  settings.dt_fraction = settings.time_step / step.collision_duration;
  settings.skin = verlet_skin(s.diameter);
  settings.step_key = SimulationSettings::StepKey::lab_test;
  Simulation sim(std::move(particles),
                 cuboid_walls(placement.low, placement.high, s.lateral_material, s.platen_material),
                 table, settings);
  bool friction_restored = !s.target_solid_fraction;
  const char* stage = s.compaction == Compaction::affine ? "compacting" : "preparing";
  const auto steer = [&](const HoldState& state) {
    if (interrupt_requested())
      throw Interrupted("interrupted while preparing the specimen: nothing was saved");
    const bool settled =
        state.max_stress_error < s.stress_tolerance && state.unbalanced < s.unbalanced_tolerance;
    if (!friction_restored && (state.solid_fraction >= *s.target_solid_fraction || settled)) {
      // Target reached, or the frictionless packing settled below it: it cannot get denser
      // at this stress, so the target is out of reach (reported).
      out.target_reached = state.solid_fraction >= *s.target_solid_fraction - 0.005;
      PairTable restored = sim.pair_table();
      set_compaction_contacts(restored, original, s, -1.0, s.compaction_restitution);
      sim.set_pair_table(std::move(restored));
      friction_restored = true;
    }
    if (progress)
      progress->update(
          std::min(1.0, sim.time() / s.max_time),
          fmt::format("{}: phi = {:.4f}, wall stress error {:.2f} %, unbalanced {:.1e}", stage,
                      state.solid_fraction, 100 * state.max_stress_error, state.unbalanced));
    return friction_restored;
  };
  const HoldCriteria criteria{s.confining_stress, s.max_strain_rate, s.stress_tolerance,
                              s.unbalanced_tolerance, s.max_time};
  if (s.compaction == Compaction::affine) {
    compact_affinely(sim, criteria, steer);
    stage = "holding";
  }
  const HoldState held = hold_isotropic(sim, criteria, steer);
  out.equilibrium_reached = held.reached;
  out.low = box_low(sim.walls());
  out.high = box_high(sim.walls());
  out.solid_fraction = solid_fraction(sim.particles(), box_volume(sim.walls()));
  out.coordination_number = coordination_number(sim);
  out.unbalanced_force_ratio = unbalanced_force_ratio(sim);
  out.max_stress_error = held.max_stress_error;
  out.simulated_time = sim.time();
  // Particles in id order, at rest (velocities dropped: the specimen is in equilibrium).
  const ParticleStore& p = sim.particles();
  for (size_t i : indices_by_id(p))
    out.particles.add(p.id[i], p.material[i], p.radius[i], s.density, p.position[i], {}, {}, false);
  return out;
}

void save_specimen(const std::string& path, const Specimen& s) {
  std::string text =
      fmt::format("# grainlab specimen: box low {} {} {} high {} {} {}\nid,material,radius,x,y,z\n",
                  exact(s.low.x), exact(s.low.y), exact(s.low.z), exact(s.high.x), exact(s.high.y),
                  exact(s.high.z));
  const ParticleStore& p = s.particles;
  for (size_t i = 0; i < p.size(); ++i)
    text += fmt::format("{},{},{},{},{},{}\n", p.id[i], p.material[i], exact(p.radius[i]),
                        exact(p.position[i].x), exact(p.position[i].y), exact(p.position[i].z));
  write_file_atomically(path, text);
}

Specimen load_specimen(const std::string& path, double density, int bead_material) {
  std::ifstream in(path);
  if (!in) throw ConfigError(fmt::format("{}: cannot read the specimen file", path));
  Specimen s;
  std::string line;
  int number = 1;
  if (!std::getline(in, line) ||
      std::sscanf(line.c_str(), "# grainlab specimen: box low %lf %lf %lf high %lf %lf %lf",
                  &s.low.x, &s.low.y, &s.low.z, &s.high.x, &s.high.y, &s.high.z) != 6)
    throw ConfigError(
        fmt::format("{} line 1: expected '# grainlab specimen: box low X Y Z high X Y Z'", path));
  for (int a = 0; a < 3; ++a)
    if (!(std::isfinite(s.low[a]) && std::isfinite(s.high[a]) && s.high[a] > s.low[a]))
      throw ConfigError(fmt::format("{} line 1: expected a finite box with high > low", path));
  std::getline(in, line);
  ++number;
  if (line != "id,material,radius,x,y,z")
    throw ConfigError(fmt::format("{} line 2: expected the header id,material,radius,x,y,z", path));
  while (std::getline(in, line)) {
    ++number;
    if (line.empty()) continue;
    long long id;
    long long material;
    double r, x, y, z;
    char rest;
    if (std::sscanf(line.c_str(), "%lld,%lld,%lf,%lf,%lf,%lf%c", &id, &material, &r, &x, &y, &z,
                    &rest) != 6 ||
        id != static_cast<long long>(s.particles.size()) || !(r > 0) || !std::isfinite(r))
      throw ConfigError(fmt::format(
          "{} line {}: expected id,material,radius,x,y,z with ids 0, 1, 2, ... and a finite "
          "radius > 0",
          path, number));
    if (material != bead_material)
      throw ConfigError(
          fmt::format("{} line {}: material {} is not the bead material of the config (index {})",
                      path, number, material, bead_material));
    const Vec3 centre{x, y, z};
    for (int a = 0; a < 3; ++a)
      if (!(centre[a] >= s.low[a] && centre[a] <= s.high[a]))
        throw ConfigError(
            fmt::format("{} line {}: the centre ({}, {}, {}) is not a finite point inside the box",
                        path, number, x, y, z));
    if (s.particles.size() >= 20'000'000)
      throw ConfigError(fmt::format("{} line {}: more than 20 million particles", path, number));
    s.particles.add(static_cast<uint32_t>(id), static_cast<int32_t>(material), r, density, centre,
                    {}, {}, false);
  }
  if (s.particles.size() == 0) throw ConfigError(fmt::format("{}: no particles", path));
  s.solid_fraction = solid_fraction(
      s.particles, (s.high.x - s.low.x) * (s.high.y - s.low.y) * (s.high.z - s.low.z));
  return s;
}

}  // namespace grainlab
