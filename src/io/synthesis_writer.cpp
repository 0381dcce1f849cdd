#include "nbar/io/synthesis_writer.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "json_text.hpp"
#include "nbar/io/model_export.hpp"
#include "nbar/io/synthesis_task.hpp"
#include "nbar/model/file_errors.hpp"
#include "nbar/render/canvas.hpp"
#include "nbar/render/plot.hpp"

namespace nbar::io {

namespace {

namespace fs = std::filesystem;
using synthesis::DesignCheck;
using synthesis::SynthesisOutcome;
using synthesis::SynthesisTask;
using Outcome = synthesis::SynthesisOutcome;
using Row = synthesis::DesignRow;

std::string grashof_name(const DesignCheck& c) { return nbar::grashof_name(c.grashof.kind, c.input_turns_fully); }

}  // namespace

std::string design_file_name(int rank) { return fmt::format("design-{:02}.yaml", rank); }

void write_synthesis_table(std::ostream& os, const SynthesisTask& task, const Outcome& out,
                           const SynthesisListing& args) {
  const std::vector<int>& shown = args.shown;
  int real = 0, clean = 0;
  for (const Row& r : out.rows) {
    real += r.real;
    clean += r.real && r.check.defect_free();
  }
  const double to_angle = 1.0 / task.units.angle_scale;
  const std::string error_unit = out.angle_errors ? task.units.angle : task.units.length;
  os << fmt::format("{} task{}: {}\n", synthesis::to_string(task.kind), task.name.empty() ? "" : " '" + task.name + "'",
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
  // Path fits list their RMS deviation beside the largest.
  const bool rms = std::any_of(out.rows.begin(), out.rows.end(), [](const Row& r) { return r.rms_error.has_value(); });
  const std::string rms_head = rms ? fmt::format(" {:>9}", "rms") : "";
  os << fmt::format("{:>4}  {:<14} {:>11} {:>11} {:>11} {:>11}  {:>8}  {:<22} {:>9}{}\n", "rank", "Grashof", "frame",
                    "input", "coupler", "output", "mu min", "defects", "error", rms_head);
  os << fmt::format("{:>4}  {:<14} {:>11} {:>11} {:>11} {:>11}  {:>8}  {:<22} {:>9}{}\n", "", "",
                    "(" + task.units.length + ")", "", "", "", "(" + task.units.angle + ")", "", "(" + error_unit + ")",
                    rms ? fmt::format(" {:>9}", "(" + error_unit + ")") : "");
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
    os << fmt::format("{:>4}  {:<14} {:>11.6g} {:>11.6g} {:>11.6g} {:>11.6g}  {:>8.4g}  {:<22} {:>9.2g}{}\n", rank,
                      c.invalid.empty() ? grashof_name(c) : "invalid", c.frame, c.input, c.coupler, c.output,
                      c.min_transmission * to_angle, synthesis::describe_defects(c), error,
                      rms ? fmt::format(" {:>9.2g}", r.rms_error.value_or(NAN)) : "");
  }
  if (!args.export_dir.empty()) os << fmt::format("exported to {}/design-01.yaml ...\n", args.export_dir);
}

std::string synthesis_json(const SynthesisTask& task, const Outcome& out, const SynthesisListing& args) {
  const std::vector<int>& shown = args.shown;
  const double to_angle = 1.0 / task.units.angle_scale;
  const auto point = [](const Eigen::Vector2d& p) { return nlohmann::ordered_json::array({p.x(), p.y()}); };
  nlohmann::ordered_json j;
  j["task"] = synthesis::to_string(task.kind);
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
      if (r.rms_error) d["rms_error"] = *r.rms_error;
      if (r.fit_max_error) d["fit_max_error"] = *r.fit_max_error;
      d["targets"] = nlohmann::ordered_json::array();
      for (const synthesis::TargetCheck& t : c.targets)
        d["targets"].push_back({{"input_angle", t.input_angle * to_angle},
                                {"branch", t.branch},
                                {"on_branch", t.on_branch},
                                {"reached", t.reached},
                                {"error", std::isfinite(t.error) ? nlohmann::ordered_json(t.error * error_scale)
                                                                 : nlohmann::ordered_json()}});
      if (!args.export_dir.empty()) d["file"] = (fs::path(args.export_dir) / design_file_name(rank)).string();
    }
    j["designs"].push_back(d);
  }
  return json_text(j, 2) + '\n';
}

