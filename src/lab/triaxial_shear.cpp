#include "lab/triaxial_shear.hpp"

#include <fmt/format.h>

#include <cmath>

#include "io/output_files.hpp"
#include "measure/boundary.hpp"
#include "measure/specimen_state.hpp"

namespace grainlab {
namespace {

constexpr const char* header =
    "time_s,axial_strain,lateral_strain_x,lateral_strain_y,volumetric_strain,"
    "axial_stress_walls_Pa,lateral_stress_x_walls_Pa,lateral_stress_y_walls_Pa,"
    "axial_stress_particles_Pa,lateral_stress_x_particles_Pa,lateral_stress_y_particles_Pa,"
    "axial_stress_boundary_Pa,lateral_stress_x_boundary_Pa,lateral_stress_y_boundary_Pa,"
    "deviator_stress_Pa,mean_stress_Pa,stress_ratio,solid_fraction,coordination_number,"
    "inertial_number,unbalanced_force_ratio";

BoxControlSettings shear_control(const ShearProgress& p) {
  // The lateral boundary held at sigma_3, the platens driven at the platen speed.
  const AxisControl lateral{AxisMode::stress, p.confining_stress};
  return {{lateral, lateral, AxisControl{AxisMode::speed, 0.0, p.platen_speed}},
          ServoRegime::holding,
          2.0 * p.platen_speed};
}

}  // namespace

TriaxialShear::TriaxialShear(ElementRun& run, const ShearProgress& progress, const std::string& dir)
    : p_(progress), dir_(dir), control_(shear_control(progress)), attached_(run.sim, control_) {
  control_.set_integrals(p_.servo_integral);
}

ShearProgress TriaxialShear::restore(const ElementRun& run) {
  return restored_test_state<ShearProgress>(run);
}

void TriaxialShear::save(ElementRun& run) const {
  ShearProgress p = p_;
  p.servo_integral = control_.integrals();
  store_test_state(run, p);
}

const char* TriaxialShear::curve_header() const {
  return header;
}

std::string TriaxialShear::position() const {
  return fmt::format("axial strain {:.2f} %", 100 * axial_strain_);
}

// Adds this step's stresses to the running sums of the output interval.
void TriaxialShear::after_step(ElementRun& run) {
  p_.interval.add_walls(run.sim);
  if (p_.step % stress_sample_steps == 0) p_.interval.add_specimen(run.sim);
  ++p_.step;
}

void TriaxialShear::observe(ElementRun& run, Progress& progress) {
  const Vec3 size = box_size(run.sim.walls());
  axial_strain_ = (p_.size0.z - size.z) / p_.size0.z;
  strain_outputs(
      p_, axial_strain_, progress, [&] { record(run); }, [&] { snapshot(run); });
}

// One row of curve.csv (stresses averaged over the interval since the last row; at the start
// the instantaneous state), and the running peaks and errors.
void TriaxialShear::record(ElementRun& run) {
  Simulation& sim = run.sim;
  ShearProgress& p = p_;
  const Vec3 size = box_high(sim.walls()) - box_low(sim.walls());
  const double axial_strain = (p.size0.z - size.z) / p.size0.z;
  const double volume = size.x * size.y * size.z, volume0 = p.size0.x * p.size0.y * p.size0.z;
  const IntervalStresses::Averages averaged = p.interval.take(sim);
  const std::array<double, 6>& w = averaged.wall;
  const std::array<double, 3>&particle = averaged.particle, &boundary = averaged.boundary;
  const double sa = 0.5 * (w[bottom] + w[top]);
  const double sx = 0.5 * (w[x_low] + w[x_high]);
  const double sy = 0.5 * (w[y_low] + w[y_high]);
  const double deviator = sa - 0.5 * (sx + sy), mean = (sa + sx + sy) / 3.0;
  const double inertial = inertial_number(p.strain_rate, p.diameter, p.density, mean);
  run.curve_rows += fmt::format(
      "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", exact(sim.time()),
      exact(axial_strain), exact((p.size0.x - size.x) / p.size0.x),
      exact((p.size0.y - size.y) / p.size0.y), exact(1.0 - volume / volume0), exact(sa), exact(sx),
      exact(sy), exact(particle[2]), exact(particle[0]), exact(particle[1]), exact(boundary[2]),
      exact(boundary[0]), exact(boundary[1]), exact(deviator), exact(mean), exact(deviator / mean),
      exact(solid_fraction(sim.particles(), volume)), exact(coordination_number(sim)),
      exact(inertial), exact(unbalanced_force_ratio(sim)));
  if (p.step > 0) {
    p.max_inertial = std::max(p.max_inertial, inertial);
    for (int k = 0; k < 4; ++k) {
      const double e = w[k] / p.confining_stress - 1.0;
      p.lateral_error2 += e * e;
      p.max_lateral_error = std::max(p.max_lateral_error, std::abs(e));
      ++p.lateral_samples;
    }
    if (axial_strain > 0.005) {  // past the start-up transient of the platens
      for (int a = 0; a < 3; ++a)
        p.worst_agreement =
            std::max(p.worst_agreement, std::abs(particle[a] - boundary[a]) / boundary[a]);
      p.platen_excess_sum += sa / boundary[2] - 1.0;
      ++p.platen_excess_rows;
    }
  }
  if (sa > p.peak_axial) p.peak_axial = sa, p.peak_strain = axial_strain;
  p.peak_deviator = std::max(p.peak_deviator, deviator);
  p.peak_ratio = std::max(p.peak_ratio, deviator / mean);
  p.last_axial = sa;
  p.last_strain = axial_strain;
}

// A ParaView snapshot: particles with velocity, displacement since the start, rotation and
// contact count; the walls; the .pvd index.
void TriaxialShear::snapshot(ElementRun& run) {
  const Simulation& sim = run.sim;
  const std::vector<int> contacts = contacts_per_particle(sim);
  add_vtk_snapshot(run, dir_, p_.step, particles_vtu(sim.particles(), &contacts),
                   walls_vtu(sim.walls(), 2.0 * p_.size0.z));
}

}  // namespace grainlab
