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
#include "nbar/request/requests.hpp"
#include "request_flags.hpp"
#include "simulation_run.hpp"
#include "validators.hpp"

namespace nbar::cli {

namespace {

struct AnimateCommand {
  std::string model;
  std::string output;
  std::unique_ptr<RequestFlags> flags;
  std::unique_ptr<RequestFlags> motion_flags;  // --simulate and its run's options
};

// "gif", "svg", "html" or "mp4" from the file name; empty when it is none of them.
std::string format_of(const std::string& path) {
  const std::size_t dot = path.rfind('.');
  const std::size_t slash = path.rfind('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == "htm") ext = "html";
  for (const char* known : {"gif", "svg", "html", "mp4"})
    if (ext == known) return ext;
  return "";
}

void write_animation(const render::Animation& animation, const std::string& format, const std::string& path) {
  if (format == "gif")
    animation.write_gif(path);
  else if (format == "svg")
    animation.write_svg_animation(path);
  else if (format == "html")
    animation.write_html_animation(path);
  else
    animation.write_mp4(path);
}

// --simulate: the frames are the simulation's rows, at their times (its stresses are not solved).
int animate_simulation(const AnimateCommand& command, const request::AnimateRequest& request,
                       const request::SimulateRequest& run, const Loaded& loaded, const render::DrawOptions& draw) {
  if (request.stress) {
    print_option_error(request::OptionError("stress", "colours the sweep's stresses: not with {simulate}"));
    return kBadUsage;
  }
  Simulation simulation;
  if (int code = simulate_model(command.model, loaded, run, simulation)) return code;
  try {
    render::Animation animation(loaded.mechanism, request::simulated_motion(simulation), draw,
                                request.frames.value_or(0), request.fps);
    write_animation(animation, request.format, command.output);
  } catch (const Error& e) {
    return fail(command.model, nbar::io::located(loaded.file.source, e));
  }
  return finish_simulation(command.model, loaded, simulation);
}

int run_animate(const AnimateCommand& command) {
  const std::string format = format_of(command.output);
  if (format.empty()) {
    std::cerr << "error: cannot tell the format of '" << command.output
              << "': the file name must end in .gif, .svg, .html or .mp4\n";
    return kBadUsage;
  }
  if (format == "mp4" && !render::Animation::program_available("ffmpeg")) {
    std::cerr << "error: MP4 needs the ffmpeg program: apt-get install ffmpeg\n";
    return kBadUsage;
  }
  request::AnimateRequest request;
  if (!read_request(*command.flags, request)) return kBadUsage;
  request.format = format;
  request::SimulatedMotionRequest motion;
  if (!read_request(*command.motion_flags, motion)) return kBadUsage;

  Loaded loaded;
  if (int code = load(command.model, loaded)) return code;
  render::DrawOptions draw;
  try {
    draw = request.picture.draw_options(loaded.mechanism->model());
  } catch (const request::OptionError& e) {
    print_option_error(e);
    return kBadUsage;
  }
  if (motion.simulation) return animate_simulation(command, request, *motion.simulation, loaded, draw);
  Analysis analysis;
  if (int code = analyse_model(command.model, loaded, request.analysis_options(loaded.mechanism->model()), analysis))
    return code;
  const SweepResult& sweep = analysis.sweep;
  if (sweep.samples.empty()) return finish(loaded, sweep);
  try {
    render::Animation animation(analysis.mechanism, sweep, draw, request.frames.value_or(0), request.fps);
    if (request.stress) animation.show_stresses(analysis);
    write_animation(animation, format, command.output);
  } catch (const Error& e) {
    return fail(command.model, nbar::io::located(loaded.file.source, e));
  }
  print_warnings(sweep.warnings);
  return finish(loaded, sweep);
}

}  // namespace

Command add_animate_command(CommandLine& app) {
  auto command = std::make_shared<AnimateCommand>();
  Subcommand* sub =
      app.add_subcommand("animate",
                         "Animate the sweep: an animated GIF, an animated SVG, a web page with play, pause and a "
                         "slider, or an MP4 video (with ffmpeg); the format is the output file's extension");
  sub->add_option("MODEL", command->model, "model file (YAML or JSON)")->required();
  sub->add_option("-o,--output", command->output, "FILE.gif, FILE.svg, FILE.html or FILE.mp4")
      ->check(nbar::cli::output_file())
      ->required();
  command->flags = std::make_unique<RequestFlags>(*sub, request::AnimateRequest::rules());
  command->flags->add({"fps", "frames", "steps", "max_steps", "at_limits", "cycles", "labels", "trace", "stress",
                       "mesh_size", "width", "height", "title"});
  command->motion_flags = std::make_unique<RequestFlags>(*sub, request::SimulatedMotionRequest::rules());
  command->motion_flags->add({"simulate", "to", "dt", "rtol", "stop_when", "at_toggle"});
  sub->footer(
      "Every format shows the same frames on one view that fits the whole sweep. A sweep that ends\n"
      "where it began loops without repeating its first pose. GIF frames are not antialiased (a\n"
      "256-colour palette); SVG animates with SMIL; the HTML page needs no network; MP4 pipes\n"
      "frames to the ffmpeg program. With --simulate the frames are the simulation's rows (nbar\n"
      "simulate's motion, the drivers marked free released), evenly spaced in time.");
  return {sub, [command] { return run_animate(*command); }};
}

}  // namespace nbar::cli
