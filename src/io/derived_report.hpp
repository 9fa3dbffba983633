// Reports of the derived contact constants (`grainlab params`, summary.json).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/scene_builder.hpp"

namespace grainlab {

nlohmann::json derived_pairs_json(const std::vector<DerivedPair>& pairs, const TimeStepChoice& dt);

// Aligned text table for a person.
std::string derived_pairs_text(const std::vector<DerivedPair>& pairs, const TimeStepChoice& dt);

}  // namespace grainlab
