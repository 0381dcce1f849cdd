// nbar draw: the mechanism in one pose, as SVG or PNG.
#include <cmath>
#include <fstream>

#include "commands.hpp"
#include "common.hpp"
#include "nbar/analysis/pose.hpp"
#include "nbar/render/drawing.hpp"
#include "nbar/render/pictures.hpp"
#include "nbar/render/stress_map.hpp"
#include "validators.hpp"

namespace nbar::cli {

namespace {

struct DrawArgs {
  std::string model, output;
  std::optional<int> step;
  std::optional<double> at;
  std::optional<int> steps;
  int max_steps = nbar::kDefaultMaxSweepSamples;
  bool labels = false;
  std::vector<std::string> traces;
  int width = 900, height = 640;
  std::string title;
  bool stress = false;
  std::optional<double> mesh_size;
};

std::string extension(const std::string& path) {
  const auto dot = path.rfind('.');
  return dot == std::string::npos ? "" : path.substr(dot + 1);
}

int run_draw(const DrawArgs& args) {
  const std::string format = extension(args.output);
  if (format != "svg" && format != "png") {
    std::cerr << "error: -o " << args.output << ": the picture's format comes from its extension: .svg or .png\n";
    return kBadUsage;
  }
  Loaded loaded;
  if (int code = load(args.model, loaded)) return code;
  const Mechanism& mech = *loaded.mechanism;
  const Model& m = mech.model();

  render::DrawOptions draw;
  draw.width = args.width;
  draw.height = args.height;
  draw.labels = args.labels;
  draw.title = args.title;
  try {
    draw.traces = render::trace_points(m, args.traces);
  } catch (const Error& e) {
    std::cerr << "error: --trace: " << e.message() << '\n';
    return kBadUsage;
  }

  AnalysisOptions options;
  options.steps = args.steps;
  options.max_steps = args.max_steps;
  options.order = 0;
  if (args.stress) {
    if (args.at) {
      std::cerr << "error: --stress colours a solved step of the sweep: give --step instead of --at\n";
      return kBadUsage;
    }
    options.stress = true;
    use_finite_elements(options, m, args.mesh_size);
  }
  Analysis analysis;
  if (int code = analyse_model(args.model, loaded, options, analysis)) return code;
  const SweepResult& sweep = analysis.sweep;

  std::vector<Eigen::Vector2d> points;
  if (args.at) {
    try {
      points = render::sample_points(mech, pose_at(mech, *args.at));
    } catch (const Error& e) {
      return fail(args.model, e);
    }
  } else {
    const int step = args.step.value_or(render::default_drawn_step(mech, sweep));
    if (!check_step(step, sweep)) return kBadUsage;
    points = render::sample_points(mech, sweep.samples[step]);
    if (args.stress) render::add_stress_maps(draw, analysis, step);
  }
  try {
    const bool written = format == "svg" ? write_file(args.output, render::drawing_svg(mech, sweep, points, draw))
                                         : write_file(args.output, render::drawing_png(mech, sweep, points, draw));
    if (!written) return kBadUsage;
  } catch (const std::runtime_error& e) {
    std::cerr << "error: " << e.what() << '\n';
    return kBadUsage;
  }
  print_warnings(sweep.warnings);
  return kOk;  // the pose was drawn, even if the sweep (for traces) stopped early
}

}  // namespace

Command add_draw_command(CLI::App& app) {
  auto args = std::make_shared<DrawArgs>();
  CLI::App* sub = app.add_subcommand("draw", "Draw the mechanism in one pose (SVG or PNG): bodies, joints, ground "
                                             "pivots, sliders, slots, labels, paths of chosen points, scale bar");
  sub->add_option("MODEL", args->model, "model file (YAML or JSON)")->required();
  sub->add_option("-o,--output", args->output, "FILE.svg or FILE.png")
      ->check(nbar::cli::output_file())->required();
  auto* step = sub->add_option("--step", args->step, "draw this sample of the sweep (default 0, the start, unless every point lies on one line there: then the most open pose)");
  sub->add_option("--at", args->at, "draw where the first driver has this value (model units; a time for time laws)")
      ->excludes(step);
  sub->add_option("--steps", args->steps, "samples of the sweep (for --step and the traces)")->check(nbar::cli::positive());
  sub->add_option("--max-steps", args->max_steps, kMaxStepsHelp)->check(nbar::cli::positive());
  sub->add_flag("--labels", args->labels, "write point names");
  sub->add_option("--trace", args->traces, "points whose paths over the sweep are drawn, e.g. P,Q")->delimiter(',');
  sub->add_option("--width", args->width, "pixels (default 900)")->check(nbar::cli::in_range(100, 10000));
  sub->add_option("--height", args->height, "pixels (default 640)")->check(nbar::cli::in_range(100, 10000));
  sub->add_option("--title", args->title, "a title at the top left");
  sub->add_flag("--stress", args->stress,
                "colour every link with a shape by its von Mises stress at the drawn step (finite elements, as "
                "`nbar stress --method fe`), with a colour legend and each link's peak marked");
  sub->add_option("--mesh-size", args->mesh_size,
                  "with --stress: element edge far from holes, in the model's length unit (default: a twentieth of "
                  "each plate's size)")
      ->check(nbar::cli::positive());
  return {sub, [args] { return run_draw(*args); }};
}

}  // namespace nbar::cli
