// Sliding-friction test analysis of a whole measurement file (docs/calibration.md): per material
// and speed the F-P fits, per material the speed curve and the quasi-static coefficient
// (the published Table 4). The fits themselves are in friction_fits.hpp.
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "calibrate/csv_table.hpp"
#include "calibrate/friction_fits.hpp"

namespace grainlab::calibrate {

struct FrictionAtSpeed {
  double speed_mm_per_min = 0.0;
  std::vector<LoadPoint> points;
  OriginFit origin;  // mu at this speed
  FreeFit free;
};

struct FrictionMaterial {
  std::string material;
  std::vector<FrictionAtSpeed> speeds;  // ascending speed
  std::optional<SpeedFit> speed_fit;
  std::string speed_fit_note;  // why there is no speed fit, when there is none
};

struct FrictionOptions {
  double breakpoint_mm_per_min = 5.0;
  double level = 0.95;
  std::map<std::string, std::string> rename;  // CSV material name -> output name
};

struct FrictionAnalysis {
  std::string source;
  FrictionOptions options;
  std::vector<FrictionMaterial> materials;  // in order of first appearance
  // Data or results outside what a sliding-friction test gives (a unit slip, a fit that explains
  // little): printed with the report and in its JSON.
  std::vector<std::string> warnings;
};

// Columns: material, speed_mm_per_min, normal_load_N, friction_force_N. Throws InputError naming
// file and line (bad cells, non-positive load or speed, negative force, fewer than two
// different loads at a speed).
FrictionAnalysis analyse_friction(const CsvTable& table, const FrictionOptions& options = {});

}  // namespace grainlab::calibrate
