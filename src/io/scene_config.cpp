#include "io/scene_config.hpp"

#include <fmt/format.h>

#include <filesystem>

#include "io/packing_csv.hpp"
#include "io/toml_reader.hpp"

namespace grainlab {
namespace {

// Physical ranges of the material constants, checked after unit conversion: a value outside is a
// unit slip (a density in g/cm^3 given as kg/m^3, E in MPa given as GPa), not a material.
constexpr double min_youngs_modulus = 1e3, max_youngs_modulus = 1e13;  // Pa: gels to diamond x 10
constexpr double min_density = 1.0, max_density = 1e5;                 // kg/m^3
constexpr const char* youngs_modulus_range =
    "expected Young's modulus E in [1 kPa, 10 TPa] (from soft gels to ten times diamond's)";

const toml::array* array_of_tables(const toml::table& root, const std::string& key,
                                   const std::string& file) {
  const toml::node* n = root.get(key);
  if (!n) return nullptr;
  const toml::array* a = n->as_array();
  if (!a || !a->is_array_of_tables())
    throw ConfigError(fmt::format("{} line {}: {}: expected [[{}]] tables", file,
                                  n->source().begin.line, key, key));
  return a;
}

int material_index(TableReader& r, const std::string& key, const std::string& name,
                   const std::vector<Material>& materials) {
  for (size_t i = 0; i < materials.size(); ++i)
    if (materials[i].name == name) return static_cast<int>(i);
  std::string known;
  for (const Material& m : materials) known += (known.empty() ? "" : ", ") + m.name;
  r.fail(key, fmt::format("unknown material \"{}\" (defined materials: {})", name,
                          known.empty() ? "none" : known));
}

}  // namespace

void read_simulation(const toml::table& root, SceneConfig& c) {
  const toml::node* n = root.get("simulation");
  if (!n || !n->is_table())
    throw ConfigError(fmt::format("{}: [simulation] table missing (required: duration)", c.file));
  TableReader r(*n->as_table(), c.file, "simulation");
  c.duration = r.number("duration", Quantity::time);
  if (!(c.duration > 0.0)) r.fail("duration", "expected a duration > 0 s");
  c.time_step = r.optional_number("dt", Quantity::time);
  if (c.time_step) c.time_step_line = r.line_of("dt");
  if (c.time_step && !(*c.time_step > 0.0)) r.fail("dt", "expected a time step > 0 s");
  if (c.time_step && r.has("dt_fraction")) r.fail("dt", "give either dt or dt_fraction, not both");
  c.dt_fraction = r.number_or("dt_fraction", Quantity::dimensionless, 0.1);
  if (!(c.dt_fraction > 0.0 && c.dt_fraction <= 0.5))
    r.fail("dt_fraction",
           "expected a fraction of the collision duration in (0, 0.5] (default 0.1)");
  c.gravity = r.vec3_or("gravity", Quantity::acceleration, {});
  const long seed = r.integer_or("seed", 1);
  if (seed < 0) r.fail("seed", "expected an integer >= 0");
  c.seed = static_cast<uint64_t>(seed);
  c.skin = r.optional_number("skin", Quantity::length);
  if (c.skin && !(*c.skin > 0.0)) r.fail("skin", "expected a Verlet skin > 0 m");
  c.max_speed = r.number_or("max_speed", Quantity::velocity, 100.0);
  if (!(c.max_speed > 0.0)) r.fail("max_speed", "expected a speed > 0 m/s");
  r.finish();
}

void read_materials(const toml::table& root, SceneConfig& c) {
  const toml::array* a = array_of_tables(root, "material", c.file);
  if (!a || a->empty()) throw ConfigError(fmt::format("{}: no [[material]] defined", c.file));
  for (size_t k = 0; k < a->size(); ++k) {
    TableReader r(*a->get(k)->as_table(), c.file, fmt::format("material[{}]", k + 1));
    Material m;
    m.name = r.string("name");
    for (const Material& other : c.materials)
      if (other.name == m.name)
        r.fail("name", fmt::format("material \"{}\" defined twice", m.name));
    m.youngs_modulus = r.optional_number("youngs_modulus", Quantity::pressure);
    if (m.youngs_modulus && !(*m.youngs_modulus > 0.0))
      r.fail("youngs_modulus", "expected Young's modulus E > 0 Pa");
    if (m.youngs_modulus &&
        !(*m.youngs_modulus >= min_youngs_modulus && *m.youngs_modulus <= max_youngs_modulus))
      r.fail("youngs_modulus", youngs_modulus_range);
    m.poisson_ratio = r.optional_number("poisson_ratio", Quantity::dimensionless);
    if (m.poisson_ratio && !(*m.poisson_ratio > -1.0 && *m.poisson_ratio < 0.5))
      r.fail("poisson_ratio", "expected a Poisson ratio in (-1, 0.5)");
    m.density = r.optional_number("density", Quantity::density);
    if (m.density && !(*m.density > 0.0)) r.fail("density", "expected a density > 0 kg/m^3");
    if (m.density && !(*m.density >= min_density && *m.density <= max_density))
      r.fail("density",
             "expected a density in [1, 100000] kg/m^3 (from aerogels to the densest metals)");
    r.finish();
    c.materials.push_back(m);
  }
}

void read_pairs(const toml::table& root, SceneConfig& c) {
  const toml::array* a = array_of_tables(root, "pair", c.file);
  if (!a) return;
  for (size_t k = 0; k < a->size(); ++k) {
    TableReader r(*a->get(k)->as_table(), c.file, fmt::format("pair[{}]", k + 1));
    PairEntry p;
    p.line = r.line_of("");
    const auto names = r.strings("materials", 2);
    p.material_a = material_index(r, "materials", names[0], c.materials);
    p.material_b = material_index(r, "materials", names[1], c.materials);
    PairProperties& q = p.properties;
    q.restitution = r.number("restitution", Quantity::dimensionless);
    if (!(q.restitution > 0.0 && q.restitution <= 1.0))
      r.fail("restitution",
             fmt::format("expected a restitution coefficient e in (0, 1], got {}", q.restitution));
    q.friction = r.number("friction", Quantity::dimensionless);
    if (!(q.friction >= 0.0))
      r.fail("friction", fmt::format("expected a friction coefficient >= 0, got {}", q.friction));
    q.rns = r.number_or("rns", Quantity::dimensionless, 0.5);
    if (!(q.rns > 0.0)) r.fail("rns", "expected k_s/k_n > 0");
    q.rzs = r.number_or("rzs", Quantity::dimensionless, 0.0);
    if (!(q.rzs >= 0.0)) r.fail("rzs", "expected c_s/c_n >= 0");
    q.arf = r.number_or("arf", Quantity::dimensionless, 0.0);
    if (!(q.arf >= 0.0)) r.fail("arf", "expected a rolling friction coefficient >= 0");
    q.rolling_damping_ratio = r.number_or("rolling_damping_ratio", Quantity::dimensionless, -1.0);
    if (r.has("rolling_damping_ratio") && !(q.rolling_damping_ratio >= 0.0))
      r.fail("rolling_damping_ratio", "expected a damping ratio >= 0");
    q.twisting_friction = r.number_or("twisting_friction", Quantity::dimensionless, 0.0);
    if (!(q.twisting_friction >= 0.0)) r.fail("twisting_friction", "expected a coefficient >= 0");
    q.rolling_force_stiffness_ratio =
        r.number_or("rolling_force_stiffness_ratio", Quantity::dimensionless, 0.0);
    q.rolling_force_friction = r.number_or("rolling_force_friction", Quantity::dimensionless, 0.0);
    if (!(q.rolling_force_stiffness_ratio >= 0.0 && q.rolling_force_friction >= 0.0))
      r.fail("rolling_force_stiffness_ratio", "expected rolling force parameters >= 0");
    q.youngs_modulus = r.optional_number("youngs_modulus", Quantity::pressure);
    if (q.youngs_modulus && !(*q.youngs_modulus > 0.0))
      r.fail("youngs_modulus", "expected Young's modulus E > 0 Pa");
    if (q.youngs_modulus &&
        !(*q.youngs_modulus >= min_youngs_modulus && *q.youngs_modulus <= max_youngs_modulus))
      r.fail("youngs_modulus", youngs_modulus_range);
    r.finish();
    for (const PairEntry& other : c.pairs)
      if ((other.material_a == p.material_a && other.material_b == p.material_b) ||
          (other.material_a == p.material_b && other.material_b == p.material_a))
        r.fail("materials", fmt::format("pair {}-{} defined twice (first at line {})", names[0],
                                        names[1], other.line));
    c.pairs.push_back(p);
  }
}

void require_particle_material(TableReader& r, const Material& m) {
  if (!m.density)
    r.fail("material", fmt::format("material \"{}\" has no density; particles need one", m.name));
}

void read_particles(const toml::table& root, SceneConfig& c) {
  if (const toml::array* a = array_of_tables(root, "particle", c.file)) {
    for (size_t k = 0; k < a->size(); ++k) {
      TableReader r(*a->get(k)->as_table(), c.file, fmt::format("particle[{}]", k + 1));
      ParticleEntry p;
      p.line = r.line_of("");
      p.material = material_index(r, "material", r.string("material"), c.materials);
      require_particle_material(r, c.materials[p.material]);
      if (r.has("diameter") == r.has("radius"))
        r.fail("radius", "give exactly one of radius or diameter");
      p.radius = r.has("radius") ? r.number("radius", Quantity::length)
                                 : 0.5 * r.number("diameter", Quantity::length);
      if (!(p.radius > 0.0))
        r.fail(r.has("radius") ? "radius" : "diameter", "expected a size > 0 m");
      p.position = r.vec3("position", Quantity::length);
      p.velocity = r.vec3_or("velocity", Quantity::velocity, {});
      p.angular_velocity = r.vec3_or("angular_velocity", Quantity::angular_velocity, {});
      p.fixed = r.boolean_or("fixed", false);
      r.finish();
      c.particles.push_back(p);
    }
  }
  if (const toml::array* a = array_of_tables(root, "particles", c.file)) {
    for (size_t k = 0; k < a->size(); ++k) {
      TableReader r(*a->get(k)->as_table(), c.file, fmt::format("particles[{}]", k + 1));
      if (r.has("file")) {  // a packing read from CSV (io/packing_csv.hpp)
        const std::filesystem::path given = r.string("file");
        const std::string path =
            given.is_absolute()
                ? given.string()
                : (std::filesystem::path(c.file).parent_path() / given).lexically_normal().string();
        int default_material = -1;
        if (r.has("material")) {
          default_material = material_index(r, "material", r.string("material"), c.materials);
          require_particle_material(r, c.materials[default_material]);
        }
        const bool fixed = r.boolean_or("fixed", false);
        r.finish();  // count, region, diameter... belong to random batches, not to a file
        std::vector<ParticleEntry> rows = read_packing_csv(
            path, c.materials, default_material, fixed,
            fmt::format("{} line {}: particles[{}].file", c.file, r.line_of("file"), k + 1));
        const int source = static_cast<int>(c.packing_files.size());
        c.packing_files.push_back(path);
        for (ParticleEntry& p : rows) p.source = source;
        c.particles.insert(c.particles.end(), rows.begin(), rows.end());
        continue;
      }
      ParticleBatch b;
      b.line = r.line_of("");
      b.material = material_index(r, "material", r.string("material"), c.materials);
      require_particle_material(r, c.materials[b.material]);
      b.count = r.integer("count");
      if (b.count < 1) r.fail("count", "expected a particle count >= 1");
      if (r.has("diameter")) {
        b.diameter_min = b.diameter_max = r.number("diameter", Quantity::length);
      } else {
        b.diameter_min = r.number("diameter_min", Quantity::length);
        b.diameter_max = r.number("diameter_max", Quantity::length);
      }
      if (!(b.diameter_min > 0.0 && b.diameter_max >= b.diameter_min))
        r.fail("diameter", "expected diameters > 0 m with diameter_min <= diameter_max");
      b.velocity = r.vec3_or("velocity", Quantity::velocity, {});
      const toml::node* region = r.node("region");
      if (!region || !region->is_table())
        r.fail("region", "expected an inline table, e.g. {type = \"box\", min = [..], max = [..]}");
      TableReader g(*region->as_table(), c.file, fmt::format("particles[{}].region", k + 1));
      const std::string type = g.string("type");
      if (type == "box") {
        b.region = RegionShape::box;
        b.box_min = g.vec3("min", Quantity::length);
        b.box_max = g.vec3("max", Quantity::length);
        for (int d = 0; d < 3; ++d)
          if (!(b.box_max[d] - b.box_min[d] >= b.diameter_max))
            g.fail("max", "the box must be at least one particle diameter wide along every axis");
      } else if (type == "cylinder") {
        b.region = RegionShape::cylinder;
        b.cylinder_base = g.vec3("base", Quantity::length);
        b.cylinder_radius = g.number("radius", Quantity::length);
        b.cylinder_height = g.number("height", Quantity::length);
        if (!(b.cylinder_radius >= 0.5 * b.diameter_max && b.cylinder_height >= b.diameter_max))
          g.fail("radius", "the cylinder must hold at least one particle");
      } else {
        g.fail("type", fmt::format("expected \"box\" or \"cylinder\", got \"{}\"", type));
      }
      g.finish();
      r.finish();
      c.batches.push_back(b);
    }
  }
  if (c.particles.empty() && c.batches.empty())
    throw ConfigError(
        fmt::format("{}: no particles: add [[particle]] or [[particles]] entries", c.file));
}

namespace {

// The wall's name heads columns of walls.csv: unique, and nothing that breaks a CSV header.
void check_wall_name(const TableReader& r, const std::string& name,
                     const std::vector<Wall>& walls) {
  if (name.empty() || name.find_first_of(",\"\r\n") != std::string::npos)
    r.fail("name",
           "expected a name without commas, quotes or line breaks (it heads the columns of "
           "walls.csv)");
  for (size_t k = 0; k < walls.size(); ++k)
    if (walls[k].name == name)
      r.fail("name", fmt::format("wall name \"{}\" is also that of wall[{}] (an unnamed wall[k] "
                                 "is called \"wallk\"); names head the columns of walls.csv",
                                 name, k + 1));
}

// How the wall moves beyond a prescribed velocity: target_stress (a servo), or mass and force (a
// free body); and the area its normal stress is measured on. The geometry is read.
WallLoad read_wall_load(TableReader& r, Wall& w) {
  WallLoad load;
  if (r.has("area")) {
    if (w.shape != WallShape::plane)
      r.fail("area", w.shape == WallShape::rectangle
                         ? "a rectangle's area is its size; `area` is for plane walls"
                         : "a cylinder has no face area for a normal stress; `area` is for plane "
                           "walls");
    load.area = r.number("area", Quantity::area);
    if (!(*load.area > 0.0)) r.fail("area", "expected an area > 0 m^2");
  } else if (w.shape == WallShape::rectangle) {
    load.area = 4.0 * w.half_u * w.half_v;
  }
  load.target_stress = r.optional_number("target_stress", Quantity::pressure);
  if (load.target_stress) {
    if (w.shape == WallShape::cylinder)
      r.fail("target_stress",
             "a servo moves a wall along its normal, which a cylinder does not have: use a "
             "plane or rectangle wall");
    if (!(*load.target_stress > 0.0))
      r.fail("target_stress", "expected a compressive normal stress > 0 Pa");
    for (const char* key : {"mass", "force", "velocity"})
      if (r.has(key))
        r.fail("target_stress",
               fmt::format("the servo sets the wall's velocity, so target_stress excludes `{}`: "
                           "give one of the two",
                           key));
    if (!load.area)
      r.fail("area",
             "missing: a plane wall with target_stress needs the area (m^2) of the face it loads, "
             "to turn its force into a stress");
    load.max_speed = r.number_or("max_speed", Quantity::velocity, default_wall_servo_max_speed);
    if (!(load.max_speed > 0.0)) r.fail("max_speed", "expected a speed > 0 m/s");
  } else if (r.has("max_speed")) {
    r.fail("max_speed", "caps the speed of a servo-held wall: give it with target_stress");
  }
  if (r.has("mass")) {
    w.mass = r.number("mass", Quantity::mass);
    if (!(w.mass > 0.0))
      r.fail("mass",
             "expected a wall mass > 0 kg (leave mass out for a wall whose velocity is "
             "prescribed)");
  }
  if (r.has("force")) {
    if (!(w.mass > 0.0))
      r.fail("force", "a constant force acts only on a wall with mass: add mass (kg)");
    w.external_force = r.vec3("force", Quantity::force);
  }
  return load;
}

}  // namespace

void read_walls(const toml::table& root, SceneConfig& c) {
  const toml::array* a = array_of_tables(root, "wall", c.file);
  if (!a) return;
  for (size_t k = 0; k < a->size(); ++k) {
    TableReader r(*a->get(k)->as_table(), c.file, fmt::format("wall[{}]", k + 1));
    Wall w;
    w.name = r.string_or("name", fmt::format("wall{}", k + 1));
    check_wall_name(r, w.name, c.walls);
    const std::string type = r.string("type");
    w.material = material_index(r, "material", r.string("material"), c.materials);
    w.point = r.vec3("point", Quantity::length);
    w.velocity = r.vec3_or("velocity", Quantity::velocity, {});
    if (type == "plane") {
      w.shape = WallShape::plane;
      w.normal = r.vec3("normal", Quantity::dimensionless);
    } else if (type == "rectangle") {
      w.shape = WallShape::rectangle;
      w.normal = r.vec3("normal", Quantity::dimensionless);
      w.axis_u = r.vec3_or("axis_u", Quantity::dimensionless, {});
      const auto size = r.numbers("size", Quantity::length, 2);
      w.half_u = 0.5 * size[0];
      w.half_v = 0.5 * size[1];
    } else if (type == "cylinder") {
      w.shape = WallShape::cylinder;
      w.axis = r.vec3_or("axis", Quantity::dimensionless, {0.0, 0.0, 1.0});
      w.radius = r.number("radius", Quantity::length);
    } else {
      r.fail("type",
             fmt::format("expected \"plane\", \"rectangle\" or \"cylinder\", got \"{}\"", type));
    }
    try {
      finish_wall_geometry(w);
    } catch (const std::invalid_argument& e) {
      r.fail(type == "cylinder" ? "radius" : "normal", e.what());
    }
    const WallLoad load = read_wall_load(r, w);
    r.finish();
    c.walls.push_back(w);
    c.wall_lines.push_back(r.line_of(""));
    c.wall_loads.push_back(load);
  }
  if (c.walls.size() > 60000) throw ConfigError(fmt::format("{}: too many walls", c.file));
}

void read_output(const toml::table& root, SceneConfig& c) {
  c.output.interval = c.duration / 100.0;
  c.output.vtk_interval = 0.0;
  const toml::node* n = root.get("output");
  if (n) {
    if (!n->is_table()) throw ConfigError(fmt::format("{}: [output] must be a table", c.file));
    TableReader r(*n->as_table(), c.file, "output");
    c.output.interval = r.number_or("interval", Quantity::time, c.output.interval);
    if (!(c.output.interval > 0.0)) r.fail("interval", "expected an output interval > 0 s");
    if (const toml::node* t = r.node("trace")) {
      if (t->is_string() &&
          (*t->value<std::string>() == "all" || *t->value<std::string>() == "none")) {
        c.output.trace_all = *t->value<std::string>() == "all";
      } else if (const toml::array* ids = t->as_array()) {
        c.output.trace_all = false;
        for (const toml::node& id : *ids) {
          if (!id.is_integer() || *id.value<int64_t>() < 0)
            r.fail("trace", "expected \"all\", \"none\" or a list of particle ids (integers >= 0)");
          c.output.trace_ids.push_back(static_cast<uint32_t>(*id.value<int64_t>()));
        }
      } else {
        r.fail("trace", "expected \"all\", \"none\" or a list of particle ids");
      }
    }
    c.output.checkpoint_interval =
        r.number_or("checkpoint_interval", Quantity::time, c.output.checkpoint_interval);
    if (!(c.output.checkpoint_interval > 0.0))
      r.fail("checkpoint_interval", "expected a wall-time interval > 0 s");
    c.output.vtk = r.boolean_or("vtk", false);
    c.output.vtk_interval = r.number_or("vtk_interval", Quantity::time, 0.0);
    if (r.has("vtk_interval") && !(c.output.vtk_interval > 0.0))
      r.fail("vtk_interval", "expected an interval > 0 s");
    r.finish();
  }
  if (c.output.vtk_interval == 0.0) c.output.vtk_interval = c.output.interval;
}

namespace {
void check_top_level_keys(const toml::table& root, const std::string& file) {
  for (const auto& [key, value] : root) {
    static const char* known[] = {"simulation", "material", "pair",  "particle",
                                  "particles",  "wall",     "output"};
    bool ok = false;
    for (const char* k : known) ok = ok || key.str() == k;
    if (!ok)
      throw ConfigError(
          fmt::format("{} line {}: {}: unknown top-level key (known: simulation, "
                      "material, pair, particle, particles, wall, output)",
                      file, value.source().begin.line, key.str()));
  }
}
}  // namespace

SceneConfig load_scene(const std::string& path) {
  SceneConfig c;
  c.file = path;
  c.source = parse_toml_file(path);
  const toml::table& root = c.source;
  check_top_level_keys(root, path);
  read_simulation(root, c);
  read_materials(root, c);
  read_pairs(root, c);
  read_particles(root, c);
  read_walls(root, c);
  read_output(root, c);
  return c;
}

}  // namespace grainlab
