// What a user asks of nbar, one type per question, read from the options every front-end fills
// (request/options.hpp). Each request owns its options' rules (ranges, defaults, choices), the
// unit conversions of its options, and the choices made from them (the analysis it needs, the
// pose it draws, the columns it selects), so that the command line, the web server and Python
// give one answer, or one error, for one request:
//
//   request::Options options;                       // filled by a front-end
//   options.set("order", 3LL);
//   const SolveRequest solve = SolveRequest::read(options);   // throws OptionError
//   Analysis a = analyse(mechanism, solve.analysis_options());
//   ResultTable t = solve.table(a);                 // the columns asked for, or OptionError
//
// Ownership: a request is a plain value; the functions that take a Mechanism or an Analysis
// keep no reference to them.
#pragma once

#include <Eigen/Core>

#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "nbar/analysis/analysis.hpp"
#include "nbar/analysis/explain.hpp"
#include "nbar/analysis/fe_tables.hpp"
#include "nbar/analysis/summary.hpp"
#include "nbar/analysis/table_stream.hpp"
#include "nbar/dynamics/equations_of_motion.hpp"
#include "nbar/dynamics/forward_dynamics.hpp"
#include "nbar/kinematics/table.hpp"
#include "nbar/model/run_control.hpp"
#include "nbar/render/drawing.hpp"
#include "nbar/render/plot.hpp"
#include "nbar/request/options.hpp"

namespace nbar::request {

// The sweep's number of samples: the model's, or `steps`; a larger sweep than `max_steps` is an
// error (every sample is kept in memory, and each takes time).
struct SweepSize {
  std::optional<int> steps;
  int max_steps = kDefaultMaxSweepSamples;
  std::optional<AtLimits> at_limits;  // what the first driver does at a limit, over the model's
  std::optional<int> cycles;          // with at_limits reverse: the cycles to run

  static std::vector<OptionRule> rules(bool with_steps = true);
  static SweepSize read(const Options& options);
  void apply(AnalysisOptions& analysis) const;
};

// How a picture looks: its size in pixels (each kind of picture has its own range), point names,
// the points whose paths are drawn, a title.
struct Picture {
  int width = 900;
  int height = 640;
  bool labels = false;
  std::vector<std::string> trace;
  std::string title;

  // The drawing options for this picture of `model`; an unknown traced point is an OptionError
  // at `trace`.
  render::DrawOptions draw_options(const Model& model) const;
};

// The size limits of each kind of picture, the same in every front-end.
struct PictureLimits {
  int min_width, min_height, max_width, max_height;
  int default_width, default_height;
};
inline constexpr PictureLimits kDrawingLimits{100, 100, 10000, 10000, 900, 640};
inline constexpr PictureLimits kAnimationLimits{64, 64, 8192, 8192, 900, 640};
inline constexpr PictureLimits kPlotLimits{200, 150, 10000, 10000, 900, 520};

// Stresses by finite elements: the element size far from holes, in the model's length unit (unset:
// each plate's own default). Converted to metres here, once for every front-end.
void use_finite_elements(AnalysisOptions& analysis, const Model& model, std::optional<double> mesh_size);

// nbar check: the model's summary.
struct CheckRequest {
  std::string format = "text";  // text or json
  int max_steps = kDefaultMaxSweepSamples;
  // As solve's: the first driver's `at_limits` and `cycles` over the model's, so that check
  // describes the sweep solve would run (a rocking driver's turns, no warning of a stop).
  std::optional<AtLimits> at_limits;
  std::optional<int> cycles;

  static const std::vector<OptionRule>& rules();
  static CheckRequest read(const Options& options);
  // The mechanism with those overrides (the same one when there are none).
  std::shared_ptr<const Mechanism> mechanism(std::shared_ptr<const Mechanism> loaded) const;
};

// nbar solve: the sweep's columns.
struct SolveRequest {
  SweepSize sweep;
  int order = 2;
  bool dynamics = false;
  std::vector<std::string> columns;  // names or globs; empty: every column
  std::string format = "csv";        // csv, json or table

