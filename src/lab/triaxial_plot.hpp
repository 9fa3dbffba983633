// curve.png of a triaxial run: axial stress and volumetric strain against axial strain with the
// laboratory and published DEM peaks marked (scripts/plot_triaxial.py, Debian's matplotlib).
#pragma once

#include <string>

namespace grainlab {

// Writes DIR/curve.png from DIR/curve.csv and DIR/summary.json. A failing plot is reported on
// stderr but does not fail the run (the numbers are already written).
void plot_triaxial_curve(const std::string& dir);

}  // namespace grainlab
