// grainlab_bench: runs a named workload for 1, 2, 4 ... threads and prints particle-steps per
// second, neighbour-list rebuilds, mean contacts per particle and peak RSS; appends one row per
// run to bench/results/<hostname>.csv. Workloads: see bench/scenes.hpp.
//
//   grainlab_bench dense-11k                       (default: 1, 2, 4 ... threads up to the
//                                                   processor count, 3 repetitions)
//   grainlab_bench dense-11k --threads 2 --reps 1 --steps 4000
//   grainlab_bench dense-11k --tile 4x4x4           (64 copies side by side: 745k beads)
//   grainlab_bench dense-11k --write-lammps-data out.data   (same packing for the peer codes)
//   grainlab_bench dense-88k --specimen DIR/specimen.csv   (the lab's plane strain specimen)
//   grainlab_bench settle-1M --allow-1m
#include <fmt/format.h>
#include <omp.h>
#include <sys/resource.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "bench/scenes.hpp"
#include "grainlab/version.hpp"
#include "lab/specimen.hpp"

using namespace grainlab;
using namespace grainlab::bench;

namespace {

double peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0;  // Linux: KiB
}

// FNV-1a over the raw bytes of the state, in permanent-id order: equal for equal results.
uint64_t state_hash(const ParticleStore& p) {
  std::vector<Vec3> x(p.size()), v(p.size());
  for (size_t k = 0; k < p.size(); ++k) {
    x[p.id[k]] = p.position[k];
    v[p.id[k]] = p.velocity[k];
  }
  uint64_t h = 1469598103934665603ull;
  auto mix = [&](const void* data, size_t bytes) {
    const auto* b = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < bytes; ++i) h = (h ^ b[i]) * 1099511628211ull;
  };
  mix(x.data(), x.size() * sizeof(Vec3));
  mix(v.data(), v.size() * sizeof(Vec3));
  return h;
}

std::string hostname() {
  char name[256] = {};
  gethostname(name, sizeof(name) - 1);
  return name;
}

// dense-88k: the plane strain reference specimen as the lab's own preparation leaves it
// (`grainlab prepare examples/plane_strain/reference.toml --out DIR`, about 10 minutes on 2
// cores since its hold ends at 1e-3, docs/performance.md sec. 46; checkpointed): its beads and
// box, read from DIR/specimen.csv.
Packing packing_of_specimen(const std::string& specimen_csv) {
  const Specimen s = load_specimen(specimen_csv, glass_density, 0);
  Packing p;
  p.radius = s.particles.radius;
  p.position = s.particles.position;
  p.box_lo = s.low;
  p.box_hi = s.high;
  return p;
}

Packing load_or_make(const std::string& workload, const std::string& cache_dir, bool allow_1m,
                     const std::string& specimen_csv) {
  std::filesystem::create_directories(cache_dir);
  const std::string path = cache_dir + "/" + workload + ".csv";
  Packing p;
  if (read_packing_csv(path, p)) {
    fmt::print(stderr, "packing {}: {} beads from {}\n", workload, p.radius.size(), path);
    return p;
  }
  fmt::print(stderr, "packing {}: not cached, building it (once)...\n", workload);
  if (workload == "dense-11k") {
    p = make_dense_packing(11636, {0.035, 0.035, 0.080}, 20190601, true);
  } else if (workload == "dense-88k") {
    if (specimen_csv.empty())
      throw CLI::ValidationError(
          "dense-88k",
          "the plane strain reference specimen: prepare it once with `grainlab prepare "
          "examples/plane_strain/reference.toml --out DIR` (about 10 minutes on 2 cores) and "
          "pass --specimen DIR/specimen.csv");
    p = packing_of_specimen(specimen_csv);
  } else if (workload == "settle-1M") {
    if (!allow_1m) throw CLI::ValidationError("settle-1M", "a million beads: pass --allow-1m");
    // Solid fraction 0.25 in a 0.25 x 0.25 x 0.27 m box; gravity does the rest.
    p = make_loose_packing(1000000, {0.25, 0.25, 0.27}, 20190603);
  } else {
    throw CLI::ValidationError("workload", "unknown workload " + workload);
  }
  write_packing_csv(p, path);
  fmt::print(stderr, "packing {}: cached in {}\n", workload, path);
  return p;
}

