// A seeded mutation fuzzer for every kind of input grainlab reads: configs (TOML: element-test
// readers, `grainlab params`' reader, scenes), quantities with units, CSV tables, specimen files
// and checkpoints. Each target starts from a corpus of valid inputs (the repository's examples;
// a specimen and a checkpoint made here), mutates them deterministically from a seed (bit flips,
// byte edits, cut/duplicated/swapped lines, numbers replaced by extreme values) and feeds each
// mutant to the reader in-process.
//
// An input may be refused only by the documented errors (ConfigError, toml::parse_error,
// InputError: exit code 2 in grainlab). Anything else thrown is a finding (it would end grainlab
// with exit 1 or worse); a crash or an input that takes longer than --time-limit seconds is one
// too: the input is saved to DIR/<target>-<kind>.input before the process ends.
//
//   fuzz_inputs --source REPO --work DIR [--inputs N] [--seed S] [--target NAME] [--time-limit S]
//
// Prints, per target, inputs tried, inputs per second, refused / accepted / findings. Exit 0
// when there is no finding.
#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <toml++/toml.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <typeinfo>
#include <vector>

#include "calibrate/csv_table.hpp"
#include "calibrate/input_error.hpp"
#include "geometry/cuboid_box.hpp"
#include "io/checkpoint_file.hpp"
#include "io/config_error.hpp"
#include "io/scene_config.hpp"
#include "io/units.hpp"
#include "lab/element_test.hpp"
#include "lab/lab_test.hpp"
#include "lab/scale_study.hpp"
#include "lab/sliding_friction_checkpoint.hpp"
#include "lab/specimen.hpp"
#include "lab/triaxial.hpp"

namespace fs = std::filesystem;
using namespace grainlab;

namespace {

// The input being tried, for the signal handlers (written with async-signal-safe calls only).
std::string current_input, crash_path_prefix;
char crash_path[4096];

void save_and_exit(int sig) {
  const char* kind = sig == SIGALRM ? "-hang.input" : "-crash.input";
  std::snprintf(crash_path, sizeof crash_path, "%s%s", crash_path_prefix.c_str(), kind);
  const int fd = ::open(crash_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd >= 0) {
    [[maybe_unused]] ssize_t n = ::write(fd, current_input.data(), current_input.size());
    ::close(fd);
  }
  const char msg[] = "fuzz_inputs: crash or hang; input saved\n";
  [[maybe_unused]] ssize_t n = ::write(2, msg, sizeof msg - 1);
  _exit(128 + sig);
}

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_file(const fs::path& p, const std::string& bytes) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out << bytes;
}

// Deterministic mutations of a text or binary input.
class Mutator {
 public:
  explicit Mutator(uint64_t seed) : rng_(seed) {}

  std::string mutate(const std::string& seed_input, bool text) {
    std::string s = seed_input;
    const int edits = 1 + static_cast<int>(below(4));
    for (int k = 0; k < edits; ++k) edit(s, text);
    return s;
  }

 private:
  size_t below(size_t n) {
    return n == 0 ? 0 : std::uniform_int_distribution<size_t>(0, n - 1)(rng_);
  }

