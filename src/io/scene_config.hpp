// The scene configuration (`grainlab run SCENE.toml`), read and validated from TOML. The schema
// is documented in docs/scene-schema.md. Everything is SI after reading.
#pragma once

#include <toml++/toml.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "contact/material.hpp"
#include "core/vec3.hpp"
#include "geometry/wall.hpp"
#include "io/checkpoint_clock.hpp"

namespace grainlab {

struct PairEntry {
  int material_a = 0, material_b = 0;
  PairProperties properties;
  int line = 0;
};

struct ParticleEntry {
  int material = 0;
  double radius = 0.0;
  Vec3 position, velocity, angular_velocity;
  bool fixed = false;
  int line = 0;     // in the config, or in the packing file
  int source = -1;  // index into SceneConfig::packing_files; -1: the config itself
};

enum class RegionShape { box, cylinder };

// N random non-overlapping spheres, diameters uniform in [diameter_min, diameter_max].
struct ParticleBatch {
  int material = 0;
  long count = 0;
  double diameter_min = 0.0, diameter_max = 0.0;
  RegionShape region = RegionShape::box;
  Vec3 box_min, box_max;  // box
  Vec3 cylinder_base;     // cylinder: centre of the bottom face, axis along z
  double cylinder_radius = 0.0, cylinder_height = 0.0;
  Vec3 velocity;
  int line = 0;
};

// Speed cap of a servo-held wall (`[[wall]] max_speed`) when none is given, m/s: the speed at which
// a wall that touches nothing approaches the particles, and the largest speed it follows them at.
inline constexpr double default_wall_servo_max_speed = 0.01;

// What a [[wall]] adds to its geometry and motion (geometry/wall.hpp): the area its normal stress
// is measured on, and a target normal stress held by a servo (io/wall_control.hpp).
struct WallLoad {
  std::optional<double> area;  // m^2: rectangle, its own; plane, the `area` key; cylinder, none
  std::optional<double> target_stress;              // Pa, compressive positive
  double max_speed = default_wall_servo_max_speed;  // m/s, servo speed cap
};

struct OutputSettings {
  double interval = 0.0;  // s
  bool trace_all = true;
  std::vector<uint32_t> trace_ids;  // when not trace_all
  bool vtk = false;
  double vtk_interval = 0.0;                                   // s
  double checkpoint_interval = default_checkpoint_interval_s;  // s of wall time
};

struct SceneConfig {
  std::string file;
  double duration = 0.0;            // s
  std::optional<double> time_step;  // s, explicit dt
  int time_step_line = 0;           // line of simulation.dt
  double dt_fraction = 0.1;         // dt = dt_fraction * t_c
  Vec3 gravity;                     // m/s^2
  uint64_t seed = 1;
  std::optional<double> skin;  // m
  double max_speed = 100.0;    // m/s
  std::vector<Material> materials;
  std::vector<PairEntry> pairs;
  std::vector<ParticleEntry> particles;    // [[particle]] entries, then packing-file rows
  std::vector<std::string> packing_files;  // [[particles]] file = ..., resolved paths
  std::vector<ParticleBatch> batches;
  std::vector<Wall> walls;
  std::vector<int> wall_lines;
  std::vector<WallLoad> wall_loads;  // one per wall
  OutputSettings output;
  toml::table source;  // the file as read, echoed into summary.json
};

// Reads and validates a scene file; throws ConfigError naming file, line and key.
SceneConfig load_scene(const std::string& path);

// The sections one by one, for virtual laboratory tests (src/lab) that build part of the scene
// themselves. Each fills its part of `c` (c.file names the file in messages).
void read_simulation(const toml::table& root, SceneConfig& c);
void read_materials(const toml::table& root, SceneConfig& c);
void read_pairs(const toml::table& root, SceneConfig& c);
void read_particles(const toml::table& root, SceneConfig& c);  // requires at least one particle
void read_walls(const toml::table& root, SceneConfig& c);
void read_output(const toml::table& root, SceneConfig& c);

}  // namespace grainlab
