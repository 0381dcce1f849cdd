// nbar synth: four-bars from a task file (five-point path generation, Burmester motion
// generation, Freudenstein function generation), checked with the kinematics engine, ranked,
// printed as a table or JSON and exported as model files. docs/synthesis.md.
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <numbers>

#include "commands.hpp"
#include "common.hpp"
#include "nbar/io/model_export.hpp"
#include "nbar/io/synthesis_task.hpp"
#include "nbar/render/canvas.hpp"
#include "nbar/synthesis/burmester.hpp"
#include "nbar/synthesis/five_point.hpp"
#include "nbar/synthesis/fourbar_design.hpp"
#include "nbar/synthesis/function_generation.hpp"

namespace nbar::cli {

namespace {

namespace fs = std::filesystem;
using io::SynthesisKind;
using io::SynthesisTask;
using synthesis::DesignCheck;
using synthesis::FourBarDesign;

// A task key given as an option instead of in a file: --input-range 90,150.
struct TaskOption {
  const char* key;   // in the task file
  const char* flag;  // on the command line
  const char* help;
  std::string value;
};

struct SynthArgs {
  std::string kind, file, format = "table", output, export_dir, curves;
  std::vector<TaskOption> task_options{
      {"name", "--name", "the task's title (names the exported models)", {}},
      {"units", "--units", "e.g. '{length: mm, angle: deg}'", {}},
      {"pivots", "--pivots", "five-point: the fixed pivots, e.g. '{a: [0, 0], b: [1, 0]}'", {}},
      {"points", "--points", "five-point: the 5 points '[[x, y], ...]'; function: the number of precision points", {}},
      {"poses", "--poses", "burmester: '[{point: [x, y], angle: a}, ...]'", {}},
      {"fixed_pivots", "--fixed-pivots", "burmester, 3 poses: '{a: [x, y], b: [x, y]}'", {}},
      {"moving_pivots", "--moving-pivots", "burmester, 3 poses: '{a: [x, y], b: [x, y]}'", {}},
      {"curves", "--window", "burmester, 4 poses: where the curves are traced, '{radius: R, step: S}'", {}},
      {"samples", "--samples", "burmester, 4 poses: dyads taken along the curves", {}},
      {"function", "--function", "function: y = f(x), e.g. 'log10(x)'", {}},
      {"x", "--x", "function: the range of x, e.g. 1,2", {}},
      {"input_range", "--input-range", "function: input angles at the ends of the range, e.g. 90,150", {}},
      {"output_range", "--output-range", "function: output angles at f of the ends, e.g. 60,120", {}},
      {"spacing", "--spacing", "function: chebyshev or even", {}},
      {"frame", "--frame", "function: length of the frame link", {}},
  };
  bool all = false;
  int top = 20;
  unsigned threads = 0;
  std::uint64_t seed = 1;
};

// A bar on standard error, only when it is a terminal; callbacks may come from worker threads.
class Progress {
 public:
  Progress() : enabled_(::isatty(STDERR_FILENO) == 1) {}
  ~Progress() { clear(); }
  void update(int done, int total, const char* what) {
    if (!enabled_ || total <= 0) return;
    const std::lock_guard lock(mutex_);
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(static_cast<long>(kWidth) * std::min(done, total) / total);
    if (filled == last_filled_ && done != total) return;
    last_filled_ = filled;
    std::cerr << fmt::format("\r{:<10} [{}{}] {}/{}", what, std::string(filled, '#'), std::string(kWidth - filled, ' '),
                             done, total)
              << std::flush;
    shown_ = true;
  }
  void clear() {
    const std::lock_guard lock(mutex_);
    if (shown_) std::cerr << '\r' << std::string(70, ' ') << '\r' << std::flush;
    shown_ = false;
    last_filled_ = -1;
  }

