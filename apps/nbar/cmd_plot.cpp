// nbar plot: columns of the result table against another column, as an SVG or PNG line plot
// (render/plot.hpp). kPlotHelp below, shown by `nbar plot --help`, says how to use it.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.hpp"
#include "common.hpp"
#include "nbar/analysis/columns.hpp"
#include "nbar/kinematics/table.hpp"
#include "nbar/render/image_canvas.hpp"
#include "nbar/render/plot.hpp"
#include "nbar/request/requests.hpp"
#include "request_flags.hpp"
#include "validators.hpp"

namespace nbar::cli {

namespace {

struct PlotCommand {
  std::string model, output;
  std::unique_ptr<RequestFlags> flags;
};

const char* const kPlotHelp =
    "Plots columns of `nbar solve` against the first driver (against time, t, when a driver\n"
    "follows a time law), or against any other column with\n"
    "--x. Name the columns, or globs of them, comma-separated as with `solve --columns`.\n"
    "Inverse-dynamics columns (crank.torque, A.crank>coupler.Fx, energy.*...) switch on\n"
    "--dynamics by themselves, and jerk or higher derivatives raise --order as needed.\n"
    "Columns in different units share the plot, and each legend entry then names its unit.\n"
    "The file name's extension picks the format: .svg or .png.\n"
    "\n"
    "Examples:\n"
    "  nbar plot examples/fourbar-crank-rocker.yaml --y rocker.angle,rocker.omega -o rocker.svg\n"
    "  nbar plot examples/fourbar-crank-rocker.yaml --y 'rocker.*' -o rocker.png\n"
    "  nbar plot examples/compressor-myszka-kinetics.yaml --y '*.torque' -o torque.svg\n"
    "  nbar plot examples/fourbar-crank-rocker.yaml --x P.x --y P.y -o coupler-curve.svg\n"
    "  nbar plot examples/fourbar-crank-rocker.yaml --y rocker.alpha --y-range -5000,5000 -o alpha.svg\n";

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

int write_plot(const render::PlotSpec& spec, const std::string& format, const std::string& path) {
  if (format == ".svg") {
    render::SvgCanvas canvas(spec.width, spec.height);
    render::draw_plot(canvas, spec);
    Output output;
    if (!output.open(path)) return kBadUsage;
    output.stream() << canvas.document();
    return output.finish() ? kOk : kBadUsage;
  }
  render::ImageCanvas canvas(spec.width, spec.height);
  render::draw_plot(canvas, spec);
  try {
    canvas.write_png(path);
  } catch (const Error& e) {
    std::cerr << "error: " << said(e) << '\n';
    return exit_code(e.kind());
  }
  return kOk;
}

int run_plot(const PlotCommand& command) {
  const std::string format = lower_extension(command.output);
  if (format != ".svg" && format != ".png") {
    std::cerr << "error: -o: cannot tell the format of '" << command.output << "': name it .svg or .png\n";
    return kBadUsage;
  }
  request::PlotRequest request;
  if (!read_request(*command.flags, request)) return kBadUsage;
  request.format = format.substr(1);

  Loaded loaded;
  if (int code = load(command.model, loaded)) return code;
  AnalysisOptions options;
  try {
    options = request.analysis_options(*loaded.mechanism);
  } catch (const request::OptionError& e) {
    print_option_error(e);
    return kBadUsage;
  }
  Analysis analysis;
  if (int code = analyse_model(command.model, loaded, options, analysis)) return code;
  render::PlotSpec spec;
  try {
    spec = request.plot(analysis, std::filesystem::path(command.model).stem().string());
  } catch (const request::OptionError& e) {
    print_option_error(e);
    return kBadUsage;
  }
  if (int code = write_plot(spec, format, command.output)) return code;
  print_warnings(analysis.warnings());
  return finish(loaded, analysis.sweep);
}

}  // namespace

Command add_plot_command(CommandLine& app) {
  auto command = std::make_shared<PlotCommand>();
  Subcommand* sub =
      app.add_subcommand("plot",
                         "Plot result columns (angles, velocities, forces...) against a driver or any other column, "
                         "as SVG or PNG");
  sub->add_option("MODEL", command->model, "model file (YAML or JSON)")->required();
  command->flags = std::make_unique<RequestFlags>(*sub, request::PlotRequest::rules());
  command->flags->add({"y"});
  command->flags->option("y")->required();
  command->flags->add({"x"});
  sub->add_option("-o,--output", command->output, "the picture to write: FILE.svg or FILE.png")
      ->check(nbar::cli::output_file())
      ->required();
  command->flags->add(
      {"steps", "max_steps", "at_limits", "cycles", "order", "dynamics", "y_range", "title", "width", "height"});
  sub->footer(kPlotHelp);
  return {sub, [command] { return run_plot(*command); }};
}

}  // namespace nbar::cli
