// The plane-stress finite elements on a link-sized mesh (~5000 nodes): assembling and
// factorising once, then one load case (back-substitution and stress recovery) per step.
// The target, 10 links x 360 steps in 2 s on one core, is 0.55 ms per solve.
#include <benchmark/benchmark.h>

#include "nbar/stress/plane_stress.hpp"
#include "structured_t6.hpp"

namespace {

using namespace nbar::fe;

const ElasticMaterial kSteel{200e9, 0.3, 0.01, 7850};

// A lug 0.2 m long and 0.04 m wide with a 0.02 m hole: 128 edges around it, 19 rings, 4992 nodes.
TriMesh link_mesh() { return structured::plate_with_hole(-0.04, -0.02, 0.16, 0.02, {0, 0}, 0.01, 64, 19, 2.5); }

LoadCase step_loads(const TriMesh& mesh, int step) {
  const double angle = 0.0175 * step;
  LoadCase loads;
  loads.bearings.push_back({0, {-1000 * std::cos(angle), 1000 * std::sin(angle)}});
  loads.couples.push_back({0, 2.0 * std::cos(angle)});
  loads.body = RigidBodyField{{0.08, 0}, {3, -2}, 10.0, 50.0 * std::sin(angle), {0, -9.81}};
  structured::add_edge_traction(
      mesh, kSteel.thickness,
      [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() > 0.1599 && b.x() > 0.1599; },
      [&](const Eigen::Vector2d&) -> Eigen::Vector2d {
        return Eigen::Vector2d(1000 * std::cos(angle), -1000 * std::sin(angle)) / (0.04 * kSteel.thickness);
      },
      loads.nodal);
  return loads;
}

void BM_AssembleAndFactorise(benchmark::State& state) {
  const TriMesh mesh = link_mesh();
  for (auto _ : state) {
    PlateModel model(mesh, kSteel);
    benchmark::DoNotOptimize(model);
  }
  state.counters["nodes"] = static_cast<double>(mesh.nodes.size());
}
BENCHMARK(BM_AssembleAndFactorise)->Unit(benchmark::kMillisecond);

void BM_SolveOneStep(benchmark::State& state) {
  const TriMesh mesh = link_mesh();
  const PlateModel model(mesh, kSteel);
  std::vector<LoadCase> steps;
  for (int i = 0; i < 360; ++i) steps.push_back(step_loads(mesh, i));
  int step = 0;
  for (auto _ : state) {
    StressField field = model.solve(steps[step]);
    benchmark::DoNotOptimize(field.peak);
    step = (step + 1) % 360;
  }
  state.counters["nodes"] = static_cast<double>(mesh.nodes.size());
}
BENCHMARK(BM_SolveOneStep)->Unit(benchmark::kMicrosecond);

// All 360 steps of a sweep through solve_many (blocks of cases share each read of the factor);
// the time is per step.
void BM_SolveManyPerStep(benchmark::State& state) {
  const TriMesh mesh = link_mesh();
  const PlateModel model(mesh, kSteel);
  std::vector<LoadCase> steps;
  for (int i = 0; i < 360; ++i) steps.push_back(step_loads(mesh, i));
  for (auto _ : state) {
    std::vector<StressField> fields = model.solve_many(steps);
    benchmark::DoNotOptimize(fields.back().peak);
  }
  state.SetItemsProcessed(state.iterations() * 360);
  state.counters["per_step_us"] =
      benchmark::Counter(360.0 * state.iterations() * 1e-6, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_SolveManyPerStep)->Unit(benchmark::kMillisecond);

// The same per step on the mesher's mesh of a two-hole bar (0.28 m x 0.04 m, 20 mm holes, size
// 4 mm: 5954 nodes), pulled by its pins, spinning: the link pipeline's kind of mesh and loads.
void BM_MeshedBarSolveManyPerStep(benchmark::State& state) {
  MeshOptions options;
  options.size = 0.004;
  const TriMesh mesh = mesh_region(nbar::make_bar({0, 0}, {0.2, 0}, 0.04, 0.04, 0.01, 0.01), options);
  const PlateModel model(mesh, kSteel);
  std::vector<LoadCase> steps;
  for (int i = 0; i < 360; ++i) {
    const Eigen::Vector2d pin(1000 * std::cos(0.0175 * i), 300 * std::sin(0.0175 * i));
    LoadCase loads;
    loads.bearings = {{0, -pin}, {1, pin}};
    loads.couples = {{0, 1.0}, {1, -1.0}};
    loads.body = RigidBodyField{{0.1, 0}, {2, 1}, 10.0, 30.0, {0, -9.81}};
    steps.push_back(loads);
  }
  for (auto _ : state) {
    std::vector<StressField> fields = model.solve_many(steps);
    benchmark::DoNotOptimize(fields.back().peak);
  }
  state.counters["nodes"] = static_cast<double>(mesh.nodes.size());
  state.counters["per_step_us"] =
      benchmark::Counter(360.0 * state.iterations() * 1e-6, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_MeshedBarSolveManyPerStep)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
