#include "lab/plane_strain_shear.hpp"

#include <fmt/format.h>

#include <cmath>

#include "io/output_files.hpp"
#include "lab/plane_strain_band.hpp"
#include "measure/boundary.hpp"
#include "measure/specimen_state.hpp"

namespace grainlab {
namespace {

constexpr const char* header =
    "time_s,axial_strain,lateral_strain,out_of_plane_strain,volumetric_strain,"
    "axial_stress_platens_Pa,axial_stress_particles_Pa,lateral_stress_membrane_Pa,"
    "lateral_stress_particles_Pa,lateral_stress_boundary_Pa,out_of_plane_stress_walls_Pa,"
    "out_of_plane_stress_particles_Pa,"
    "q_Pa,p_Pa,stress_ratio_q_over_p,mobilised_sin_phi,solid_fraction,coordination_number,"
    "inertial_number,membrane_beads,escaped_beads";

// Front and back fixed (plane strain), the platens driven at the platen speed.
std::array<AxisControl, 2> shear_axes(const PlaneStrainProgress& p) {
  return {AxisControl{}, AxisControl{AxisMode::speed, 0.0, p.platen_speed}};
}

}  // namespace

PlaneStrainShear::PlaneStrainShear(ElementRun& run, const PlaneStrainProgress& progress,
                                   const std::string& dir, const std::string* membrane_state)
    : p_(progress),
      dir_(dir),
      membrane_(plane_strain_membrane(progress.confining_stress, progress.diameter)),
      control_(membrane_, shear_axes(progress), ServoRegime::holding, 0.0),
      membrane_attached_(run.sim, membrane_),
      control_attached_(run.sim, control_) {
  if (membrane_state) {  // the forces are in the restored simulation already
    StateReader in(*membrane_state);
    membrane_.restore(in, run.sim);
  } else {
    membrane_.start(run.sim);
  }
}

PlaneStrainProgress PlaneStrainShear::restore(const ElementRun& run, std::string& membrane_state) {
  StateReader in(run.test_state);
  const PlaneStrainProgress p = in.value<PlaneStrainProgress>();
  membrane_state = in.text();
  return p;
}

void PlaneStrainShear::save(ElementRun& run) const {
  StateWriter membrane;
  membrane_.save(membrane, run.sim);
  StateWriter out;
  out.value(p_);
  out.text(membrane.bytes());
  run.test_state = out.bytes();
}

const char* PlaneStrainShear::curve_header() const {
  return header;
}

std::string PlaneStrainShear::position() const {
  return fmt::format("axial strain {:.2f} %", 100 * axial_strain_);
}

// Adds the current walls' and membrane's stresses (and, with `specimen`, the particles' and the
// boundary's average stress: a pass over all contacts) to the sums of the output interval.
void PlaneStrainShear::add_sample(const Simulation& sim, bool specimen) {
  const PlaneStrainBox box = plane_strain_box(sim, membrane_);
  for (int k = 0; k < 4; ++k) p_.wall_sum[k] += plane_strain_wall_stress(sim, box, k);
  // The membrane's applied stress: the forces along x it set this step over the face area.
  for (int side = 0; side < 2; ++side) p_.applied_sum[side] += membrane_.applied_stress(sim, side);
  ++p_.wall_samples;
  if (!specimen) return;
  const Tensor3 s = love_weber_stress(sim, box.volume());
  const Tensor3 b = boundary_stress(sim, box.centre(), box.volume());
  for (int a = 0; a < 3; ++a) p_.particle_sum[a] += s[a][a], p_.boundary_sum[a] += b[a][a];
  ++p_.particle_samples;
}

void PlaneStrainShear::after_step(ElementRun& run) {
  add_sample(run.sim, p_.step % plane_strain_sample_steps == 0);
  ++p_.step;
}

void PlaneStrainShear::observe(ElementRun& run, Progress& progress) {
  const double height =
      run.sim.walls()[top_platen].point.z - run.sim.walls()[bottom_platen].point.z;
  axial_strain_ = (p_.size0.z - height) / p_.size0.z;
  strain_outputs(
      p_, axial_strain_, progress, [&] { record(run); }, [&] { snapshot(run); });
}

// One row of curve.csv (stresses averaged over the interval since the last row; at the start
// the instantaneous state), and the running peak and membrane checks.
void PlaneStrainShear::record(ElementRun& run) {
  const Simulation& sim = run.sim;
  PlaneStrainProgress& p = p_;
  const PlaneStrainBox box = plane_strain_box(sim, membrane_);
  const Vec3 size = box.size();
  if (p.wall_samples == 0 || p.particle_samples == 0) {  // the first row: the state itself
    p.wall_sum = {}, p.applied_sum = {}, p.particle_sum = {}, p.boundary_sum = {};
    p.wall_samples = 0, p.particle_samples = 0;
    add_sample(sim, true);
  }
  std::array<double, 4> w;
  for (int k = 0; k < 4; ++k) w[k] = p.wall_sum[k] / p.wall_samples;
  std::array<double, 3> particle, boundary;
  for (int a = 0; a < 3; ++a) {
    particle[a] = p.particle_sum[a] / p.particle_samples;
    boundary[a] = p.boundary_sum[a] / p.particle_samples;
  }
  const double applied = 0.5 * (p.applied_sum[0] + p.applied_sum[1]) / p.wall_samples;
  p.wall_sum = {}, p.applied_sum = {}, p.particle_sum = {}, p.boundary_sum = {};
  p.wall_samples = 0, p.particle_samples = 0;

  const double s1 = 0.5 * (w[bottom_platen] + w[top_platen]);  // axial (platens)
  const double s2 = 0.5 * (w[front] + w[back]);                // out of plane
  const double s3 = applied;                                   // lateral (membrane)
  const double q =
      std::sqrt(0.5 * ((s1 - s2) * (s1 - s2) + (s2 - s3) * (s2 - s3) + (s3 - s1) * (s3 - s1)));
  const double mean = (s1 + s2 + s3) / 3.0;
  const double sin_phi = (s1 - s3) / (s1 + s3);
  const Vec3 strain = box_strain(p.size0, size);
  const double volumetric = volumetric_strain(p.size0, size);
  const double inertial = inertial_number(p.strain_rate, p.diameter, p.density, mean);
  const MembraneFaces faces = membrane_.measure(sim);
  run.curve_rows += fmt::format(
      "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", exact(sim.time()),
      exact(strain.z), exact(strain.x), exact(strain.y), exact(volumetric), exact(s1),
      exact(particle[2]), exact(s3), exact(particle[0]), exact(boundary[0]), exact(s2),
      exact(particle[1]), exact(q), exact(mean), exact(q / mean), exact(sin_phi),
      exact(solid_fraction(sim.particles(), box.volume())), exact(coordination_number(sim)),
      exact(inertial), faces.beads, faces.escaped);
  p.max_escaped = std::max(p.max_escaped, faces.escaped);
  p.max_out_of_plane_strain = std::max(p.max_out_of_plane_strain, std::abs(strain.y));
  if (p.step > 0) {
    p.max_inertial = std::max(p.max_inertial, inertial);
    if (strain.z > 0.005) {  // past the start-up transient of the platens
      const double e = particle[0] / boundary[0] - 1.0;
      p.membrane_error2 += e * e;
      p.max_membrane_error = std::max(p.max_membrane_error, std::abs(e));
      p.max_applied_error = std::max(p.max_applied_error, std::abs(particle[0] / s3 - 1.0));
      p.wall_friction_share_sum += boundary[0] / s3 - 1.0;
      ++p.membrane_samples;
    }
  }
  if (s1 > p.peak_axial) {
    p.peak_axial = s1, p.peak_strain = strain.z, p.peak_lateral = s3;
    p.peak_deviator = s1 - s3;
  }
  p.last_axial = s1;
  p.last_strain = strain.z;
}

// A ParaView snapshot: particles (with the local shear strain since the start) and the walls.
void PlaneStrainShear::snapshot(ElementRun& run) {
  const Simulation& sim = run.sim;
  const std::vector<int> contacts = contacts_per_particle(sim);
  const std::vector<double> shear = local_shear_strain(sim.particles(), p_.diameter);
  add_vtk_snapshot(run, dir_, p_.step, particles_vtu(sim.particles(), &contacts, &shear),
                   walls_vtu(sim.walls(), 2.0 * p_.size0.z));
}

}  // namespace grainlab
