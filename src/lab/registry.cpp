#include <fmt/format.h>

#include "io/config_error.hpp"
#include "lab/flat_throw.hpp"
#include "lab/lab_test.hpp"
#include "lab/sliding_friction.hpp"
#include "lab/triaxial.hpp"

namespace grainlab {

const std::vector<LabTestEntry>& lab_tests() {
  static const std::vector<LabTestEntry> table{
      {"flat_throw", "simulated flat-throw restitution test (DESIGN.md sec. 5)", run_flat_throw},
      {"sliding_friction", "simulated sliding-friction test, with inverse mode (DESIGN.md sec. 5)",
       run_sliding_friction},
      {"triaxial",
       "triaxial test of a cuboid specimen with servo-held lateral walls (DESIGN.md sec. 5)",
       run_triaxial},
  };
  return table;
}

void run_lab_test(const std::string& path, const toml::table& root, const RunOptions& options) {
  const toml::node* test = root.get("test");
  std::string known;
  for (const LabTestEntry& e : lab_tests())
    known += (known.empty() ? "" : ", ") + std::string(e.type);
  const toml::table* t = test ? test->as_table() : nullptr;
  const toml::node* type = t ? t->get("type") : nullptr;
  if (!type || !type->is_string())
    throw ConfigError(fmt::format("{} line {}: test.type: missing; expected one of: {}", path,
                                  test ? test->source().begin.line : 0, known));
  for (const LabTestEntry& e : lab_tests())
    if (*type->value<std::string>() == e.type) return e.run(path, root, options);
  throw ConfigError(fmt::format("{} line {}: test.type: unknown test \"{}\"; expected one of: {}",
                                path, type->source().begin.line, *type->value<std::string>(),
                                known));
}

}  // namespace grainlab
