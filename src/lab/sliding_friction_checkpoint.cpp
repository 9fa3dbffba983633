#include "lab/sliding_friction_checkpoint.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>

#include "core/simulation.hpp"
#include "io/config_error.hpp"

namespace grainlab {
namespace {

constexpr uint64_t sliding_magic = 0x67726e6c73667231;  // "grnlsfr1"
constexpr const char* sliding_kind = "sliding-friction checkpoint";

void write_record(StateWriter& out, const std::vector<std::array<double, 4>>& record) {
  out.array(record);
}

std::vector<std::array<double, 4>> read_record(StateReader& in) {
  std::vector<std::array<double, 4>> record;
  in.array(record);
  for (const auto& row : record)
    for (double v : row)
      if (!std::isfinite(v)) throw std::runtime_error("a force record with a non-finite value");
  return record;
}

// A yes/no flag (one byte, 0 or 1: any other value is damage).
bool flag(StateReader& in, const char* what) {
  const uint8_t v = in.value<uint8_t>();
  if (v > 1) throw std::runtime_error(fmt::format("{} is not a yes/no flag", what));
  return v == 1;
}

// A deposited bed as read, checked as thoroughly as a restored simulation's particles.
void check_bed(const ParticleStore& p, int bead_material) {
  const size_t count = p.size();
  const_cast<ParticleStore&>(p).for_each_field([&](const auto& field) {
    if (field.size() != count) throw std::runtime_error("bed fields of different lengths");
  });
  auto finite3 = [](const Vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
  };
  for (size_t i = 0; i < count; ++i) {
    if (p.material[i] != bead_material)
      throw std::runtime_error(fmt::format("bed bead {} has material index {} (expected {})", i,
                                           p.material[i], bead_material));
    if (p.id[i] >= count)
      throw std::runtime_error(fmt::format("bed bead {} has id {} of {}", i, p.id[i], count));
    if (!(finite3(p.position[i]) && finite3(p.velocity[i]) && finite3(p.angular_velocity[i]) &&
          std::isfinite(p.radius[i]) && p.radius[i] > 0 && std::isfinite(p.inverse_mass[i]) &&
          p.inverse_mass[i] >= 0 && std::isfinite(p.inverse_inertia[i]) &&
          p.inverse_inertia[i] >= 0))
      throw std::runtime_error(fmt::format(
          "bed bead {} has a non-finite or negative position, velocity, radius or mass", i));
  }
}

double finite(StateReader& in, const char* what) {
  const double v = in.value<double>();
  if (!std::isfinite(v)) throw std::runtime_error(fmt::format("{} is not finite", what));
  return v;
}

}  // namespace

SlidingFrictionCheckpoints::SlidingFrictionCheckpoints(std::string path, CheckpointHeader header,
                                                       double interval_s)
    : path_(std::move(path)), header_(std::move(header)), clock_(interval_s) {}

bool SlidingFrictionCheckpoints::is_one(const std::string& path) {
  return has_checkpoint_magic(path, sliding_magic);
}

CheckpointHeader SlidingFrictionCheckpoints::peek(const std::string& path) {
  CheckpointHeader header;
  open_checkpoint(path, sliding_magic, sliding_kind, header);
  return header;
}

SlidingFrictionCheckpoints SlidingFrictionCheckpoints::resume(const std::string& path,
                                                              double interval_s, int bead_material,
                                                              const PairTable& table) {
  CheckpointHeader header;
  StateReader in = open_checkpoint(path, sliding_magic, sliding_kind, header);
  SlidingFrictionCheckpoints out(path, header, interval_s);
  try {
    out.wall_time_before_ = finite(in, "the wall time");
    for (uint64_t n = in.count(4 * sizeof(double)); n > 0; --n) {
      const double friction = finite(in, "a pull's friction");
      LoadRun run;
      run.load = finite(in, "a pull's load");
      run.mean_force = finite(in, "a pull's mean force");
      run.force_sd = finite(in, "a pull's force deviation");
      run.record = read_record(in);
      out.pulls_.emplace_back(friction, std::move(run));
    }
    for (uint64_t n = in.count(2 * sizeof(double)); n > 0; --n) {
      SavedBed bed;
      bed.friction = finite(in, "the bed's friction");
      bed.top = finite(in, "the bed's top");
      bed.particles.for_each_field([&](auto& field) { in.array(field); });
      check_bed(bed.particles, bead_material);
      out.beds_.push_back(std::move(bed));
    }
    if (flag(in, "the pull-under-way flag")) {
      PullState pull;
      pull.friction = finite(in, "the pull's friction");
      pull.load = finite(in, "the pull's load");
      pull.pulling = flag(in, "the pull's phase");
      pull.anchor = finite(in, "the rope's anchor");
      pull.start_anchor = finite(in, "the rope's start");
      pull.start_time = finite(in, "the pull's start time");
      pull.pull_steps = in.value<long>();
      if (pull.pull_steps < 0) throw std::runtime_error("a negative step count");
      pull.record = read_record(in);
      pull.simulation = in.text();
      StateReader state(pull.simulation);
      const Simulation restored(state, table);  // throws on an inconsistent state
      if (!state.at_end()) throw std::runtime_error("trailing data after the pull's state");
      out.pull_ = std::move(pull);
    }
    if (!in.at_end()) throw std::runtime_error("trailing data");
  } catch (const std::runtime_error& e) {
    throw unresumable_checkpoint(path, e);
  }
  return out;
}

const LoadRun* SlidingFrictionCheckpoints::finished_pull(double friction, double load) const {
  for (const auto& [f, run] : pulls_)
    if (f == friction && run.load == load) return &run;
  return nullptr;
}

const SavedBed* SlidingFrictionCheckpoints::bed(double friction) const {
  for (const SavedBed& b : beds_)
    if (b.friction == friction) return &b;
  return nullptr;
}

std::optional<PullState> SlidingFrictionCheckpoints::take_pull(double friction, double load) {
  if (!pull_ || pull_->friction != friction || pull_->load != load) return std::nullopt;
  std::optional<PullState> out = std::move(pull_);
  pull_.reset();
  return out;
}

void SlidingFrictionCheckpoints::record_bed(double friction, const ParticleStore& particles,
                                            double top) {
  // Every trial's bed is kept, so that a resumed inverse search deposits none of them again.
  for (SavedBed& b : beds_)
    if (b.friction == friction) {
      b = SavedBed{friction, particles, top};
      return;
    }
  beds_.push_back(SavedBed{friction, particles, top});
}

void SlidingFrictionCheckpoints::record_pull(double friction, const LoadRun& run) {
  pulls_.emplace_back(friction, run);
}

void SlidingFrictionCheckpoints::save(const PullState& pull) const {
  StateWriter out;
  write_checkpoint_header(out, sliding_magic, header_);
  out.value(wall_time());
  out.value(static_cast<uint64_t>(pulls_.size()));
  for (const auto& [friction, run] : pulls_) {
    out.value(friction), out.value(run.load), out.value(run.mean_force), out.value(run.force_sd);
    write_record(out, run.record);
  }
  out.value(static_cast<uint64_t>(beds_.size()));
  for (const SavedBed& bed : beds_) {
    out.value(bed.friction), out.value(bed.top);
    const_cast<ParticleStore&>(bed.particles).for_each_field([&](const auto& f) { out.array(f); });
  }
  out.value(uint8_t{1});
  out.value(pull.friction), out.value(pull.load), out.value(static_cast<uint8_t>(pull.pulling)),
      out.value(pull.anchor), out.value(pull.start_anchor), out.value(pull.start_time),
      out.value(pull.pull_steps);
  write_record(out, pull.record);
  out.text(pull.simulation);
  write_sealed(out, path_);
}

std::string SlidingFrictionCheckpoints::describe() const {
  std::string out = fmt::format("{} pull(s) done", pulls_.size());
  if (pull_)
    out += fmt::format(", the pull at P = {:.4g} N (slider friction {:.4g}) {}", pull_->load,
                       pull_->friction,
                       pull_->pulling ? fmt::format("{} steps into the pull", pull_->pull_steps)
                                      : std::string("settling under its load"));
  return out;
}

std::string SlidingFrictionCheckpoints::interrupted_message() const {
  return fmt::format("interrupted; checkpoint written, continue with: grainlab run --resume {}",
                     std::filesystem::path(path_).parent_path().string());
}

}  // namespace grainlab
