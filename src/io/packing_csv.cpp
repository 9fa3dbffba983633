#include "io/packing_csv.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <optional>
#include <string_view>

#include "io/config_error.hpp"

namespace grainlab {
namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> out;
  size_t start = 0;
  while (true) {
    const size_t comma = line.find(',', start);
    out.push_back(trim(line.substr(start, comma - start)));
    if (comma == std::string_view::npos) return out;
    start = comma + 1;
  }
}

enum Column { id, material, radius, x, y, z, vx, vy, vz, wx, wy, wz, column_count };
constexpr const char* column_names[column_count] = {"id", "material", "radius", "x",  "y",  "z",
                                                    "vx", "vy",       "vz",     "wx", "wy", "wz"};

}  // namespace

std::vector<ParticleEntry> read_packing_csv(const std::string& path,
                                            const std::vector<Material>& materials,
                                            int default_material, bool fixed,
                                            const std::string& named_by) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ConfigError(fmt::format("{}: cannot read the packing file {}", named_by, path));
  auto fail = [&](long line, const std::string& what) -> ConfigError {
    return ConfigError(fmt::format("{} line {}: {}", path, line, what));
  };

  std::optional<size_t> where[column_count];
  size_t field_count = 0;
  std::vector<ParticleEntry> rows;
  std::vector<long> ids;
  std::string text;
  long line = 0;
  bool have_header = false;
  while (std::getline(in, text)) {
    ++line;
    std::string_view content = trim(text);
    if (line == 1 && content.substr(0, 3) == "\xEF\xBB\xBF") content = trim(content.substr(3));
    if (content.empty() || content.front() == '#') continue;
    const std::vector<std::string_view> fields = split(content);
    if (!have_header) {
      for (size_t k = 0; k < fields.size(); ++k) {
        if (fields[k].empty())
          throw fail(line,
                     fmt::format("column {} of the header has no name (a trailing comma?)", k + 1));
        const auto* known = std::find(std::begin(column_names), std::end(column_names), fields[k]);
        if (known == std::end(column_names))
          throw fail(line, fmt::format("unknown column '{}' (known: id, material, radius, x, y, z, "
                                       "vx, vy, vz, wx, wy, wz)",
                                       fields[k]));
        auto& slot = where[known - std::begin(column_names)];
        if (slot) throw fail(line, fmt::format("column '{}' appears twice", fields[k]));
        slot = k;
      }
      for (Column c : {radius, x, y, z})
        if (!where[c])
          throw fail(line, fmt::format("the header has no '{}' column (required: radius, x, y, z)",
                                       column_names[c]));
      if (!where[material] && default_material < 0)
        throw fail(line,
                   "no 'material' column: add one, or set material = \"...\" in [[particles]]");
      field_count = fields.size();
      have_header = true;
      continue;
    }
    if (fields.size() != field_count)
      throw fail(line, fmt::format("expected {} fields as in the header, found {}", field_count,
                                   fields.size()));
    auto number = [&](Column c, double fallback) {
      if (!where[c]) return fallback;
      std::string_view cell = fields[*where[c]];
      if (!cell.empty() && cell.front() == '+') cell.remove_prefix(1);
      double v = 0.0;
      const auto [end, error] = std::from_chars(cell.data(), cell.data() + cell.size(), v);
      if (error != std::errc() || end != cell.data() + cell.size() || !std::isfinite(v))
        throw fail(line,
                   fmt::format("column '{}': '{}' is not a finite number", column_names[c], cell));
      return v;
    };
    ParticleEntry p;
    p.line = line;
    p.fixed = fixed;
    p.radius = number(radius, 0.0);
    if (!(p.radius > 0.0)) throw fail(line, "column 'radius': expected a radius > 0 m");
    p.position = {number(x, 0.0), number(y, 0.0), number(z, 0.0)};
    p.velocity = {number(vx, 0.0), number(vy, 0.0), number(vz, 0.0)};
    p.angular_velocity = {number(wx, 0.0), number(wy, 0.0), number(wz, 0.0)};
    p.material = default_material;
    if (where[material]) {
      const std::string_view name = fields[*where[material]];
      p.material = -1;
      for (size_t m = 0; m < materials.size(); ++m)
        if (materials[m].name == name) p.material = static_cast<int>(m);
      int index = -1;
      const auto [end, error] = std::from_chars(name.data(), name.data() + name.size(), index);
      if (p.material < 0 && error == std::errc() && end == name.data() + name.size() &&
          index >= 0 && index < static_cast<int>(materials.size()))
        p.material = index;
      if (p.material < 0)
        throw fail(line, fmt::format("column 'material': '{}' is neither a [[material]] name nor "
                                     "an index 0..{}",
                                     name, materials.size() - 1));
    }
    if (!materials[p.material].density)
      throw fail(line, fmt::format("material \"{}\" has no density; particles need one",
                                   materials[p.material].name));
    if (where[id]) {
      const std::string_view cell = fields[*where[id]];
      long v = -1;
      const auto [end, error] = std::from_chars(cell.data(), cell.data() + cell.size(), v);
      if (error != std::errc() || end != cell.data() + cell.size() || v < 0)
        throw fail(line, fmt::format("column 'id': '{}' is not an integer >= 0", cell));
      ids.push_back(v);
    }
    rows.push_back(p);
  }
  if (!have_header)
    throw ConfigError(
        fmt::format("{} (named by {}): no header line (radius, x, y, z, ...)", path, named_by));
  if (rows.empty())
    throw ConfigError(
        fmt::format("{} (named by {}): no particles after the header", path, named_by));
  if (!where[id]) return rows;

  // With ids: a permutation of 0 .. N-1, and the particles in id order.
  std::vector<ParticleEntry> ordered(rows.size());
  std::vector<long> seen_on(rows.size(), 0);
  for (size_t k = 0; k < rows.size(); ++k) {
    const long v = ids[k];
    if (v >= static_cast<long>(rows.size()))
      throw fail(rows[k].line, fmt::format("id {} is out of range: the {} ids must be 0 .. {}", v,
                                           rows.size(), rows.size() - 1));
    if (seen_on[v])
      throw fail(rows[k].line,
                 fmt::format("id {} appears twice (first on line {})", v, seen_on[v]));
    seen_on[v] = rows[k].line;
    ordered[v] = rows[k];
  }
  return ordered;
}

}  // namespace grainlab
