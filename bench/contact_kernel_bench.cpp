// Google Benchmark of the contact law alone (contact/contact_law.hpp): one sticking and one
// sliding glass-glass contact, the pieces the reference workload uses (normal + sliding).
// What it shows: the arithmetic cost of a contact without memory traffic, the floor under the
// force loop of the step (docs/performance.md).
#include <benchmark/benchmark.h>

#include "bench/scenes.hpp"
#include "contact/contact_law.hpp"

using namespace grainlab;

namespace {

ContactKinematics glass_contact(double tangential_speed) {
  ContactKinematics k;
  k.normal = {0.0, 0.0, 1.0};
  k.overlap = 1e-7;
  k.overlap_rate = 1e-4;
  k.tangential_velocity = {tangential_speed, 0.0, 0.0};
  k.tangential_displacement = 8e-8 * k.tangential_velocity;  // dt = 8e-8 s
  k.relative_angular_velocity = {0.0, 1e-3, 0.0};            // slow rolling
  k.relative_rotation = 8e-8 * k.relative_angular_velocity;
  k.effective_radius = 0.5e-3;
  k.effective_mass = 0.5 * 2500.0 * 4.0 / 3.0 * 3.14159 * 1e-9;
  return k;
}

template <bool Rolling>
void run(benchmark::State& state, double tangential_speed) {
  const PairTable table =
      bench::reference_table(bench::glass_E, bench::glass_restitution, bench::glass_friction);
  const ContactKinematics k = glass_contact(tangential_speed);
  Vec3 spring{1e-9, 0.0, 0.0}, rolling{};
  double twist = 0.0;
  Vec3 rf{};
  for (auto _ : state) {
    ContactHistoryRef h{&spring, &rolling, &twist, &rf};
    const ContactResponse r = contact_response<Rolling, false, false>(
        table(0, 0), normal_params(table(0, 0), k.effective_radius, k.effective_mass), k, 1e-13,
        1e-5, h);
    benchmark::DoNotOptimize(r);
    benchmark::ClobberMemory();
    if (Rolling) rolling = {};
    spring = {1e-9, 0.0, 0.0};
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_ContactSticking(benchmark::State& s) {
  run<false>(s, 1e-6);
}
void BM_ContactSliding(benchmark::State& s) {
  run<false>(s, 1.0);
}
void BM_ContactStickingWithRolling(benchmark::State& s) {
  run<true>(s, 1e-6);
}

}  // namespace

BENCHMARK(BM_ContactSticking);
BENCHMARK(BM_ContactSliding);
BENCHMARK(BM_ContactStickingWithRolling);
BENCHMARK_MAIN();
