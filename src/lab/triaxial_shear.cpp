#include "lab/triaxial_shear.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "control/box_controller.hpp"
#include "io/config_error.hpp"
#include "io/output_files.hpp"
#include "lab/interrupt.hpp"
#include "measure/boundary.hpp"
#include "measure/specimen_state.hpp"

namespace grainlab {
namespace {

constexpr uint64_t checkpoint_magic = 0x67726e6c74726933;  // "grnltri3"

// Adds the Love-Weber and boundary-average diagonals to the interval sums.
void add_specimen_stresses(ShearRun& run) {
  const Simulation& sim = run.sim;
  ShearProgress& p = run.progress;
  const Vec3 lo = box_low(sim.walls()), hi = box_high(sim.walls());
  const double volume = box_volume(sim.walls());
  const Tensor3 particles = love_weber_stress(sim, volume);
  const Tensor3 boundary = boundary_stress(sim, 0.5 * (lo + hi), volume);
  for (int a = 0; a < 3; ++a) {
    p.particle_stress_sum[a] += particles[a][a];
    p.boundary_stress_sum[a] += boundary[a][a];
  }
}

// Adds this step's stresses to the running sums of the output interval.
void accumulate(ShearRun& run) {
  Simulation& sim = run.sim;
  ShearProgress& p = run.progress;
  for (int k = 0; k < 6; ++k) p.wall_stress_sum[k] += wall_stress(sim.walls(), k);
  ++p.wall_samples;
  if (p.step % stress_sample_steps == 0) {
    add_specimen_stresses(run);
    ++p.particle_samples;
  }
}

// One row of curve.csv (stresses averaged over the interval since the last row; at the start
// the instantaneous state), and the running peaks and errors.
void record(ShearRun& run) {
  Simulation& sim = run.sim;
  ShearProgress& p = run.progress;
  const Vec3 size = box_high(sim.walls()) - box_low(sim.walls());
  const double axial_strain = (p.size0.z - size.z) / p.size0.z;
  const double volume = size.x * size.y * size.z, volume0 = p.size0.x * p.size0.y * p.size0.z;
  if (p.wall_samples == 0) {  // first row: the state itself
    for (int k = 0; k < 6; ++k) p.wall_stress_sum[k] = wall_stress(sim.walls(), k);
    p.wall_samples = 1;
    add_specimen_stresses(run);
    p.particle_samples = 1;
  }
  std::array<double, 6> w;
  for (int k = 0; k < 6; ++k) w[k] = p.wall_stress_sum[k] / p.wall_samples;
  std::array<double, 3> particle, boundary;
  for (int a = 0; a < 3; ++a) {
    particle[a] = p.particle_stress_sum[a] / std::max(1L, p.particle_samples);
    boundary[a] = p.boundary_stress_sum[a] / std::max(1L, p.particle_samples);
  }
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
  p.wall_stress_sum = {};
  p.wall_samples = 0;
  p.particle_stress_sum = {};
  p.boundary_stress_sum = {};
  p.particle_samples = 0;
}

// A ParaView snapshot: particles with velocity, displacement since the start, rotation and
// contact count; the walls; the .pvd index.
void snapshot(ShearRun& run, const std::string& dir) {
  const Simulation& sim = run.sim;
  std::filesystem::create_directories(dir + "/vtk");
  const std::string name = fmt::format("vtk/particles_{:08d}.vtu", run.progress.step);
  const std::vector<int> contacts = contacts_per_particle(sim);
  write_file_atomically(dir + "/" + name, particles_vtu(sim.particles(), &contacts));
  const std::string walls = fmt::format("vtk/walls_{:08d}.vtu", run.progress.step);
  write_file_atomically(dir + "/" + walls, walls_vtu(sim.walls(), 2.0 * run.progress.size0.z));
  run.vtk_index +=
      fmt::format("    <DataSet timestep=\"{:.9g}\" part=\"0\" file=\"{}\"/>\n", sim.time(), name);
  run.vtk_index +=
      fmt::format("    <DataSet timestep=\"{:.9g}\" part=\"1\" file=\"{}\"/>\n", sim.time(), walls);
  write_file_atomically(
      dir + "/particles.pvd",
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\">\n  <Collection>\n" +
          run.vtk_index + "  </Collection>\n</VTKFile>\n");
}

void write_curve(const ShearRun& run, const std::string& dir) {
  write_file_atomically(dir + "/curve.csv.partial",
                        std::string(curve_header) + "\n" + run.curve_rows);
}

}  // namespace

void shear(ShearRun& run, const std::string& dir, double checkpoint_interval_s,
           Progress& progress) {
  Simulation& sim = run.sim;
  ShearProgress& p = run.progress;
  // The lateral boundary held at sigma_3, the platens driven at the platen speed.
  const AxisControl lateral{AxisMode::stress, p.confining_stress};
  BoxController control(
      BoxControlSettings{{lateral, lateral, {AxisMode::speed, 0.0, p.platen_speed}},
                         ServoRegime::holding,
                         2.0 * p.platen_speed});
  control.set_integrals(p.servo_integral);
  const ScopedListener attached(sim, control);
  const auto session_start = std::chrono::steady_clock::now();
  auto last_checkpoint = session_start;
  auto checkpoint = [&] {
    p.servo_integral = control.integrals();
    const double before = p.wall_time_before;
    p.wall_time_before +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - session_start).count();
    write_curve(run, dir);
    save_checkpoint(run, dir + "/checkpoint.bin");
    p.wall_time_before = before;
    last_checkpoint = std::chrono::steady_clock::now();
  };
  for (;; ++p.step) {
    const Vec3 size = box_high(sim.walls()) - box_low(sim.walls());
    const double axial_strain = (p.size0.z - size.z) / p.size0.z;
    if (axial_strain >= p.next_output * p.output_strain_interval - 1e-12 ||
        p.step == p.total_steps) {
      ++p.next_output;
      record(run);
      progress.update(static_cast<double>(p.step) / p.total_steps,
                      fmt::format("axial strain {:.2f} %, axial stress {:.1f} kPa",
                                  100 * axial_strain, 1e-3 * p.last_axial));
    }
    if (p.vtk_strain_interval > 0 &&
        (axial_strain >= p.next_vtk * p.vtk_strain_interval - 1e-12 || p.step == p.total_steps)) {
      ++p.next_vtk;
      snapshot(run, dir);
    }
    if (p.step == p.total_steps) break;
    if (interrupt_requested()) {
      checkpoint();
      throw Interrupted(
          fmt::format("interrupted at axial strain {:.2f} %; checkpoint written, continue with: "
                      "grainlab run --resume {}",
                      100 * axial_strain, dir));
    }
    if (p.step % 1000 == 0 &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - last_checkpoint).count() >
            checkpoint_interval_s)
      checkpoint();
    sim.step();
    accumulate(run);
  }
  p.wall_time_before +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - session_start).count();
  write_curve(run, dir);
  std::filesystem::rename(dir + "/curve.csv.partial", dir + "/curve.csv");
  std::error_code ec;
  std::filesystem::remove(dir + "/checkpoint.bin", ec);
}