 private:
  bool enabled_;
  bool shown_ = false;
  int last_filled_ = -1;
  std::mutex mutex_;
};

// One solution: a real linkage with its check, or (five-point, --all) a complex one.
struct Row {
  bool real = true;
  FourBarDesign design;
  DesignCheck check;
  std::optional<synthesis::InputMotion> motion;  // for the exported model, instead of check.motion
  double solver_residual = 0;
  double solver_condition = 0;  // five-point: the homotopy's condition number at the endpoint
  std::optional<double> structural_error;  // function generation: worst output error over the range (rad)
};

struct Outcome {
  std::string method;
  std::vector<Row> rows;
  std::vector<std::string> notes;
  bool angle_errors = false;  // errors are output angles (function generation), not lengths
};

// ---- solving each kind of task ----

void check_rows(Outcome& out, const std::function<DesignCheck(const FourBarDesign&)>& check, Progress& progress) {
  int done = 0;
  const int total = static_cast<int>(out.rows.size());
  for (Row& row : out.rows) {
    if (row.real) row.check = check(row.design);
    progress.update(++done, total, "checking");
  }
  progress.clear();
}

Outcome five_point(const SynthesisTask& task, const SynthArgs& args, Progress& progress) {
  synthesis::FivePointTask problem;
  problem.pivot_a = task.pivot_a;
  problem.pivot_b = task.pivot_b;
  std::copy(task.points.begin(), task.points.end(), problem.points.begin());
  synthesis::SolverOptions options;
  options.threads = args.threads;
  options.seed = args.seed;
  options.progress = [&](int done, int total) { progress.update(done, total, "paths"); };
  const synthesis::FivePointResult result = synthesis::solve_five_point(problem, options);
  progress.clear();
  Outcome out;
  out.method = result.method;
  for (const synthesis::FivePointSolution& s : result.solutions) {
    Row row;
    row.real = s.real;
    row.design = s.design;
    row.solver_residual = s.residual;
    row.solver_condition = s.condition;
    out.rows.push_back(row);
  }
  std::vector<synthesis::Target> targets;
  for (const Eigen::Vector2d& p : task.points) targets.push_back({p, std::nullopt});
  check_rows(
      out, [&](const FourBarDesign& d) { return synthesis::check_design(d, targets); }, progress);
  if (result.failed_paths > 0)
    out.notes.push_back(fmt::format("{} of {} paths failed", result.failed_paths, result.paths));
  return out;
}

// Dyads spread evenly (by arc length) along the centre-point curves.
std::vector<synthesis::BurmesterPair> spread_dyads(const synthesis::BurmesterCurves& curves, int count) {
  std::vector<synthesis::BurmesterPair> all;
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
  std::vector<synthesis::BurmesterPair> out;
  for (int i = 0; i < count; ++i) {
    const double wanted = length * (i + 0.5) / count;
    const auto k = std::lower_bound(at.begin(), at.end(), wanted) - at.begin();
    out.push_back(all[std::min<std::size_t>(k, all.size() - 1)]);
  }
  return out;
}

// The Burmester curves as CSV, JSON or an SVG picture.
void write_curves(const std::string& path, const SynthesisTask& task, const synthesis::BurmesterCurves& curves) {
  const std::string ext = fs::path(path).extension().string();
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path);
  const auto each = [&](const auto& visit) {
    for (const char* which : {"centre", "circle"}) {
      const auto& lines = std::string(which) == "centre" ? curves.centre_curve : curves.circle_curve;
      for (std::size_t b = 0; b < lines.size(); ++b) visit(which, static_cast<int>(b), lines[b]);
    }
  };
  if (ext == ".json") {
    nlohmann::ordered_json j;
    j["units"] = task.units.length;
    j["window"] = {{"centre", {curves.window_centre.x(), curves.window_centre.y()}}, {"radius", curves.window_radius}};
    for (const char* which : {"centre_curve", "circle_curve"}) j[which] = nlohmann::ordered_json::array();
    each([&](const char* which, int, const std::vector<synthesis::BurmesterPair>& line) {
      nlohmann::ordered_json samples = nlohmann::ordered_json::array();
      for (const auto& s : line)
        samples.push_back({{"centre", {s.centre.x(), s.centre.y()}}, {"circle", {s.circle.x(), s.circle.y()}}});
      j[std::string(which) + "_curve"].push_back(samples);
    });
    out << j.dump(2) << '\n';
  } else if (ext == ".svg") {
    // Both curves at one scale: centre points in blue, circle points in orange, the poses'
    // reference points as dots.
    constexpr int kSize = 700;
    const Eigen::Vector2d half = Eigen::Vector2d::Constant(curves.window_radius);
    const render::View view(curves.window_centre - half, curves.window_centre + half, kSize, kSize, 30);
    render::SvgCanvas canvas(kSize, kSize);
    each([&](const char* which, int, const std::vector<synthesis::BurmesterPair>& line) {
      const bool centre = std::string(which) == "centre";
      std::vector<Eigen::Vector2d> points;
      for (const auto& s : line) points.push_back(view.to_pixels(centre ? s.centre : s.circle));
      canvas.polyline(points, render::Stroke{render::Color::rgb(centre ? 0x0072b2 : 0xe69f00), 1.5, {}});
    });
    for (const synthesis::BodyPose& p : task.poses)
      canvas.circle(view.to_pixels(p.point), 3.0, render::Paint{render::Color::rgb(0x000000), std::nullopt});
    canvas.text({30, 20}, "centre-point curve (blue), circle-point curve (orange), poses (dots)", 13,
                render::Anchor::Start, render::Color::rgb(0x000000));
    out << canvas.document();
  } else {
    out << "curve,branch,centre_x,centre_y,circle_x,circle_y\n";
    each([&](const char* which, int branch, const std::vector<synthesis::BurmesterPair>& line) {
      for (const auto& s : line)
        out << fmt::format("{},{},{},{},{},{}\n", which, branch, s.centre.x(), s.centre.y(), s.circle.x(),
                           s.circle.y());
    });
  }
  if (!out) throw std::runtime_error("cannot write " + path);
}

Outcome burmester(const SynthesisTask& task, const SynthArgs& args, Progress& progress) {
  Outcome out;
  const auto& poses = task.poses;
  const auto row_of = [](const FourBarDesign& d) {
    Row row;
    row.design = d;
    return row;
  };
  // Two dyads make a four-bar unless they share a pivot; such pairs are skipped.
  const auto add_pair = [&](const synthesis::BurmesterPair& input, const synthesis::BurmesterPair& output) {
    try {
      out.rows.push_back(row_of(synthesis::design_from_pairs(input, output, poses[0].point)));
    } catch (const std::invalid_argument&) {
    }
  };
  if (poses.size() == 3) {
    out.method = task.given == synthesis::PivotChoice::Fixed ? "three positions, fixed pivots chosen"
                                                             : "three positions, moving pivots chosen";
    out.rows.push_back(row_of(
        synthesis::three_position_design({poses[0], poses[1], poses[2]}, task.given, task.given_a, task.given_b)));
  } else if (poses.size() == 4) {
    const synthesis::BurmesterCurves curves =
        synthesis::four_position_curves({poses[0], poses[1], poses[2], poses[3]}, task.curves);
    if (!args.curves.empty()) write_curves(args.curves, task, curves);
    const auto dyads = spread_dyads(curves, task.samples);
    out.method = fmt::format("four positions: {} dyads along the centre-point curve, every ordered pair", dyads.size());
    for (std::size_t i = 0; i < dyads.size(); ++i)
      for (std::size_t j = 0; j < dyads.size(); ++j)
        if (i != j) add_pair(dyads[i], dyads[j]);
  } else {
    const synthesis::FivePositionResult r =
        synthesis::five_position_burmester({poses[0], poses[1], poses[2], poses[3], poses[4]});
    out.method = fmt::format("five positions: {} real Burmester points, every ordered pair", r.points.size());
    for (std::size_t i = 0; i < r.points.size(); ++i)
      for (std::size_t j = 0; j < r.points.size(); ++j)
        if (i != j) add_pair(r.points[i], r.points[j]);
    if (r.complex_points > 0) out.notes.push_back(fmt::format("{} complex Burmester points", r.complex_points));
  }
  std::vector<synthesis::Target> targets;
  for (const synthesis::BodyPose& p : poses) targets.push_back({p.point, p.angle - poses[0].angle});
  check_rows(
      out, [&](const FourBarDesign& d) { return synthesis::check_design(d, targets); }, progress);
  return out;
}

Outcome function(const SynthesisTask& task, Progress& progress) {
  synthesis::FunctionTask problem;
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
    xs = synthesis::chebyshev_spacing(task.x_start, task.x_end, task.precision_points);
  } else {
    for (int i = 0; i < task.precision_points; ++i)
      xs.push_back(task.x_start + (task.x_end - task.x_start) * i / (task.precision_points - 1));
  }
  const synthesis::FunctionDesign fd = synthesis::freudenstein_design(problem, xs);

