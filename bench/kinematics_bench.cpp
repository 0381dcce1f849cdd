// Kinematics benchmarks: the cost of one sweep step (position, velocity and acceleration) for
// a four-bar and for chains of N four-bar loops, and the one-time cost of compiling and
// assembling a large chain.
//
// The per-step benchmarks drive nbar::track() themselves, the way run_sweep() does for a
// proportional from/to sweep (the tracking parameter is the time, the series hold max(3, order +
// 1) terms, and after track() state.series already holds the Taylor coefficients of q in time).
// Mechanism construction and assembly happen in the setup, outside the timed region; every
// benchmark iteration is one full input revolution in 360 steps of 1 degree, continuing from
// where the previous iteration stopped, so no reset is needed.
// Counters: per_step (and per_step_per_loop for chains), CPU seconds per sample, printed with an
// SI prefix (803n = 803 ns); track_substeps_per_step, the accepted continuation steps per sample
// (1 when no step had to be shortened).
//
// BM_FourBarSweep/<steps> times the whole run_sweep() (assembly, recording, branch watch) for
// comparison: (time(3601) - time(1)) / 3600 is run_sweep's own cost per step.
//
// BM_FourBarStepOverClosedForm and BM_ChainPerLoopOverFourBar/<N> are the ratios of issue 14,
// each measured interleaved in one benchmark (CPU time of the thread), so that a shared
// machine's load falls on both sides alike. BM_StraightFourBarStepOverClosedForm times the same
// algorithm written straight for this one four-bar (straight_four_bar.hpp): the gap between it
// and the engine is what the engine's generality costs. The measured ratios, dated, and what
// each change bought are in docs/benchmarks.md.
//
// Run: kinematics_bench --benchmark_min_time=0.2
//      kinematics_bench --benchmark_filter='Over' --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
//      /usr/bin/python3 bench/kinematics_rounds.py --rounds 10 [--baseline OLD/kinematics_bench]

#include <benchmark/benchmark.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bench_models.hpp"
#include "nbar/kinematics/continuation.hpp"
#include "nbar/kinematics/mechanism.hpp"
#include "nbar/kinematics/position.hpp"
#include "nbar/kinematics/sweep.hpp"
#include "nbar/model/model.hpp"
#include "norton_closed_form.hpp"
#include "straight_four_bar.hpp"