  static const std::vector<OptionRule>& rules();
  static SolveRequest read(const Options& options);
  AnalysisOptions analysis_options() const;
  // The columns asked for; an OptionError at `columns` names the columns there are (and says when
  // the ones asked for need the dynamics).
  ResultTable table(const Analysis& analysis) const;
  // The columns asked for as a table of numbers (Python's arrays), with the columns on request
  // they name, or the same OptionError.
  ColumnTable columns_of(const Analysis& analysis) const;
  // The columns asked for of a table of numbers, or the same OptionError.
  ColumnTable columns_of(const Mechanism& mechanism, const ColumnTable& table) const;
  // The columns on request that `columns` names, for a TableStream to compute.
  ColumnsOnRequest columns_on_request(const Mechanism& mechanism) const;
  // The columns asked for of a streamed table (the CLI's CSV), or the same OptionError.
  void select(const Mechanism& mechanism, TableStream& stream) const;

 private:
  [[noreturn]] void explain_column_error(const Mechanism& mechanism, const std::string& problem) const;
};

// nbar stress: every shaped link's largest stress, or one link's sections at one step.
struct StressRequest {
  SweepSize sweep;
  StressMethod method = StressMethod::beam;
  int sections = 200;
  std::optional<double> mesh_size;  // the model's length unit
  std::string format = "table";     // table, csv or json
  std::string section_profile;      // a body: its sections at `step` instead of the peaks
  std::optional<int> step;
  // fe: the field of the `section_profile` body at `step` read at points (each "X,Y" or a point's
  // name), along a line ("X1,Y1,X2,Y2" or two points' names) or around a hole (a point's name
  // or its number from 1, optionally "BODY:" first), in the body's frame or model coordinates.
  std::vector<std::string> at, along;
  std::string around_hole;
  std::string coordinates = "body";  // body or model
  int samples = 101;                 // points along the line or the circle; cuts of an fe section profile
  std::optional<double> radius;      // around_hole: a circle of this radius instead of the edge

  std::string export_mesh;  // fe: a directory for each link's mesh and field (.vtu and CSV)

  static const std::vector<OptionRule>& rules();
  static StressRequest read(const Options& options);
  AnalysisOptions analysis_options(const Model& model) const;
  // The meshes to export: the {section_profile} body or every analysed link, at {step} or at each
  // link's peak step, each with the stem of its files ("crank-step12").
  struct MeshExport {
    int body = -1, step = 0;
    std::string stem;
  };
  std::vector<MeshExport> mesh_exports(const Analysis& analysis) const;
  // A table of one body at one step is asked for (a section profile or an fe query), not the peaks.
  bool profile_asked() const { return !section_profile.empty(); }
  // The section profile or fe query asked for: OptionError at the option that names what is wrong.
  ResultTable section_profile_table(const Analysis& analysis) const;

  // fe: the mesh (unset: the mesher's defaults), and a convergence study instead of one mesh.
  std::optional<int> segments_per_hole;
  std::optional<double> edge_size;  // the model's length unit
  bool converge = false;
  double tolerance = 0.01;  // relative; the option `tolerance` is in %
  // With `converge`: the meshes after the analysis of analysis_options (the first mesh), halving
  // every plate's element sizes until the peaks change by less than `tolerance`, or the next mesh
  // would pass the node budget.
  FeConvergence convergence(const Analysis& analysis, const RunControl& control = {}) const;

 private:
  void read_field_query(const Options& options);
  ResultTable field_query_table(const Analysis& analysis, int body, int step) const;
  static void read_fe_mesh_options(const Options& options, StressRequest& r);
};

// The web app's stress map under the cursor: the finite-element von Mises stress at a point of
// the drawing at one step, on whichever link's plate is drawn there (nbar/analysis/fe_tables.hpp,
// plate_under), with that point where the model draws the link: the same number as `nbar stress
// --method fe --section-profile LINK --step K --at X,Y --coordinates model`.
struct StressProbeRequest {
  SweepSize sweep;
  std::optional<double> mesh_size;  // the model's length unit
  int step = 0;
  Eigen::Vector2d at{0, 0};  // the drawing at `step`: model coordinates, the model's length unit