  const std::vector<synthesis::RotationTarget> targets = synthesis::rotation_targets(problem, xs);
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
      out, [&](const FourBarDesign& d) { return synthesis::check_design(d, targets); }, progress);
  // Over the whole range of x, when the linkage gets there.
  const double theta0 =
      std::atan2(fd.design.moving_a.y() - fd.design.ground_a.y(), fd.design.moving_a.x() - fd.design.ground_a.x());
  if (fd.whole_range) {
    const double from = theta0 + phi(task.x_start) - phi(xs[0]), to = theta0 + phi(task.x_end) - phi(xs[0]);
    out.rows[0].motion = synthesis::InputMotion{
        from, to, std::max(2, static_cast<int>(std::ceil(std::abs(to - from) * 180 / std::numbers::pi)) + 1)};
    // The linkage works over the whole range, not only between the precision points.
    out.rows[0].check.min_transmission = synthesis::min_transmission_angle(fd.design, from, to);
  } else {
    out.notes.push_back(fmt::format(
        "the linkage does not reach the whole range of x on its branch (it fails at x = {:.6g})", fd.fails_at_x));
  }
  return out;
}

// ---- output ----

std::string grashof_name(const DesignCheck& c) {
  switch (c.grashof.kind) {
    case GrashofClass::CrankRocker:
      return c.input_turns_fully ? "crank-rocker" : "rocker-crank";
    case GrashofClass::DoubleCrank:
      return "double-crank";
    case GrashofClass::DoubleRocker:
      return "double-rocker";
    case GrashofClass::TripleRocker:
      return "triple-rocker";
    case GrashofClass::ChangePoint:
      return "change-point";
  }
  return "";
}

