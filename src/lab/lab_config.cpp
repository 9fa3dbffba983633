#include "lab/lab_config.hpp"

#include <fmt/format.h>

#include "io/config_error.hpp"

namespace grainlab {

SceneConfig read_lab_materials(const std::string& path, const toml::table& root) {
  // A test builds its own particles, walls, time step and outputs: a scene table here would be
  // silently ignored, so it is an error.
  for (const auto& [key, value] : root)
    if (key.str() != "test" && key.str() != "material" && key.str() != "pair")
      throw ConfigError(fmt::format(
          "{} line {}: {}: a config with a [test] table reads only [test], [[material]] and "
          "[[pair]]; this table would be ignored (a test sets its own particles, walls, time "
          "step and outputs through [test] keys, docs/lab-tests.md)",
          path, value.source().begin.line, key.str()));
  SceneConfig c;
  c.file = path;
  read_materials(root, c);
  read_pairs(root, c);
  return c;
}

TableReader test_table_reader(const std::string& path, const toml::table& root) {
  const toml::node* test = root.get("test");
  if (!test || !test->is_table()) throw ConfigError(fmt::format("{}: [test] table missing", path));
  TableReader t(*test->as_table(), path, "test");
  t.string("type");
  return t;
}

int lab_material(const TableReader& t, const PairTable& table, const char* key,
                 const std::string& name) {
  const int m = table.find(name);
  if (m < 0) t.fail(key, fmt::format("unknown material \"{}\"", name));
  return m;
}

void require_pair(const TableReader& t, const PairTable& table, const char* key, int a, int b) {
  if (!table(a, b).defined)
    t.fail(key, fmt::format("no [[pair]] for \"{}\" and \"{}\"", table.material(a).name,
                            table.material(b).name));
}

}  // namespace grainlab