std::string design_model_yaml(const SynthesisTask& task, const Outcome& out, int row, int rank) {
  const Row& r = out.rows.at(static_cast<std::size_t>(row));
  if (!r.real || !r.check.invalid.empty())
    throw Error(ErrorKind::BadInput, "design " + std::to_string(rank) + " is not a real four-bar: it has no model");
  const std::string title = task.name.empty() ? fs::path(task.file).stem().string() : task.name;
  std::vector<std::string> comments{
      fmt::format("Design {} of nbar synth {} {}", rank, synthesis::to_string(task.kind), task.file)};
  for (std::string& line : io::design_comments(r.check, task.units)) comments.push_back(std::move(line));
  for (std::string& line : io::design_angle_comments(r.design)) comments.push_back(std::move(line));
  const Model model = synthesis::make_fourbar_model(r.design, fmt::format("{}, design {}", title, rank), task.units,
                                                    r.motion.value_or(r.check.motion));
  std::ostringstream text;
  io::write_model_yaml(text, model, comments);
  return text.str();
}

std::vector<std::pair<std::string, std::string>> design_files(const SynthesisTask& task, const Outcome& out,
                                                              const SynthesisListing& args) {
  std::vector<std::pair<std::string, std::string>> files;
  int rank = 0;
  for (int i : args.shown) {
    const Row& r = out.rows[i];
    ++rank;
    if (!r.real || !r.check.invalid.empty()) continue;
    files.emplace_back(design_file_name(rank), design_model_yaml(task, out, i, rank));
  }
  return files;
}

// DIR/design-01.yaml... for the real designs shown, in rank order.
void export_designs(const SynthesisTask& task, const Outcome& out, const SynthesisListing& args) {
  std::error_code error;
  fs::create_directories(args.export_dir, error);
  if (error) throw Error(ErrorKind::BadInput, "--export " + args.export_dir + ": " + error.message());
  for (const auto& [name, text] : design_files(task, out, args)) {
    const fs::path path = fs::path(args.export_dir) / name;
    std::ofstream file(path);
    file << text;
    if (file) file.close();  // a full disk fails here, after the text was taken
    if (!file) throw Error(ErrorKind::BadInput, cannot_write_message(path.string()));
  }
}

