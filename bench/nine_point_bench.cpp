// Alt's nine-point problem: nbar's solver from scratch (monodromy) and on new instances
// (parameter homotopy from the stored instance).
//   ./nine_point_bench                                     # everything
//   ./nine_point_bench --benchmark_filter=Instances        # the 20 random instances
// Instances: nine points uniform in [-1, 2]^2 from fixed seeds.
#include <benchmark/benchmark.h>

#include <chrono>
#include <random>

#include "nbar/synthesis/nine_point.hpp"
#include "nbar/synthesis/nine_point_start.hpp"

namespace {

using namespace nbar::synthesis;

std::array<Eigen::Vector2d, 9> instance(unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 2.0);
  std::array<Eigen::Vector2d, 9> points;
  for (auto& p : points) p = {u(rng), u(rng)};
  return points;
}

// Monodromy from one generated solution until the three-node graph closes; counters: orbits
// found and whether the graph closed.
void BM_NinePointFromScratch(benchmark::State& state) {
  std::uint64_t seed = 1;
  for (auto _ : state) {
    const NinePointStart start = generate_nine_point_start(seed++);
    state.counters["orbits"] = static_cast<double>(start.representatives.size());
    state.counters["closed"] = start.closed;
    state.counters["paths"] = start.paths;
  }
}
BENCHMARK(BM_NinePointFromScratch)->Iterations(1)->UseRealTime()->Unit(benchmark::kSecond);

// Exactly 20 random instances, so that "1442 found in 20 of 20" is a measured statement.
void BM_NinePointTwentyInstances(benchmark::State& state) {
  for (auto _ : state) {
    long complete = 0, real = 0, failed = 0, monodromy = 0;
    double worst = 0, total = 0;
    for (unsigned seed = 1; seed <= 20; ++seed) {
      const auto begin = std::chrono::steady_clock::now();
      const NinePointResult r = solve_nine_point(instance(seed));
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
      worst = std::max(worst, seconds);
      total += seconds;
      complete += r.orbits == kNinePointOrbits;
      real += r.real_orbits;
      failed += r.failed_paths;
      monodromy += r.monodromy_loops > 0;
    }
    state.counters["all_1442_found"] = static_cast<double>(complete);
    state.counters["s_per_instance"] = total / 20;
    state.counters["s_worst"] = worst;
    state.counters["real_orbits_per_instance"] = static_cast<double>(real) / 20;
    state.counters["paths_retracked"] = static_cast<double>(failed);
    state.counters["needed_monodromy"] = static_cast<double>(monodromy);
  }
}
BENCHMARK(BM_NinePointTwentyInstances)->Iterations(1)->UseRealTime()->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
