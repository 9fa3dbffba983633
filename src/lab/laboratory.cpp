#include "lab/laboratory.hpp"

#include <fmt/format.h>

namespace grainlab {

std::optional<LaboratoryValues> read_laboratory_values(const std::string& path, TableReader& t) {
  if (!t.has("laboratory")) return std::nullopt;
  const toml::table* lab = t.node("laboratory")->as_table();
  if (!lab)
    t.fail("laboratory",
           "expected a table [test.laboratory] with peak_axial_stress (and optionally "
           "axial_strain_at_peak, published_dem_peak_axial_stress, source)");
  TableReader l(*lab, path, "test.laboratory");
  LaboratoryValues v;
  v.peak_axial_stress = l.number("peak_axial_stress", Quantity::pressure);
  if (!(v.peak_axial_stress > 0))
    l.fail("peak_axial_stress", "expected the laboratory's peak axial stress > 0 Pa");
  v.axial_strain_at_peak = l.optional_number("axial_strain_at_peak", Quantity::dimensionless);
  if (v.axial_strain_at_peak && !(*v.axial_strain_at_peak > 0 && *v.axial_strain_at_peak < 0.5))
    l.fail("axial_strain_at_peak", "expected a strain in (0, 0.5)");
  v.published_dem_peak_axial_stress =
      l.optional_number("published_dem_peak_axial_stress", Quantity::pressure);
  if (v.published_dem_peak_axial_stress && !(*v.published_dem_peak_axial_stress > 0))
    l.fail("published_dem_peak_axial_stress", "expected a peak axial stress > 0 Pa");
  v.source = l.string_or("source", "laboratory");
  l.finish();
  return v;
}

LaboratoryComparison compare_with_laboratory(const std::optional<LaboratoryValues>& laboratory,
                                             double peak_axial_stress,
                                             double axial_strain_at_peak) {
  LaboratoryComparison out;
  if (!laboratory) return out;
  const LaboratoryValues& lab = *laboratory;
  out.json = {{"source", lab.source},
              {"laboratory_peak_axial_stress_Pa", lab.peak_axial_stress},
              {"difference_to_laboratory", peak_axial_stress / lab.peak_axial_stress - 1.0}};
  out.text = fmt::format("; laboratory {:.2f} kPa", 1e-3 * lab.peak_axial_stress);
  if (lab.axial_strain_at_peak) {
    out.json["laboratory_axial_strain_at_peak"] = *lab.axial_strain_at_peak;
    out.json["strain_at_peak_difference_to_laboratory"] =
        axial_strain_at_peak / *lab.axial_strain_at_peak - 1.0;
    out.text += fmt::format(" at {:.2f} % (stress {:+.1f} %, strain at peak {:+.1f} %)",
                            100 * *lab.axial_strain_at_peak,
                            100 * (peak_axial_stress / lab.peak_axial_stress - 1.0),
                            100 * (axial_strain_at_peak / *lab.axial_strain_at_peak - 1.0));
  } else {
    out.text +=
        fmt::format(" ({:+.1f} %)", 100 * (peak_axial_stress / lab.peak_axial_stress - 1.0));
  }
  if (lab.published_dem_peak_axial_stress) {
    out.json["published_dem_peak_axial_stress_Pa"] = *lab.published_dem_peak_axial_stress;
    out.json["difference_to_published_dem"] =
        peak_axial_stress / *lab.published_dem_peak_axial_stress - 1.0;
    out.text += fmt::format(", published DEM {:.2f} kPa ({:+.1f} %)",
                            1e-3 * *lab.published_dem_peak_axial_stress,
                            100 * (peak_axial_stress / *lab.published_dem_peak_axial_stress - 1.0));
  }
  return out;
}

}  // namespace grainlab
