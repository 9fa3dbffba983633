#include "io/checkpoint_file.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string_view>

#include "io/config_error.hpp"
#include "io/output_files.hpp"

namespace grainlab {

uint64_t checkpoint_checksum(std::string_view bytes) {  // FNV-1a
  uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char b : bytes) h = (h ^ b) * 0x100000001b3ULL;
  return h;
}

void write_sealed(StateWriter& out, const std::string& path) {
  out.value(checkpoint_checksum(out.bytes()));
  write_file_atomically(path, out.bytes());
}

std::string read_sealed(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ConfigError(fmt::format("{}: no checkpoint to resume from", path));
  std::ostringstream s;
  s << in.rdbuf();
  std::string bytes = s.str();
  uint64_t stored = 0;
  if (bytes.size() < sizeof stored)
    throw ConfigError(fmt::format("{}: damaged checkpoint (truncated)", path));
  std::memcpy(&stored, bytes.data() + bytes.size() - sizeof stored, sizeof stored);
  bytes.resize(bytes.size() - sizeof stored);
  if (checkpoint_checksum(bytes) != stored)
    throw ConfigError(fmt::format(
        "{}: damaged checkpoint (checksum mismatch): it cannot be resumed; rerun the test", path));
  return bytes;
}

bool has_checkpoint_magic(const std::string& path, uint64_t magic) {
  std::ifstream in(path, std::ios::binary);
  uint64_t first = 0;
  return in.read(reinterpret_cast<char*>(&first), sizeof first) && first == magic;
}

void write_checkpoint_header(StateWriter& out, uint64_t magic, const CheckpointHeader& header) {
  out.value(magic);
  out.text(header.type);
  out.text(header.config_path);
  out.text(header.config_text);
}

StateReader open_checkpoint(const std::string& path, uint64_t magic, const char* kind,
                            CheckpointHeader& header) {
  StateReader in(read_sealed(path));
  try {
    if (in.value<uint64_t>() != magic)
      throw std::runtime_error(fmt::format("not a grainlab {}", kind));
    header.type = in.text();
    header.config_path = in.text();
    header.config_text = in.text();
  } catch (const std::runtime_error& e) {
    throw unresumable_checkpoint(path, e);
  }
  return in;
}

ConfigError unresumable_checkpoint(const std::string& path, const std::exception& why) {
  return ConfigError(fmt::format("{}: cannot resume from this checkpoint ({})", path, why.what()));
}

}  // namespace grainlab
