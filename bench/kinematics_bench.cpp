// Kinematics benchmarks: the cost of one sweep step (position, velocity and acceleration) for
// a four-bar and for chains of N four-bar loops, and the one-time cost of compiling and
// assembling a large chain.
//
// The per-step benchmarks drive nbar::track() themselves, the way run_sweep() does for a
// proportional from/to sweep (the tracking parameter is the time, the predictor series holds
// max(4, order + 1) terms, and after track() state.series already holds the Taylor
// coefficients of q in time). Mechanism construction and assembly happen in the setup, outside
// the timed region; every benchmark iteration is one full input revolution in 360 steps of 1
// degree, continuing from where the previous iteration stopped, so no reset is needed.
// Counters: per_step (and per_step_per_loop for chains), CPU seconds per sample, printed with an
// SI prefix (803n = 803 ns); track_substeps_per_step, the accepted continuation steps per sample
// (1 when no step had to be shortened).
//
// BM_FourBarSweep/<steps> times the whole run_sweep() (assembly, recording, branch watch) for
// comparison: (time(3601) - time(1)) / 3600 is run_sweep's own cost per step.
//
// Run: kinematics_bench --benchmark_min_time=0.2

#include <benchmark/benchmark.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "kinematics/continuation.hpp"
#include "kinematics/mechanism.hpp"
#include "kinematics/position.hpp"
#include "kinematics/sweep.hpp"
#include "model/model.hpp"

