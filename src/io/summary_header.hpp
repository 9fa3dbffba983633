// The first keys of every summary.json / specimen.json grainlab writes: the version that wrote it,
// the config file, and (where given) the config's contents as JSON, so a result says what made it.
#pragma once

#include <toml++/toml.h>

#include <nlohmann/json.hpp>
#include <string>

namespace grainlab {

nlohmann::json toml_as_json(const toml::table& t);

nlohmann::json summary_header(const std::string& config_path, const toml::table* inputs = nullptr);

}  // namespace grainlab
