// `grainlab run SCENE.toml --out DIR`: builds the scene, integrates it for the configured
// duration and writes trace.csv, final.csv, summary.json and optional VTK snapshots.
#pragma once

#include <string>

namespace grainlab {

struct RunOptions {
  std::string out_dir;
  bool overwrite = false;
  int threads = 0;  // 0: OpenMP's default
  bool quiet = false;
  // Element tests: continue the preparation checkpointed in out_dir (grainlab run --resume), with
  // the config text stored there; empty for a fresh run.
  std::string resumed_preparation_config;
};

// Throws ConfigError for bad input (nothing is written then), BlowUpError if the run blows up.
void run_scene(const std::string& config_path, const RunOptions& options);

}  // namespace grainlab