  void edit(std::string& s, bool text) {
    static const char* extremes[] = {"0",
                                     "-1",
                                     "1e308",
                                     "-1e308",
                                     "nan",
                                     "inf",
                                     "-inf",
                                     "1e-320",
                                     "9223372036854775807",
                                     "-9223372036854775808",
                                     "4294967296",
                                     "\"inf s\"",
                                     "\"nan\"",
                                     "\"1e9 mm\"",
                                     "\"-0 kPa\"",
                                     "\"1e300 GPa\"",
                                     "\"\"",
                                     "[]",
                                     "{}",
                                     "true",
                                     "0.0000001",
                                     "1e30",
                                     "\"\\xff\\xfe\"",
                                     "\"2 mm mm\"",
                                     "100000000"};
    const size_t op = below(text ? 9 : 5);
    if (s.empty()) {
      s.push_back(static_cast<char>(below(256)));
      return;
    }
    const size_t at = below(s.size());
    switch (op) {
      case 0:  // flip a bit
        s[at] = static_cast<char>(s[at] ^ (1 << below(8)));
        break;
      case 1:  // replace a byte
        s[at] = static_cast<char>(below(256));
        break;
      case 2:  // insert a byte
        s.insert(s.begin() + static_cast<long>(at), static_cast<char>(below(256)));
        break;
      case 3:  // cut a range
        s.erase(at, 1 + below(std::min<size_t>(64, s.size() - at)));
        break;
      case 4: {  // duplicate a range
        const std::string piece = s.substr(at, 1 + below(64));
        s.insert(below(s.size()), piece);
        break;
      }
      case 5:  // truncate (text only)
        s.resize(at);
        break;
      case 6: {  // replace a number (or any token after '=' or ',') by an extreme value
        size_t start = s.find_first_of("0123456789\"", at);
        if (start == std::string::npos) start = at;
        size_t end = s.find_first_of(",\n]", start);
        if (end == std::string::npos) end = s.size();
        s.replace(start, end - start, extremes[below(std::size(extremes))]);
        break;
      }
      case 7: {  // swap two lines
        std::vector<std::string> lines = split(s);
        if (lines.size() > 1) std::swap(lines[below(lines.size())], lines[below(lines.size())]);
        s = join(lines);
        break;
      }
      default: {  // delete or duplicate a line
        std::vector<std::string> lines = split(s);
        const size_t i = below(lines.size());
        if (below(2) == 0)
          lines.erase(lines.begin() + static_cast<long>(i));
        else
          lines.insert(lines.begin() + static_cast<long>(i), lines[i]);
        s = join(lines);
      }
    }
  }

  static std::vector<std::string> split(const std::string& s) {
    std::vector<std::string> lines;
    std::istringstream in(s);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    if (lines.empty()) lines.emplace_back();
    return lines;
  }
  static std::string join(const std::vector<std::string>& lines) {
    std::string s;
    for (const std::string& l : lines) s += l + "\n";
    return s;
  }

  std::mt19937_64 rng_;
};

struct Target {
  std::string name;
  std::vector<std::string> corpus;
  bool text = true;
  // Feeds one input to the reader; throws what the reader throws.
  std::function<void(const std::string&)> feed;
};

struct Tally {
  long tried = 0, refused = 0, accepted = 0, findings = 0;
  double seconds = 0;
};

std::vector<std::string> files_with_extension(const fs::path& dir, const std::string& ext) {
  std::vector<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file() && e.path().extension() == ext) out.push_back(read_file(e.path()));
  return out;
}

toml::table parse_config(const std::string& text, const std::string& path) {
  return toml::parse(text, path);
}

// A small prepared specimen and a checkpoint of it, as seeds of the two binary/record targets.
void make_state_seeds(const fs::path& source, const fs::path& work, std::string& specimen_csv,
                      std::string& checkpoint_payload, std::string& sliding_payload,
                      PairTable& table) {
  const std::string config_path = (source / "examples/triaxial/small.toml").string();
  const std::string config_text = read_file(config_path);
  const toml::table root = parse_config(config_text, config_path);
  TriaxialConfig c = read_triaxial_config(config_path, root);
  c.settings.specimen.count = 60;
  c.settings.specimen.nominal_box = {0.008, 0.008, 0.012};
  c.settings.specimen.target_solid_fraction.reset();
  table = c.table;
  const Specimen s = prepare_cuboid_specimen(c.settings.specimen, c.table, nullptr);
  save_specimen((work / "seed-specimen.csv").string(), s);
  specimen_csv = read_file(work / "seed-specimen.csv");
  const ElementTimeStep step = element_time_step(c.settings.specimen, c.table, s.particles);
  ElementRun run{Simulation(s.particles,
                            cuboid_walls(s.low, s.high, c.settings.specimen.lateral_material,
                                         c.settings.specimen.platen_material),
                            c.table, step.settings),
                 "triaxial",
                 config_path,
                 config_text,
                 "{}",
                 "0,0\n",
                 "",
                 "",
                 0.0};
  run.sim.advance(50);
  save_checkpoint(run, (work / "seed-checkpoint.bin").string());
  const std::string sealed = read_file(work / "seed-checkpoint.bin");
  checkpoint_payload = sealed.substr(0, sealed.size() - sizeof(uint64_t));
  // A sliding-friction checkpoint: a bed, a finished pull and a pull under way (interval 0: the
  // first poll saves).
  const std::string sliding_path = (work / "seed-sliding.bin").string();
  SlidingFrictionCheckpoints sliding(sliding_path, {"sliding_friction", config_path, config_text},
                                     0.0);
  sliding.record_bed(0.21, s.particles, 0.01);
  sliding.record_pull(0.21, LoadRun{0.1, 0.02, 0.001, {{0.0, 0.0, 0.02, 0.01}}});
  StateWriter state;
  run.sim.save_state(state);
  sliding.poll([&] {
    return PullState{0.21,         0.2, true, 0.003, 0.001, 0.05, 10, {{0.0, 0.0, 0.02, 0.01}},
                     state.bytes()};
  });
  const std::string sliding_sealed = read_file(sliding_path);
  sliding_payload = sliding_sealed.substr(0, sliding_sealed.size() - sizeof(uint64_t));
}

}  // namespace

