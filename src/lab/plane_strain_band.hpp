// The shear band of a plane strain run: the local shear strain of every bead since the start
// (measure/local_strain.hpp, over neighbours within two diameters, in the x-z plane), its map over
// the specimen's face in cells one diameter wide averaged through the thickness
// (measure/shear_band.hpp), the band found on it, and the comparison with the classical
// predictions of its inclination to the minor principal stress direction (x):
//   Mohr-Coulomb 45 + phi/2,  Roscoe 45 + psi/2,  Arthur 45 + (phi + psi)/4   (degrees).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/particles.hpp"
#include "measure/shear_band.hpp"

namespace grainlab {

// Per particle (storage order), the in-plane (x-z) maximum shear strain since the start.
std::vector<double> local_shear_strain(const ParticleStore& p, double diameter);

struct BandAnalysis {
  StrainMap map;
  ShearBand band;
};
BandAnalysis analyse_shear_band(const ParticleStore& p, double diameter);

// band_map.csv (x_m, z_m, shear_strain per cell of the current configuration).
void write_band_map(const std::string& path, const StrainMap& map);

// The band's figures for summary.json, against the theories at phi and psi (degrees).
nlohmann::json band_json(const ShearBand& band, double diameter, double phi_deg, double psi_deg);

}  // namespace grainlab