void save_checkpoint(const ShearRun& run, const std::string& path) {
  StateWriter out;
  out.value(checkpoint_magic);
  out.text(run.config_path);
  out.text(run.config_text);
  out.value(run.progress);
  out.text(run.curve_rows);
  out.text(run.run_info);
  out.text(run.vtk_index);
  run.sim.save_state(out);
  write_file_atomically(path, out.bytes());
}

namespace {
std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ConfigError(fmt::format("{}: no checkpoint to resume from", path));
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}
}  // namespace

void peek_checkpoint_config(const std::string& path, std::string& config_path,
                            std::string& config_text) {
  StateReader in(read_all(path));
  try {
    if (in.value<uint64_t>() != checkpoint_magic)
      throw std::runtime_error("not a grainlab triaxial checkpoint");
    config_path = in.text();
    config_text = in.text();
  } catch (const std::runtime_error& e) {
    throw ConfigError(fmt::format("{}: {}", path, e.what()));
  }
}

ShearRun load_checkpoint(const std::string& path, PairTable table) {
  StateReader in(read_all(path));
  try {
    if (in.value<uint64_t>() != checkpoint_magic)
      throw std::runtime_error("not a grainlab triaxial checkpoint");
    std::string config_path = in.text(), config_text = in.text();
    const ShearProgress progress = in.value<ShearProgress>();
    std::string rows = in.text(), info = in.text(), vtk = in.text();
    Simulation sim(in, std::move(table));
    if (!in.at_end()) throw std::runtime_error("trailing data");
    return ShearRun{std::move(sim),        progress,       std::move(rows),
                    std::move(info),       std::move(vtk), std::move(config_path),
                    std::move(config_text)};
  } catch (const std::runtime_error& e) {
    throw ConfigError(fmt::format("{}: damaged checkpoint ({})", path, e.what()));
  }
}

}  // namespace grainlab
