#include "io/output_files.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "io/config_error.hpp"
#include "io/output_manifest.hpp"
#include "io/wall_control.hpp"

namespace grainlab {
namespace fs = std::filesystem;

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_file_atomically(const std::string& path, const std::string& content) {
  record_output(path);
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot write " + tmp);
    out << content;
    out.flush();
    if (!out) throw std::runtime_error("error writing " + tmp + " (disk full?)");
  }
  fs::rename(tmp, path);
}

CsvStream::CsvStream(std::string path, const std::string& header) : path_(std::move(path)) {
  record_output(path_);
  file_ = std::fopen((path_ + ".partial").c_str(), "w");
  if (!file_) throw std::runtime_error("cannot write " + path_ + ".partial");
  std::fputs((header + "\n").c_str(), file_);
}

CsvStream CsvStream::resumed(std::string path, long bytes) {
  CsvStream s;
  s.path_ = std::move(path);
  record_output(s.path_);
  const std::string partial = s.path_ + ".partial";
  std::error_code ec;
  const auto size = fs::file_size(partial, ec);
  if (ec || static_cast<long>(size) < bytes)
    throw std::runtime_error(partial +
                             " is shorter than at the checkpoint: it cannot be continued");
  fs::resize_file(partial, static_cast<uintmax_t>(bytes));
  s.file_ = std::fopen(partial.c_str(), "a");
  if (!s.file_) throw std::runtime_error("cannot write " + partial);
  return s;
}

long CsvStream::flushed_bytes() {
  if (std::fflush(file_) != 0) throw std::runtime_error("error writing " + path_ + " (disk full?)");
  return std::ftell(file_);
}

CsvStream::~CsvStream() {
  if (file_) std::fclose(file_);  // left as .partial: the run did not finish
}

void CsvStream::close() {
  if (!file_) return;
  const bool ok = std::fflush(file_) == 0;
  std::fclose(file_);
  file_ = nullptr;
  if (!ok) throw std::runtime_error("error writing " + path_ + " (disk full?)");
  fs::rename(path_ + ".partial", path_);
}

std::string exact(double v) {
  return fmt::format("{:.17g}", v);
}

std::string trace_row(double t, const ParticleStore& p, size_t i) {
  const Vec3 &x = p.position[i], &v = p.velocity[i], &w = p.angular_velocity[i];
  return fmt::format("{},{},{},{},{},{},{},{},{},{},{}\n", exact(t), p.id[i], exact(x.x),
                     exact(x.y), exact(x.z), exact(v.x), exact(v.y), exact(v.z), exact(w.x),
                     exact(w.y), exact(w.z));
}

std::string walls_header(const std::vector<Wall>& walls) {
  std::string out = "time_s";
  for (const Wall& w : walls)
    out += fmt::format(
        ",{0}_force_x_N,{0}_force_y_N,{0}_force_z_N,{0}_normal_stress_Pa,{0}_contacts,{0}_x_m,"
        "{0}_y_m,{0}_z_m",
        w.name);
  return out;
}

std::string walls_row(double t, const std::vector<Wall>& walls,
                      const std::vector<std::optional<double>>& areas_m2) {
  std::string out = exact(t);
  for (size_t k = 0; k < walls.size(); ++k) {
    const Wall& w = walls[k];
    const std::string stress =
        areas_m2[k] ? exact(compressive_normal_stress(w, *areas_m2[k])) : std::string();
    out += fmt::format(",{},{},{},{},{},{},{},{}", exact(w.force.x), exact(w.force.y),
                       exact(w.force.z), stress, w.contact_count, exact(w.point.x),
                       exact(w.point.y), exact(w.point.z));
  }
  return out + "\n";
}

std::vector<size_t> indices_by_id(const ParticleStore& p) {
  std::vector<size_t> order(p.size());
  for (size_t i = 0; i < p.size(); ++i) order[p.id[i]] = i;
  return order;
}

std::string final_table(const ParticleStore& p) {
  std::string out = "id,material,radius,x,y,z,vx,vy,vz,wx,wy,wz\n";
  for (size_t i : indices_by_id(p)) {
    const Vec3 &x = p.position[i], &v = p.velocity[i], &w = p.angular_velocity[i];
    out += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{}\n", p.id[i], p.material[i],
                       exact(p.radius[i]), exact(x.x), exact(x.y), exact(x.z), exact(v.x),
                       exact(v.y), exact(v.z), exact(w.x), exact(w.y), exact(w.z));
  }
  return out;
}

namespace {
void vector_array(std::string& out, const char* name, const std::vector<size_t>& order,
                  auto&& value) {
  out += fmt::format(
      "        <DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"3\" "
      "format=\"ascii\">\n",
      name);
  for (size_t i : order) {
    const Vec3 v = value(i);
    out += fmt::format("{:.9g} {:.9g} {:.9g}\n", v.x, v.y, v.z);
  }
  out += "        </DataArray>\n";
}
}  // namespace

