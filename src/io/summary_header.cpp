#include "io/summary_header.hpp"

#include <sstream>

#include "grainlab/version.hpp"

namespace grainlab {

nlohmann::json toml_as_json(const toml::table& t) {
  std::ostringstream s;
  s << toml::json_formatter{t};
  return nlohmann::json::parse(s.str());
}

nlohmann::json summary_header(const std::string& config_path, const toml::table* inputs) {
  nlohmann::json j;
  j["grainlab_version"] = version_string;
  j["config_file"] = config_path;
  if (inputs) j["inputs"] = toml_as_json(*inputs);
  return j;
}

}  // namespace grainlab
