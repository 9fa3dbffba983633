// Results of the calibration analyses, for a person (aligned text tables shaped like the
// published Tables 3 and 4) and for programs (JSON; the plot script reads the same JSON).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "calibrate/friction.hpp"
#include "calibrate/restitution.hpp"
#include "calibrate/trajectory.hpp"

namespace grainlab::calibrate {

std::string restitution_text(const RestitutionAnalysis& analysis);
std::string trajectory_text(const TrajectoryResult& result);
std::string friction_text(const FrictionAnalysis& analysis);

// JSON documents; "analysis" names the kind ("restitution", "trajectory", "friction").
// Numbers that do not exist (e.g. sd of one throw) are null.
nlohmann::json restitution_json(const RestitutionAnalysis& analysis);
nlohmann::json trajectory_json(const TrajectoryResult& result);
nlohmann::json friction_json(const FrictionAnalysis& analysis);

}  // namespace grainlab::calibrate