namespace {

// Calls visit(which, branch, line) on every line of the centre-point curve, then of the
// circle-point curve.
template <typename Visit>
void each_burmester_line(const synthesis::BurmesterCurves& curves, const Visit& visit) {
  for (const char* which : {"centre", "circle"}) {
    const auto& lines = std::string(which) == "centre" ? curves.centre_curve : curves.circle_curve;
    for (std::size_t b = 0; b < lines.size(); ++b) visit(which, static_cast<int>(b), lines[b]);
  }
}

void write_burmester_json(std::ostream& out, const SynthesisTask& task, const synthesis::BurmesterCurves& curves) {
  nlohmann::ordered_json j;
  j["units"] = task.units.length;
  j["window"] = {{"centre", {curves.window_centre.x(), curves.window_centre.y()}}, {"radius", curves.window_radius}};
  for (const char* which : {"centre_curve", "circle_curve"}) j[which] = nlohmann::ordered_json::array();
  each_burmester_line(curves, [&](const char* which, int, const std::vector<synthesis::BurmesterPair>& line) {
    nlohmann::ordered_json samples = nlohmann::ordered_json::array();
    for (const auto& s : line)
      samples.push_back({{"centre", {s.centre.x(), s.centre.y()}}, {"circle", {s.circle.x(), s.circle.y()}}});
    j[std::string(which) + "_curve"].push_back(samples);
  });
  out << json_text(j, 2) << '\n';
}

// Both curves at one scale, on a grid with labelled axes in the task's length unit, so that
// pivots can be read off: centre points in blue, circle points in orange, each pose's
// reference point as a dot with its number and a tick along its angle.
void write_burmester_svg(std::ostream& out, const SynthesisTask& task, const synthesis::BurmesterCurves& curves) {
  constexpr int kSize = 760;
  constexpr double kMargin = 64;  // room for the tick labels
  const Eigen::Vector2d half = Eigen::Vector2d::Constant(curves.window_radius);
  const Eigen::Vector2d lo = curves.window_centre - half, hi = curves.window_centre + half;
  const render::View view(lo, hi, kSize, kSize, kMargin);
  render::SvgCanvas canvas(kSize, kSize);
  const render::Colour ink = render::Colour::rgb(0x000000), grid = render::Colour::rgb(0xdddddd);
  const Eigen::Vector2d corner_lo = view.to_pixels(lo), corner_hi = view.to_pixels(hi);  // y grows down
  canvas.begin_group("grid", "grid");
  const std::vector<double> all_x = render::nice_ticks(lo.x(), hi.x(), 8),
                            all_y = render::nice_ticks(lo.y(), hi.y(), 8);
  std::vector<double> xs, ys;
  for (double t : all_x)
    if (t >= lo.x() - 1e-9 * curves.window_radius && t <= hi.x() + 1e-9 * curves.window_radius) xs.push_back(t);
  for (double t : all_y)
    if (t >= lo.y() - 1e-9 * curves.window_radius && t <= hi.y() + 1e-9 * curves.window_radius) ys.push_back(t);
  const std::vector<std::string> x_labels = render::format_ticks(xs), y_labels = render::format_ticks(ys);
  for (std::size_t i = 0; i < xs.size(); ++i) {
    const double px = view.to_pixels({xs[i], lo.y()}).x();
    canvas.polyline({{px, corner_lo.y()}, {px, corner_hi.y()}}, render::Stroke{grid, 1.0, {}});
    canvas.text({px, corner_lo.y() + 16}, x_labels[i], 11, render::Anchor::Middle, ink);
  }
  for (std::size_t i = 0; i < ys.size(); ++i) {
    const double py = view.to_pixels({lo.x(), ys[i]}).y();
    canvas.polyline({{corner_lo.x(), py}, {corner_hi.x(), py}}, render::Stroke{grid, 1.0, {}});
    canvas.text({corner_lo.x() - 6, py + 4}, y_labels[i], 11, render::Anchor::End, ink);
  }
  canvas.end_group();
  canvas.begin_group("axes", "axes");
  canvas.polyline({{corner_lo.x(), corner_lo.y()},
                   {corner_hi.x(), corner_lo.y()},
                   {corner_hi.x(), corner_hi.y()},
                   {corner_lo.x(), corner_hi.y()},
                   {corner_lo.x(), corner_lo.y()}},
                  render::Stroke{ink, 1.0, {}});
  canvas.text({0.5 * (corner_lo.x() + corner_hi.x()), corner_lo.y() + 36}, "x (" + task.units.length + ")", 12,
              render::Anchor::Middle, ink);
  canvas.text({corner_lo.x() - 6, corner_hi.y() - 10}, "y (" + task.units.length + ")", 12, render::Anchor::Middle,
              ink);
  canvas.end_group();
  canvas.begin_group("curves", "curves");
  each_burmester_line(curves, [&](const char* which, int, const std::vector<synthesis::BurmesterPair>& line) {
    const bool centre = std::string(which) == "centre";
    std::vector<Eigen::Vector2d> points;
    for (const auto& s : line) points.push_back(view.to_pixels(centre ? s.centre : s.circle));
    canvas.polyline(points, render::Stroke{render::Colour::rgb(centre ? 0x0072b2 : 0xe69f00), 1.5, {}});
  });
  canvas.end_group();
  canvas.begin_group("poses", "poses");
  for (std::size_t i = 0; i < task.poses.size(); ++i) {
    const synthesis::BodyPose& p = task.poses[i];
    const Eigen::Vector2d at = view.to_pixels(p.point);
    const Eigen::Vector2d along(std::cos(p.angle), -std::sin(p.angle));  // pixels: y down
    canvas.polyline({at, at + 22.0 * along}, render::Stroke{ink, 1.5, {}});
    canvas.circle(at, 3.0, render::Paint{ink, std::nullopt});
    canvas.text(at - 10.0 * along + Eigen::Vector2d(0, 4), std::to_string(i + 1), 12, render::Anchor::Middle, ink);
  }
  canvas.end_group();
  canvas.text({kMargin, 20},
              "centre-point curve (blue), circle-point curve (orange), poses 1-" + std::to_string(task.poses.size()) +
                  " with their angles",
              13, render::Anchor::Start, ink);
  out << canvas.document();
}

void write_burmester_csv(std::ostream& out, const synthesis::BurmesterCurves& curves) {
  out << "curve,branch,centre_x,centre_y,circle_x,circle_y\n";
  each_burmester_line(curves, [&](const char* which, int branch, const std::vector<synthesis::BurmesterPair>& line) {
    for (const auto& s : line)
      out << fmt::format("{},{},{},{},{},{}\n", which, branch, s.centre.x(), s.centre.y(), s.circle.x(), s.circle.y());
  });
}

}  // namespace

// The Burmester curves as CSV, JSON or an SVG picture.
void write_burmester_curves(const std::string& path, const SynthesisTask& task,
                            const synthesis::BurmesterCurves& curves) {
  const std::string ext = fs::path(path).extension().string();
  std::ofstream out(path);
  if (!out) throw Error(ErrorKind::BadInput, cannot_write_message(path));
  if (ext == ".json") {
    write_burmester_json(out, task, curves);
  } else if (ext == ".svg") {
    write_burmester_svg(out, task, curves);
  } else {
    write_burmester_csv(out, curves);
  }
  if (!out) throw Error(ErrorKind::BadInput, cannot_write_message(path));
}

}  // namespace nbar::io