int main(int argc, char** argv) {
  fs::path source = ".", work = "fuzz-work";
  long inputs = 1000;
  uint64_t seed = 1;
  std::string only;
  unsigned time_limit = 10;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i], value = argv[i + 1];
    if (key == "--source")
      source = value;
    else if (key == "--work")
      work = value;
    else if (key == "--inputs")
      inputs = std::stol(value);
    else if (key == "--seed")
      seed = std::stoull(value);
    else if (key == "--target")
      only = value;
    else if (key == "--time-limit")
      time_limit = static_cast<unsigned>(std::stoul(value));
    else {
      fmt::print(stderr, "fuzz_inputs: unknown option {}\n", key);
      return 2;
    }
  }
  fs::create_directories(work);
  for (int sig : {SIGSEGV, SIGABRT, SIGFPE, SIGBUS, SIGILL, SIGALRM}) signal(sig, save_and_exit);

  std::string specimen_csv, checkpoint_payload, sliding_payload;
  PairTable table{std::vector<Material>{}};
  make_state_seeds(source, work, specimen_csv, checkpoint_payload, sliding_payload, table);
  const std::vector<std::string> lab_configs = [&] {
    std::vector<std::string> out;
    for (const char* d : {"examples/triaxial", "examples/plane_strain", "examples/oedometer"})
      if (fs::exists(source / d))
        for (const std::string& t : files_with_extension(source / d, ".toml")) out.push_back(t);
    return out;
  }();
  const fs::path scratch = work / "input";

  std::vector<Target> targets;
  targets.push_back({"element_test_config", lab_configs, true, [&](const std::string& in) {
                       const std::string path = scratch.string() + ".toml";
                       const toml::table root = parse_config(in, path);
                       for (const LabTestEntry& e : lab_tests())
                         if (e.element_config) try {
                             e.element_config(path, root);
                           } catch (const ConfigError&) {
                           }
                       element_test_scene(path, root);  // grainlab params
                     }});
  const std::vector<std::string> study_configs = [&] {
    std::vector<std::string> out;
    for (const char* d : {"examples/scale_study", "bench/scale_study"})
      if (fs::exists(source / d))
        for (const std::string& t : files_with_extension(source / d, ".toml")) out.push_back(t);
    return out;
  }();
  targets.push_back({"scale_study_config", study_configs, true, [&](const std::string& in) {
                       const std::string path = scratch.string() + ".toml";
                       read_scale_study_config(path, parse_config(in, path));
                     }});
  targets.push_back({"scene_config", files_with_extension(source / "examples", ".toml"), true,
                     [&](const std::string& in) {
                       const std::string path = scratch.string() + ".toml";
                       write_file(path, in);
                       load_scene(path);
                     }});
  targets.push_back({"quantity",
                     {"2 mm", "150 kPa", "46.2 GPa", "2500 kg/m3", "0.5 s", "0.01 m/s", "9.81 m/s2",
                      "15 %", "1e-3", "300 s", "5 min"},
                     true,
                     [&](const std::string& in) {
                       int refusals = 0;
                       for (Quantity q :
                            {Quantity::dimensionless, Quantity::length, Quantity::time,
                             Quantity::pressure, Quantity::density, Quantity::velocity})
                         try {  // its refusal; the config readers turn it into ConfigError
                           parse_quantity(in, q);
                         } catch (const std::invalid_argument&) {
                           ++refusals;
                         }
                       if (refusals == 6) throw ConfigError("refused as every quantity");
                     }});
  targets.push_back({"csv_table", files_with_extension(source / "examples", ".csv"), true,
                     [&](const std::string& in) { calibrate::CsvTable::parse(in, "input.csv"); }});
  targets.push_back({"specimen_file", {specimen_csv}, true, [&](const std::string& in) {
                       write_file(scratch.string() + ".csv", in);
                       load_specimen(scratch.string() + ".csv", 2500.0, 0);
                     }});
  // Checkpoints: the mutated bytes are sealed again, so the reader behind the checksum is fuzzed
  // (an unsealed mutation is refused by the checksum, checked by ctest lab.checkpoint_corrupt).
  targets.push_back({"checkpoint", {checkpoint_payload}, false, [&](const std::string& in) {
                       std::string sealed = in;
                       const uint64_t sum = checkpoint_checksum(in);
                       sealed.append(reinterpret_cast<const char*>(&sum), sizeof sum);
                       write_file(scratch.string() + ".bin", sealed);
                       load_checkpoint(scratch.string() + ".bin", table);
                     }});
  targets.push_back({"sliding_checkpoint", {sliding_payload}, false, [&](const std::string& in) {
                       std::string sealed = in;
                       const uint64_t sum = checkpoint_checksum(in);
                       sealed.append(reinterpret_cast<const char*>(&sum), sizeof sum);
                       write_file(scratch.string() + ".bin", sealed);
                       SlidingFrictionCheckpoints::resume(scratch.string() + ".bin", 60.0,
                                                          table.find("glass"), table);
                     }});

  long findings = 0;
  fmt::print("{:<20} {:>10} {:>12} {:>10} {:>10} {:>9}\n", "target", "inputs", "inputs/s",
             "refused", "accepted", "findings");
  for (const Target& t : targets) {
    if (!only.empty() && t.name != only) continue;
    if (t.corpus.empty()) {
      fmt::print("{:<20} no corpus\n", t.name);
      continue;
    }
    crash_path_prefix = (work / t.name).string();
    Mutator mutate(seed ^ std::hash<std::string>{}(t.name));
    Tally tally;
    const auto start = std::chrono::steady_clock::now();
    for (long k = 0; k < inputs; ++k) {
      current_input = mutate.mutate(t.corpus[static_cast<size_t>(k) % t.corpus.size()], t.text);
      alarm(time_limit);
      ++tally.tried;
      try {
        t.feed(current_input);
        ++tally.accepted;
      } catch (const ConfigError&) {
        ++tally.refused;
      } catch (const toml::parse_error&) {
        ++tally.refused;
      } catch (const calibrate::InputError&) {
        ++tally.refused;
      } catch (const std::exception& e) {
        ++tally.findings;
        const fs::path saved = work / fmt::format("{}-finding-{}.input", t.name, tally.findings);
        write_file(saved, current_input);
        if (tally.findings <= 5)
          fmt::print(stderr, "{}: {} \"{}\" (input saved to {})\n", t.name, typeid(e).name(),
                     e.what(), saved.string());
      }
      alarm(0);
    }
    tally.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    fmt::print("{:<20} {:>10} {:>12.0f} {:>10} {:>10} {:>9}\n", t.name, tally.tried,
               tally.tried / std::max(tally.seconds, 1e-9), tally.refused, tally.accepted,
               tally.findings);
    findings += tally.findings;
  }
  return findings == 0 ? 0 : 1;
}
