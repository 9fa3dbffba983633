#include "lab/lab_config.hpp"

#include <fmt/format.h>

#include "io/config_error.hpp"

namespace grainlab {

SceneConfig read_lab_materials(const std::string& path, const toml::table& root) {
  check_top_level_keys(root, path, true);
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
