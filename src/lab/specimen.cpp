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
#include "io/interrupt.hpp"
#include "io/output_files.hpp"
#include "io/progress.hpp"
#include "measure/boundary.hpp"
#include "measure/specimen_state.hpp"

namespace grainlab {

MaterialTimeStep specimen_time_step(const SpecimenSettings& s, const PairTable& table,
                                    double min_radius) {
  return material_time_step(s.dt_fraction, table, s.bead_material,
                            {s.bead_material, s.lateral_material, s.platen_material}, min_radius,
                            s.density);
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
