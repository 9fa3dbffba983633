// Reading a triaxial test configuration ([test] type = "triaxial"); also used by `prepare`.
#pragma once

#include <toml++/toml.h>

#include <string>

#include "contact/pair_table.hpp"
#include "io/scene_config.hpp"
#include "lab/triaxial.hpp"

namespace grainlab {

struct TriaxialConfig {
  SceneConfig scene;  // materials and pairs
  PairTable table{{}};
  TriaxialSettings settings;
};

TriaxialConfig read_triaxial_config(const std::string& path, const toml::table& root);

}  // namespace grainlab
