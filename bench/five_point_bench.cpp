// The five-point four-bar synthesis problem (Morgan–Wampler): nbar's solver, and Debian's
// PHCpack (`phc -b`, blackbox: its own start system and path tracker) on the same instances.
//   ./five_point_bench                                    # everything
//   ./five_point_bench --benchmark_filter=Nbar            # nbar only
//   ./five_point_bench --benchmark_filter=SynthCommand    # the whole command against phc -b
// Instances: pivots (0,0), (1,0); five points uniform in [-1,2]^2 from fixed seeds.
// BM_SynthCommandOverPhcpack, 7 instances, medians (2026-11-25, 2-core machine under load): the
// whole `nbar synth five-point` in 28.5 ms CPU (both threads summed; 42 ms before the shared
// curve sampling and the parallel design checks) against `phc -b` in 2.1 s: 74x faster (60x in
// wall time), all 36 solutions in 7 of 7.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>

#include <sys/resource.h>
#include <unistd.h>

#include "nbar/synthesis/five_point.hpp"
#include "phc_support.hpp"

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

// The whole `nbar synth five-point` command (read the task, solve, check and rank every design,
// write the answer) against `phc -b` on the same instance, both as processes, interleaved so
// that load from other processes falls on both alike. Times are CPU times of the child (user +
// system, so nbar's two threads count twice: a ratio to its disadvantage) and wall times, which
// on a shared machine include the waits for a core. Counters: `ratio` = median phc CPU time
// over median nbar CPU time (how many times faster nbar is), `ratio_wall` the same in wall
// time, the medians themselves, and the instances where nbar reports all 36 solutions.
struct ChildTimes {
  double cpu = 0.0, wall = 0.0;
};
double children_cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_CHILDREN, &u);
  const auto seconds = [](const timeval& t) {
    return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec);
  };
  return seconds(u.ru_utime) + seconds(u.ru_stime);
}
template <class Run>
ChildTimes time_children(const Run& run, bool& ok) {
  const double cpu = children_cpu_seconds();
  const auto start = std::chrono::steady_clock::now();
  ok = run();
  return {children_cpu_seconds() - cpu,
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()};
}

void BM_SynthCommandOverPhcpack(benchmark::State& state) {
  if (!nbar::phc::available()) {
    state.SkipWithError("phc not found (apt-get install phcpack)");
    return;
  }
  const std::vector<std::string> names{"c1", "s1", "c2", "s2", "c3", "s3", "c4", "s4", "x1", "x2", "y1", "y2"};
  const auto dir =
      std::filesystem::temp_directory_path() / std::string("nbar-synth-").append(std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto task = dir / "task.yaml", answer = dir / "answer.json";
  unsigned seed = 1;
  long complete = 0;
  std::vector<double> nbar_cpu, phc_cpu, nbar_wall, phc_wall;
  for (auto _ : state) {
    const FivePointTask t = instance(seed++);
    {
      std::ofstream out(task);
      out.precision(17);
      out << "task: five-point\npivots: {a: [0, 0], b: [1, 0]}\npoints:\n";
      for (const auto& p : t.points) out << "  - [" << p.x() << ", " << p.y() << "]\n";
    }
    const std::string command = std::string(NBAR_BINARY " synth five-point --all --format json ")
                                    .append(task.string())
                                    .append(" > ")
                                    .append(answer.string());
    bool nbar_ok = false, phc_ok = false;
    const ChildTimes nbar_time = time_children([&] { return std::system(command.c_str()) == 0; }, nbar_ok);
    const ChildTimes phc_time = time_children(
        [&] { return nbar::phc::solve(five_point_system(t.points), names, dir / "phc").has_value(); }, phc_ok);
    if (!nbar_ok || !phc_ok) {
      state.SkipWithError(!nbar_ok ? "nbar synth failed" : "phc -b failed");
      break;
    }
    std::ifstream in(answer);
    const std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    complete += json.find("\"solutions\": 36,") != std::string::npos;
    nbar_cpu.push_back(nbar_time.cpu);
    phc_cpu.push_back(phc_time.cpu);
    nbar_wall.push_back(nbar_time.wall);
    phc_wall.push_back(phc_time.wall);
  }
  std::filesystem::remove_all(dir);
  if (nbar_cpu.empty()) return;
  const auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  state.counters["nbar_cpu_ms"] = 1e3 * median(nbar_cpu);
  state.counters["phc_cpu_ms"] = 1e3 * median(phc_cpu);
  state.counters["nbar_wall_ms"] = 1e3 * median(nbar_wall);
  state.counters["phc_wall_ms"] = 1e3 * median(phc_wall);
  state.counters["ratio"] = median(phc_cpu) / median(nbar_cpu);
  state.counters["ratio_wall"] = median(phc_wall) / median(nbar_wall);
  state.counters["all_36_found"] = static_cast<double>(complete);
}
BENCHMARK(BM_SynthCommandOverPhcpack)->Iterations(7)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
