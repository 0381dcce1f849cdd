// The five-point four-bar synthesis problem (Morgan–Wampler): nbar's solver, and Debian's
// PHCpack (`phc -b`, blackbox: its own start system and path tracker) on the same instances.
//   ./five_point_bench                                    # everything
//   ./five_point_bench --benchmark_filter=Nbar            # nbar only
// Instances: pivots (0,0), (1,0); five points uniform in [-1,2]^2 from fixed seeds.
#include <benchmark/benchmark.h>

#include <chrono>
#include <filesystem>
#include <random>
#include <string>

#include <unistd.h>

#include "phc_support.hpp"
#include "nbar/synthesis/five_point.hpp"

namespace {

using namespace nbar::synthesis;

FivePointTask instance(unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 2.0);
  FivePointTask t;
  for (auto& p : t.points) p = {u(rng), u(rng)};
  return t;
}

// One instance per iteration, on every core; counters: solutions found and fallbacks used.
void BM_NbarFivePoint(benchmark::State& state) {
  unsigned seed = 1;
  long complete = 0, instances = 0, fallbacks = 0;
  SolverOptions options;
  options.threads = static_cast<unsigned>(state.range(0));
  for (auto _ : state) {
    const FivePointResult r = solve_five_point(instance(seed++), options);
    benchmark::DoNotOptimize(r.solutions.data());
    complete += r.solutions.size() == 36;
    fallbacks += r.used_fallback;
    ++instances;
  }
  state.counters["instances"] = static_cast<double>(instances);
  state.counters["all_36_found"] = static_cast<double>(complete);
  state.counters["fallbacks"] = static_cast<double>(fallbacks);
}
BENCHMARK(BM_NbarFivePoint)->Arg(1)->Arg(0)->ArgName("threads")->UseRealTime()->Unit(benchmark::kMillisecond);

// Exactly 1000 instances, so that "36 found in 1000 of 1000" is a measured statement.
void BM_NbarFivePointThousand(benchmark::State& state) {
  double seconds = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    long complete = 0, fallbacks = 0, real = 0;
    for (unsigned seed = 1; seed <= 1000; ++seed) {
      const FivePointResult r = solve_five_point(instance(seed));
      complete += r.solutions.size() == 36;
      fallbacks += r.used_fallback;
      for (const auto& s : r.solutions) real += s.real;
    }
    state.counters["all_36_found"] = static_cast<double>(complete);
    state.counters["fallbacks"] = static_cast<double>(fallbacks);
    state.counters["real_per_instance"] = static_cast<double>(real) / 1000.0;
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  state.counters["ms_per_instance"] = seconds / static_cast<double>(state.iterations());  // s per 1000 = ms each
}
BENCHMARK(BM_NbarFivePointThousand)->Iterations(1)->UseRealTime()->Unit(benchmark::kSecond);

// `phc -b` on the same instances; counter: instances where PHCpack reports 36 regular solutions.
void BM_PhcpackFivePoint(benchmark::State& state) {
  if (!nbar::phc::available()) {
    state.SkipWithError("phc not found (apt-get install phcpack)");
    return;
  }
  const std::vector<std::string> names{"c1", "s1", "c2", "s2", "c3", "s3", "c4", "s4", "x1", "x2", "y1", "y2"};
  const auto dir = std::filesystem::temp_directory_path() / std::string("nbar-phc-").append(std::to_string(::getpid()));
  unsigned seed = 1;
  long complete = 0, instances = 0;
  for (auto _ : state) {
    const auto result = nbar::phc::solve(five_point_system(instance(seed++).points), names, dir);
    if (!result) {
      state.SkipWithError("phc -b failed");
      break;
    }
    complete += result->reported_regular == 36;
    ++instances;
  }
  std::filesystem::remove_all(dir);
  state.counters["instances"] = static_cast<double>(instances);
  state.counters["all_36_found"] = static_cast<double>(complete);
}
BENCHMARK(BM_PhcpackFivePoint)->Iterations(5)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
