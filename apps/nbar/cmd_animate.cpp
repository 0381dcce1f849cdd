// nbar animate: the sweep as a moving picture, in the format the output file's name ends with.
#include <algorithm>
#include <cctype>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.hpp"
#include "common.hpp"
#include "nbar/render/animation.hpp"
#include "validators.hpp"

namespace nbar::cli {

namespace {

struct AnimateArgs {
  std::string model;
  std::string output;
  double fps = 24.0;
  std::optional<int> frames;
  std::optional<int> steps;
  int max_steps = nbar::kDefaultMaxSweepSamples;
  bool labels = false;
  std::vector<std::string> traces;
  int width = 900, height = 640;
  bool stress = false;
  std::optional<double> mesh_size;
};

// "gif", "svg", "html" or "mp4" from the file name; empty when it is none of them.
std::string format_of(const std::string& path) {
  const std::size_t dot = path.rfind('.');
  const std::size_t slash = path.rfind('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == "htm") ext = "html";
  for (const char* known : {"gif", "svg", "html", "mp4"})
    if (ext == known) return ext;
  return "";
}

int run_animate(const AnimateArgs& args) {
  const std::string format = format_of(args.output);
  if (format.empty()) {
    std::cerr << "error: cannot tell the format of '" << args.output
              << "': the file name must end in .gif, .svg, .html or .mp4\n";
    return kBadUsage;
  }
  if (format == "mp4" && !nbar::render::Animation::program_available("ffmpeg")) {
    std::cerr << "error: MP4 needs the ffmpeg program: apt-get install ffmpeg\n";
    return kBadUsage;
  }

  Loaded loaded;
  if (int code = load(args.model, loaded)) return code;

  nbar::render::DrawOptions draw;
  draw.width = args.width;
  draw.height = args.height;
  draw.labels = args.labels;
  try {
    draw.traces = nbar::render::trace_points(loaded.mechanism->model(), args.traces);
  } catch (const nbar::Error& e) {
    std::cerr << "error: --trace: " << e.message() << '\n';
    return kBadUsage;
  }

  nbar::AnalysisOptions options;
  options.steps = args.steps;
  options.max_steps = args.max_steps;
  options.order = 0;  // positions are all a picture needs
  if (args.stress) {
    options.stress = true;
    use_finite_elements(options, loaded.mechanism->model(), args.mesh_size);
  }
  nbar::Analysis analysis;
  if (int code = analyse_model(args.model, loaded, options, analysis)) return code;
  const nbar::SweepResult& sweep = analysis.sweep;
  if (sweep.samples.empty()) return finish(loaded, sweep);

  try {
    nbar::render::Animation animation(analysis.mechanism, sweep, draw, args.frames.value_or(0), args.fps);
    if (args.stress) animation.show_stresses(analysis);
    if (format == "gif")
      animation.write_gif(args.output);
    else if (format == "svg")
      animation.write_svg_animation(args.output);
    else if (format == "html")
      animation.write_html_animation(args.output);
    else
      animation.write_mp4(args.output);
  } catch (const std::invalid_argument& e) {
    std::cerr << "error: " << e.what() << '\n';
    return kBadUsage;
  } catch (const std::runtime_error& e) {
    std::cerr << "error: " << e.what() << '\n';
    return kBadUsage;
  }
  print_warnings(sweep.warnings);
  return finish(loaded, sweep);
}

}  // namespace

Command add_animate_command(CLI::App& app) {
  auto args = std::make_shared<AnimateArgs>();
  CLI::App* sub = app.add_subcommand(
      "animate", "Animate the sweep: an animated GIF, an animated SVG, a web page with play, pause and a "
                 "slider, or an MP4 video (with ffmpeg); the format is the output file's extension");
  sub->add_option("MODEL", args->model, "model file (YAML or JSON)")->required();
  sub->add_option("-o,--output", args->output, "FILE.gif, FILE.svg, FILE.html or FILE.mp4")
      ->check(nbar::cli::output_file())->required();
  sub->add_option("--fps", args->fps, "frames per second (default 24)")->check(nbar::cli::in_range(0.1, 120.0));
  sub->add_option("--frames", args->frames,
                  "number of frames, evenly spaced over the sweep (default: every sample, at most 120)")
      ->check(nbar::cli::in_range(1, 100000));
  sub->add_option("--steps", args->steps, "number of samples of the sweep, ends included (overrides the model's)")
      ->check(nbar::cli::positive());
  sub->add_option("--max-steps", args->max_steps, kMaxStepsHelp)->check(nbar::cli::positive());
  sub->add_flag("--labels", args->labels, "write the name of every point");
  sub->add_option("--trace", args->traces, "draw the paths of these points, comma-separated, e.g. P,B")
      ->delimiter(',');
  sub->add_flag("--stress", args->stress,
                "GIF and MP4: colour every link with a shape by its von Mises stress in every frame (finite "
                "elements, one colour scale for the whole sweep), each link's peak marked");
  sub->add_option("--mesh-size", args->mesh_size,
                  "with --stress: element edge far from holes, in the model's length unit")
      ->check(nbar::cli::positive());
  sub->add_option("--width", args->width, "picture width in pixels (default 900)")->check(nbar::cli::in_range(64, 8192));
  sub->add_option("--height", args->height, "picture height in pixels (default 640)")->check(nbar::cli::in_range(64, 8192));
  sub->footer(
      "Every format shows the same frames on one view that fits the whole sweep. A sweep that ends\n"
      "where it began loops without repeating its first pose. GIF frames are not antialiased (a\n"
      "256-colour palette); SVG animates with SMIL; the HTML page needs no network; MP4 pipes\n"
      "frames to the ffmpeg program.");
  return {sub, [args] { return run_animate(*args); }};
}

}  // namespace nbar::cli
