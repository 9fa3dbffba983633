// The plane strain test (the reference study's second test): a cuboid specimen 100 high x 60 wide
// x 100 thick mm (z, x, y) of about 88,400 glass beads, prepared between rigid walls, then its two
// lateral faces (x) held at the confining stress by a flexible membrane on the outermost beads
// (control/membrane.hpp), the front and back walls (y) fixed so that the strain through the
// thickness is zero, and the platens (z) driven at the fastest rate with inertial number I below
// the bound (or a given speed), to 15 % axial strain; without gravity unless test.gravity is given
// (then from the re-equilibration on, the bottom platen carrying the weight). Results: the curve
// (stresses from the boundary and from the particles), peak, friction and dilatancy angles,
// membrane error, escaped beads, and the shear band (lab/plane_strain_band.hpp).
#pragma once

#include <toml++/toml.h>

#include <string>

#include "io/scene_run.hpp"
#include "lab/element_test.hpp"

namespace grainlab {

struct PlaneStrainConfig : ElementTestConfig {
  double max_axial_strain = 0.15;
};

// The plane strain box's walls for a prepared specimen, its re-equilibration under the membrane at
// the confining stress, and its volume (lab/element_test.hpp).
SpecimenMount plane_strain_mount(const ElementTestSettings& s);

// The weight of the particles (N) under the simulation's gravity along -z.
double specimen_weight(const Simulation& sim);

PlaneStrainConfig read_plane_strain_config(const std::string& path, const toml::table& root);
void run_plane_strain(const std::string& path, const toml::table& root, const RunOptions& options);
void resume_plane_strain(ElementRun run, const toml::table& root, const RunOptions& options);

}  // namespace grainlab
