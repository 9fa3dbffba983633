#include "io/toml_reader.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>

namespace grainlab {
namespace {
const char* type_name(const toml::node& n) {
  if (n.is_string()) return "a string";
  if (n.is_boolean()) return "a boolean";
  if (n.is_array()) return "an array";
  if (n.is_table()) return "a table";
  return "a date or time";
}
}  // namespace

TableReader::TableReader(const toml::table& table, std::string file, std::string where)
    : table_(table), file_(std::move(file)), where_(std::move(where)) {}

int TableReader::line_of(const std::string& key) const {
  const toml::node* n = table_.get(key);
  if (n) return static_cast<int>(n->source().begin.line);
  return static_cast<int>(table_.source().begin.line);
}

void TableReader::fail(const std::string& key, const std::string& what) const {
  const std::string path = where_.empty() ? key : (key.empty() ? where_ : where_ + "." + key);
  throw ConfigError(fmt::format("{} line {}: {}: {}", file_, line_of(key), path, what));
}

const toml::node* TableReader::node(const std::string& key) {
  read_.insert(key);
  return table_.get(key);
}

const toml::node& TableReader::required(const std::string& key) {
  const toml::node* n = node(key);
  if (!n) fail(key, "missing (required)");
  return *n;
}

double TableReader::to_number(const toml::node& n, const std::string& key, Quantity q) const {
  if (auto v = n.value<double>(); v && (n.is_floating_point() || n.is_integer())) {
    if (!std::isfinite(*v)) fail(key, "expected a finite number");
    return *v;
  }
  if (auto s = n.value<std::string>()) {
    try {
      return parse_quantity(*s, q);
    } catch (const std::invalid_argument& e) {
      fail(key, e.what());
    }
  }
  fail(key, fmt::format("expected a number (in {}) or a string with a unit, got {}", si_unit(q),
                        type_name(n)));
}

double TableReader::number(const std::string& key, Quantity q) {
  return to_number(required(key), key, q);
}

double TableReader::number_or(const std::string& key, Quantity q, double fallback) {
  const toml::node* n = node(key);
  return n ? to_number(*n, key, q) : fallback;
}

std::optional<double> TableReader::optional_number(const std::string& key, Quantity q) {
  const toml::node* n = node(key);
  if (!n) return std::nullopt;
  return to_number(*n, key, q);
}

long TableReader::integer(const std::string& key) {
  const toml::node& n = required(key);
  if (!n.is_integer()) fail(key, "expected an integer");
  return static_cast<long>(*n.value<int64_t>());
}

long TableReader::integer_or(const std::string& key, long fallback) {
  return table_.contains(key) ? integer(key) : (read_.insert(key), fallback);
}

std::string TableReader::string(const std::string& key) {
  const toml::node& n = required(key);
  if (!n.is_string()) fail(key, "expected a string");
  return *n.value<std::string>();
}

std::string TableReader::string_or(const std::string& key, const std::string& fallback) {
  return table_.contains(key) ? string(key) : (read_.insert(key), fallback);
}

bool TableReader::boolean_or(const std::string& key, bool fallback) {
  const toml::node* n = node(key);
  if (!n) return fallback;
  if (!n->is_boolean()) fail(key, "expected true or false");
  return *n->value<bool>();
}

std::vector<double> TableReader::numbers(const std::string& key, Quantity q, size_t count) {
  const toml::node& n = required(key);
  const toml::array* a = n.as_array();
  if (!a || a->size() != count)
    fail(key, fmt::format("expected an array of {} numbers (in {})", count, si_unit(q)));
  std::vector<double> out;
  for (const toml::node& item : *a) out.push_back(to_number(item, key, q));
  return out;
}

std::vector<std::string> TableReader::strings(const std::string& key, size_t count) {
  const toml::node& n = required(key);
  const toml::array* a = n.as_array();
  if (!a || a->size() != count) fail(key, fmt::format("expected an array of {} strings", count));
  std::vector<std::string> out;
  for (const toml::node& item : *a) {
    if (!item.is_string()) fail(key, fmt::format("expected an array of {} strings", count));
    out.push_back(*item.value<std::string>());
  }
  return out;
}

Vec3 TableReader::vec3(const std::string& key, Quantity q) {
  const std::vector<double> v = numbers(key, q, 3);
  return {v[0], v[1], v[2]};
}

Vec3 TableReader::vec3_or(const std::string& key, Quantity q, const Vec3& fallback) {
  return table_.contains(key) ? vec3(key, q) : (read_.insert(key), fallback);
}

void TableReader::finish() const {
  for (const auto& [key, value] : table_) {
    const std::string k(key.str());
    if (!read_.count(k)) {
      std::string known;
      for (const std::string& r : read_) known += (known.empty() ? "" : ", ") + r;
      throw ConfigError(fmt::format("{} line {}: {}: unknown key (known keys here: {})", file_,
                                    value.source().begin.line,
                                    where_.empty() ? k : where_ + "." + k, known));
    }
  }
}

toml::table parse_toml_file(const std::string& path) {
  if (!std::filesystem::is_regular_file(path))
    throw ConfigError(fmt::format("{}: no such file (expected a TOML configuration)", path));
  try {
    return toml::parse_file(path);
  } catch (const toml::parse_error& e) {
    throw ConfigError(fmt::format("{} line {}: TOML syntax error: {}", path, e.source().begin.line,
                                  e.description()));
  }
}

}  // namespace grainlab
