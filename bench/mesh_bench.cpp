// Mesher benchmark: plates of the sizes the finite-element stresses use.
//
// BM_MeshThesisLink meshes the crank of the ANSYS four-bar in docs/kinetics.md (1.2 m x 0.5 m,
// 20 mm pin holes 1 m apart) with the default options; BM_MeshRoundedCrank the
// slotted crank of examples/fourbar-rounded-crank.yaml (arc ends), about 3000 nodes;
// BM_MeshBySize a 1.2 m bar at element sizes giving about 1000 to 20000 nodes.
//
// Run: mesh_bench --benchmark_min_time=0.2
#include <benchmark/benchmark.h>

#include "nbar/stress/mesh.hpp"

namespace {

void BM_MeshThesisLink(benchmark::State& st) {
  const nbar::Region r = nbar::make_bar({0, 0}, {1.0, 0}, 0.5, 0.1, 0.01, 0.01);
  std::size_t nodes = 0;
  for (auto _ : st) {
    const nbar::fe::TriMesh m = nbar::fe::mesh_region(r);
    nodes = m.nodes.size();
    benchmark::DoNotOptimize(m.nodes.data());
  }
  st.counters["nodes"] = static_cast<double>(nodes);
}
BENCHMARK(BM_MeshThesisLink)->Unit(benchmark::kMillisecond);

void BM_MeshRoundedCrank(benchmark::State& st) {
  nbar::Region r;
  r.outline = {{0, -0.01}, {0.08, -0.01}, {0.08, 0.01}, {0, 0.01}};
  r.outline_bulges = {0, 1, 0, 1};
  r.circle_holes = {{{0, 0}, 0.005}, {{0.08, 0}, 0.005}};
  std::size_t nodes = 0;
  for (auto _ : st) {
    const nbar::fe::TriMesh m = nbar::fe::mesh_region(r);
    nodes = m.nodes.size();
    benchmark::DoNotOptimize(m.nodes.data());
  }
  st.counters["nodes"] = static_cast<double>(nodes);
}
BENCHMARK(BM_MeshRoundedCrank)->Unit(benchmark::kMillisecond);

// The argument is the element size far from the holes in mm.
void BM_MeshBySize(benchmark::State& st) {
  const nbar::Region r = nbar::make_bar({0, 0}, {1.2, 0}, 0.5, 0.25, 0.01, 0.01);
  nbar::fe::MeshOptions o;
  o.size = static_cast<double>(st.range(0)) / 1000;
  std::size_t nodes = 0;
  for (auto _ : st) {
    const nbar::fe::TriMesh m = nbar::fe::mesh_region(r, o);
    nodes = m.nodes.size();
    benchmark::DoNotOptimize(m.nodes.data());
  }
  st.counters["nodes"] = static_cast<double>(nodes);
}
BENCHMARK(BM_MeshBySize)->Arg(100)->Arg(50)->Arg(25)->Arg(12)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
