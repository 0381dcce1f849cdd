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
#include "nbar/render/plot.hpp"
#include "nbar/render/image_canvas.hpp"
#include "validators.hpp"

namespace nbar::cli {

namespace {

struct PlotArgs {
  std::string model, output, x, title;
  std::vector<std::string> y;
  std::vector<double> y_range;
  std::optional<int> steps, order;
  int max_steps = nbar::kDefaultMaxSweepSamples;
  bool dynamics = false;
  int width = 900, height = 520;
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
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

int run_plot(const PlotArgs& args) {
  const std::string format = lower_extension(args.output);
  if (format != ".svg" && format != ".png") {
    std::cerr << "error: -o: cannot tell the format of '" << args.output << "': name it .svg or .png\n";
    return kBadUsage;
  }
  if (!args.y_range.empty() && !(std::isfinite(args.y_range[0]) && std::isfinite(args.y_range[1]) &&
                                 std::abs(args.y_range[0]) <= 1e300 && std::abs(args.y_range[1]) <= 1e300 &&
                                 args.y_range[0] < args.y_range[1])) {
    std::cerr << "error: --y-range: LO and HI must be finite numbers with LO < HI\n";
    return kBadUsage;
  }

  Loaded loaded;
  if (int code = load(args.model, loaded)) return code;
  const Model& m = loaded.mechanism->model();
  const std::string x_pattern = !args.x.empty() ? args.x : default_abscissa(m);

  // Which stages and order the columns need, from the library's column catalogue.
  std::vector<std::string> patterns = args.y;
  patterns.push_back(x_pattern);
  const ColumnNeeds needs = column_needs(*loaded.mechanism, patterns, args.order, args.dynamics);
  if (needs.unmatched >= 0) {
    std::cerr << "error: " << (needs.unmatched < static_cast<int>(args.y.size()) ? "--y" : "--x") << ": "
              << needs.message << '\n';
    return kBadUsage;
  }
  AnalysisOptions options;
  options.steps = args.steps;
  options.max_steps = args.max_steps;
  options.order = needs.order;
  options.dynamics = needs.dynamics;
  Analysis analysis;
  if (int code = analyse_model(args.model, loaded, options, analysis)) return code;
  const ResultTable table = result_table(analysis);

  const ResultTable x_column = select_columns(table, {x_pattern});
  if (x_column.columns.size() != 1) {
    std::cerr << "error: --x: '" << x_pattern << "' matches " << x_column.columns.size() << " columns ("
              << join(x_column.columns) << "); name one\n";
    return kBadUsage;
  }
  const ResultTable y_columns = select_columns(table, args.y);

  render::PlotSpec spec;
  spec.title = !args.title.empty() ? args.title
               : !m.name.empty()   ? m.name
                                   : std::filesystem::path(args.model).stem().string();
  if (!args.y_range.empty()) {
    spec.y_lo = args.y_range[0];
    spec.y_hi = args.y_range[1];
  }
  spec.width = args.width;
  spec.height = args.height;
  render::set_plot_data(spec, x_column, y_columns);

  if (format == ".svg") {
    render::SvgCanvas canvas(spec.width, spec.height);
    render::draw_plot(canvas, spec);
    Output output;
    if (!output.open(args.output)) return kBadUsage;
    output.stream() << canvas.document();
    if (!output.finish()) return kBadUsage;
  } else {
    render::ImageCanvas canvas(spec.width, spec.height);
    render::draw_plot(canvas, spec);
    try {
      canvas.write_png(args.output);
    } catch (const std::runtime_error& e) {
      std::cerr << "error: " << e.what() << '\n';
      return kBadUsage;
    }
  }

  print_warnings(analysis.warnings());
  return finish(loaded, analysis.sweep);
}

}  // namespace

Command add_plot_command(CLI::App& app) {
  auto shared = std::make_shared<PlotArgs>();
  PlotArgs& args = *shared;
  CLI::App* sub = app.add_subcommand(
      "plot", "Plot result columns (angles, velocities, forces...) against a driver or any other column, "
              "as SVG or PNG");
  sub->add_option("MODEL", args.model, "model file (YAML or JSON)")->required();
  sub->add_option("--y", args.y, "columns to plot: names or globs, comma-separated, e.g. 'rocker.omega,B.v*'")
      ->required()
      ->delimiter(',');
  sub->add_option("--x", args.x, "the column along the x axis (default: the first driver's, or t when a driver follows a time law)");
  sub->add_option("-o,--output", args.output, "the picture to write: FILE.svg or FILE.png")
      ->check(nbar::cli::output_file())->required();
  sub->add_option("--steps", args.steps, "number of samples, ends included (overrides the model's sweep)")
      ->check(nbar::cli::positive());
  sub->add_option("--max-steps", args.max_steps, kMaxStepsHelp)->check(nbar::cli::positive());
  sub->add_option("--order", args.order, "highest time derivative to solve, 0 to 5 (default: 2, or what the "
                                         "columns need)")
      ->check(nbar::cli::in_range(0, 5));
  sub->add_flag("--dynamics", args.dynamics,
                "add the inverse-dynamics columns (joint forces, driver torques and forces, energies); "
                "on by itself when a column asked for needs it");
  sub->add_option("--y-range", args.y_range, "a fixed y range LO,HI instead of one covering the data")
      ->expected(2)
      ->delimiter(',');
  sub->add_option("--title", args.title, "the title at the top (default: the model's name)");
  sub->add_option("--width", args.width, "picture width in pixels (default 900)")->check(nbar::cli::in_range(200, 10000));
  sub->add_option("--height", args.height, "picture height in pixels (default 520)")->check(nbar::cli::in_range(150, 10000));
  sub->footer(kPlotHelp);
  return {sub, [shared] { return run_plot(*shared); }};
}

}  // namespace nbar::cli