  static const std::vector<OptionRule>& rules();
  static StressProbeRequest read(const Options& options);
  AnalysisOptions analysis_options(const Model& model) const;
  // What is under the point: no link, or the link, the point on it (model coordinates) and its
  // stresses there (fe_points_table's one row, model coordinates).
  struct Answer {
    std::optional<PlateUnder> link;
    ResultTable stresses;
  };
  Answer probe(const Analysis& analysis) const;
};

// A solved step of the sweep, checked: OptionError at `step` ("step 999 is not a solved step
// (0 to 12)") when the sweep has no such sample.
int solved_step(const SweepResult& sweep, int step);

// nbar draw: the mechanism in one pose.
struct DrawRequest {
  SweepSize sweep;
  std::optional<int> step;   // a sample of the sweep (default: render::default_drawn_step)
  std::optional<double> at;  // or where the first driver has this value (model units)
  Picture picture;
  bool stress = false;
  std::optional<double> mesh_size;
  std::string format = "svg";  // svg or png (or the web app's scene)

  static const std::vector<OptionRule>& rules();
  static DrawRequest read(const Options& options);
  AnalysisOptions analysis_options(const Model& model) const;
  // The pose drawn: a sample of the sweep (`step`, or render::default_drawn_step, chosen once
  // here) with its positions, or the positions at `at` on the sweep's path (no step).
  struct Pose {
    std::optional<int> step;
    std::vector<Eigen::Vector2d> points;  // m
  };
  Pose pose(const Analysis& analysis, const RunControl& control = {}) const;
  // The sample drawn, when the pose is a sample (not `at`).
  int drawn_step(const Analysis& analysis) const;
};

// nbar animate: the sweep as a moving picture.
struct AnimateRequest {
  SweepSize sweep;
  Picture picture;
  double fps = 24.0;
  std::optional<int> frames;  // unset: every sample, at most 120
  bool stress = false;
  std::optional<double> mesh_size;
  std::string format = "html";  // gif, svg, html or mp4

  static const std::vector<OptionRule>& rules();
  static AnimateRequest read(const Options& options);
  AnalysisOptions analysis_options(const Model& model) const;
};

// nbar plot: columns against a column.
struct PlotRequest {
  SweepSize sweep;
  std::vector<std::string> y;
  std::string x;  // empty: default_abscissa
  std::optional<int> order;
  bool dynamics = false;
  std::optional<std::pair<double, double>> y_range;
  int width = kPlotLimits.default_width;
  int height = kPlotLimits.default_height;
  std::string title;
  std::string format = "svg";  // svg or png

  static const std::vector<OptionRule>& rules();
  static PlotRequest read(const Options& options);
  // The stages and order the columns need; an OptionError at `y` or `x` when one matches nothing.
  AnalysisOptions analysis_options(const Mechanism& mechanism) const;
  // The plot of the analysis; `fallback_title` when neither the request nor the model names it.
  render::PlotSpec plot(const Analysis& analysis, const std::string& fallback_title) const;
};

// nbar report: one HTML page about the mechanism.
struct ReportRequest {
  SweepSize sweep;
  int frames = 72;
  StressMethod stress_method = StressMethod::beam;
  std::optional<double> mesh_size;

  static const std::vector<OptionRule>& rules();
  static ReportRequest read(const Options& options);
  // The stages the report shows (what the summary says the model has), with this sweep and method.
  AnalysisOptions analysis_options(const ModelSummary& summary, const Model& model) const;
};

// nbar export: the links' plates for cutting, as drawn in the model file or in one pose.
struct ExportRequest {
  std::optional<double> at;    // where the first driver has this value (model units); unset: as drawn
  std::string format = "svg";  // svg (true size in mm) or dxf (the model's length unit)

  static const std::vector<OptionRule>& rules();
  static ExportRequest read(const Options& options);
  // Where the plates lie (m): the points as drawn, or the pose at `at` on the first driver's path.
  std::vector<Eigen::Vector2d> points(const Mechanism& mechanism, const RunControl& control = {}) const;
  // The plates placed at `points`, in `format`.
  std::string plates(const Mechanism& mechanism, const std::vector<Eigen::Vector2d>& points) const;
};

// nbar simulate: the motion under the loads, the free drivers released (forward dynamics).
struct SimulateRequest {
  double to = 0.0;                         // s, the simulated time; 0: the model's (`simulation: {to}`)
  std::optional<double> dt;                // s between rows; unset: to / 100
  double rtol = 1e-8;                      // the integrator's relative tolerance
  long max_steps = 10'000'000;             // integration steps
  std::vector<std::string> columns;        // names or globs; empty: every column
  std::string format = "csv";              // csv, json or table
  std::optional<StopCondition> stop_when;  // "slider.x > 0.2": the run ends where it comes to hold
  AtToggle at_toggle = AtToggle::stop;
  bool rtol_given = false, at_toggle_given = false;  // else the model's `simulation:` may set them
  unsigned threads = 0;                              // 1 or 2; 0: SimulationOptions' default

