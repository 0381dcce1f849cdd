// nbar explain: the method, step by step, at one sample of the sweep (Gruebler count, q, Phi,
// Phi_q, Newton's iterations, the velocity and acceleration systems, the instant centres), as
// text, Markdown, LaTeX or JSON, and optionally a drawing with the instant centres marked.
#include <algorithm>
#include <fstream>

#include "commands.hpp"
#include "common.hpp"
#include "nbar/analysis/explain.hpp"
#include "nbar/io/explain_writer.hpp"
#include "nbar/render/drawing.hpp"
#include "nbar/render/image_canvas.hpp"

namespace nbar::cli {

namespace {

struct ExplainArgs {
  std::string model, output, format = "text", draw;
  int step = 0;
  std::optional<int> steps;
};

std::string extension(const std::string& path) {
  const auto dot = path.rfind('.');
  return dot == std::string::npos ? "" : path.substr(dot + 1);
}

// The pose with its finite instant centres marked; the view takes in the centres that are not
// too far from the mechanism.
int draw_centres(const ExplainArgs& args, const Explanation& ex) {
  const Mechanism& mech = *ex.mechanism;
  const Model& m = mech.model();
  const double lu = m.units.length_scale;
  const std::vector<Eigen::Vector2d> points = point_positions(mech, ex.q * lu);
  Eigen::Vector2d lo = points.front(), hi = lo;
  for (const auto& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Eigen::Vector2d centre = 0.5 * (lo + hi);
  const double reach = 2.0 * std::max(mech.characteristic_length(), (hi - lo).norm());
  // Links numbered as textbooks do: 1 the ground, then the bodies; I23 is the centre of links 2, 3.
  std::vector<int> number(m.bodies.size() + 1, 0);  // by body index + 1
  std::string legend;
  number[0] = 1;
  legend = "1 ground";
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    number[b + 1] = static_cast<int>(b) + 2;
    legend += ", " + std::to_string(b + 2) + " " + m.bodies[b].name;
  }
  const bool short_labels = m.bodies.size() + 1 < 10;
  render::DrawOptions draw;
  draw.labels = true;
  draw.title = "Instant centres at step " + std::to_string(ex.step) + " (links: " + legend + ")";
  int off_picture = 0;
  for (const InstantCentre& c : ex.centres) {
    if (c.at_infinity || c.indeterminate) continue;
    const Eigen::Vector2d at = c.position * lu;
    if ((at - centre).norm() > reach) {
      ++off_picture;
      continue;
    }
    lo = lo.cwiseMin(at);
    hi = hi.cwiseMax(at);
    const int a = number[c.body_a + 1], b = number[c.body_b + 1];
    draw.marked_points.push_back({at, short_labels ? "I" + std::to_string(a) + std::to_string(b)
                                                   : "I(" + std::to_string(a) + "," + std::to_string(b) + ")"});
  }
  const render::View view(lo, hi, draw.width, draw.height, draw.margin + 30.0);
  SweepResult none;  // no traces, no guide spans from a sweep: the pose alone
  const std::string format = extension(args.draw);
  try {
    if (format == "svg") {
      render::SvgCanvas canvas(draw.width, draw.height);
      render::draw_mechanism(canvas, view, mech, none, points, draw);
      std::ofstream out(args.draw);
      if (!(out << canvas.document())) {
        std::cerr << "error: cannot write " << args.draw << '\n';
        return kBadUsage;
      }
    } else {
      render::ImageCanvas canvas(draw.width, draw.height);
      render::draw_mechanism(canvas, view, mech, none, points, draw);
      canvas.write_png(args.draw);
    }
  } catch (const std::runtime_error& e) {
    std::cerr << "error: " << e.what() << '\n';
    return kBadUsage;
  }
  if (off_picture > 0)
    std::cerr << "note: --draw: " << off_picture << " instant centre" << (off_picture == 1 ? " lies" : "s lie")
              << " too far from the mechanism to draw\n";
  return kOk;
}

int run_explain(const ExplainArgs& args) {
  if (!args.draw.empty() && extension(args.draw) != "svg" && extension(args.draw) != "png") {
    std::cerr << "error: --draw " << args.draw << ": the picture's format comes from its extension: .svg or .png\n";
    return kBadUsage;
  }
  Loaded loaded;
  if (int code = load(args.model, loaded)) return code;
  ExplainOptions options;
  options.step = args.step;
  options.steps = args.steps;
  Explanation ex;
  try {
    ex = explain(loaded.mechanism, options);
  } catch (const Error& e) {
    return fail(args.model, e);
  }
  Output output;
  if (!output.open(args.output)) return kBadUsage;
  std::ostream& out = output.stream();
  if (args.format == "json")
    out << io::explanation_json(ex).dump(2) << '\n';
  else
    out << render_explanation(ex, args.format == "markdown" ? ExplainFormat::Markdown
                                  : args.format == "latex"  ? ExplainFormat::Latex
                                                            : ExplainFormat::Text);
  out.flush();
  if (!args.draw.empty()) return draw_centres(args, ex);
  return kOk;
}

}  // namespace

Command add_explain_command(CLI::App& app) {
  auto args = std::make_shared<ExplainArgs>();
  CLI::App* sub = app.add_subcommand("explain", "The method step by step at one sample: Gruebler count, q, the "
                                                "constraint equations and their Jacobian, Newton's iterations, the "
                                                "velocity and acceleration systems, the instant centres");
  sub->add_option("MODEL", args->model, "model file (YAML or JSON)")->required();
  sub->add_option("--step", args->step, "the sample of the sweep to explain (default 0, the start)")
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--steps", args->steps, "samples of the sweep, ends included (overrides the model's sweep)")
      ->check(CLI::PositiveNumber);
  sub->add_option("--format", args->format, "text (default), markdown (with LaTeX maths, for Jupyter), latex or json")
      ->check(CLI::IsMember({"text", "markdown", "latex", "json"}));
  sub->add_option("-o,--output", args->output, "write to FILE instead of standard output");
  sub->add_option("--draw", args->draw, "also draw the pose with its instant centres marked: FILE.svg or FILE.png");
  return {sub, [args] { return run_explain(*args); }};
}

}  // namespace nbar::cli
