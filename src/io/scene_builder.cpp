#include "io/scene_builder.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "contact/time_step.hpp"
#include "core/random_insertion.hpp"
#include "io/config_error.hpp"

namespace grainlab {

PairTable build_pair_table(const SceneConfig& c) {
  PairTable table(c.materials);
  for (const PairEntry& p : c.pairs) {
    try {
      table.set(p.material_a, p.material_b, p.properties);
    } catch (const std::invalid_argument& e) {
      throw ConfigError(fmt::format("{} line {}: pair {}-{}: {}", c.file, p.line,
                                    c.materials[p.material_a].name, c.materials[p.material_b].name,
                                    e.what()));
    }
  }
  return table;
}

ParticleStore build_particles(const SceneConfig& c) {
  std::vector<Sphere> spheres;
  std::vector<int> material, line, source;
  std::vector<bool> fixed;
  spheres.reserve(c.particles.size());
  for (const ParticleEntry& p : c.particles) {
    spheres.push_back({p.position, p.radius});
    material.push_back(p.material);
    line.push_back(p.line);
    source.push_back(p.source);
    fixed.push_back(p.fixed);
  }
  // "FILE line N" of particle i: the config, or the packing file it was read from.
  auto where = [&](size_t i) {
    return fmt::format("{} line {}", source[i] < 0 ? c.file : c.packing_files[source[i]], line[i]);
  };
  // Overlaps among explicit particles (generated ones never overlap): a prepared specimen carries
  // overlaps of ~1e-5 of a radius, so only more than 1 % of the smaller radius is an error. A cell
  // grid makes the check linear in the particle count (10^6 beads in about a second).
  const size_t explicit_count = c.particles.size();
  if (explicit_count > 0) {
    double largest = 0.0;
    for (const Sphere& s : spheres) largest = std::max(largest, s.radius);
    SphereGrid grid(2.0 * largest);
    for (size_t i = 0; i < explicit_count; ++i) {
      grid.find_near(spheres[i], [&](uint32_t j) {
        const double gap =
            norm(spheres[i].centre - spheres[j].centre) - spheres[i].radius - spheres[j].radius;
        if (-gap > 0.01 * std::min(spheres[i].radius, spheres[j].radius))
          throw ConfigError(fmt::format(
              "{}: particle[{}] overlaps particle[{}] ({}) by {:.3g} m, more than 1 % of the "
              "smaller radius: move them apart",
              where(i), i + 1, j + 1, where(j), -gap));
        return false;
      });
      grid.add(spheres[i], static_cast<uint32_t>(i));
    }
  }
  std::mt19937_64 rng(c.seed);
  for (const ParticleBatch& b : c.batches) {
    InsertionRegion region;
    region.cylinder = b.region == RegionShape::cylinder;
    region.box_min = b.box_min;
    region.box_max = b.box_max;
    region.base = b.cylinder_base;
    region.radius = b.cylinder_radius;
    region.height = b.cylinder_height;
    const long placed =
        insert_random_spheres(spheres, region, b.count, b.diameter_min, b.diameter_max, rng);
    if (placed < b.count)
      throw ConfigError(fmt::format(
          "{} line {}: particles.count: only {} of {} particles fit in the region without overlap "
          "(random insertion saturates near a solid fraction of 0.35): enlarge the region or "
          "lower the count",
          c.file, b.line, placed, b.count));
    material.insert(material.end(), static_cast<size_t>(placed), b.material);
    line.insert(line.end(), static_cast<size_t>(placed), b.line);
    source.insert(source.end(), static_cast<size_t>(placed), -1);
    fixed.insert(fixed.end(), static_cast<size_t>(placed), false);
  }
  for (size_t i = 0; i < spheres.size(); ++i)
    for (size_t w = 0; w < c.walls.size(); ++w)
      if (!inside_wall(c.walls[w], spheres[i].centre))
        throw ConfigError(fmt::format(
            "{}: particle[{}] at ({:.4g}, {:.4g}, {:.4g}) m lies outside wall[{}] '{}' ({} line "
            "{}): particles must be on the side the wall's normal points to (inside a cylinder)",
            where(i), i + 1, spheres[i].centre.x, spheres[i].centre.y, spheres[i].centre.z, w + 1,
            c.walls[w].name, c.file, c.wall_lines[w]));

  ParticleStore store;
  for (size_t i = 0; i < spheres.size(); ++i) {
    const Vec3 v = i < explicit_count ? c.particles[i].velocity : Vec3{};
    const Vec3 w = i < explicit_count ? c.particles[i].angular_velocity : Vec3{};
    store.add(static_cast<uint32_t>(i), material[i], spheres[i].radius,
              *c.materials[material[i]].density, spheres[i].centre, v, w, fixed[i]);
  }
  // Batch velocities.
  size_t k = explicit_count;
  for (const ParticleBatch& b : c.batches)
    for (long n = 0; n < b.count; ++n, ++k) store.velocity[k] = b.velocity;
  return store;
}

namespace {

double sphere_mass(double radius, double density) {
  return density * 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
}

DerivedPair derive(const SceneConfig& c, const PairTable& table, int a, int b, double ra, double rb,
                   bool wall) {
  const PairParams& p = table(a, b);
  DerivedPair d;
  d.material_a = c.materials[a].name;
  d.material_b = c.materials[b].name;
  d.wall_pair = wall;
  d.radius_a = ra;
  d.radius_b = wall ? 0.0 : rb;
  const double ma = sphere_mass(ra, *c.materials[a].density);
  d.effective_radius = wall ? ra : ra * rb / (ra + rb);
  d.effective_mass = wall ? ma : 1.0 / (1.0 / ma + 1.0 / sphere_mass(rb, *c.materials[b].density));
  d.normal_stiffness = p.stiffness_per_radius * d.effective_radius;
  d.sliding_stiffness = p.rns * d.normal_stiffness;
  d.rolling_stiffness = 4.0 * d.effective_radius * d.effective_radius * d.sliding_stiffness;
  d.normal_damping = 2.0 * p.damping_ratio * std::sqrt(d.normal_stiffness * d.effective_mass);
  d.sliding_damping = p.rzs * d.normal_damping;
  d.damping_ratio = p.damping_ratio;
  d.damping_ratio_textbook = p.textbook_damping_ratio;
  d.restitution = p.restitution;
  d.friction = p.friction;
  d.arf = p.arf;
  const double overlap = 0.005 * d.effective_radius;
  d.rolling_moment_per_force_at_half_percent =
      p.arf * (wall ? std::sqrt(ra * ra - (ra - overlap) * (ra - overlap))
                    : std::sqrt(std::max(0.0, d.effective_radius * 2.0 * overlap)));
  // t_c = pi / omega_d with the textbook zeta; equals Eq. 11 for equal spheres and on a wall.
  const double l = std::log(p.restitution);
  d.collision_duration = std::sqrt((std::numbers::pi * std::numbers::pi + l * l) *
                                   d.effective_mass / d.normal_stiffness);
  const ContactBody body_b = wall ? ContactBody{} : ContactBody{rb, *c.materials[b].density};
  d.spring_dashpots = spring_dashpots(p, {ra, *c.materials[a].density}, body_b);
  d.step_limit = step_limit(d.spring_dashpots);
  return d;
}

}  // namespace

std::vector<DerivedPair> derive_pairs(const SceneConfig& c, const PairTable& table,
                                      const ParticleStore& particles) {
  // Smallest radius of each particle material in use.
  std::vector<double> min_radius(c.materials.size(), 0.0);
  for (size_t i = 0; i < particles.size(); ++i) {
    double& r = min_radius[particles.material[i]];
    r = r == 0.0 ? particles.radius[i] : std::min(r, particles.radius[i]);
  }
  std::vector<DerivedPair> out;
  auto require = [&](int a, int b) {
    if (!table(a, b).defined)
      throw ConfigError(fmt::format(
          "{}: no [[pair]] for materials \"{}\" and \"{}\", which touch in this scene: add "
          "[[pair]] materials = [\"{}\", \"{}\"] with restitution and friction",
          c.file, c.materials[a].name, c.materials[b].name, c.materials[a].name,
          c.materials[b].name));
  };
  const int m = static_cast<int>(c.materials.size());
  for (int a = 0; a < m; ++a) {
    if (min_radius[a] == 0.0) continue;
    for (int b = a; b < m; ++b) {
      if (min_radius[b] == 0.0) continue;
      // A material alone in the scene (one bead) cannot touch itself: its pair is reported when
      // defined but not required.
      const bool can_touch =
          a != b || std::count(particles.material.begin(), particles.material.end(), a) > 1;
      if (!can_touch && !table(a, b).defined) continue;
      if (can_touch) require(a, b);
      out.push_back(derive(c, table, a, b, min_radius[a], min_radius[b], false));
      out.back().can_touch = can_touch;
    }
    std::vector<bool> seen(m, false);
    for (const Wall& w : c.walls) {
      if (seen[w.material]) continue;
      seen[w.material] = true;
      require(a, w.material);
      out.push_back(derive(c, table, a, w.material, min_radius[a], 0.0, true));
    }
  }
  return out;
}

TimeStepChoice choose_time_step(const SceneConfig& c, const std::vector<DerivedPair>& pairs) {
  TimeStepChoice t;
  t.collision_duration = INFINITY;
  for (const DerivedPair& p : pairs) {
    t.collision_duration = std::min(t.collision_duration, p.collision_duration);
    if (p.can_touch && p.step_limit.time_step < t.stable_limit) {
      t.stable_limit = p.step_limit.time_step;
      t.stable_limit_set_by = describe(p.step_limit.limiting, p.material_a + "-" + p.material_b);
      t.stable_limit_damped = p.step_limit.limiting.damping_ratio > 0.0;
    }
  }
  if (c.time_step) {
    t.time_step = *c.time_step;
    t.explicit_dt = true;
    t.dt_fraction = std::isfinite(t.collision_duration) ? t.time_step / t.collision_duration : 0.0;
    if (t.time_step > t.stable_limit)
      throw ConfigError(fmt::format(
          "{} line {}: simulation.dt: {:.4g} s is above the stable step {:.4g} s of {} (held by "
          "four such contacts, as in a packing; docs/contact-model.md): lower simulation.dt{}",
          c.file, c.time_step_line, t.time_step, t.stable_limit, t.stable_limit_set_by,
          t.stable_limit_damped ? ", or the damping" : ""));
  } else {
    if (!std::isfinite(t.collision_duration))
      throw ConfigError(
          fmt::format("{}: simulation: no contacts possible, so no collision duration "
                      "to derive dt from: set simulation.dt",
                      c.file));
    t.dt_fraction = c.dt_fraction;
    t.time_step = c.dt_fraction * t.collision_duration;
    if (t.time_step > t.stable_limit) {  // a stiffer or more damped piece than the normal one
      t.time_step = t.stable_limit;
      t.dt_fraction = t.time_step / t.collision_duration;
      t.limited_by_stability = true;
    }
  }
  return t;
}

SimulationSettings simulation_settings(const SceneConfig& c, const TimeStepChoice& dt,
                                       const ParticleStore& particles) {
  SimulationSettings s;
  s.time_step = dt.time_step;
  s.dt_fraction = dt.dt_fraction;
  s.gravity = c.gravity;
  double max_radius = 0.0;
  for (double r : particles.radius) max_radius = std::max(max_radius, r);
  s.skin = c.skin ? *c.skin : verlet_skin(2.0 * max_radius);
  s.max_speed = c.max_speed;
  return s;
}

}  // namespace grainlab
