// The sealed file format shared by grainlab's checkpoints (the loading's checkpoint.bin and the
// preparation's preparation.bin): the bytes of a StateWriter followed by their FNV-1a checksum,
// written atomically. A damaged file is refused (ConfigError naming it) instead of resuming to a
// different result.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "core/state_io.hpp"

namespace grainlab {

// The checksum that seals a checkpoint's bytes (FNV-1a, 64 bit).
uint64_t checkpoint_checksum(std::string_view bytes);

// Appends the checksum to `out` and writes it to `path` atomically.
void write_sealed(StateWriter& out, const std::string& path);

// The file's bytes without the checksum, after verifying it; ConfigError when the file is
// missing, truncated or damaged.
std::string read_sealed(const std::string& path);

}  // namespace grainlab