namespace {

using namespace nbar_bench;

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
    options.terms = std::max(3, kOrder + 1);
    path = [f = from, v = speed](double t, int terms, std::vector<nbar::Series>& out) {
      out.resize(f.size());
      for (std::size_t d = 0; d < f.size(); ++d) out[d].set_line(terms, f[d], v[d], t);
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
  for (const nbar::Warning& w : r.warnings) die(what + ": unexpected sweep warning: " + w.message);
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

// The reference: Norton's closed form of the same crank-rocker, one step of it (angles,
// angular velocities and accelerations, and the pins' positions, velocities and accelerations:
// what the engine's step gives), the crank stepping as the engine's does.
struct ClosedForm {
  ClosedForm() {
    // The engine's branch: the root whose B is the drawn one (the model is drawn at crank angle 0).
    const nbar::Model m = four_bar_model();
    const NortonFourBar::Pose open = linkage.solve(0.0, 0.0, 0.0);
    linkage.crossed = std::hypot(open.bx - m.points[3].position.x(), open.by - m.points[3].position.y()) > 1e-9;
    omega2 = m.drivers[0].speed;
    step_angle = (*m.drivers[0].to - *m.drivers[0].from) / kStepsPerTurn;
  }
  NortonFourBar::Pose step() {
    ++steps;
    return linkage.solve(steps * step_angle, omega2, 0.0);
  }
  NortonFourBar linkage{0.080, 0.180, 0.150, 0.200};
  double omega2 = 0.0, step_angle = 0.0;
  long long steps = 0;
};

// The closed form and the engine agree at every step of a turn, or the ratio means nothing.
void check_closed_form() {
  const nbar::Mechanism mech(four_bar_model());
  const nbar::SweepResult r = nbar::run_sweep(mech, {.steps = kStepsPerTurn + 1, .order = kOrder});
  ClosedForm closed;
  closed.steps = -1;
  const int bx = mech.column_of(3);
  for (const nbar::Sample& s : r.samples) {
    const NortonFourBar::Pose p = closed.step();
    const double errors[] = {s.taylor(bx, 0) - p.bx,
                             s.taylor(bx + 1, 0) - p.by,
                             s.derivative(bx, 1) - p.bvx,
                             s.derivative(bx + 1, 1) - p.bvy,
                             (s.derivative(bx, 2) - p.bax) / 100.0,
                             (s.derivative(bx + 1, 2) - p.bay) / 100.0};
    for (double e : errors)
      if (!(std::abs(e) < 1e-9)) die("Norton's closed form and the engine disagree at step " + std::to_string(s.step));
  }
}

void BM_FourBarClosedForm(benchmark::State& st) {
  check_closed_form();
  ClosedForm closed;
  for (auto _ : st) {
    for (int i = 0; i < kStepsPerTurn; ++i) {
      NortonFourBar::Pose p = closed.step();
      benchmark::DoNotOptimize(p);
    }
  }
  const auto per = benchmark::Counter::kIsRate | benchmark::Counter::kInvert;
  st.counters["per_step"] = benchmark::Counter(static_cast<double>(closed.steps), per);
}
BENCHMARK(BM_FourBarClosedForm)->Unit(benchmark::kMicrosecond);

// CPU time of this thread: on a machine shared with other work, wall time would count the waits
// for a core.
double thread_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}
double seconds_since(double start) { return thread_seconds() - start; }

// Per iteration one turn of `step` and one turn of the closed form, each timed in CPU time, so
// that load from other processes falls on both alike. Counters: <name>_step_us,
// closed_form_step_us and `ratio`, the first over the second. `step(&why)` is false, with the
// reason, when it fails.
template <class Step>
void time_against_closed_form(benchmark::State& st, const std::string& name, Step&& step) {
  ClosedForm closed;
  double timed = 0.0, reference = 0.0;
  std::string why;
  for (auto _ : st) {
    double start = thread_seconds();
    for (int i = 0; i < kStepsPerTurn; ++i)
      if (!step(&why)) {
        st.SkipWithError((name + " step failed: " + why).c_str());
        return;
      }
    timed += seconds_since(start);
    start = thread_seconds();
    for (int i = 0; i < kStepsPerTurn; ++i) {
      NortonFourBar::Pose p = closed.step();
      benchmark::DoNotOptimize(p);
    }
    reference += seconds_since(start);
  }
  const double steps = static_cast<double>(st.iterations()) * kStepsPerTurn;
  st.counters[name + "_step_us"] = 1e6 * timed / steps;
  st.counters["closed_form_step_us"] = 1e6 * reference / steps;
  st.counters["ratio"] = timed / reference;
}

// The ratio the issue asks for: one turn of the engine (BM_FourBarStep's work) against one of the
// closed form, interleaved.
void BM_FourBarStepOverClosedForm(benchmark::State& st) {
  check_closed_form();
  Tracker tracker(four_bar_model());
  time_against_closed_form(st, "engine", [&](std::string* why) { return tracker.step(why); });
}
BENCHMARK(BM_FourBarStepOverClosedForm)->Unit(benchmark::kMicrosecond);

// The engine's algorithm written straight for this four-bar (straight_four_bar.hpp), started on
// the engine's branch from the closed form's series at the first step and the one before it.
StraightFourBar straight_four_bar() {
  const ClosedForm closed;
  const NortonFourBar& f = closed.linkage;
  const double dt = closed.step_angle / closed.omega2;
  double series[2][3][StraightFourBar::kN];
  for (int p = 0; p < 2; ++p) {
    const NortonFourBar::Pose pose = f.solve(-p * closed.step_angle, closed.omega2, 0.0);
    const double q[3][StraightFourBar::kN] = {{pose.ax, pose.ay, pose.bx, pose.by},
                                              {pose.avx, pose.avy, pose.bvx, pose.bvy},
                                              {pose.aax / 2, pose.aay / 2, pose.bax / 2, pose.bay / 2}};
    std::copy(&q[0][0], &q[0][0] + 3 * StraightFourBar::kN, &series[p][0][0]);
  }
  return StraightFourBar(f.a, f.b, f.c, f.d, closed.omega2, dt, series[0], series[1]);
}

// It agrees with the closed form along a turn, or its time means nothing.
void check_straight_four_bar() {
  StraightFourBar straight = straight_four_bar();
  ClosedForm closed;
  for (int i = 0; i < kStepsPerTurn; ++i) {
    if (!straight.step()) die("the straight four-bar step failed at step " + std::to_string(i + 1));
    const NortonFourBar::Pose p = closed.step();
    const double errors[] = {straight.coefficient(0, 2) - p.bx,
                             straight.coefficient(0, 3) - p.by,
                             straight.coefficient(1, 2) - p.bvx,
                             straight.coefficient(1, 3) - p.bvy,
                             (2 * straight.coefficient(2, 2) - p.bax) / 100.0,
                             (2 * straight.coefficient(2, 3) - p.bay) / 100.0};
    for (double e : errors)
      if (!(std::abs(e) < 1e-9))
        die("Norton's closed form and the straight step disagree at step " + std::to_string(i + 1));
  }
}

// What the algorithm costs without the engine's generality: the straight step against the closed
// form, interleaved as BM_FourBarStepOverClosedForm is.
void BM_StraightFourBarStepOverClosedForm(benchmark::State& st) {
  check_straight_four_bar();
  StraightFourBar straight = straight_four_bar();
  time_against_closed_form(st, "straight", [&](std::string* why) {
    if (straight.step()) return true;
    *why = "Newton did not converge or the Jacobian is singular";
    return false;
  });
  benchmark::DoNotOptimize(straight.coefficient(2, 3));
  st.counters["corrections_per_step"] = straight.corrections() / (static_cast<double>(st.iterations()) * kStepsPerTurn);
}
BENCHMARK(BM_StraightFourBarStepOverClosedForm)->Unit(benchmark::kMicrosecond);

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
// 15 and 16 loops (60 and 64 coordinates) straddle LinearSolver::kDenseConditionLimit, above
// which a near-singular Jacobian's condition is Hager's estimate rather than a dense LU's.
BENCHMARK(BM_ChainOfFourBars)->Arg(1)->Arg(10)->Arg(15)->Arg(16)->Arg(100)->Arg(1000)->Unit(benchmark::kMicrosecond);

// A chain's cost per loop against the single four-bar's step, interleaved as above: per
// iteration one turn of the chain and one of the four-bar. Counter `ratio`: chain time per
// step per loop over four-bar time per step.
void BM_ChainPerLoopOverFourBar(benchmark::State& st) {
  const int loops = static_cast<int>(st.range(0));
  const nbar::Model model = chain_model(loops);
  check_sweep(nbar::Mechanism(model), "chain of " + std::to_string(loops) + " four-bars");
  Tracker chain(model), single(four_bar_model());
  double chain_time = 0.0, single_time = 0.0;
  std::string why;
  for (auto _ : st) {
    double start = thread_seconds();
    for (int i = 0; i < kStepsPerTurn; ++i)
      if (!chain.step(&why)) {
        st.SkipWithError(("tracking failed: " + why).c_str());
        return;
      }
    chain_time += seconds_since(start);
    start = thread_seconds();
    for (int i = 0; i < kStepsPerTurn; ++i)
      if (!single.step(&why)) {
        st.SkipWithError(("tracking failed: " + why).c_str());
        return;
      }
    single_time += seconds_since(start);
  }
  const double steps = static_cast<double>(st.iterations()) * kStepsPerTurn;
  st.counters["per_loop_step_us"] = 1e6 * chain_time / steps / loops;
  st.counters["four_bar_step_us"] = 1e6 * single_time / steps;
  st.counters["ratio"] = chain_time / loops / single_time;
}
BENCHMARK(BM_ChainPerLoopOverFourBar)->Arg(1)->Arg(10)->Arg(100)->Arg(1000)->Unit(benchmark::kMicrosecond);

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
