#include "nbar/synthesis/run.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <exception>
#include <mutex>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <thread>
#include <utility>

#include "nbar/model/diagnostics.hpp"
#include "nbar/synthesis/five_point.hpp"
#include "nbar/synthesis/function_generation.hpp"
#include "nbar/synthesis/nine_point.hpp"
#include "nbar/synthesis/path_fit.hpp"

namespace nbar::synthesis {

std::string to_string(SynthesisKind kind) {
  switch (kind) {
    case SynthesisKind::FivePoint: return "five-point";
    case SynthesisKind::Burmester: return "burmester";
    case SynthesisKind::Function: return "function";
    case SynthesisKind::NinePoint: return "nine-point";
    case SynthesisKind::Path: return "path";
  }
  return {};
}

namespace {

using Row = DesignRow;
using Outcome = SynthesisOutcome;

// Every real design checked, on `threads` threads (0: every hardware thread): each check is
// independent of the others and writes only its own row, so the outcome is the same whatever
// the number of threads. Workers take rows in turn and stop at the first checkpoint that says
// to; its error is thrown once every worker has stopped.
void check_rows(Outcome& out, const std::function<DesignCheck(const FourBarDesign&)>& check, const RunControl& control,
                unsigned threads) {
  const int total = static_cast<int>(out.rows.size());
  std::atomic<int> next{0}, done{0};
  std::atomic<bool> stop{false}, cancelled{false};
  std::mutex mutex;
  std::exception_ptr failure;  // a check that threw (out of memory): rethrown here
  const auto work = [&] {
    try {
      for (int i = next++; i < total && !stop; i = next++) {
        if (control.should_stop("checking", done, total)) {
          cancelled = stop = true;
          return;
        }
        Row& row = out.rows[i];
        if (row.real) row.check = check(row.design);
        ++done;
      }
    } catch (...) {
      const std::lock_guard lock(mutex);
      if (!failure) failure = std::current_exception();
      stop = true;
    }
  };
  unsigned n = threads ? threads : std::max(1u, std::thread::hardware_concurrency());
  n = std::min<unsigned>(n, static_cast<unsigned>(std::max(1, total)));
  std::vector<std::thread> workers;
  for (unsigned t = 1; t < n; ++t) workers.emplace_back(work);
  work();
  for (std::thread& w : workers) w.join();
  if (failure) std::rethrow_exception(failure);
  if (cancelled) control.throw_stopped("checking");
  control.checkpoint("checking", done, total);
}

// A fixed pivot on a target point: a coupler point that passes through a fixed pivot belongs only
// to a degenerate linkage (a crank of no length, or a coupler point on the pivot's joint), so
// the designs found are not what was asked for. Said, not refused: the solver still runs. Lengths
// within a millionth of the pivots' distance count as the same place (the task is in its unit).
void note_pivots_on_targets(const SynthesisTask& task, Outcome& out) {
  const double near = 1e-6 * (task.pivot_a - task.pivot_b).norm();
  const std::array<std::pair<const char*, Eigen::Vector2d>, 2> pivots{{{"a", task.pivot_a}, {"b", task.pivot_b}}};
  for (const auto& [name, pivot] : pivots)
    for (std::size_t i = 0; i < task.points.size(); ++i)
      if ((task.points[i] - pivot).norm() <= near)
        out.notes.push_back(
            fmt::format("pivot {} is at target point {} ({:.6g}, {:.6g} {}): the coupler point would "
                        "pass through a fixed pivot, which only a degenerate linkage does; move "
                        "the pivot or the point",
                        name, i + 1, pivot.x(), pivot.y(), task.units.length));
}

Outcome five_point(const SynthesisTask& task, const SynthesisRunOptions& run) {
  FivePointTask problem;
  problem.pivot_a = task.pivot_a;
  problem.pivot_b = task.pivot_b;
  std::copy(task.points.begin(), task.points.end(), problem.points.begin());
  SolverOptions options;
  options.threads = run.threads;
  options.seed = run.seed;
  options.progress = [&run](int done, int total) {
    // A callback that asks to stop cancels the remaining paths.
    if (run.control.on_progress && !run.control.on_progress(Progress{"paths", done, total})) run.control.token.cancel();
  };
  options.stop = [&run] { return run.control.token.cancelled(); };
  const FivePointResult result = solve_five_point(problem, options);
  run.control.checkpoint("paths", result.paths, result.paths);
  Outcome out;
  out.method = result.method;
  for (const FivePointSolution& s : result.solutions) {
    Row row;
    row.real = s.real;
    row.design = s.design;
    row.solver_residual = s.residual;
    row.solver_condition = s.condition;
    out.rows.push_back(row);
  }
  std::vector<Target> targets;
  for (const Eigen::Vector2d& p : task.points) targets.push_back({p, std::nullopt});
  check_rows(
      out, [&](const FourBarDesign& d) { return check_design(d, targets); }, run.control, run.threads);
  if (result.failed_paths > 0)
    out.notes.push_back(fmt::format("{} of {} paths failed", result.failed_paths, result.paths));
  note_pivots_on_targets(task, out);
  return out;
}

// Every real cognate triple: three rows, the solution and its two Roberts cognates.
Outcome nine_point(const SynthesisTask& task, const SynthesisRunOptions& run) {
  if (task.points.size() != 9) throw Error(ErrorKind::InvalidModel, "a nine-point task needs exactly 9 points");
  std::array<Eigen::Vector2d, 9> points;
  std::copy(task.points.begin(), task.points.end(), points.begin());
  NinePointOptions options;
  options.threads = run.threads;
  options.seed = run.seed;
  options.progress = [&run](const std::string& stage, int done, int total) {
    if (run.control.on_progress &&
        !run.control.on_progress(Progress{stage == "paths" ? "paths" : "monodromy", done, total}))
      run.control.token.cancel();
  };
  options.stop = [&run] { return run.control.token.cancelled(); };
  options.time_budget = run.nine_point_budget;
  NinePointResult result;
  try {
    result = solve_nine_point(points, options);
  } catch (const Error&) {
    if (run.control.token.cancelled()) run.control.checkpoint("paths", 0, 0);  // throws Cancelled
    throw;
  }
  run.control.checkpoint("paths", result.paths, result.paths);
  Outcome out;
  out.method = result.method;
  for (const NinePointLinkage& linkage : result.linkages)
    for (const FourBarDesign& design : linkage.designs) {
      Row row;
      row.design = design;
      row.solver_residual = linkage.residual;
      row.solver_condition = linkage.condition;
      out.rows.push_back(row);
    }
  std::vector<Target> targets;
  for (const Eigen::Vector2d& p : task.points) targets.push_back({p, std::nullopt});
  check_rows(
      out, [&](const FourBarDesign& d) { return check_design(d, targets); }, run.control, run.threads);
  out.notes.push_back(fmt::format("{} of {} orbits (Roberts cognate triples) found, {} of them real: {}", result.orbits,
                                  kNinePointOrbits, result.real_orbits, result.certificate));
  if (result.failed_paths > 0)
    out.notes.push_back(fmt::format("{} of {} paths from the stored instance were tracked again", result.failed_paths,
                                    kNinePointOrbits));
  if (result.budget_spent)
    out.notes.push_back(
        fmt::format("the solve stopped at its time budget of {:g} s (the paths not yet tracked were "
                    "skipped): the designs listed are those found by then",
                    options.time_budget));
  return out;
}

// Dyads spread evenly (by arc length) along the centre-point curves.
std::vector<BurmesterPair> spread_dyads(const BurmesterCurves& curves, int count) {
  std::vector<BurmesterPair> all;
  std::vector<double> at;  // arc length of each sample, the curves laid end to end
  double length = 0.0;
  for (const auto& branch : curves.centre_curve) {
    for (std::size_t k = 0; k < branch.size(); ++k) {
      if (k > 0) length += (branch[k].centre - branch[k - 1].centre).norm();
      all.push_back(branch[k]);
      at.push_back(length);
    }
  }
  if (static_cast<int>(all.size()) <= count) return all;
  std::vector<BurmesterPair> out;
  for (int i = 0; i < count; ++i) {
    const double wanted = length * (i + 0.5) / count;
    const auto k = std::lower_bound(at.begin(), at.end(), wanted) - at.begin();
    out.push_back(all[std::min<std::size_t>(k, all.size() - 1)]);
  }
  return out;
}

Outcome burmester(const SynthesisTask& task, const SynthesisRunOptions& run) {
  Outcome out;
  const auto& poses = task.poses;
  const auto row_of = [](const FourBarDesign& d) {
    Row row;
    row.design = d;
    return row;
  };
  // Two dyads make a four-bar unless they share a pivot; such pairs are skipped.
  const auto add_pair = [&](const BurmesterPair& input, const BurmesterPair& output) {
    try {
      out.rows.push_back(row_of(design_from_pairs(input, output, poses[0].point)));
    } catch (const Error& e) {  // the two dyads share a pivot
      if (e.kind() != ErrorKind::InvalidModel) throw;
    }
  };
  if (poses.size() == 3) {
    out.method = task.given == PivotChoice::Fixed ? "three positions, fixed pivots chosen"
                                                  : "three positions, moving pivots chosen";
    out.rows.push_back(
        row_of(three_position_design({poses[0], poses[1], poses[2]}, task.given, task.given_a, task.given_b)));
  } else if (poses.size() == 4) {
    const BurmesterCurves curves = four_position_curves({poses[0], poses[1], poses[2], poses[3]}, task.curves);
    out.curves = curves;
    const auto dyads = spread_dyads(curves, task.samples);
    out.method = fmt::format("four positions: {} dyads along the centre-point curve, every ordered pair", dyads.size());
    if (dyads.empty())
      out.notes.push_back(fmt::format(
          "no part of the centre-point curve was traced within the window (radius {:.6g} {} about ({:.6g}, {:.6g})){}",
          curves.window_radius, task.units.length, curves.window_centre.x(), curves.window_centre.y(),
          task.curves.radius > 0 ? "; the curve passes through the poles of the poses: leave `curves: {radius}` out "
                                   "for a window that holds them"
                                 : ""));
    for (std::size_t i = 0; i < dyads.size(); ++i)
      for (std::size_t j = 0; j < dyads.size(); ++j)
        if (i != j) add_pair(dyads[i], dyads[j]);
  } else {
    const FivePositionResult r = five_position_burmester({poses[0], poses[1], poses[2], poses[3], poses[4]});
    out.method = fmt::format("five positions: {} real Burmester points, every ordered pair", r.points.size());
    for (std::size_t i = 0; i < r.points.size(); ++i)
      for (std::size_t j = 0; j < r.points.size(); ++j)
        if (i != j) add_pair(r.points[i], r.points[j]);
    if (r.complex_points > 0) out.notes.push_back(fmt::format("{} complex Burmester points", r.complex_points));
  }
  std::vector<Target> targets;
  for (const BodyPose& p : poses) targets.push_back({p.point, p.angle - poses[0].angle});
  check_rows(
      out, [&](const FourBarDesign& d) { return check_design(d, targets); }, run.control, run.threads);
  return out;
}

Outcome function(const SynthesisTask& task, const SynthesisRunOptions& run) {
  FunctionTask problem;
  const Law& law = *task.function;
  problem.f = [&law](double x) { return law.value(x); };
  problem.x_start = task.x_start;
  problem.x_end = task.x_end;
  problem.input_start = task.input_from;
  problem.input_range = task.input_to - task.input_from;
  problem.output_start = task.output_from;
  problem.output_range = task.output_to - task.output_from;
  problem.frame_length = task.frame;
  std::vector<double> xs;
  if (task.chebyshev) {
    xs = chebyshev_spacing(task.x_start, task.x_end, task.precision_points);
  } else {
    for (int i = 0; i < task.precision_points; ++i)
      xs.push_back(task.x_start + (task.x_end - task.x_start) * i / (task.precision_points - 1));
  }
  const FunctionDesign fd = freudenstein_design(problem, xs);

  const std::vector<RotationTarget> targets = rotation_targets(problem, xs);
  // The input angle the task asks for at x.
  const auto phi = [&](double x) {
    return task.input_from + (x - task.x_start) / (task.x_end - task.x_start) * (task.input_to - task.input_from);
  };

  Outcome out;
  out.angle_errors = true;
  out.method = fmt::format("Freudenstein, {} {} precision points{}", xs.size(),
                           task.chebyshev ? "Chebyshev" : "evenly spaced", xs.size() > 3 ? " (least squares)" : "");
  Row row;
  row.design = fd.design;
  row.structural_error = std::abs(fd.worst.angle);
  out.rows.push_back(row);
  out.notes.push_back(fmt::format("structural error: the output is off by up to {:.3g} {} ({:.3g} in y) at x = {:.6g}",
                                  std::abs(fd.worst.angle) / task.units.angle_scale, task.units.angle,
                                  std::abs(fd.worst.value), fd.worst.x));
  check_rows(
      out, [&](const FourBarDesign& d) { return check_design(d, targets); }, run.control, run.threads);
  // Over the whole range of x, when the linkage gets there.
  // In the task's input angles (the design's input angle offset included).
  const double theta0 =
      std::atan2(fd.design.moving_a.y() - fd.design.ground_a.y(), fd.design.moving_a.x() - fd.design.ground_a.x()) +
      fd.design.input_angle_offset;
  if (fd.whole_range) {
    const double from = theta0 + phi(task.x_start) - phi(xs[0]), to = theta0 + phi(task.x_end) - phi(xs[0]);
    out.rows[0].motion = InputMotion{
        from, to, std::max(2, static_cast<int>(std::ceil(std::abs(to - from) * 180 / std::numbers::pi)) + 1)};
    // The linkage works over the whole range, not only between the precision points.
    out.rows[0].check.min_transmission = min_transmission_angle(fd.design, from, to);
  } else {
    out.notes.push_back(fmt::format(
        "the linkage does not reach the whole range of x on its branch (it fails at x = {:.6g})", fd.fails_at_x));
  }
  return out;
}

// Best fit through many points: the distinct local optima, each checked like a five-point
// design (the targets, in order, on one branch), defect-free ones first, then by RMS deviation.
Outcome path(const SynthesisTask& task, const SynthesisRunOptions& run) {
  PathFitTask problem;
  problem.targets = task.points;
  problem.constraints = task.constraints;
  PathFitOptions options;
  options.seed = run.seed;
  options.nine_point_subsets = task.nine_point_starts;
  // A nine-point subset is a whole nine-point solve (seconds to a minute): each asked for
  // brings its own share of time.
  options.time_budget = kDefaultPathFitBudget * (1 + task.nine_point_starts);
  options.stop = [&run] { return run.control.should_stop("starts", 0, 0); };
  options.progress = [&run](int done, int total) {
    if (run.control.on_progress && !run.control.on_progress(Progress{"starts", done, total}))
      run.control.token.cancel();
  };
  const PathFitResult result = fit_path(problem, options);
  run.control.checkpoint("starts", result.starts, result.starts);
  Outcome out;
  out.method = fmt::format("Levenberg-Marquardt fit to {} points from {} starts", task.points.size(), result.starts);
  out.ranked = true;
  for (const PathFit& fit : result.fits) {
    Row row;
    row.design = fit.design;
    row.rms_error = fit.rms_deviation;
    row.fit_max_error = fit.max_deviation;
    out.rows.push_back(row);
  }
  std::vector<Target> targets;
  for (const Eigen::Vector2d& p : task.points) targets.push_back({p, std::nullopt});
  check_rows(
      out, [&](const FourBarDesign& d) { return check_design(d, targets); }, run.control, run.threads);
  // The engine's deviations, when it reached every target, are the ones listed.
  for (Row& row : out.rows) {
    if (row.check.unreached() || row.check.targets.empty()) continue;
    double sum = 0;
    for (const TargetCheck& t : row.check.targets) sum += t.error * t.error;
    row.rms_error = std::sqrt(sum / static_cast<double>(row.check.targets.size()));
  }
  std::stable_sort(out.rows.begin(), out.rows.end(), [](const Row& x, const Row& y) {
    if (x.check.defect_free() != y.check.defect_free()) return x.check.defect_free();
    return x.rms_error < y.rms_error;
  });
  out.notes.push_back(fmt::format("starts: {}; {} coupler-point evaluations", fmt::join(result.start_counts, ", "),
                                  result.evaluations));
  if (result.budget_spent)
    out.notes.push_back(
        fmt::format("the fit stopped at its time budget of {:g} s after {} starts (the solves and fits "
                    "not yet run were skipped): the designs listed are the best found by then",
                    options.time_budget, result.starts));
  if (result.rejected > 0)
    out.notes.push_back(fmt::format("{} local {} a constraint and {} not listed", result.rejected,
                                    result.rejected == 1 ? "optimum broke" : "optima broke",
                                    result.rejected == 1 ? "is" : "are"));
  return out;
}

}  // namespace

SynthesisOutcome run_synthesis(const SynthesisTask& task, const SynthesisRunOptions& options) {
  options.control.checkpoint("paths", 0, 0);
  try {
    switch (task.kind) {
      case SynthesisKind::FivePoint: return five_point(task, options);
      case SynthesisKind::Burmester: return burmester(task, options);
      case SynthesisKind::Function: return function(task, options);
      case SynthesisKind::NinePoint: return nine_point(task, options);
      case SynthesisKind::Path: return path(task, options);
    }
  } catch (const Error& e) {  // the solvers' complaints about the task's data, placed at the task
    if (e.kind() != ErrorKind::InvalidModel || !e.file().empty()) throw;
    throw Error(ErrorKind::InvalidModel, e.message(), {}, task.file, task.where);
  }
  return {};
}

// The rows to show, best first: real defect-free ones, or with --all every real one, then
// the complex ones.
std::vector<int> shown_rows(const SynthesisOutcome& out, bool all, int top) {
  std::vector<DesignCheck> checks;
  std::vector<int> real;
  for (std::size_t i = 0; i < out.rows.size(); ++i)
    if (out.rows[i].real) {
      real.push_back(static_cast<int>(i));
      checks.push_back(out.rows[i].check);
    }
  std::vector<int> order = rank_designs(checks);
  if (out.ranked)
    std::sort(order.begin(), order.end(), [&](int i, int j) {
      if (checks[i].defect_free() != checks[j].defect_free()) return checks[i].defect_free();
      return i < j;
    });
  std::vector<int> shown;
  for (int k : order)
    if (all || checks[k].defect_free()) shown.push_back(real[k]);
  if (all)
    for (std::size_t i = 0; i < out.rows.size(); ++i)
      if (!out.rows[i].real) shown.push_back(static_cast<int>(i));
  if (top > 0 && static_cast<int>(shown.size()) > top) shown.resize(top);
  return shown;
}

}  // namespace nbar::synthesis