// The rows to show, best first: real defect-free ones, or with --all every real one, then
// the complex ones.
std::vector<int> shown_rows(const Outcome& out, bool all, int top) {
  std::vector<DesignCheck> checks;
  std::vector<int> real;
  for (std::size_t i = 0; i < out.rows.size(); ++i)
    if (out.rows[i].real) {
      real.push_back(static_cast<int>(i));
      checks.push_back(out.rows[i].check);
    }
  std::vector<int> shown;
  for (int k : synthesis::rank_designs(checks))
    if (all || checks[k].defect_free()) shown.push_back(real[k]);
  if (all)
    for (std::size_t i = 0; i < out.rows.size(); ++i)
      if (!out.rows[i].real) shown.push_back(static_cast<int>(i));
  if (top > 0 && static_cast<int>(shown.size()) > top) shown.resize(top);
  return shown;
}

std::string file_name(int rank) { return fmt::format("design-{:02}.yaml", rank); }

void print_table(std::ostream& os, const SynthesisTask& task, const Outcome& out, const std::vector<int>& shown,
                 const SynthArgs& args) {
  int real = 0, clean = 0;
  for (const Row& r : out.rows) {
    real += r.real;
    clean += r.real && r.check.defect_free();
  }
  const double to_angle = 1.0 / task.units.angle_scale;
  const std::string error_unit = out.angle_errors ? task.units.angle : task.units.length;
  os << fmt::format("{} task{}: {}\n", io::to_string(task.kind), task.name.empty() ? "" : " '" + task.name + "'",
                    out.method);
  os << fmt::format("{} solution{}, {} real, {} without defects\n", out.rows.size(), out.rows.size() == 1 ? "" : "s",
                    real, clean);
  for (const std::string& n : out.notes) os << "note: " << n << '\n';
  if (shown.empty()) {
    os << (real > 0 ? "no design without defects; --all lists them all\n" : "no real design\n");
    return;
  }
  const int listable = args.all ? static_cast<int>(out.rows.size()) : clean;
  if (static_cast<int>(shown.size()) < listable)
    os << fmt::format("the best {} of {} (--top N for more)\n", shown.size(), listable);
  os << fmt::format("{:>4}  {:<14} {:>11} {:>11} {:>11} {:>11}  {:>8}  {:<22} {:>9}\n", "rank", "Grashof", "frame",
                    "input", "coupler", "output", "mu min", "defects", "error");
  os << fmt::format("{:>4}  {:<14} {:>11} {:>11} {:>11} {:>11}  {:>8}  {:<22} {:>9}\n", "", "",
                    "(" + task.units.length + ")", "", "", "", "(" + task.units.angle + ")", "",
                    "(" + error_unit + ")");
  int rank = 0;
  for (int i : shown) {
    const Row& r = out.rows[i];
    ++rank;
    if (!r.real) {
      os << fmt::format("{:>4}  {:<14} {:>11} {:>11} {:>11} {:>11}  {:>8}  {:<22} {:>9.2g}\n", rank, "complex", "-",
                        "-", "-", "-", "-", "-", r.solver_residual);
      continue;
    }
    const DesignCheck& c = r.check;
    const double error = out.angle_errors ? c.max_error * to_angle : c.max_error;
    os << fmt::format("{:>4}  {:<14} {:>11.6g} {:>11.6g} {:>11.6g} {:>11.6g}  {:>8.4g}  {:<22} {:>9.2g}\n", rank,
                      c.invalid.empty() ? grashof_name(c) : "invalid", c.frame, c.input, c.coupler, c.output,
                      c.min_transmission * to_angle, synthesis::describe_defects(c), error);
  }
  if (!args.export_dir.empty()) os << fmt::format("exported to {}/design-01.yaml ...\n", args.export_dir);
}

