// The shear band of a specimen, found on a map of the local shear strain (measure/
// local_strain.hpp) over one face, as the laboratory finds it on its digital image correlation
// field.
//
//   strain_map       the per-particle values averaged over square cells of the (a, b) plane
//                    (through the whole third axis: plane strain makes the field uniform along it);
//                    cells with fewer than half the typical particle count, and the ring of cells
//                    along the specimen's edge (one-sided neighbourhoods), are left empty
//   find_shear_band  the straight line along which the mean strain is largest (a Radon-transform
//                    search over directions 15-165 degrees from axis a and every offset, lines at
//                    least 60 % of the map's shorter side long); its inclination to axis a; the
//                    profile of the strain across it and the band's thickness as the full width at
//                    half the height of that profile above the map's median (the background).
#pragma once

#include <vector>

#include "core/vec3.hpp"

namespace grainlab {

struct StrainMap {
  int n_a = 0, n_b = 0;                   // cells along axes a and b
  double low_a = 0, low_b = 0, cell = 0;  // m
  std::vector<double> value;              // n_a * n_b, row k_b * n_a + k_a; NaN where empty
  double at(int ka, int kb) const { return value[static_cast<size_t>(kb) * n_a + ka]; }
};

StrainMap strain_map(const std::vector<Vec3>& positions, const std::vector<double>& values, int a,
                     int b, double cell);

struct ShearBand {
  bool found = false;
  double direction_deg = 0;    // of the band line, from axis a towards axis b, in (0, 180)
  double inclination_deg = 0;  // to axis a, in [0, 90]
  double offset = 0;           // m: the line is n . (p - low) = offset, n = (-sin, cos)
  double thickness = 0;        // m, full width at half height of the profile
  double peak = 0, background = 0;
  std::vector<double> profile_distance, profile_value;  // m, across the band
};

ShearBand find_shear_band(const StrainMap& map);

}  // namespace grainlab
