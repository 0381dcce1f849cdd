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
#include "nbar/dynamics/dynamics_table.hpp"
#include "nbar/kinematics/table.hpp"
#include "nbar/render/plot.hpp"
#include "nbar/render/image_canvas.hpp"

namespace nbar::cli {

namespace {

struct PlotArgs {
  std::string model, output, x, title;
  std::vector<std::string> y;
  std::vector<double> y_range;
  std::optional<int> steps, order;
  bool dynamics = false;
  int width = 900, height = 520;
};

const char* const kPlotHelp =
    "Plots columns of `nbar solve` against the first driver, or against any other column with\n"
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

// The column names of the table at a sweep order, without solving anything.
std::vector<std::string> kinematic_columns(const Mechanism& mech, int order) {
  SweepResult empty;
  empty.order = order;
  return make_table(mech, empty).columns;
}

// The inverse-dynamics column names, or none when the model cannot have them.
std::vector<std::string> dynamics_columns(const Mechanism& mech) {
  SweepResult empty;
  ResultTable names;
  try {
    append_dynamics(mech, empty, names);
  } catch (const std::exception&) {
    return {};
  }
  return names.columns;
}

bool matches(const std::vector<std::string>& columns, const std::string& pattern) {
  ResultTable t;
  t.columns = columns;
  t.units.resize(columns.size());
  try {
    select_columns(t, {pattern});
    return true;
  } catch (const std::invalid_argument&) {
    return false;
  }
}

int unknown_column(const std::string& option, const std::string& pattern, const std::vector<std::string>& kinematic,
                   const std::vector<std::string>& dynamic) {
  std::cerr << "error: " << option << ": no column matches '" << pattern << "'; the columns are: " << join(kinematic);
  if (!dynamic.empty()) std::cerr << "; with inverse dynamics also: " << join(dynamic);
  std::cerr << '\n';
  return kBadUsage;
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
  const Mechanism& mech = *loaded.mechanism;
  const Model& m = mech.model();
  const std::string x_pattern = !args.x.empty() ? args.x : m.drivers.empty() ? std::string("t") : m.drivers[0].name;

  // Which columns exist, and whether the request needs inverse dynamics or a higher order.
  std::vector<std::string> patterns = args.y;
  patterns.push_back(x_pattern);
  const std::vector<std::string> all_kinematic = kinematic_columns(mech, 5);
  const std::vector<std::string> dynamic = dynamics_columns(mech);
  bool dynamics = args.dynamics;
  std::vector<std::string> kinematic_patterns;
  for (const std::string& p : patterns) {
    if (!matches(all_kinematic, p) && matches(dynamic, p))
      dynamics = true;
    else
      kinematic_patterns.push_back(p);
  }
  int order = args.order.value_or(2);
  if (!args.order) {
    for (int k = 2; k <= 5; ++k) {
      const std::vector<std::string> names = kinematic_columns(mech, k);
      const bool all = std::all_of(kinematic_patterns.begin(), kinematic_patterns.end(),
                                   [&](const std::string& p) { return matches(names, p); });
      if (all) {
        order = k;
        break;
      }
    }
  }
  if (dynamics) order = std::max(order, 2);
  std::vector<std::string> available = kinematic_columns(mech, order);
  const std::vector<std::string> empty;
  if (dynamics) available.insert(available.end(), dynamic.begin(), dynamic.end());
  for (const std::string& p : args.y)
    if (!matches(available, p)) return unknown_column("--y", p, available, dynamics ? empty : dynamic);
  if (!matches(available, x_pattern)) return unknown_column("--x", x_pattern, available, dynamics ? empty : dynamic);

  SweepOptions options;
  options.steps = args.steps;
  options.order = order;
  SweepResult sweep;
  if (int code = sweep_model(args.model, mech, options, sweep)) return code;
  ResultTable table = make_table(mech, sweep);
  std::optional<DynamicsSummary> summary;
  if (dynamics) {
    try {
      summary = append_dynamics(mech, sweep, table);
    } catch (const std::domain_error& e) {  // a load's law undefined at some time
      std::cerr << "error: " << args.model << ": " << e.what() << '\n';
      return kInvalidModel;
    } catch (const std::invalid_argument& e) {
      std::cerr << "error: " << args.model << ": " << e.what() << '\n';
      return kInvalidModel;
    }
  }

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
  spec.x_name = x_column.columns[0];
  spec.x_unit = x_column.units[0];
  for (const auto& row : x_column.rows) spec.x.push_back(row[0]);
  for (std::size_t c = 0; c < y_columns.columns.size(); ++c) {
    render::PlotSeries s{y_columns.columns[c], y_columns.units[c], {}};
    for (const auto& row : y_columns.rows) s.y.push_back(row[c]);
    spec.series.push_back(std::move(s));
  }

  if (format == ".svg") {
    render::SvgCanvas canvas(spec.width, spec.height);
    render::draw_plot(canvas, spec);
    Output output;
    if (!output.open(args.output)) return kBadUsage;
    output.stream() << canvas.document();
    output.stream().flush();
    if (!output.stream()) {
      std::cerr << "error: cannot write " << args.output << '\n';
      return kBadUsage;
    }
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

  for (const std::string& w : sweep.warnings) std::cerr << "warning: " << w << '\n';
  if (summary)
    for (const std::string& w : summary->warnings) std::cerr << "warning: " << w << '\n';
  return finish(args.model, sweep);
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
  sub->add_option("--x", args.x, "the column along the x axis (default: the first driver's)");
  sub->add_option("-o,--output", args.output, "the picture to write: FILE.svg or FILE.png")->required();
  sub->add_option("--steps", args.steps, "number of samples, ends included (overrides the model's sweep)")
      ->check(CLI::PositiveNumber);
  sub->add_option("--order", args.order, "highest time derivative to solve, 0 to 5 (default: 2, or what the "
                                         "columns need)")
      ->check(CLI::Range(0, 5));
  sub->add_flag("--dynamics", args.dynamics,
                "add the inverse-dynamics columns (joint forces, driver torques and forces, energies); "
                "on by itself when a column asked for needs it");
  sub->add_option("--y-range", args.y_range, "a fixed y range LO,HI instead of one covering the data")
      ->expected(2)
      ->delimiter(',');
  sub->add_option("--title", args.title, "the title at the top (default: the model's name)");
  sub->add_option("--width", args.width, "picture width in pixels (default 900)")->check(CLI::Range(200, 10000));
  sub->add_option("--height", args.height, "picture height in pixels (default 520)")->check(CLI::Range(150, 10000));
  sub->footer(kPlotHelp);
  return {sub, [shared] { return run_plot(*shared); }};
}

}  // namespace nbar::cli
