// The oedometer test: one-dimensional compression of a prepared specimen. The four lateral walls
// are fixed (lateral strain exactly zero), the platens compress it at the rate of the inertial-
// number bound until the axial stress reaches max_axial_stress, then move apart until it is back
// at unload_stress. Results: the axial stress-strain curve, the constrained modulus
// M = d(sigma_v)/d(eps_v) on loading and unloading, and the coefficient of earth pressure at rest
// K0 = sigma_h / sigma_v from the walls and from the particles (Love-Weber).
#pragma once

#include <toml++/toml.h>

#include <string>

#include "io/scene_run.hpp"
#include "lab/element_test.hpp"

namespace grainlab {

struct OedometerConfig : ElementTestConfig {
  double max_axial_stress = 600e3;  // Pa
  double unload_stress = 0.0;       // Pa; 0: back to the confining stress
  double max_axial_strain = 0.10;   // stop with an error if max_axial_stress is not reached
};

OedometerConfig read_oedometer_config(const std::string& path, const toml::table& root);
void run_oedometer(const std::string& path, const toml::table& root, const RunOptions& options);
void resume_oedometer(ElementRun run, const toml::table& root, const RunOptions& options);

}  // namespace grainlab
