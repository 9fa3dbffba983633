#include "lab/sliding_friction.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "calibrate/friction_fits.hpp"
#include "contact/stability.hpp"
#include "contact/time_step.hpp"
#include "core/random_insertion.hpp"
#include "io/checkpoint_file.hpp"
#include "io/config_error.hpp"
#include "io/progress.hpp"
#include "lab/deposition.hpp"
#include "lab/sliding_friction_checkpoint.hpp"

namespace grainlab {
namespace {

Wall box_plane(int material, const Vec3& point, const Vec3& normal) {
  Wall w;
  w.shape = WallShape::plane;
  w.material = material;
  w.point = point;
  w.normal = normal;
  finish_wall_geometry(w);
  return w;
}

struct Bed {
  ParticleStore particles;
  std::vector<Wall> walls;
  double top = 0.0;  // m
};

SimulationSettings settings_for(const SlidingFrictionSettings& s, const PairTable& table, int bead,
                                double density) {
  const double r_min = 0.5 * s.diameter * 0.99;
  // The bed's box is made of the bead material; the slider touches the beads.
  const MaterialTimeStep step = material_time_step(
      s.dt_fraction, table, bead, {bead, table.find(s.slider_material)}, r_min, density);
  SimulationSettings out;
  out.time_step = step.time_step;
  out.dt_fraction = step.dt_fraction;  // below s.dt_fraction if stability lowered it
  out.gravity = {0.0, 0.0, -s.gravity};
  out.skin = verlet_skin(s.diameter);
  out.step_key = SimulationSettings::StepKey::lab_test;  // advice names test.dt_fraction
  return out;
}

// Where the slider starts: centred across the bed, its rear edge one diameter from the back wall.
// Covering the bed: centred so that it overhangs the back wall by the pull and a diameter.
Vec3 slider_start(const SlidingFrictionSettings& s, double bed_top) {
  const double x = s.slider_covers_bed ? 0.5 * (s.bed_length - s.slide_distance)
                                       : s.diameter + 0.5 * s.slider_length;
  return {x, 0.5 * s.bed_width, bed_top + 0.02 * s.diameter};
}

Bed fixed_bead_patch(const SlidingFrictionSettings& s, int bead, double density) {
  const double d = s.diameter, r = 0.5 * d;
  const Vec3 c = slider_start(s, d);
  const double x_lo = c.x - 0.5 * s.slider_length + s.slide_distance + 0.5 * d;
  const double x_hi = c.x + 0.5 * s.slider_length - 0.5 * d;
  const double half_width = 0.5 * (s.bed_width - 2.0 * d) - 0.5 * d;
  Bed bed;
  uint32_t id = 0;
  for (double x = x_lo; x <= x_hi; x += d)
    for (double y = c.y - half_width; y <= c.y + half_width + 1e-12; y += d)
      bed.particles.add(id++, bead, r, density, {x, y, r}, {}, {}, true);
  if (bed.particles.size() == 0)
    throw std::runtime_error(
        "sliding friction: the slider is too short for the slide distance (no fixed bead stays "
        "under it)");
  bed.top = d;
  return bed;
}

// The box of a deposited bed: floor, ends and sides, of the bead material.
std::vector<Wall> bed_walls(const SlidingFrictionSettings& s, int bead) {
  const double L = s.bed_length, W = s.bed_width;
  return {box_plane(bead, {0, 0, 0}, {0, 0, 1}), box_plane(bead, {0, 0, 0}, {1, 0, 0}),
          box_plane(bead, {L, 0, 0}, {-1, 0, 0}), box_plane(bead, {0, 0, 0}, {0, 1, 0}),
          box_plane(bead, {0, W, 0}, {0, -1, 0})};
}

// A pull's simulation restored from a checkpoint; ConfigError naming the file when the state is
// damaged or is not this test's pull: a bed with its slider (`wall_count` walls), integrated with
// the `expected` settings, the slider pair at the pull's friction.
Simulation restored_pull(const PullState& pull, const PairTable& table, size_t wall_count,
                         const SimulationSettings& expected, int bead, int slider,
                         const std::string& file) {
  try {
    StateReader in(pull.simulation);
    Simulation sim(in, table);
    const SimulationSettings& got = sim.settings();
    if (!in.at_end() || sim.walls().size() != wall_count || got.time_step != expected.time_step ||
        !(got.gravity == expected.gravity) || got.skin != expected.skin ||
        sim.pair_table()(bead, slider).friction != pull.friction)
      throw std::runtime_error("not the state of this test's pull");
    return sim;
  } catch (const std::runtime_error& e) {
    throw unresumable_checkpoint(file, e);
  }
}

Bed make_bed(const SlidingFrictionSettings& s, const PairTable& table, int bead, double density) {
  if (s.fixed_bed) return fixed_bead_patch(s, bead, density);
  const double d = s.diameter, L = s.bed_length, W = s.bed_width;
  const long count =
      static_cast<long>(s.layers) * static_cast<long>(L / d) * static_cast<long>(W / d);
  // Insert loosely (solid fraction 0.2) above the floor, then let the beads fall and settle.
  const double insert_height = count * (M_PI / 6.0) * d * d * d / (0.2 * L * W);
  std::vector<Sphere> spheres;
  std::mt19937_64 rng(s.seed);
  InsertionRegion region;
  region.box_min = {0, 0, 0};
  region.box_max = {L, W, insert_height};
  if (insert_random_spheres(spheres, region, count, 0.99 * d, 1.01 * d, rng) < count)
    throw std::runtime_error("sliding friction: could not insert the bed's beads");
  Bed bed;
  for (size_t i = 0; i < spheres.size(); ++i)
    bed.particles.add(static_cast<uint32_t>(i), bead, spheres[i].radius, density, spheres[i].centre,
                      {}, {}, false);
  bed.walls = bed_walls(s, bead);
  DepositionSettings dep;
  dep.min_time = std::sqrt(2.0 * insert_height / s.gravity);
  dep.max_time = dep.min_time + 0.2;
  dep.rest_speed = 1e-3;
  DepositionResult r = deposit(std::move(bed.particles), bed.walls, table,
                               settings_for(s, table, bead, density), dep);
  bed.particles = std::move(r.particles);
  for (Vec3& v : bed.particles.velocity) v = {};
  for (Vec3& w : bed.particles.angular_velocity) w = {};
  for (size_t i = 0; i < bed.particles.size(); ++i)
    bed.top = std::max(bed.top, bed.particles.position[i].z + bed.particles.radius[i]);
  return bed;
}

LoadRun pull_slider(const Bed& bed, const SlidingFrictionSettings& s, const PairTable& table,
                    int bead, int slider_material, double density, double load,
                    SlidingFrictionCheckpoints* checkpoints) {
  const double d = s.diameter, W = s.bed_width;
  const double slider_length = s.slider_length;
  Wall slider;
  slider.name = "slider";
  slider.shape = WallShape::rectangle;
  slider.material = slider_material;
  slider.point = slider_start(s, bed.top);
  slider.normal = {0, 0, 1};
  slider.axis_u = {1, 0, 0};
  slider.half_u = 0.5 * slider_length;
  slider.half_v = 0.5 * W - (s.slider_side_gap >= 0.0 ? s.slider_side_gap : 0.2 * d);
  slider.mass = s.slider_mass;
  finish_wall_geometry(slider);
  std::vector<Wall> walls = bed.walls;
  walls.push_back(slider);
  const size_t k = walls.size() - 1;
  const double friction = table(bead, slider_material).friction;
  std::optional<PullState> resumed =
      checkpoints ? checkpoints->take_pull(friction, load) : std::nullopt;
  const SimulationSettings settings = settings_for(s, table, bead, density);
  Simulation sim = resumed ? restored_pull(*resumed, table, walls.size(), settings, bead,
                                           slider_material, checkpoints->path())
                           : Simulation(bed.particles, walls, table, settings);

  // The rope and force sensor: a spring with a parallel dashpot that damps the slider-rope
  // oscillator critically (c = 2 sqrt(k m)), as the slow laboratory pull is quasi-static; the
  // slider runs on a guide (no sideways motion).
  const double rope_damping = 2.0 * std::sqrt(s.spring_stiffness * s.slider_mass);
  double anchor = resumed ? resumed->anchor : slider.point.x, anchor_speed = 0.0;
  const double guide_y = slider.point.y;
  auto step = [&] {
    const Wall& w = sim.walls()[k];
    sim.set_wall_external_force(k, {s.spring_stiffness * (anchor - w.point.x) +
                                        rope_damping * (anchor_speed - w.velocity.x),
                                    0.0, -load});
    sim.step();
    const Wall& after = sim.walls()[k];
    sim.set_wall_velocity(k, {after.velocity.x, 0.0, after.velocity.z});
    sim.set_wall_point(k, {after.point.x, guide_y, after.point.z});
  };
  // Load: the slider settles on the bed under P with the rope anchored where it starts.
  const double dt = sim.settings().time_step;
  const long chunk = std::max(1L, static_cast<long>(2e-4 / dt));
  LoadRun run;
  run.load = load;
  double start_anchor = 0.0, t0 = 0.0;
  long n = 0;  // steps of the pull
  // The pull's state for a checkpoint (the simulation between two steps).
  const auto now = [&](bool pulling) {
    StateWriter state;
    sim.save_state(state);
    return PullState{friction, load, pulling,    anchor,       start_anchor,
                     t0,       n,    run.record, state.bytes()};
  };
  if (!resumed || !resumed->pulling) {
    while (sim.time() < 0.03) {
      for (long i = 0; i < chunk; ++i) step();
      if (sim.time() > 0.002 && std::abs(sim.walls()[k].velocity.z) < 1e-4) break;
      if (checkpoints) checkpoints->poll([&] { return now(false); });
    }
    start_anchor = anchor, t0 = sim.time();
  } else {
    start_anchor = resumed->start_anchor, t0 = resumed->start_time;
    n = resumed->pull_steps, run.record = std::move(resumed->record);
  }
  // Pull: the far end of the rope moves at V; the rope force is the spring's extension.
  const double duration = s.slide_distance / s.speed;
  const long record_every = std::max(1L, static_cast<long>(duration / dt / 400));
  anchor_speed = s.speed;
  while (sim.time() - t0 < duration) {
    anchor = start_anchor + s.speed * (sim.time() - t0);
    step();
    if (n % record_every == 0) {
      const Wall& w = sim.walls()[k];
      anchor = start_anchor + s.speed * (sim.time() - t0);  // rope end at the slider's time
      const double rope_force =
          s.spring_stiffness * (anchor - w.point.x) + rope_damping * (anchor_speed - w.velocity.x);
      run.record.push_back({sim.time() - t0, anchor - start_anchor, rope_force, w.point.z});
    }
    ++n;
    if (checkpoints && n % 256 == 0) checkpoints->poll([&] { return now(true); });
  }
  // Steady sliding: the second half of the pull.
  double sum = 0.0, sum2 = 0.0;
  size_t rows = 0;
  for (const auto& r : run.record)
    if (r[1] >= 0.5 * s.slide_distance) {
      sum += r[2];
      sum2 += r[2] * r[2];
      ++rows;
    }
  run.mean_force = sum / rows;
  run.force_sd = std::sqrt(std::max(0.0, sum2 / rows - run.mean_force * run.mean_force));
  return run;
}

}  // namespace

double sliding_time_step(const SlidingFrictionSettings& s, const PairTable& table, double density) {
  return settings_for(s, table, table.find(s.bead_material), density).time_step;
}

SlidingFrictionResult simulate_sliding_friction(const SlidingFrictionSettings& s,
                                                const PairTable& table, double density,
                                                Progress* progress,
                                                SlidingFrictionCheckpoints* checkpoints) {
  const int bead = table.find(s.bead_material), slider = table.find(s.slider_material);
  SlidingFrictionResult out;
  out.friction_input = table(bead, slider).friction;
  // A deposited bed: from the checkpoint of an interrupted run, else deposited (and recorded
  // there). A fixed patch is laid again (at once, and exactly the same).
  const bool keep = checkpoints && !s.fixed_bed;
  const SavedBed* saved = keep ? checkpoints->bed(out.friction_input) : nullptr;
  Bed bed;
  if (saved) {
    bed.particles = saved->particles, bed.top = saved->top;
    bed.walls = bed_walls(s, bead);
  } else {
    bed = make_bed(s, table, bead, density);
    if (keep) checkpoints->record_bed(out.friction_input, bed.particles, bed.top);
  }
  out.bead_count = static_cast<int>(bed.particles.size());
  out.bed_height = bed.top;
  out.time_step = settings_for(s, table, bead, density).time_step;
  std::vector<calibrate::LoadPoint> points;
  for (size_t i = 0; i < s.loads.size(); ++i) {
    const LoadRun* done =
        checkpoints ? checkpoints->finished_pull(out.friction_input, s.loads[i]) : nullptr;
    out.runs.push_back(
        done ? *done : pull_slider(bed, s, table, bead, slider, density, s.loads[i], checkpoints));
    if (checkpoints && !done) checkpoints->record_pull(out.friction_input, out.runs.back());
    points.push_back({i + 1, s.speed * 6e4, s.loads[i], out.runs.back().mean_force});
    if (progress)
      progress->update(
          double(i + 1) / s.loads.size(),
          fmt::format("P = {:.3g} N: F = {:.4g} N", s.loads[i], out.runs.back().mean_force));
  }
  if (points.size() >= 2) {
    const calibrate::OriginFit fit = calibrate::fit_through_origin(points);
    out.friction_apparent = fit.slope;
    out.friction_apparent_se = fit.standard_error;
    out.r_squared = fit.r_squared;
  } else {
    out.friction_apparent = out.runs[0].mean_force / out.runs[0].load;
  }
  return out;
}

}  // namespace grainlab