nlohmann::ordered_json to_json(const SynthesisTask& task, const Outcome& out, const std::vector<int>& shown,
                               const SynthArgs& args) {
  const double to_angle = 1.0 / task.units.angle_scale;
  const auto point = [](const Eigen::Vector2d& p) { return nlohmann::ordered_json::array({p.x(), p.y()}); };
  nlohmann::ordered_json j;
  j["task"] = io::to_string(task.kind);
  j["name"] = task.name;
  j["method"] = out.method;
  j["units"] = {{"length", task.units.length}, {"angle", task.units.angle}};
  j["error_unit"] = out.angle_errors ? task.units.angle : task.units.length;
  j["solutions"] = out.rows.size();
  j["notes"] = out.notes;
  j["designs"] = nlohmann::ordered_json::array();
  int rank = 0;
  for (int i : shown) {
    const Row& r = out.rows[i];
    nlohmann::ordered_json d;
    d["rank"] = ++rank;
    d["real"] = r.real;
    d["solver_residual"] = r.solver_residual;
    if (r.solver_condition > 0) d["solver_condition"] = r.solver_condition;
    if (r.real) {
      const DesignCheck& c = r.check;
      d["pivots"] = {{"ground_a", point(r.design.ground_a)},
                     {"ground_b", point(r.design.ground_b)},
                     {"moving_a", point(r.design.moving_a)},
                     {"moving_b", point(r.design.moving_b)},
                     {"coupler_point", point(r.design.coupler_point)}};
      d["valid"] = c.invalid.empty();
      if (!c.invalid.empty()) d["invalid"] = c.invalid;
      d["grashof"] = grashof_name(c);
      d["input_turns_fully"] = c.input_turns_fully;
      d["lengths"] = {{"frame", c.frame}, {"input", c.input}, {"coupler", c.coupler}, {"output", c.output}};
      d["min_transmission"] = c.min_transmission * to_angle;
      d["min_transmission_full"] = c.min_transmission_full * to_angle;
      d["defect_free"] = c.defect_free();
      d["defects"] = {{"circuit", c.circuit_defect},
                      {"branch", c.toggle_between},
                      {"order", c.order_defect},
                      {"unreached", c.unreached()}};
      d["direction"] = c.direction > 0 ? "counter-clockwise" : "clockwise";
      d["travel"] = c.travel * to_angle;
      const double error_scale = out.angle_errors ? to_angle : 1.0;
      d["max_error"] = c.max_error * error_scale;
      d["max_rotation_error"] = c.max_rotation_error * to_angle;
      if (r.structural_error) d["structural_error"] = *r.structural_error * to_angle;
      d["targets"] = nlohmann::ordered_json::array();
      for (const synthesis::TargetCheck& t : c.targets)
        d["targets"].push_back({{"input_angle", t.input_angle * to_angle},
                                {"branch", t.branch},
                                {"on_branch", t.on_branch},
                                {"reached", t.reached},
                                {"error", std::isfinite(t.error) ? nlohmann::ordered_json(t.error * error_scale)
                                                                 : nlohmann::ordered_json()}});
      if (!args.export_dir.empty()) d["file"] = (fs::path(args.export_dir) / file_name(rank)).string();
    }
    j["designs"].push_back(d);
  }
  return j;
}

