// Strict reading of one TOML table: every key read is marked, and finish() rejects any key
// that was not (a misspelt key is an error, never silently ignored). Errors are ConfigError
// with "FILE line N: KEY: what was expected".
#pragma once

#include <toml++/toml.h>

#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/vec3.hpp"
#include "io/config_error.hpp"
#include "io/units.hpp"

namespace grainlab {

class TableReader {
 public:
  // `where` names the table for messages, e.g. "material[2]" or "simulation".
  TableReader(const toml::table& table, std::string file, std::string where);

  bool has(const std::string& key) const { return table_.contains(key); }
  double number(const std::string& key, Quantity q);
  double number_or(const std::string& key, Quantity q, double fallback);
  std::optional<double> optional_number(const std::string& key, Quantity q);
  long integer(const std::string& key);
  long integer_or(const std::string& key, long fallback);
  std::string string(const std::string& key);
  std::string string_or(const std::string& key, const std::string& fallback);
  bool boolean_or(const std::string& key, bool fallback);
  Vec3 vec3(const std::string& key, Quantity q);
  Vec3 vec3_or(const std::string& key, Quantity q, const Vec3& fallback);
  std::vector<double> numbers(const std::string& key, Quantity q, size_t count);
  std::vector<std::string> strings(const std::string& key, size_t count);
  const toml::node* node(const std::string& key);  // marks the key as read

  // Throws on any key not read. Call after reading all keys.
  void finish() const;

  [[noreturn]] void fail(const std::string& key, const std::string& what) const;
  int line_of(const std::string& key) const;
  const std::string& file() const { return file_; }
  const std::string& where() const { return where_; }

 private:
  const toml::node& required(const std::string& key);
  double to_number(const toml::node& n, const std::string& key, Quantity q) const;

  const toml::table& table_;
  std::string file_, where_;
  std::set<std::string> read_;
};

// Parses a TOML file; syntax errors become ConfigError with file and line.
toml::table parse_toml_file(const std::string& path);

}  // namespace grainlab
