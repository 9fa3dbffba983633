// The element-test checkpoint file: magic, test type, config, run info, curve and VTK index so
// far, the stage's own state, wall time, the simulation state, sealed with a checksum
// (io/checkpoint_file.hpp; lab/element_test.hpp: save_checkpoint, peek_checkpoint,
// load_checkpoint).
#include <fmt/format.h>

#include <cstring>
#include <fstream>
#include <sstream>
#include <string_view>

#include "io/checkpoint_file.hpp"
#include "io/config_error.hpp"
#include "io/output_files.hpp"
#include "lab/element_test.hpp"

namespace grainlab {

namespace {

constexpr uint64_t checkpoint_magic = 0x67726e6c656c7432;  // "grnlelt2"
constexpr const char* checkpoint_kind = "element-test checkpoint";

}  // namespace

void save_checkpoint(const ElementRun& run, const std::string& path) {
  StateWriter out;
  write_checkpoint_header(out, checkpoint_magic, {run.type, run.config_path, run.config_text});
  out.text(run.run_info);
  out.text(run.curve_rows);
  out.text(run.vtk_index);
  out.text(run.test_state);
  out.value(run.wall_time_before);
  run.sim.save_state(out);
  write_sealed(out, path);
}

CheckpointHeader peek_checkpoint(const std::string& path) {
  CheckpointHeader header;
  open_checkpoint(path, checkpoint_magic, checkpoint_kind, header);
  return header;
}

ElementRun load_checkpoint(const std::string& path, PairTable table) {
  CheckpointHeader h;
  StateReader in = open_checkpoint(path, checkpoint_magic, checkpoint_kind, h);
  try {
    std::string info = in.text(), rows = in.text(), vtk = in.text(), state = in.text();
    const double wall_time_before = in.value<double>();
    Simulation sim(in, std::move(table));
    if (!in.at_end()) throw std::runtime_error("trailing data");
    return ElementRun{std::move(sim),           std::move(h.type), std::move(h.config_path),
                      std::move(h.config_text), std::move(info),   std::move(rows),
                      std::move(vtk),           std::move(state),  wall_time_before};
  } catch (const std::runtime_error& e) {
    throw unresumable_checkpoint(path, e);
  }
}

}  // namespace grainlab
