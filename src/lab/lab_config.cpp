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

}  // namespace grainlab
