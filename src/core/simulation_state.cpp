// Simulation's state as a checkpoint holds it: save_state, the constructor that restores it, and
// the consistency checks a restored state must pass (core/state_io.hpp for the byte format).
#include <fmt/format.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/simulation.hpp"

namespace grainlab {
namespace {

void write_walls(StateWriter& out, const std::vector<Wall>& walls) {
  out.value<uint64_t>(walls.size());
  for (const Wall& w : walls) {
    out.text(w.name);
    out.value(w.shape), out.value(w.material), out.value(w.point), out.value(w.normal),
        out.value(w.axis_u);
    out.value(w.axis_v), out.value(w.half_u), out.value(w.half_v), out.value(w.axis),
        out.value(w.radius);
    out.value(w.velocity), out.value(w.mass), out.value(w.external_force), out.value(w.force);
    out.value(w.contact_stiffness), out.value(w.contact_count);
  }
}

std::vector<Wall> read_walls(StateReader& in) {
  // Each wall record holds at least its name's length and its numbers.
  std::vector<Wall> walls(in.count(sizeof(uint64_t) + 10 * sizeof(Vec3)));
  for (Wall& w : walls) {
    w.name = in.text();
    w.shape = in.value<WallShape>(), w.material = in.value<int>(), w.point = in.value<Vec3>();
    w.normal = in.value<Vec3>(), w.axis_u = in.value<Vec3>(), w.axis_v = in.value<Vec3>();
    w.half_u = in.value<double>(), w.half_v = in.value<double>(), w.axis = in.value<Vec3>();
    w.radius = in.value<double>(), w.velocity = in.value<Vec3>(), w.mass = in.value<double>();
    w.external_force = in.value<Vec3>(), w.force = in.value<Vec3>(),
    w.contact_stiffness = in.value<double>();
    w.contact_count = in.value<int>();
  }
  return walls;
}

constexpr uint64_t state_magic = 0x67726e6c61623035;  // "grnlab05"

}  // namespace

void Simulation::save_state(StateWriter& out) const {
  out.value(state_magic);
  out.value(settings_);
  out.value(pieces_);
  out.array(table_.entries());
  auto write = [&](const auto& field) { out.array(field); };
  const_cast<ParticleStore&>(particles_).for_each_field(write);
  write_walls(out, walls_);
  const_cast<PairContacts&>(pairs_).for_each_field(write);
  const_cast<WallContacts&>(wall_contacts_).for_each_field(write);
  const_cast<NeighborSearch&>(neighbors_).for_each_field(write);
  out.value(const_cast<NeighborSearch&>(neighbors_).rebuild_count_ref());
  out.value(const_cast<NeighborSearch&>(neighbors_).refresh_count_ref());
  out.value(time_), out.value(step_count_), out.value(max_overlap_fraction_),
      out.value(max_speed2_), out.value(external_forces_);
}

Simulation::Simulation(StateReader& in, PairTable table)
    : table_(std::move(table)), neighbors_(1.0) {
  const uint64_t magic = in.value<uint64_t>();
  // The last byte is the format's version (ASCII digits); the first seven say "grnlab0".
  if ((magic >> 8) == (state_magic >> 8) && magic != state_magic)
    throw std::runtime_error(fmt::format(
        "a simulation state of format {} (another grainlab version); this build reads format {}: "
        "start the run again",
        static_cast<char>(magic & 0xff), static_cast<char>(state_magic & 0xff)));
  if (magic != state_magic) throw std::runtime_error("not a grainlab simulation state");
  settings_ = in.value<SimulationSettings>();
  pieces_ = in.value<ContactPieces>();
  std::vector<PairParams> entries;
  in.array(entries);
  if (entries.size() != table_.entries().size())
    throw std::runtime_error("the checkpoint's materials do not match the configuration");
  table_.restore_entries(entries);
  neighbors_ = NeighborSearch(settings_.skin, settings_.skin * settings_.list_skin_fraction);
  auto read = [&](auto& field) { in.array(field); };
  particles_.for_each_field(read);
  walls_ = read_walls(in);
  pairs_.for_each_field(read);
  wall_contacts_.for_each_field(read);
  neighbors_.for_each_field(read);
  neighbors_.rebuild_count_ref() = in.value<long>();
  neighbors_.refresh_count_ref() = in.value<long>();
  time_ = in.value<double>(), step_count_ = in.value<long>();
  max_overlap_fraction_ = in.value<double>(), max_speed2_ = in.value<double>();
  external_forces_ = in.value<bool>();
  check_restored_state();
  index_entry_owners(true);
}

// A restored state is used as it is, so every index it holds is checked first: a damaged or
// foreign checkpoint must stop with a message, never index out of bounds.
void Simulation::check_restored_state() const {
  auto fail = [](const std::string& what) {
    throw std::runtime_error("inconsistent state: " + what);
  };
  const ParticleStore& p = particles_;
  const size_t n = p.size();
  const_cast<ParticleStore&>(p).for_each_field([&](const auto& field) {
    if (field.size() != n) fail("particle fields of different lengths");
  });
  const int materials = table_.material_count();
  for (size_t i = 0; i < n; ++i) {
    if (p.material[i] < 0 || p.material[i] >= materials)
      fail(fmt::format("particle {} has material index {} (the config has {})", i, p.material[i],
                       materials));
    if (!(p.radius[i] > 0.0 && std::isfinite(p.radius[i])) || !(p.inverse_mass[i] >= 0.0) ||
        !std::isfinite(norm2(p.position[i])) || p.id[i] >= n)
      fail(fmt::format("particle {} has an invalid radius, mass, position or id", i));
  }
  for (const Wall& w : walls_)
    if (w.material < 0 || w.material >= materials)
      fail(fmt::format("wall {} has material index {}", w.name, w.material));
  auto check_rows = [&](const std::vector<uint32_t>& rows, size_t entries, const char* what) {
    if (rows.size() != n + 1 || rows.front() != 0 || rows.back() != entries)
      fail(std::string(what) + " rows do not match the particles");
    for (size_t i = 0; i < n; ++i)
      if (rows[i] > rows[i + 1]) fail(std::string(what) + " rows are not ordered");
  };
  const PairContacts& c = pairs_;
  check_rows(c.row_start, c.partner.size(), "pair");
  check_rows(c.col_start, c.col_pair.size(), "pair column");
  for (uint32_t j : c.partner)
    if (j >= n) fail("a pair entry names a particle that does not exist");
  for (uint32_t e : c.col_pair)
    if (e >= c.partner.size()) fail("a pair column names an entry that does not exist");
  const_cast<PairContacts&>(c).for_each_field([&](const auto& field) {
    if (field.size() != c.partner.size() && field.size() != n + 1 && !field.empty() &&
        field.size() != c.col_pair.size())
      fail("pair contact fields of unexpected length");
  });
  if (!(settings_.list_skin_fraction > 0.0 && settings_.list_skin_fraction <= 1.0))
    fail("the list skin fraction is not in (0, 1]");
  if (const std::string what = neighbors_.inconsistency(n, c.partner.size()); !what.empty())
    fail(what);
  const WallContacts& wc = wall_contacts_;
  check_rows(wc.row_start, wc.wall.size(), "wall contact");
  for (uint32_t w : wc.wall)
    if (w >= walls_.size()) fail("a wall contact names a wall that does not exist");
}

}  // namespace grainlab
