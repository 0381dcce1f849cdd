// Kinetics and stress benchmark: a full 360-step sweep of a machine of 11 bodies (a chain of
// five four-bar loops, every link a steel bar with pin holes) with inverse dynamics at every step
// and the stresses at 200 sections of every link, as `nbar stress` computes them.
//
// BM_SweepDynamicsStress times it all (kinematics sweep, dynamics, stresses, peaks), with the
// one-time work (compiling the mechanism, cutting the sections) outside; BM_SectionSetup times
// that one-time cut of every link.
//
// Run: dynamics_bench --benchmark_min_time=0.2
#include <benchmark/benchmark.h>

#include "bench_models.hpp"
#include "nbar/dynamics/inverse_dynamics.hpp"
#include "nbar/kinematics/sweep.hpp"
#include "nbar/stress/link_stress.hpp"

namespace {

using namespace nbar_bench;

constexpr int kSections = 200;

void BM_SweepDynamicsStress(benchmark::State& st) {
  const auto shared = std::make_shared<const nbar::Mechanism>(steel_chain(5));
  const nbar::Mechanism& mech = *shared;
  if (mech.model().bodies.size() < 10) die("the benchmark machine needs at least 10 bodies");
  const auto dynamics = std::make_shared<const nbar::InverseDynamics>(shared);
  const nbar::LinkStress stress(dynamics, kSections);
  nbar::SweepOptions options;
  options.order = 2;
  std::size_t sections = 0;
  for (std::size_t b = 0; b < mech.model().bodies.size(); ++b) sections += stress.section_count(static_cast<int>(b));
  for (auto _ : st) {
    const nbar::SweepResult sweep = nbar::run_sweep(mech, options);
    if (!sweep.complete || sweep.samples.size() != kStepsPerTurn + 1) die("the sweep did not complete");
    std::vector<nbar::DynamicsResult> forces;
    forces.reserve(sweep.samples.size());
    for (const nbar::Sample& sample : sweep.samples) forces.push_back(dynamics->solve(sample));
    const auto peaks = nbar::stress_peaks(stress, sweep, forces);
    benchmark::DoNotOptimize(peaks.data());
  }
  st.counters["bodies"] = static_cast<double>(mech.model().bodies.size());
  st.counters["sections_per_body"] = static_cast<double>(sections) / mech.model().bodies.size();
  st.counters["per_step"] = benchmark::Counter(static_cast<double>(st.iterations()) * kStepsPerTurn,
                                               benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_SweepDynamicsStress)->Unit(benchmark::kMillisecond);

void BM_SectionSetup(benchmark::State& st) {
  const auto dynamics =
      std::make_shared<const nbar::InverseDynamics>(std::make_shared<const nbar::Mechanism>(steel_chain(5)));
  for (auto _ : st) {
    const nbar::LinkStress stress(dynamics, kSections);
    benchmark::DoNotOptimize(&stress);
  }
}
BENCHMARK(BM_SectionSetup)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
