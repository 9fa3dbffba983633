// Laboratory values a shear test compares its result with ([test.laboratory] in the config), and
// the comparison itself: in the run's last line, summary.json ("reference") and curve.png.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "io/toml_reader.hpp"

namespace grainlab {

// Laboratory values a shear test's result is compared with ([test.laboratory]); without them a run
// reports its own result only, since a specimen that is not the laboratory's has nothing to be
// compared with.
struct LaboratoryValues {
  double peak_axial_stress = 0.0;                         // Pa
  std::optional<double> axial_strain_at_peak;             // -
  std::optional<double> published_dem_peak_axial_stress;  // Pa, another simulation's peak
  std::string source;                                     // where the values come from, for legends
};

// [test.laboratory] read from the [test] table `t` (none without it); ConfigError naming the key
// for a bad value.
std::optional<LaboratoryValues> read_laboratory_values(const std::string& path, TableReader& t);

// The "reference" entry of a shear test's summary.json (the laboratory values and the differences
// to them) and the comparison's words for the run's last line ("" without [test.laboratory]).
struct LaboratoryComparison {
  nlohmann::json json;
  std::string text;
};
LaboratoryComparison compare_with_laboratory(const std::optional<LaboratoryValues>& laboratory,
                                             double peak_axial_stress, double axial_strain_at_peak);

}  // namespace grainlab
