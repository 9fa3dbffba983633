#include "lab/plane_strain_band.hpp"

#include <fmt/format.h>

#include <cmath>

#include "io/output_files.hpp"
#include "measure/local_strain.hpp"

namespace grainlab {

std::vector<double> local_shear_strain(const ParticleStore& p, double diameter) {
  const std::vector<Matrix3> g =
      local_displacement_gradient(p.initial_position, p.position, 2.0 * diameter);
  std::vector<double> out(g.size());
  for (size_t i = 0; i < g.size(); ++i) out[i] = max_shear_strain(g[i], 0, 2);
  return out;
}

BandAnalysis analyse_shear_band(const ParticleStore& p, double diameter) {
  BandAnalysis a;
  a.map = strain_map(p.position, local_shear_strain(p, diameter), 0, 2, diameter);
  a.band = find_shear_band(a.map);
  return a;
}

void write_band_map(const std::string& path, const StrainMap& m) {
  std::string text = "x_m,z_m,shear_strain\n";
  for (int kb = 0; kb < m.n_b; ++kb)
    for (int ka = 0; ka < m.n_a; ++ka)
      text += fmt::format("{},{},{}\n", exact(m.low_a + (ka + 0.5) * m.cell),
                          exact(m.low_b + (kb + 0.5) * m.cell), exact(m.at(ka, kb)));
  write_file_atomically(path, text);
}

nlohmann::json band_json(const ShearBand& band, double diameter, double phi, double psi) {
  if (!band.found) return {{"found", false}};
  const double mohr_coulomb = 45 + phi / 2, roscoe = 45 + psi / 2, arthur = 45 + (phi + psi) / 4;
  return {{"found", true},
          {"inclination_to_horizontal_deg", band.inclination_deg},
          {"direction_deg", band.direction_deg},
          {"thickness_m", band.thickness},
          {"thickness_in_diameters", band.thickness / diameter},
          {"peak_shear_strain", band.peak},
          {"background_shear_strain", band.background},
          {"theories_deg",
           {{"mohr_coulomb_45_plus_phi_over_2", mohr_coulomb},
            {"roscoe_45_plus_psi_over_2", roscoe},
            {"arthur_45_plus_phi_plus_psi_over_4", arthur}}},
          {"difference_deg",
           {{"mohr_coulomb", band.inclination_deg - mohr_coulomb},
            {"roscoe", band.inclination_deg - roscoe},
            {"arthur", band.inclination_deg - arthur}}},
          {"method",
           "local shear strain since the start (best-fit displacement gradient over neighbours "
           "within 2 d), mapped on the x-z face in cells of 1 d averaged through the thickness; "
           "band = straight line of largest mean strain; thickness = full width at half height "
           "of the strain profile across it above the map's median"}};
}

}  // namespace grainlab
