// A packing read from a CSV file (`[[particles]] file = "packing.csv"`), so that large packings
// need not be written as TOML tables (docs/scene-schema.md, "a packing read from CSV").
//
// Format: lines starting with '#' and blank lines are skipped; the first other line is a header
// naming the columns, in any order: radius, x, y, z (required; m), and optionally id, material,
// vx, vy, vz (m/s), wx, wy, wz (rad/s). `material` is a material name or its index in the
// config's [[material]] list; without the column every row takes the entry's `material`. With
// an `id` column the ids must be 0 .. N-1, each once, and the particles take that order (a
// grainlab final.csv reads back as it was written, except `fixed`, which it does not record).
// Every error names the file and line.
#pragma once

#include <string>
#include <vector>

#include "contact/material.hpp"
#include "io/scene_config.hpp"

namespace grainlab {

// default_material: index for rows without a material column (-1: the column is required).
// named_by: where the config names the file ("scene.toml line 26: particles[1].file"), for
// errors about the file as a whole. Each entry's `line` is its line in the CSV file. A UTF-8
// byte-order mark and a leading '+' on numbers are accepted. Throws ConfigError.
std::vector<ParticleEntry> read_packing_csv(const std::string& path,
                                            const std::vector<Material>& materials,
                                            int default_material, bool fixed,
                                            const std::string& named_by);

}  // namespace grainlab