// DIR/design-01.yaml... for the real designs shown, in rank order.
int export_designs(const SynthesisTask& task, const Outcome& out, const std::vector<int>& shown,
                   const SynthArgs& args) {
  std::error_code error;
  fs::create_directories(args.export_dir, error);
  if (error) {
    std::cerr << "error: --export " << args.export_dir << ": " << error.message() << '\n';
    return kBadUsage;
  }
  const std::string title = task.name.empty() ? fs::path(task.file).stem().string() : task.name;
  int rank = 0;
  for (int i : shown) {
    const Row& r = out.rows[i];
    ++rank;
    if (!r.real || !r.check.invalid.empty()) continue;
    std::vector<std::string> comments{
        fmt::format("Design {} of nbar synth {} {}", rank, io::to_string(task.kind), task.file)};
    for (std::string& line : io::design_comments(r.check, task.units)) comments.push_back(std::move(line));
    const Model model = synthesis::make_fourbar_model(r.design, fmt::format("{}, design {}", title, rank), task.units,
                                                      r.motion.value_or(r.check.motion));
    const fs::path path = fs::path(args.export_dir) / file_name(rank);
    std::ofstream file(path);
    io::write_model_yaml(file, model, comments);
    if (!file) {
      std::cerr << "error: cannot write " << path.string() << '\n';
      return kBadUsage;
    }
  }
  return kOk;
}

// The task options as a task file, one key a line, so that the file's checks and messages
// serve them too: a message about line k is about the option of that line.
class OptionTask {
 public:
  explicit OptionTask(const SynthArgs& args) {
    text_ = "task: " + args.kind + "\n";
    for (const TaskOption& o : args.task_options) {
      if (o.value.empty()) continue;
      std::string value = o.value;
      if (std::string(o.key) == "function" || std::string(o.key) == "name") {
        value = nlohmann::json(value).dump();  // a quoted YAML string
      } else if (value.find(',') != std::string::npos && value.front() != '[' && value.front() != '{') {
        value = "[" + value + "]";  // 1,2 for [1, 2]
      }
      lines_.push_back(&o);
      text_ += std::string(o.key) + ": " + value + "\n";
    }
  }
  bool empty() const { return lines_.empty(); }
  SynthesisTask parse() const { return io::parse_synthesis_task(text_, kFile); }
  // "--points: message", or the message when it concerns no single option.
  std::string explain(const io::ModelFileError& e) const {
    const int line = e.mark().line;
    if (e.file() != kFile) return e.what();
    if (line < 2 || line - 2 >= static_cast<int>(lines_.size())) return "task options: " + e.message();
    return std::string(lines_[line - 2]->flag) + ": " + e.message();
  }

 private:
  static constexpr const char* kFile = "<options>";
  std::string text_;
  std::vector<const TaskOption*> lines_;
};

