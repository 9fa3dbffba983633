#include "io/output_manifest.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <vector>

#include "io/config_error.hpp"

namespace grainlab {
namespace fs = std::filesystem;
namespace {

// One run per process: the directory being written and what is already listed.
fs::path current_dir;
std::set<std::string> recorded;

std::vector<std::string> read_manifest(const fs::path& dir) {
  std::vector<std::string> entries;
  std::ifstream in(dir / manifest_name);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) entries.push_back(line);
  return entries;
}

// A listed entry must stay inside the directory (a damaged manifest must not delete elsewhere).
bool safe_entry(const std::string& entry) {
  const fs::path p(entry);
  if (p.is_absolute() || entry.empty()) return false;
  for (const fs::path& part : p)
    if (part == "..") return false;
  return true;
}

// The names of the result files grainlab writes at the top of an output directory.
constexpr const char* result_names[] = {
    "summary.json",   "trace.csv",      "final.csv",       "walls.csv",     "particles.pvd",
    "curve.csv",      "curve.png",      "specimen.csv",    "specimen.json", "trajectory.csv",
    "force_time.csv", "checkpoint.bin", "preparation.bin", "band.png",      "band_map.csv"};

}  // namespace

void prepare_output_dir(const std::string& dir, bool overwrite) {
  std::error_code ec;
  const fs::path d(dir);
  if (fs::exists(d, ec)) {
    if (!fs::is_directory(d, ec))
      throw ConfigError(fmt::format("--out {}: exists and is not a directory", dir));
    if (!fs::is_empty(d, ec) && !overwrite)
      throw ConfigError(fmt::format(
          "--out {}: directory exists and is not empty; choose another directory or pass "
          "--overwrite to replace the results an earlier run wrote there",
          dir));
    if (overwrite) {
      std::vector<std::string> entries = read_manifest(d);
      // Deepest first, so that a directory is tried after its files.
      std::sort(entries.begin(), entries.end(), std::greater<>());
      for (const std::string& e : entries) {
        if (!safe_entry(e)) continue;
        const fs::path p = d / e;
        if (e.back() == '/') {
          if (fs::is_directory(p, ec) && fs::is_empty(p, ec)) fs::remove(p, ec);
        } else {
          for (const char* suffix : {"", ".tmp", ".partial"})
            fs::remove(fs::path(p.string() + suffix), ec);
        }
      }
      fs::remove(d / manifest_name, ec);
      for (const char* name : result_names)
        if (fs::exists(d / name, ec))
          throw ConfigError(fmt::format(
              "--out {}: {} was not written by grainlab (it is not listed in {}), so --overwrite "
              "leaves it alone and the run would replace it; move it away or choose another "
              "directory",
              dir, name, manifest_name));
    }
  }
  fs::create_directories(d, ec);
  if (ec)
    throw ConfigError(fmt::format("--out {}: cannot create directory: {}", dir, ec.message()));
  current_dir = fs::absolute(d, ec);
  recorded.clear();
}

void continue_in_output_dir(const std::string& dir) {
  std::error_code ec;
  current_dir = fs::absolute(fs::path(dir), ec);
  recorded.clear();
  for (const std::string& e : read_manifest(current_dir)) recorded.insert(e);
}

void record_output(const std::string& path) {
  if (current_dir.empty()) return;
  std::error_code ec;
  const fs::path relative = fs::absolute(fs::path(path), ec)
                                .lexically_normal()
                                .lexically_relative(current_dir.lexically_normal());
  std::string entry = relative.generic_string();
  if (entry.empty() || entry == "." || !safe_entry(entry)) return;  // outside the directory
  if (path.back() == '/' && entry.back() != '/') entry += '/';
  if (!recorded.insert(entry).second) return;
  // Its directories first (e.g. vtk/), so they are removed too once empty.
  for (fs::path parent = fs::path(entry).parent_path(); !parent.empty();
       parent = parent.parent_path())
    if (recorded.insert(parent.generic_string() + "/").second) {
      std::ofstream(current_dir / manifest_name, std::ios::app) << parent.generic_string() << "/\n";
    }
  std::ofstream out(current_dir / manifest_name, std::ios::app);
  out << entry << "\n";
  if (!out) throw std::runtime_error("cannot write " + (current_dir / manifest_name).string());
}

}  // namespace grainlab
