// Restitution coefficients from a flat-throw test (docs/calibration.md; Tang et al. 2019, Table 3).
//
// A bead leaves a horizontal launch lip at height H above a plate of the test material and
// rebounds to an apex at height h. The vertical impact speed is sqrt(2 g H) and the rebound
// speed sqrt(2 g h), so the coefficient of restitution is e = sqrt(h / H) (air drag neglected).
//
// Symbols: H launch height (m), h rebound apex height (m), e restitution (-), n throws.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "calibrate/csv_table.hpp"
#include "calibrate/statistics.hpp"

namespace grainlab::calibrate {

struct Throw {
  std::size_t line = 0;           // line in the input file
  double launch_height_m = 0.0;   // H
  double rebound_height_m = 0.0;  // h
  double restitution = 0.0;       // e = sqrt(h / H)
};

struct RestitutionResult {
  std::string material;
  std::vector<Throw> throws;
  std::size_t n = 0;
  double mean = 0.0;
  double sd = 0.0;              // sample standard deviation; NaN when n == 1
  double standard_error = 0.0;  // sd / sqrt(n)
  ConfidenceInterval ci;        // Student t, n - 1 dof; [mean, mean] when n == 1
};

// e per throw and its statistics, for each material (materials in order of first appearance).
struct RestitutionAnalysis {
  std::string source;  // the input file
  std::vector<RestitutionResult> materials;
};

// Columns: material, H_m, h_m (or H_mm, h_mm). `rename` maps CSV material names to the names
// used in the output (e.g. a scene's material name). Throws InputError naming file and line.
RestitutionAnalysis analyse_throws(const CsvTable& table,
                                   const std::map<std::string, std::string>& rename = {},
                                   double level = 0.95);

// Statistics of a list of throws (exposed for tests).
RestitutionResult summarise_throws(std::string material, std::vector<Throw> throws,
                                   double level = 0.95);

}  // namespace grainlab::calibrate
