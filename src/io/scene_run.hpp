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
  // grainlab run --resume: the config text stored in out_dir's checkpoint, which the run
  // continues (an element test's preparation.bin, a sliding-friction test's checkpoint.bin);
  // empty for a fresh run.
  std::string resumed_config;
};

// Throws ConfigError for bad input (nothing is written then), BlowUpError if the run blows up.
void run_scene(const std::string& config_path, const RunOptions& options);

// Scene runs write DIR/checkpoint.bin every output.checkpoint_interval of wall time and on
// Ctrl-C / SIGTERM; `grainlab run --resume DIR` continues one bit-identically (the config file
// must be the one it started from). Whether DIR/checkpoint.bin is a scene run's:
bool is_scene_checkpoint(const std::string& path);
void resume_scene(const RunOptions& options);

}  // namespace grainlab
