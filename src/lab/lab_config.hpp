// What every virtual test's config shares: the top-level keys (a [test] table allowed), the
// materials and the pairs, and a strict reader of the [test] table with its `type` consumed.
#pragma once

#include <toml++/toml.h>

#include <string>

#include "contact/pair_table.hpp"
#include "io/scene_config.hpp"
#include "io/toml_reader.hpp"

namespace grainlab {

SceneConfig read_lab_materials(const std::string& path, const toml::table& root);

// The [test] table (ConfigError if missing), with `type` already read.
TableReader test_table_reader(const std::string& path, const toml::table& root);

// Index of the material named `name`, read from test key `key`; a ConfigError naming the key if
// there is no such material.
int lab_material(const TableReader& t, const PairTable& table, const char* key,
                 const std::string& name);

// A ConfigError naming `key` unless the pair (a, b) is defined.
void require_pair(const TableReader& t, const PairTable& table, const char* key, int a, int b);

}  // namespace grainlab