namespace {

constexpr double kPi = std::numbers::pi;
constexpr int kStepsPerTurn = 360;  // a 361-sample sweep of one turn
constexpr int kOrder = 2;           // position, velocity, acceleration

[[noreturn]] void die(const std::string& message) {
  std::fprintf(stderr, "kinematics_bench: %s\n", message.c_str());
  std::fflush(stderr);
  std::abort();
}

// prefix + i, built by appending: GCC 12 warns falsely (-Wrestrict, PR 105651) on "G" + to_string(i).
std::string indexed(const char* prefix, int i) {
  std::string s(prefix);
  s += std::to_string(i);
  return s;
}

// Model entities by member rather than aggregate initialisation, so that fields added to them
// later keep their defaults without warnings.
nbar::Point point(std::string name, const Eigen::Vector2d& position, bool ground) {
  nbar::Point p;
  p.name = std::move(name);
  p.position = position;
  p.ground = ground;
  return p;
}

nbar::Body body(std::string name, std::vector<int> points, std::optional<double> length = std::nullopt) {
  nbar::Body b;
  b.name = std::move(name);
  b.points = std::move(points);
  b.length = length;
  return b;
}

Eigen::Vector2d unit(double angle) { return {std::cos(angle), std::sin(angle)}; }

// Where the coupler-output pin of a four-bar lies: the intersection of the circle of radius
// `coupler` about the crank pin `a` with the circle of radius `output` about the output pivot
// `o4`, on the left of the line from a to o4 when `left` (one assembly branch), else the right.
Eigen::Vector2d coupler_output_pin(const Eigen::Vector2d& a, const Eigen::Vector2d& o4, double coupler,
                                   double output, bool left) {
  const Eigen::Vector2d d = o4 - a;
  const double dist = d.norm();
  const double along = (coupler * coupler - output * output + dist * dist) / (2.0 * dist);
  const double h2 = coupler * coupler - along * along;
  if (!(h2 > 0.0)) die("four-bar cannot be assembled in the drawn pose");
  const Eigen::Vector2d e = d / dist, n(-e.y(), e.x());
  return a + along * e + (left ? 1.0 : -1.0) * std::sqrt(h2) * n;
}

// Crank-rocker four-bar without coupler point: ground 0.200, crank 0.080, coupler 0.180,
// rocker 0.150 m (Grashof: 0.080 + 0.200 < 0.180 + 0.150, shortest link next to the frame).
// The crank turns one full revolution at 120 rpm.
nbar::Model four_bar_model() {
  const double ground = 0.200, crank = 0.080, coupler = 0.180, rocker = 0.150;
  const Eigen::Vector2d o2(0.0, 0.0), o4(ground, 0.0), a(crank, 0.0);
  const Eigen::Vector2d b = coupler_output_pin(a, o4, coupler, rocker, true);
  nbar::Model m;
  m.name = "crank-rocker four-bar";
  m.points = {point("O2", o2, true), point("O4", o4, true), point("A", a, false), point("B", b, false)};
  m.bodies = {body("crank", {0, 2}, crank), body("coupler", {2, 3}, coupler), body("rocker", {1, 3}, rocker)};
  nbar::Driver d;
  d.name = "crank";
  d.kind = nbar::DriverKind::Angle;
  d.body = 0;
  d.from = 0.0;
  d.to = 2.0 * kPi;
  d.speed = 4.0 * kPi;  // 120 rpm
  m.drivers = {d};
  m.sweep.steps = kStepsPerTurn + 1;
  return m;
}

// A chain of N four-bar loops with one degree of freedom, every link turning fully.
//
// Ground pivots G0..GN lie on the x axis, one frame length (0.01 m) apart. Loop i has the frame Gi-G(i+1), the
// crank Gi-Ai, the coupler Ai-Bi and the output G(i+1)-Bi. The output of loop i is a ternary
// link G(i+1), Bi, A(i+1) whose third point, diametrically opposite Bi about G(i+1), is the
// crank pin of loop i+1.
//
// Every loop is the same Grashof double-crank (the frame is the shortest link: s + l = 1 + 2.5
// < p + q = 2 + 2.2, well away from a change point), with crank and output lengths swapped in
// odd loops. With the pin opposite Bi, loop i+1 is then loop i run backwards turned by half a
// turn: if loop i maps crank angle th to output angle ph, loop i+1 maps ph + pi to th + pi. The
// input-output relation of consecutive loops cancels, so every even loop's crank turns exactly
// with the input and every odd loop's crank with loop 0's output: velocity ratios stay bounded
// however long the chain, and no loop comes near a toggle.
nbar::Model chain_model(int loops) {
  if (loops < 1) die("a chain needs at least one loop");
  const double s = 0.01;                     // m per unit of length
  const double frame = 1.0 * s, coupler = 2.5 * s;
  const double la = 2.0 * s, lc = 2.2 * s;   // crank and output of even loops; swapped in odd loops
  const double theta0 = 0.3;                 // drawn input angle, rad

  nbar::Model m;
  m.name = "chain of " + std::to_string(loops) + " four-bars";
  m.points.reserve(3 * loops + 1);
  for (int i = 0; i <= loops; ++i) m.points.push_back(point(indexed("G", i), {i * frame, 0.0}, true));
  auto g = [](int i) { return i; };
  auto a = [loops](int i) { return loops + 1 + 2 * i; };
  auto b = [loops](int i) { return loops + 2 + 2 * i; };

  // Drawn pose: loop 0 at theta0 with B0 left of the line A0-G1 (above it); then the cancelling
  // relation gives every other loop in closed form.
  const Eigen::Vector2d a0 = unit(theta0) * la;
  const Eigen::Vector2d b0 = coupler_output_pin(a0, {frame, 0.0}, coupler, lc, true);
  const double phi0 = std::atan2(b0.y(), b0.x() - frame);
  for (int i = 0; i < loops; ++i) {
    const Eigen::Vector2d gi(i * frame, 0.0), gn((i + 1) * frame, 0.0);
    Eigen::Vector2d pa, pb;
    if (i % 2 == 0) {
      pa = gi + la * unit(theta0);
      pb = gn + lc * unit(phi0);
    } else {
      pa = gi + lc * unit(phi0 + kPi);
      pb = gn + la * unit(theta0 + kPi);
    }
    m.points.push_back(point(indexed("A", i), pa, false));
    m.points.push_back(point(indexed("B", i), pb, false));
  }

  m.bodies.reserve(2 * loops + 1);
  m.bodies.push_back(body("crank0", {g(0), a(0)}, la));
  for (int i = 0; i < loops; ++i) {
    m.bodies.push_back(body(indexed("coupler", i), {a(i), b(i)}, coupler));
    const double out = i % 2 == 0 ? lc : la;
    if (i + 1 < loops)
      m.bodies.push_back(body(indexed("output", i), {g(i + 1), b(i), a(i + 1)}));  // lengths: 2-point bodies only
    else
      m.bodies.push_back(body(indexed("output", i), {g(i + 1), b(i)}, out));
  }

  nbar::Driver d;
  d.name = "input";
  d.kind = nbar::DriverKind::Angle;
  d.body = 0;
  d.from = theta0;
  d.to = theta0 + 2.0 * kPi;
  d.speed = 2.0 * kPi;  // 60 rpm
  m.drivers = {d};
  m.sweep.steps = kStepsPerTurn + 1;
  return m;
}

// A mechanism assembled at the start of its sweep, ready to be tracked step by step exactly as
// run_sweep() does for a constant-speed from/to sweep.
struct Tracker {
  explicit Tracker(nbar::Model model) : mech(std::move(model)), state(mech) {
    const nbar::Model& m = mech.model();
    for (const nbar::Driver& d : m.drivers) {
      if (d.law || d.accel != 0.0 || !d.from || !d.to) die("Tracker: constant-speed from/to drivers only");
      from.push_back(*d.from);
      speed.push_back(d.speed);
    }
    // One turn of the first driver in kStepsPerTurn steps; the others move in proportion.
    step_time = (*m.drivers[0].to - *m.drivers[0].from) / m.drivers[0].speed / kStepsPerTurn;
    options.terms = std::max(4, kOrder + 1);
    path = [f = from, v = speed](double t, int terms, std::vector<nbar::Series>& out) {
      out.resize(f.size());
      for (std::size_t d = 0; d < f.size(); ++d) out[d] = f[d] + v[d] * nbar::Series::variable(terms, t);
    };
    nbar::assemble(mech, state, from);
    state.parameter = 0.0;
    std::vector<nbar::Series> values;
    path(state.parameter, options.terms, values);
    nbar::set_drivers(mech, state, values);
    nbar::compute_series(mech, state, options.terms);
    sample.resize(mech.coordinate_count(), kOrder + 1);
  }