// The timed steps' stages per thread (--phase-times): the mean over the threads and the largest,
// in µs per step; the parts outside the regions are the stepping thread's.
void print_phase_times(const grainlab::StepPhaseTimes& t) {
  using grainlab::StepPhaseTimes;
  if (t.steps() == 0) return;
  const double per_step = 1e6 / static_cast<double>(t.steps());
  fmt::print(
      "        stages over {} steps, {} threads: µs per step, mean over the threads / largest\n",
      t.steps(), t.threads());
  double total = 0.0;
  for (int k = 0; k < StepPhaseTimes::part_count; ++k) {
    const auto part = static_cast<StepPhaseTimes::Part>(k);
    total += t.mean(part);
    if (t.largest(part) == 0.0) continue;  // (stages the steps did not run)
    fmt::print("          {:<16} {:>10.1f} {:>10.1f}\n", StepPhaseTimes::names[k],
               t.mean(part) * per_step, t.largest(part) * per_step);
  }
  fmt::print("          {:<16} {:>10.1f}\n", "step (sum)", total * per_step);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"grainlab benchmark runner"};
  std::string workload = "dense-11k";
  // 1, 2, 4, ... threads up to the machine's processor count, and the count itself
  std::vector<int> threads;
  for (int t = 1; t <= omp_get_num_procs(); t *= 2) threads.push_back(t);
  if (threads.back() != omp_get_num_procs()) threads.push_back(omp_get_num_procs());
  int reps = 3;
  long steps = 0, warmup = 200;
  std::string cache_dir = "bench-cache";
  std::string results_dir = std::string(GRAINLAB_SOURCE_DIR) + "/bench/results";
  std::string lammps_data, tile, specimen_csv;
  std::string label = "";
  bool allow_1m = false, no_csv = false, rebuild_peak = false, phase_times = false;
  int refresh_cost = 0, rebuild_cost = 0;
  std::string one_sweep = "automatic", chunk_tail = "even", drift_sharing = "automatic",
              gather_walk = "automatic";
  long chunks_per_thread = 0;  // 0: automatic (Simulation::chunk_sharing)
  std::string owner_keeps_last = "automatic";
  app.add_option("workload", workload, "dense-11k | dense-88k | settle-1M");
  app.add_option("--threads", threads,
                 "thread counts to run (default: 1, 2, 4, ... up to the processor count)")
      ->delimiter(',');
  app.add_option("--reps", reps, "repetitions per thread count");
  app.add_option("--steps", steps, "timed steps per run (default: ~2.5e7 particle-steps)");
  app.add_option("--warmup", warmup, "untimed steps before each run");
  app.add_option("--cache-dir", cache_dir, "where packings are cached");
  app.add_option("--results-dir", results_dir, "where <hostname>.csv gets a row per run");
  app.add_option("--write-lammps-data", lammps_data,
                 "write the packing as a LAMMPS data file and exit");
  app.add_option("--specimen", specimen_csv,
                 "dense-88k: the specimen.csv of `grainlab prepare "
                 "examples/plane_strain/reference.toml` (read once, then cached)");
  app.add_option("--tile", tile, "run NXxNYxNZ copies of the packing side by side");
  app.add_option("--label", label, "free text stored in the CSV row (e.g. the commit)");
  app.add_flag("--allow-1m", allow_1m, "allow building the settle-1M workload");
  app.add_flag("--no-csv", no_csv, "do not append to the results CSV");
  app.add_flag("--rebuild-peak", rebuild_peak,
               "after the timed steps, force one neighbour-list rebuild (one wall moved out by a "
               "skin) and print the peak RSS with it");
  app.add_option("--refresh-cost", refresh_cost,
                 "after the timed steps, time this many selections of the active pair list at "
                 "the same positions (the refresh a step makes when a bead has moved half the "
                 "list skin) and print the time of one")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--rebuild-cost", rebuild_cost,
                 "after the timed steps, time this many neighbour-list rebuilds at the same "
                 "positions (binning, sorting, candidates, the active list) and print the time of "
                 "one")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("--phase-times", phase_times,
               "time each thread's stages of the timed steps and its waits after them, and print "
               "them after the run (core/step_phase_times.hpp; the same results)");
  app.add_option(
         "--chunk-tail", chunk_tail,
         "even | shrinking: the chunks at the back of each thread's block in the force stages "
         "and of the swept steps' tails (core/chunk_queue.hpp; the same results)")
      ->check(CLI::IsMember({"even", "shrinking"}));
  app.add_option("--one-sweep", one_sweep,
                 "automatic | always | never: steps as one sweep (core/one_sweep.cpp; the same "
                 "results)")
      ->check(CLI::IsMember({"automatic", "always", "never"}));
  app.add_option("--drift-sharing", drift_sharing,
                 "automatic | always | never: the drift's particles through a chunk queue "
                 "(automatic: on 4 threads or more; Simulation::set_drift_sharing, the same "
                 "results)")
      ->check(CLI::IsMember({"automatic", "always", "never"}));
  app.add_option(
         "--gather-walk", gather_walk,
         "automatic | flat | one-by-one: the gather walks each block's entries flat or takes "
         "the particles one by one (automatic: the faster by the steps' own times, "
         "core/gather_walk_trial.hpp; Simulation::set_gather_walk, the same results)")
      ->check(CLI::IsMember({"automatic", "flat", "one-by-one"}));
  app.add_option("--chunks-per-thread", chunks_per_thread,
                 "about this many chunks of each thread's block in the stages of a step "
                 "(default automatic: 8 below 8 threads, 16 from 8; Simulation::set_chunk_sharing, "
                 "the same results)")
      ->check(CLI::PositiveNumber);
  app.add_option("--owner-keeps-last", owner_keeps_last,
                 "automatic | yes | no: whether a block's last untaken chunk stays with its owner "
                 "(automatic: yes below 8 threads; the same results)")
      ->check(CLI::IsMember({"automatic", "yes", "no"}));
  CLI11_PARSE(app, argc, argv);
  // (--one-sweep and --drift-sharing: automatic | always | never, the choices' enumerators)
  const auto choice = []<class Choice>(const std::string& word, Choice) {
    return word == "always" ? Choice::always : word == "never" ? Choice::never : Choice::automatic;
  };
  const Simulation::OneSweep sweep_choice = choice(one_sweep, Simulation::OneSweep{});
  const Simulation::DriftSharing drift_choice = choice(drift_sharing, Simulation::DriftSharing{});
  const Simulation::GatherWalk walk_choice = gather_walk == "flat" ? Simulation::GatherWalk::flat
                                             : gather_walk == "one-by-one"
                                                 ? Simulation::GatherWalk::one_by_one
                                                 : Simulation::GatherWalk::automatic;

  Packing packing;
  try {
    packing = load_or_make(workload, cache_dir, allow_1m, specimen_csv);
  } catch (const std::runtime_error& e) {  // a workload it cannot make, a bad specimen file
    fmt::print(stderr, "grainlab_bench: {}\n", e.what());
    return 2;
  }
  std::string name = workload;
  if (!tile.empty()) {
    int nx = 1, ny = 1, nz = 1;
    if (std::sscanf(tile.c_str(), "%dx%dx%d", &nx, &ny, &nz) != 3) {
      fmt::print(stderr, "--tile wants NXxNYxNZ\n");
      return 2;
    }
    packing = tile_packing(packing, nx, ny, nz);
    name += "-tile" + tile;
  }
  if (!lammps_data.empty()) {
    write_lammps_data(packing, lammps_data);
    fmt::print(stderr, "wrote {}\n", lammps_data);
    return 0;
  }
  const long n = static_cast<long>(packing.radius.size());
  if (steps <= 0) steps = std::max<long>(50, static_cast<long>(2.5e7 / n));
  const Vec3 gravity = workload == "settle-1M" ? Vec3{0, 0, -9.81} : Vec3{};

  const std::string csv = results_dir + "/" + hostname() + ".csv";
  if (!no_csv) {
    std::filesystem::create_directories(results_dir);
    if (!std::filesystem::exists(csv)) {
      std::FILE* f = std::fopen(csv.c_str(), "w");
      std::fprintf(
          f,
          "date_utc,version,label,workload,particles,threads,steps,seconds,particle_steps_per_s,"
          "ns_per_particle_step,rebuilds,contacts_per_particle,peak_rss_mb,bytes_per_particle,"
          "state_hash,list_entries_per_particle\n");
      std::fclose(f);
    }
  }
  // the pair force loop in use (GRAINLAB_SIMD chooses it; core/pair_kernel_simd.hpp)
  const std::string kernel = grainlab::select_simd_pair_kernel().name;
  const std::string csv_label = label.empty() ? kernel : label + " " + kernel;
  fmt::print("workload {}  N = {}  steps {} (+{} warm-up)  version {}  pair kernel {}\n", name, n,
             steps, warmup, grainlab::version_string, kernel);
  fmt::print("{:>7} {:>4} {:>14} {:>10} {:>9} {:>9} {:>10} {:>10}  {:16} {:>8} {:>7} {:>7}\n",
             "threads", "rep", "p-steps/s", "ns/p-step", "rebuilds", "Z", "RSS MB", "B/particle",
             "state hash", "entries", "sweeps", "flat");
  for (int t : threads) {
    omp_set_num_threads(t);
    for (int r = 0; r < reps; ++r) {
      Simulation sim = make_simulation(packing, gravity);
      sim.set_one_sweep(sweep_choice);
      if (chunks_per_thread > 0 || owner_keeps_last != "automatic") {
        // (what is not given stays as automatic chooses it for this team)
        Simulation::ChunkSharing sharing = sim.chunk_sharing(t);
        if (chunks_per_thread > 0) sharing.chunks_per_thread = chunks_per_thread;
        if (owner_keeps_last != "automatic") sharing.owner_keeps_last = owner_keeps_last == "yes";
        sim.set_chunk_sharing(sharing);
      }
      sim.set_drift_sharing(drift_choice);
      sim.set_gather_walk(walk_choice);
      sim.set_chunk_tail(chunk_tail == "shrinking" ? grainlab::ChunkQueue::Tail::shrinking
                                                   : grainlab::ChunkQueue::Tail::even);
      sim.advance(warmup);
      sim.time_step_phases(phase_times);
      const long rebuilds0 = sim.rebuild_count(), sweeps0 = sim.one_sweep_steps(),
                 flat0 = sim.flat_gather_steps();
      const auto start = std::chrono::steady_clock::now();
      sim.advance(steps);
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const double rate = static_cast<double>(n) * steps / seconds;
      const long rebuilds = sim.rebuild_count() - rebuilds0;
      // Z: mean number of touching particle-particle contacts per particle (2 C / N).
      const double z = 2.0 * sim.touching_pair_count() / n;
      const double rss = peak_rss_mb();
      const uint64_t hash = state_hash(sim.particles());
      // entries: half-list entries (pairs within the skin) per particle
      const double entries = static_cast<double>(sim.pair_contacts().size()) / n;
      // sweeps: the share of the timed steps run as one sweep (core/one_sweep.cpp)
      const double sweeps = static_cast<double>(sim.one_sweep_steps() - sweeps0) / steps;
      // flat: the share of the timed steps whose gather walked flat (the automatic walk is
      // chosen by timing the steps: core/gather_walk_trial.hpp)
      const double flat = static_cast<double>(sim.flat_gather_steps() - flat0) / steps;
      fmt::print(
          "{:>7} {:>4} {:>14.4g} {:>10.1f} {:>9} {:>9.3f} {:>10.1f} {:>10.0f}  {:016x} {:>8.2f} "
          "{:>7.3f} {:>7.3f}\n",
          t, r, rate, 1e9 / rate, rebuilds, z, rss, rss * 1048576.0 / n, hash, entries, sweeps,
          flat);
      if (phase_times) print_phase_times(sim.step_phase_times());
      // ms per call of `update`, timed over `count` calls in a row
      const auto ms_each = [](int count, auto&& update) {
        const auto start = std::chrono::steady_clock::now();
        for (int k = 0; k < count; ++k) update();
        return 1e3 *
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() /
               count;
      };
      if (refresh_cost > 0) {
        // (after the figures above: a refresh at the same positions selects the same list,
        // with the same histories, so it changes no result)
        const double ms = ms_each(refresh_cost, [&] { sim.refresh_pair_list(); });
        const double refresh_rss = peak_rss_mb();
        fmt::print(
            "        list refresh: {:.2f} ms each ({} refreshes, {} entries); peak RSS with them "
            "{:.1f} MB, {:.0f} B per particle\n",
            ms, refresh_cost, sim.pair_contacts().size(), refresh_rss, refresh_rss * 1048576.0 / n);
      }
      if (rebuild_cost > 0)
        fmt::print("        list rebuild: {:.2f} ms each ({} rebuilds)\n",
                   ms_each(rebuild_cost, [&] { sim.rebuild_pair_list(); }), rebuild_cost);
      if (rebuild_peak) {
        // The timed run rebuilds rarely or never; a real run rebuilds every few hundred steps,
        // and the rebuild holds the old contact store while it builds the new one. Moving one
        // wall outwards by a skin (more than the skin/2 that triggers a rebuild) makes the next
        // step rebuild; the beads along that face lose the wall for that step, which is all
        // the packing sees of it (the figures above are taken before).
        const long rebuilds_before = sim.rebuild_count();
        const Wall& moved = sim.walls().front();
        sim.set_wall_point(0, moved.point - sim.settings().skin * moved.normal);
        sim.step();
        if (sim.rebuild_count() == rebuilds_before)
          throw std::runtime_error("--rebuild-peak: moving the wall did not cause a rebuild");
        const double rebuild_rss = peak_rss_mb();
        fmt::print("        peak RSS with one rebuild: {:.1f} MB, {:.0f} B per particle\n",
                   rebuild_rss, rebuild_rss * 1048576.0 / n);
      }
      std::fflush(stdout);
      if (!no_csv) {
        std::FILE* f = std::fopen(csv.c_str(), "a");
        const std::time_t now = std::time(nullptr);
        char date[32];
        std::strftime(date, sizeof(date), "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
        std::fprintf(f, "%s,%s,%s,%s,%ld,%d,%ld,%.4f,%.6g,%.2f,%ld,%.4f,%.1f,%.0f,%016llx,%.3f\n",
                     date, grainlab::version_string, csv_label.c_str(), name.c_str(), n, t, steps,
                     seconds, rate, 1e9 / rate, rebuilds, z, rss, rss * 1048576.0 / n,
                     static_cast<unsigned long long>(hash), entries);
        std::fclose(f);
      }
    }
  }
  return 0;
}
