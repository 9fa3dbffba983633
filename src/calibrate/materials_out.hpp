// Writes calibrated coefficients as the `[[pair]]` entries that `grainlab run` reads:
//
//   [[pair]]
//   materials = ["glass", "rubber_membrane"]
//   # restitution: mean of 20 throws in throws.csv (95 % CI [0.571, 0.589])
//   restitution = 0.5801
//
// An existing file is merged, not overwritten: the keys being written replace the old ones (and
// their "# key: ..." provenance comments) of the same material pair, everything else of every
// pair is kept, new pairs are appended. So `calibrate restitution` and `calibrate friction`
// can write into one file, in either order. A file with anything besides [[pair]] tables (e.g.
// a whole scene) is refused rather than rewritten. The file is replaced atomically.
#pragma once

#include <string>
#include <vector>

namespace grainlab::calibrate {

struct PairValue {
  std::string key;  // "restitution" or "friction"
  double value = 0.0;
  std::string provenance;  // one line: where the value came from (file, n, CI)
};

struct PairUpdate {
  std::string material_a;  // the bead material, e.g. "glass"
  std::string material_b;  // the test material, e.g. "rubber_membrane"
  std::vector<PairValue> values;
};

// The new file content: `existing` merged with `updates` (`existing` may be empty).
// `file_name` is only for error messages. Throws InputError.
std::string merge_materials_toml(const std::string& existing, const std::string& file_name,
                                 const std::vector<PairUpdate>& updates);

// Reads `path` if it exists, merges, writes `path` atomically (temporary file + rename).
void write_materials_toml(const std::string& path, const std::vector<PairUpdate>& updates);

// Writes `content` to `path` through a temporary file in the same directory and a rename, so
// readers never see a partial file. Throws std::runtime_error.
void write_file_atomically(const std::string& path, const std::string& content);

}  // namespace grainlab::calibrate