  // One sample further along; false (with the reason) when the branch cannot be followed.
  bool step(std::string* why) {
    ++steps;
    const nbar::TrackReport r = nbar::track(mech, state, path, steps * step_time, options);
    substeps += r.steps;
    if (!r.reached) {
      if (why) *why = r.reason;
      return false;
    }
    sample = state.series.leftCols(kOrder + 1);  // q, dq/dt, d2q/dt2 / 2
    benchmark::DoNotOptimize(sample.data());
    return true;
  }

  nbar::Mechanism mech;
  nbar::State state;
  std::vector<double> from, speed;
  nbar::DriverPath path;
  nbar::TrackOptions options;
  double step_time = 0.0;
  long long steps = 0;     // samples taken since assembly
  long long substeps = 0;  // accepted continuation steps
  Eigen::MatrixXd sample;
};

// The full sweep must run to its end on one branch, or the timings mean nothing.
void check_sweep(const nbar::Mechanism& mech, const std::string& what) {
  const nbar::SweepResult r = nbar::run_sweep(mech, {.steps = kStepsPerTurn + 1, .order = kOrder});
  if (!r.complete) die(what + ": the sweep does not complete: " + r.stop_reason);
  if (static_cast<int>(r.samples.size()) != kStepsPerTurn + 1) die(what + ": the sweep is short");
  for (const std::string& w : r.warnings) die(what + ": unexpected sweep warning: " + w);
  if (!(r.max_residual <= mech.tolerance())) die(what + ": residual above tolerance");
}

void run_turns(benchmark::State& st, Tracker& tracker, int loops) {
  const long long steps0 = tracker.steps, substeps0 = tracker.substeps;
  std::string why;
  for (auto _ : st) {
    for (int i = 0; i < kStepsPerTurn; ++i) {
      if (!tracker.step(&why)) {
        st.SkipWithError(("tracking failed: " + why).c_str());
        return;
      }
    }
  }
  const double steps = static_cast<double>(tracker.steps - steps0);
  st.SetItemsProcessed(static_cast<int64_t>(steps));
  // CPU seconds per step (printed with an SI prefix: "803n" is 803 ns).
  const auto per = benchmark::Counter::kIsRate | benchmark::Counter::kInvert;
  st.counters["per_step"] = benchmark::Counter(steps, per);
  if (loops > 0) st.counters["per_step_per_loop"] = benchmark::Counter(steps * loops, per);
  st.counters["track_substeps_per_step"] = static_cast<double>(tracker.substeps - substeps0) / steps;
}

// 1. One step of the crank-rocker: position solve, velocity and acceleration.
void BM_FourBarStep(benchmark::State& st) {
  const nbar::Model model = four_bar_model();
  check_sweep(nbar::Mechanism(model), "four-bar");
  Tracker tracker(model);
  run_turns(st, tracker, 0);
}
BENCHMARK(BM_FourBarStep)->Unit(benchmark::kMicrosecond);

// The whole run_sweep() with `steps` samples (assembly and recording included).
void BM_FourBarSweep(benchmark::State& st) {
  const nbar::Mechanism mech(four_bar_model());
  const int steps = static_cast<int>(st.range(0));
  for (auto _ : st) {
    nbar::SweepResult r = nbar::run_sweep(mech, {.steps = steps, .order = kOrder});
    if (!r.complete) {
      st.SkipWithError(r.stop_reason.c_str());
      return;
    }
    benchmark::DoNotOptimize(r.samples.data());
  }
  st.SetItemsProcessed(st.iterations() * steps);
}
BENCHMARK(BM_FourBarSweep)->Arg(1)->Arg(361)->Arg(3601)->Unit(benchmark::kMicrosecond);

// 2. One step of a chain of N four-bars.
void BM_ChainOfFourBars(benchmark::State& st) {
  const int loops = static_cast<int>(st.range(0));
  const nbar::Model model = chain_model(loops);
  check_sweep(nbar::Mechanism(model), "chain of " + std::to_string(loops) + " four-bars");
  Tracker tracker(model);
  run_turns(st, tracker, loops);
}
// 15 and 16 loops (60 and 64 coordinates) straddle LinearSolver::kDenseLimit, the switch from
// dense to sparse LU.
BENCHMARK(BM_ChainOfFourBars)->Arg(1)->Arg(10)->Arg(15)->Arg(16)->Arg(100)->Arg(1000)->Unit(benchmark::kMicrosecond);

// 3. One-time cost: compiling the model into a Mechanism (validation, rows, pattern, loop
// search, mobility analysis), then that plus assembling it at the start of the sweep.
void BM_ChainBuild(benchmark::State& st) {
  const int loops = static_cast<int>(st.range(0));
  const nbar::Model model = chain_model(loops);
  for (auto _ : st) {
    st.PauseTiming();
    nbar::Model copy = model;
    st.ResumeTiming();
    nbar::Mechanism mech(std::move(copy));
    benchmark::DoNotOptimize(&mech);
  }
}
// 150 loops (600 coordinates) is the largest chain whose mobility analysis is dense (cubic).
BENCHMARK(BM_ChainBuild)->Arg(10)->Arg(100)->Arg(150)->Arg(1000)->Unit(benchmark::kMillisecond);

void BM_ChainBuildAndAssemble(benchmark::State& st) {
  const int loops = static_cast<int>(st.range(0));
  const nbar::Model model = chain_model(loops);
  const std::vector<double> start{*model.drivers[0].from};
  for (auto _ : st) {
    st.PauseTiming();
    nbar::Model copy = model;
    st.ResumeTiming();
    nbar::Mechanism mech(std::move(copy));
    nbar::State state(mech);
    const nbar::AssemblyReport r = nbar::assemble(mech, state, start);
    benchmark::DoNotOptimize(r.residual);
  }
}
BENCHMARK(BM_ChainBuildAndAssemble)->Arg(10)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