std::string particles_vtu(const ParticleStore& p, const std::vector<int>* contact_count,
                          const std::vector<double>* shear_strain) {
  const std::vector<size_t> order = indices_by_id(p);
  const size_t n = p.size();
  std::string out =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
      "byte_order=\"LittleEndian\">\n"
      "  <UnstructuredGrid>\n";
  out += fmt::format("    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", n, n);
  out += "      <PointData Scalars=\"radius\" Vectors=\"velocity\">\n";
  out += "        <DataArray type=\"Float64\" Name=\"radius\" format=\"ascii\">\n";
  for (size_t i : order) out += fmt::format("{:.9g}\n", p.radius[i]);
  out += "        </DataArray>\n        <DataArray type=\"Int32\" Name=\"id\" format=\"ascii\">\n";
  for (size_t i : order) out += fmt::format("{}\n", p.id[i]);
  out +=
      "        </DataArray>\n        <DataArray type=\"Int32\" Name=\"material\" "
      "format=\"ascii\">\n";
  for (size_t i : order) out += fmt::format("{}\n", p.material[i]);
  out += "        </DataArray>\n";
  if (contact_count) {
    out += "        <DataArray type=\"Int32\" Name=\"contacts\" format=\"ascii\">\n";
    for (size_t i : order) out += fmt::format("{}\n", (*contact_count)[i]);
    out += "        </DataArray>\n";
  }
  if (shear_strain) {
    out += "        <DataArray type=\"Float64\" Name=\"shear_strain\" format=\"ascii\">\n";
    for (size_t i : order) out += fmt::format("{:.6g}\n", (*shear_strain)[i]);
    out += "        </DataArray>\n";
  }
  vector_array(out, "velocity", order, [&](size_t i) { return p.velocity[i]; });
  vector_array(out, "angular_velocity", order, [&](size_t i) { return p.angular_velocity[i]; });
  vector_array(out, "displacement", order,
               [&](size_t i) { return p.position[i] - p.initial_position[i]; });
  vector_array(out, "rotation", order, [&](size_t i) { return p.rotation[i]; });
  out += "      </PointData>\n      <Points>\n";
  vector_array(out, "position", order, [&](size_t i) { return p.position[i]; });
  out += "      </Points>\n      <Cells>\n";
  out += "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (size_t k = 0; k < n; ++k) out += fmt::format("{}\n", k);
  out +=
      "        </DataArray>\n        <DataArray type=\"Int64\" Name=\"offsets\" "
      "format=\"ascii\">\n";
  for (size_t k = 0; k < n; ++k) out += fmt::format("{}\n", k + 1);
  out +=
      "        </DataArray>\n        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for (size_t k = 0; k < n; ++k) out += "1\n";  // VTK_VERTEX
  out += "        </DataArray>\n      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  return out;
}

std::string walls_vtu(const std::vector<Wall>& walls, double extent) {
  std::vector<Vec3> points;
  std::vector<std::array<size_t, 4>> quads;
  for (const Wall& w : walls) {
    auto quad = [&](const Vec3& c, const Vec3& u, const Vec3& v) {
      const size_t b = points.size();
      points.push_back(c - u - v);
      points.push_back(c + u - v);
      points.push_back(c + u + v);
      points.push_back(c - u + v);
      quads.push_back({b, b + 1, b + 2, b + 3});
    };
    if (w.shape == WallShape::rectangle) {
      quad(w.point, w.half_u * w.axis_u, w.half_v * w.axis_v);
    } else if (w.shape == WallShape::plane) {
      const Vec3 t = std::abs(w.normal.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
      const Vec3 u =
          (1.0 / norm(t - dot(t, w.normal) * w.normal)) * (t - dot(t, w.normal) * w.normal);
      quad(w.point, 0.5 * extent * u, 0.5 * extent * cross(w.normal, u));
    } else {
      const Vec3 u = w.axis_u, v = cross(w.axis, w.axis_u);
      const int segments = 32;
      for (int s = 0; s < segments; ++s) {
        const double a0 = 2 * M_PI * s / segments, a1 = 2 * M_PI * (s + 1) / segments;
        const Vec3 p0 = w.point + w.radius * (std::cos(a0) * u + std::sin(a0) * v);
        const Vec3 p1 = w.point + w.radius * (std::cos(a1) * u + std::sin(a1) * v);
        const Vec3 mid = 0.5 * (p0 + p1);
        quad(mid, 0.5 * (p1 - p0), 0.5 * extent * w.axis);
      }
    }
  }
  std::string out =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
      "byte_order=\"LittleEndian\">\n"
      "  <UnstructuredGrid>\n";
  out += fmt::format("    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n      <Points>\n",
                     points.size(), quads.size());
  out += "        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (const Vec3& p : points) out += fmt::format("{:.9g} {:.9g} {:.9g}\n", p.x, p.y, p.z);
  out += "        </DataArray>\n      </Points>\n      <Cells>\n";
  out += "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (const auto& q : quads) out += fmt::format("{} {} {} {}\n", q[0], q[1], q[2], q[3]);
  out +=
      "        </DataArray>\n        <DataArray type=\"Int64\" Name=\"offsets\" "
      "format=\"ascii\">\n";
  for (size_t k = 0; k < quads.size(); ++k) out += fmt::format("{}\n", 4 * (k + 1));
  out +=
      "        </DataArray>\n        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for (size_t k = 0; k < quads.size(); ++k) out += "9\n";  // VTK_QUAD
  out += "        </DataArray>\n      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  return out;
}

std::string pvd_index(const std::vector<std::pair<double, std::string>>& snapshots) {
  std::string out =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\">\n  <Collection>\n";
  for (const auto& [t, file] : snapshots)
    out += fmt::format("    <DataSet timestep=\"{:.9g}\" file=\"{}\"/>\n", t, file);
  out += "  </Collection>\n</VTKFile>\n";
  return out;
}

}  // namespace grainlab
