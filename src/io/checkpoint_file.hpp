// The sealed file format shared by grainlab's checkpoints (the loading's checkpoint.bin and the
// preparation's preparation.bin): the bytes of a StateWriter followed by their FNV-1a checksum,
// written atomically. A damaged file is refused (ConfigError naming it) instead of resuming to a
// different result.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "core/state_io.hpp"
#include "io/config_error.hpp"

namespace grainlab {

// The checksum that seals a checkpoint's bytes (FNV-1a, 64 bit).
uint64_t checkpoint_checksum(std::string_view bytes);

// Appends the checksum to `out` and writes it to `path` atomically.
void write_sealed(StateWriter& out, const std::string& path);

// The file's bytes without the checksum, after verifying it; ConfigError when the file is
// missing, truncated or damaged.
std::string read_sealed(const std::string& path);

// Whether the file at `path` starts with `magic` (a checkpoint of that kind; not verified).
bool has_checkpoint_magic(const std::string& path, uint64_t magic);

// What every checkpoint starts with, after its kind's magic number: the test type and the config
// (path and text) the run was started from, so that a resume needs nothing but the file.
struct CheckpointHeader {
  std::string type, config_path, config_text;
};
void write_checkpoint_header(StateWriter& out, uint64_t magic, const CheckpointHeader& header);
// The sealed file verified and its header read into `header`; the reader continues after it.
// ConfigError naming the file when it is missing, damaged or not a `kind` (its magic number).
StateReader open_checkpoint(const std::string& path, uint64_t magic, const char* kind,
                            CheckpointHeader& header);

// The error for a checkpoint that was read but cannot be resumed (a simulation state of another
// format, or contents that do not fit this run): the file and the reason, for the caller to throw.
ConfigError unresumable_checkpoint(const std::string& path, const std::exception& why);

}  // namespace grainlab
