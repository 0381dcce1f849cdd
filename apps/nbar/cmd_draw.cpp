// nbar draw: the mechanism in one pose, as SVG or PNG.
#include "commands.hpp"
#include "common.hpp"
#include "nbar/render/pictures.hpp"
#include "nbar/render/stress_map.hpp"
#include "nbar/request/requests.hpp"
#include "request_flags.hpp"
#include "validators.hpp"

namespace nbar::cli {

namespace {

struct DrawCommand {
  std::string model, output;
  std::unique_ptr<RequestFlags> flags;
};

int run_draw(const DrawCommand& command) {
  const std::string format = extension(command.output);
  if (format != "svg" && format != "png") {
    std::cerr << "error: -o " << command.output << ": the picture's format comes from its extension: .svg or .png\n";
    return kBadUsage;
  }
  request::DrawRequest request;
  if (!read_request(*command.flags, request)) return kBadUsage;
  request.format = format;
  Loaded loaded;
  if (int code = load(command.model, loaded)) return code;
  const Mechanism& mech = *loaded.mechanism;

  Analysis analysis;
  if (int code = analyse_model(command.model, loaded, request.analysis_options(mech.model()), analysis)) return code;
  render::DrawOptions draw;
  std::vector<Eigen::Vector2d> points;
  try {
    draw = request.picture.draw_options(mech.model());
    const request::DrawRequest::Pose pose = request.pose(analysis);
    points = pose.points;
    // A stress map is refused at `at` (DrawRequest::read): its pose is a sample.
    if (request.stress) render::add_stress_maps(draw, analysis, pose.step.value());
  } catch (const request::OptionError& e) {
    print_option_error(e);
    return kBadUsage;
  } catch (const Error& e) {
    return fail(command.model, nbar::io::located(loaded.file.source, e));
  }
  const bool written = format == "svg"
                           ? write_file(command.output, render::drawing_svg(mech, analysis.sweep, points, draw))
                           : write_file(command.output, render::drawing_png(mech, analysis.sweep, points, draw));
  if (!written) return kBadUsage;
  print_warnings(analysis.sweep.warnings);
  return kOk;  // the pose was drawn, even if the sweep (for traces) stopped early
}

}  // namespace

Command add_draw_command(CommandLine& app) {
  auto command = std::make_shared<DrawCommand>();
  Subcommand* sub = app.add_subcommand("draw",
                                       "Draw the mechanism in one pose (SVG or PNG): bodies, joints, ground "
                                       "pivots, sliders, slots, labels, paths of chosen points, scale bar");
  sub->add_option("MODEL", command->model, "model file (YAML or JSON)")->required();
  sub->add_option("-o,--output", command->output, "FILE.svg or FILE.png")->check(nbar::cli::output_file())->required();
  command->flags = std::make_unique<RequestFlags>(*sub, request::DrawRequest::rules());
  command->flags->add(
      {"step", "at", "steps", "max_steps", "labels", "trace", "width", "height", "title", "stress", "mesh_size"});
  return {sub, [command] { return run_draw(*command); }};
}

}  // namespace nbar::cli