int run_synth(const SynthArgs& args) {
  const OptionTask options(args);
  if (!options.empty() && !args.file.empty()) {
    std::cerr << "error: give a task file or task options (--points, --poses, --function...), not both\n";
    return kBadUsage;
  }
  if (options.empty() && args.file.empty()) {
    std::cerr << "error: nbar synth " << args.kind << " needs a task file (or task options); see docs/synthesis.md\n";
    return kBadUsage;
  }
  // Problems in a file are an invalid model (1); in options, bad usage (2).
  const int bad_task = options.empty() ? kInvalidModel : kBadUsage;
  SynthesisTask task;
  try {
    task = options.empty() ? io::load_synthesis_task(args.file) : options.parse();
  } catch (const io::ModelFileError& e) {
    std::cerr << "error: " << options.explain(e) << '\n';
    return bad_task;
  }
  if (io::to_string(task.kind) != args.kind) {
    std::cerr << "error: " << args.file << ": this is a " << io::to_string(task.kind) << " task: run `nbar synth "
              << io::to_string(task.kind) << " " << args.file << "`\n";
    return kBadUsage;
  }
  if (!args.curves.empty() && !(task.kind == SynthesisKind::Burmester && task.poses.size() == 4)) {
    std::cerr << "error: --curves applies to burmester tasks with 4 poses\n";
    return kBadUsage;
  }
  Progress progress;
  Outcome out;
  try {
    switch (task.kind) {
      case SynthesisKind::FivePoint:
        out = five_point(task, args, progress);
        break;
      case SynthesisKind::Burmester:
        out = burmester(task, args, progress);
        break;
      case SynthesisKind::Function:
        out = function(task, progress);
        break;
    }
  } catch (const std::invalid_argument& e) {  // the solvers' complaints about the task itself
    progress.clear();
    std::cerr << "error: " << options.explain(io::ModelFileError(task.file, task.where, e.what())) << '\n';
    return bad_task;
  } catch (const std::runtime_error& e) {  // --curves not writable
    progress.clear();
    std::cerr << "error: " << e.what() << '\n';
    return kBadUsage;
  }
  const std::vector<int> shown = shown_rows(out, args.all, args.top);

  Output output;
  if (!output.open(args.output)) return kBadUsage;
  if (!args.export_dir.empty())
    if (int code = export_designs(task, out, shown, args)) return code;
  if (args.format == "json")
    output.stream() << to_json(task, out, shown, args).dump(2) << '\n';
  else
    print_table(output.stream(), task, out, shown, args);
  output.stream().flush();
  return kOk;
}

}  // namespace

Command add_synth_command(CLI::App& app) {
  static SynthArgs args;
  CLI::App* synth = app.add_subcommand(
      "synth",
      "Synthesise four-bars from a task file: five-point path generation, Burmester motion generation or "
      "function generation; every real solution is checked for defects and ranked");
  synth->add_option("TASK", args.kind, "five-point, burmester or function")
      ->required()
      ->check(CLI::IsMember({"five-point", "burmester", "function"}));
  synth->add_option("FILE", args.file, "task file (YAML; see docs/synthesis.md), or the task options below");
  synth->add_option("--format", args.format, "table (default) or json")->check(CLI::IsMember({"table", "json"}));
  synth->add_option("-o,--output", args.output, "write the table or JSON to FILE instead of standard output");
  synth->add_option("--export", args.export_dir, "write every design listed as DIR/design-01.yaml, ... (model files)");
  synth->add_flag("--all", args.all, "also list defective designs and (five-point) complex solutions");
  synth->add_option("--top", args.top, "list (and export) at most N designs, best first; 0 for all (default 20)")
      ->check(CLI::NonNegativeNumber);
  synth->add_option("--threads", args.threads, "threads for path tracking (default: all)");
  synth->add_option("--seed", args.seed, "random seed of the homotopy (default 1)");
  synth->add_option("--curves", args.curves,
                    "burmester, 4 poses: write the centre- and circle-point curves to FILE (.csv, .json or .svg)");
  for (TaskOption& o : args.task_options) synth->add_option(o.flag, o.value, o.help)->group("Task (instead of a file)");
  return {synth, [] { return run_synth(args); }};
}

}  // namespace nbar::cli
