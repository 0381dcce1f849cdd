// Finite-element stress benchmark: the 11-body machine of dynamics_bench (a chain of five
// four-bar loops, every link a steel bar with pin holes) over a 360-step sweep, with the
// plane-stress finite elements of every link (about 5000 nodes each) at every step, as
// `nbar stress --method fe` computes them. The target (issue 12): under 2 s on one core.
//
// BM_FeSweep times the per-step work on one thread (each step's loads from the kept inverse
// dynamics, one back-substitution per link, the peaks), BM_FeSweepTwoThreads the same on two,
// and BM_FeSetup the one-time work (meshing and factorising every link). The inverse dynamics,
// solved once by the pipeline, are outside.
//
// Run: link_fe_bench --benchmark_min_time=1
#include <benchmark/benchmark.h>

#include <cmath>

#include "bench_models.hpp"
#include "nbar/dynamics/inverse_dynamics.hpp"
#include "nbar/kinematics/sweep.hpp"
#include "nbar/model/materials.hpp"
#include "nbar/stress/link_fe.hpp"

namespace {

using namespace nbar_bench;

constexpr int kTargetNodes = 5000;

// The machine with its sweep and inverse dynamics solved once, as the pipeline keeps them.
struct Machine {
  std::shared_ptr<const nbar::InverseDynamics> dynamics;
  nbar::SweepResult sweep;
  std::vector<nbar::DynamicsResult> forces;
  Machine() {
    const auto mech = std::make_shared<const nbar::Mechanism>(steel_chain(5));
    if (mech->model().bodies.size() < 10) die("the benchmark machine needs at least 10 bodies");
    dynamics = std::make_shared<const nbar::InverseDynamics>(mech);
    nbar::SweepOptions options;
    options.order = 2;
    sweep = nbar::run_sweep(*mech, options);
    if (!sweep.complete || sweep.samples.size() != kStepsPerTurn + 1) die("the sweep did not complete");
    for (const nbar::Sample& s : sweep.samples) forces.push_back(dynamics->solve(s));
  }
};

const Machine& machine() {
  static const Machine m;
  return m;
}

double mean_nodes(const nbar::LinkFe& fe, int bodies) {
  double nodes = 0.0;
  for (int b = 0; b < bodies; ++b) nodes += static_cast<double>(fe.plate(b).mesh().nodes.size());
  return nodes / bodies;
}

// The mesh size that gives about kTargetNodes nodes per link (nodes go as 1/size^2), found once.
double mesh_size_for_target() {
  static const double size = [] {
    const Machine& m = machine();
    const int bodies = static_cast<int>(m.dynamics->mechanism().model().bodies.size());
    nbar::FeOptions options;
    options.mesh_size = 3e-4;
    for (int k = 0; k < 3; ++k) {
      const nbar::LinkFe fe(m.dynamics, options);
      options.mesh_size *= std::sqrt(mean_nodes(fe, bodies) / kTargetNodes);
    }
    return options.mesh_size;
  }();
  return size;
}

void run_sweep_fe(benchmark::State& st, int threads) {
  const Machine& m = machine();
  nbar::FeOptions options;
  options.mesh_size = mesh_size_for_target();
  options.threads = threads;
  const nbar::LinkFe fe(m.dynamics, options);
  const int bodies = static_cast<int>(m.dynamics->mechanism().model().bodies.size());
  double worst_unbalance = 0.0;
  for (auto _ : st) {
    const auto peaks = nbar::fe_peaks(fe, m.sweep, m.forces);
    for (const nbar::FePeak& p : peaks) worst_unbalance = std::max(worst_unbalance, p.load_unbalance);
    benchmark::DoNotOptimize(peaks.data());
  }
  st.counters["bodies"] = bodies;
  st.counters["nodes_per_body"] = mean_nodes(fe, bodies);
  st.counters["mesh_size_um"] = options.mesh_size * 1e6;
  st.counters["unbalance"] = worst_unbalance;
  st.counters["per_step"] = benchmark::Counter(static_cast<double>(st.iterations()) * kStepsPerTurn,
                                               benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_FeSweep(benchmark::State& st) { run_sweep_fe(st, 1); }
BENCHMARK(BM_FeSweep)->Unit(benchmark::kMillisecond);

void BM_FeSweepTwoThreads(benchmark::State& st) { run_sweep_fe(st, 2); }
BENCHMARK(BM_FeSweepTwoThreads)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_FeSetup(benchmark::State& st) {
  const Machine& m = machine();
  nbar::FeOptions options;
  options.mesh_size = mesh_size_for_target();
  for (auto _ : st) {
    const nbar::LinkFe fe(m.dynamics, options);
    benchmark::DoNotOptimize(&fe);
  }
}
BENCHMARK(BM_FeSetup)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