  // At most this many rows (every row is kept until the run ends).
  static constexpr double kMaxRows = 1e6;

  static const std::vector<OptionRule>& rules();
  // A `dt` that gives more than kMaxRows rows is an OptionError at `dt`.
  static SimulateRequest read(const Options& options);
  static void check_rows(double to, std::optional<double> dt);
  // The options as given (`to` must be).
  SimulationOptions simulation_options() const;
  // The options, each one not given taken from the model's `simulation:` section: an
  // OptionError at `to` when neither gives it, Error(InvalidModel) at the section's
  // `stop_when` when it names no column, an OptionError at `columns` when one of them is none
  // of the table's (all before the run).
  SimulationOptions simulation_options(const Mechanism& mechanism) const;
  // The columns asked for, or an OptionError at `columns` naming the columns there are.
  ResultTable table(const Mechanism& mechanism, const Simulation& simulation) const;
  // The answer in `format`: the JSON (with the statistics, the drift and the events), the text
  // table (`table_width` characters wide, 0: unbounded) followed by an "Event: ..." line per event,
  // or the CSV, rows only (a front-end says the events beside it).
  void write(std::ostream& out, const Mechanism& mechanism, const Simulation& simulation, const ResultTable& table,
             std::size_t table_width) const;
};

// nbar explain: the method step by step at one sample; with `simulate`, the equations of motion
// at the time `at` of the simulation `nbar simulate` runs (its options dt, rtol and
// at_toggle, each not given taken from the model's `simulation:` as simulate does).
struct ExplainRequest {
  SweepSize sweep;
  int step = 0;
  std::string format = "text";  // text, markdown, latex or json; with simulate: text or json
  bool simulate = false;
  double at = 0.0;      // s, with simulate: from 0 to kMaxTime
  SimulateRequest run;  // with simulate: the run's options (its `to` is `at`)

  static constexpr double kMaxTime = 1e6;  // s: the latest time `at` may ask for

  static const std::vector<OptionRule>& rules();
  // OptionError: `at` or a run's option without `simulate`, `simulate` without `at`, `step` or
  // a format other than text and json with `simulate`.
  static ExplainRequest read(const Options& options);
  ExplainOptions explain_options() const;
  // With simulate: the equations of motion at `at` (equations_of_motion_at's errors).
  EquationsOfMotionAt equations_of_motion(const Mechanism& mechanism, const RunControl& control = {}) const;
  // The equations of motion as the answer in `format`: the text, or the JSON.
  void write(std::ostream& out, const Mechanism& mechanism, const EquationsOfMotionAt& equations) const;
};

// A simulation's rows as a sweep's samples (order 2: positions, velocities, accelerations at each
// row's time), for what draws a sweep: the web app's scene, an animation, the report's pictures.
// Every row is a sample, so a frame or a scene's step k is the simulation's row k.
SweepResult simulated_motion(const Simulation& simulation);

// The same as an analysis of the mechanism with no stage but its motion, for what renders an
// Analysis (the report): its sweep is simulated_motion's.
Analysis simulated_analysis(std::shared_ptr<const Mechanism> mechanism, const Simulation& simulation);

// A simulation to draw instead of the sweep (`nbar animate --simulate --to 3`, `nbar report
// --simulate ...`): `simulate` with `nbar simulate`'s options of the run (to, dt, rtol, stop_when,
// at_toggle), read by SimulateRequest's own rules.
struct SimulatedMotionRequest {
  std::optional<SimulateRequest> simulation;  // unset: the sweep

  static const std::vector<OptionRule>& rules();
  // A run's option without `simulate` is an OptionError at that option; `simulate` without `to`
  // takes the model's `simulation:` section, and without either is SimulateRequest's error at `to`
  // when the run's options are resolved.
  static SimulatedMotionRequest read(const Options& options);
};

}  // namespace nbar::request
