// Result files: the output directory, atomic writes (a file is either complete or absent),
// particle tables as CSV and ParaView (VTK XML) snapshots.
#pragma once

#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "core/particles.hpp"
#include "geometry/wall.hpp"
#include "io/output_manifest.hpp"

namespace grainlab {

// The whole content of the file at `path` ("" when it cannot be read).
std::string read_file(const std::string& path);

// Writes `content` to `path` via a temporary file and rename, so a reader never sees half a file.
void write_file_atomically(const std::string& path, const std::string& content);

// Line-buffered CSV written to PATH.partial and renamed to PATH by close(): an interrupted run
// leaves no file that looks complete.
class CsvStream {
 public:
  CsvStream(std::string path, const std::string& header);
  // Continues PATH.partial of an interrupted run, cut back to the `bytes` it had at its checkpoint.
  static CsvStream resumed(std::string path, long bytes);
  // Flushes and returns the bytes written so far (for a checkpoint).
  long flushed_bytes();
  ~CsvStream();
  CsvStream(const CsvStream&) = delete;
  CsvStream& operator=(const CsvStream&) = delete;
  void write(const std::string& line) { std::fputs(line.c_str(), file_); }
  void close();
  CsvStream(CsvStream&& other) noexcept : path_(std::move(other.path_)), file_(other.file_) {
    other.file_ = nullptr;
  }

 private:
  CsvStream() = default;
  std::string path_;
  std::FILE* file_ = nullptr;
};

// Round-trip exact text of a double (17 significant digits).
std::string exact(double v);

// One CSV row per particle: t,id,x,y,z,vx,vy,vz,wx,wy,wz (SI units).
inline constexpr const char* trace_header = "t,id,x,y,z,vx,vy,vz,wx,wy,wz";
std::string trace_row(double time, const ParticleStore& p, size_t index);

// walls.csv: `time_s`, then per wall (in config order, named by the wall's name)
// NAME_force_x_N, NAME_force_y_N, NAME_force_z_N (exerted by the particles on the wall),
// NAME_normal_stress_Pa (compressive, over `areas_m2[k]`; empty where the wall has no area),
// NAME_contacts, NAME_x_m, NAME_y_m, NAME_z_m (the wall's point).
std::string walls_header(const std::vector<Wall>& walls);
std::string walls_row(double time, const std::vector<Wall>& walls,
                      const std::vector<std::optional<double>>& areas_m2);

// Every particle, sorted by id: id,material,radius,x,y,z,vx,vy,vz,wx,wy,wz.
std::string final_table(const ParticleStore& p);

// Indices of the particles sorted by id.
std::vector<size_t> indices_by_id(const ParticleStore& p);

// One VTK UnstructuredGrid (.vtu) of the particles as points, with radius, velocity, angular
// velocity, displacement since the start, accumulated rotation, id and material.
// `contact_count` (per particle index, optional) adds a "contacts" array, `shear_strain` a
// "shear_strain" array (the local in-plane shear strain, measure/local_strain.hpp).
std::string particles_vtu(const ParticleStore& p, const std::vector<int>* contact_count = nullptr,
                          const std::vector<double>* shear_strain = nullptr);

// A .vtu of the walls: planes and rectangles as quads, cylinders as a ring of quads, sized to
// `extent` (m) where the wall itself is unbounded.
std::string walls_vtu(const std::vector<Wall>& walls, double extent);

// The ParaView collection index (.pvd) listing (time, file) pairs.
std::string pvd_index(const std::vector<std::pair<double, std::string>>& snapshots);

}  // namespace grainlab
