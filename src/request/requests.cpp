#include "nbar/request/requests.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "io/explain_writer.hpp"
#include "io/json_text.hpp"
#include "nbar/analysis/columns.hpp"
#include "nbar/analysis/fe_tables.hpp"
#include "nbar/analysis/pose.hpp"
#include "nbar/io/dxf_writer.hpp"
#include "nbar/io/results_writer.hpp"
#include "nbar/render/report.hpp"
#include "request/option_rules.hpp"

namespace nbar::request {

namespace {

using namespace rule_builders;

std::vector<OptionRule> joined(std::vector<std::vector<OptionRule>> groups) {
  std::vector<OptionRule> all;
  for (auto& group : groups)
    for (auto& rule : group) all.push_back(std::move(rule));
  return all;
}

// The rules of a picture's size, labels, traces and title, within `limits`.
std::vector<OptionRule> picture_rules(const PictureLimits& limits, bool with_title = true) {
  std::vector<OptionRule> rules{
      flag("labels", "write the name of every point"),
      names("trace", "points whose paths over the sweep are drawn, comma-separated, e.g. P,Q"),
      integer_rule("width", "picture width in pixels (default " + std::to_string(limits.default_width) + ")",
                   limits.min_width, limits.max_width),
      integer_rule("height", "picture height in pixels (default " + std::to_string(limits.default_height) + ")",
                   limits.min_height, limits.max_height),
  };
  if (with_title) rules.push_back(text("title", "a title at the top left"));
  return rules;
}

Picture read_picture(const Options& options, const std::vector<OptionRule>& rules, const PictureLimits& limits) {
  Picture p;
  p.width = static_cast<int>(read_integer(options, rule_of(rules, "width")).value_or(limits.default_width));
  p.height = static_cast<int>(read_integer(options, rule_of(rules, "height")).value_or(limits.default_height));
  p.labels = read_flag(options, rule_of(rules, "labels"));
  p.trace = read_names(options, rule_of(rules, "trace"));
  if (std::any_of(rules.begin(), rules.end(), [](const OptionRule& r) { return r.key == "title"; }))
    p.title = read_text(options, rule_of(rules, "title")).value_or("");
  return p;
}

std::vector<OptionRule> stress_map_rules(const std::string& what) {
  return {flag("stress", what),
          positive_number("mesh_size",
                          "with {stress}: element edge far from holes, in the model's length unit "
                          "(default: a twentieth of each plate's size)")};
}

std::optional<int> optional_int(std::optional<long long> v) {
  return v ? std::optional<int>(static_cast<int>(*v)) : std::nullopt;
}

}  // namespace

// ------------------------------------------------------------------------------ shared parts

std::vector<OptionRule> SweepSize::rules(bool with_steps) {
  std::vector<OptionRule> rules;
  if (with_steps) {
    rules.push_back(positive_integer("steps", "number of samples, ends included (overrides the model's sweep)"));
    rules.push_back(choice("at_limits",
                           "what the sweep does at a limit of the mechanism, over the model's `at_limits`: stop, or "
                           "reverse (turn back there and rock between the limits)",
                           {"stop", "reverse"}));
    rules.push_back(positive_integer("cycles",
                                     "with {at_limits} reverse: the rocking cycles to run (over the "
                                     "model's `cycles`; each comes back to the start's pose)"));
  }
  rules.push_back(
      positive_integer("max_steps", "the most samples the sweep may have, the model's or {steps} (default " +
                                        std::to_string(kDefaultMaxSweepSamples) +
                                        "; every sample is kept in memory, except by solve's CSV)"));
  return rules;
}

SweepSize SweepSize::read(const Options& options) {
  static const std::vector<OptionRule> rules = SweepSize::rules();
  SweepSize size;
  size.steps = optional_int(read_integer(options, rule_of(rules, "steps")));
  if (const std::optional<std::string> at = read_text(options, rule_of(rules, "at_limits")))
    size.at_limits = *at == "reverse" ? AtLimits::Reverse : AtLimits::Stop;
  size.cycles = optional_int(read_integer(options, rule_of(rules, "cycles")));
  if (size.cycles && *size.cycles > kMaxRockingCycles)
    throw OptionError("cycles",
                      "must be at most " + std::to_string(kMaxRockingCycles) + ", not " + std::to_string(*size.cycles));
  size.max_steps =
      static_cast<int>(read_integer(options, rule_of(rules, "max_steps")).value_or(kDefaultMaxSweepSamples));
  return size;
}

void SweepSize::apply(AnalysisOptions& analysis) const {
  analysis.steps = steps;
  analysis.max_steps = max_steps;
  analysis.at_limits = at_limits;
  analysis.cycles = cycles;
}

render::DrawOptions Picture::draw_options(const Model& model) const {
  render::DrawOptions draw;
  draw.width = width;
  draw.height = height;
  draw.labels = labels;
  draw.title = title;
  try {
    draw.traces = render::trace_points(model, trace);
  } catch (const Error& e) {
    throw OptionError("trace", literal(e.message()));
  }
  return draw;
}

void use_finite_elements(AnalysisOptions& analysis, const Model& model, std::optional<double> mesh_size) {
  analysis.stress_method = StressMethod::fe;
  if (mesh_size) analysis.fe.mesh_size = *mesh_size * model.units.length_scale;
}

int solved_step(const SweepResult& sweep, int step) {
  const int solved = static_cast<int>(sweep.samples.size());
  if (step < 0 || step >= solved)
    throw OptionError("step", std::to_string(step) + " is not a solved step (0 to " + std::to_string(solved - 1) + ")",
                      true);
  return step;
}

// ----------------------------------------------------------------------------------- check

const std::vector<OptionRule>& CheckRequest::rules() {
  static const std::vector<OptionRule> rules = joined({
      {choice("format", "text (default) or json (the same summary as data, in the model's units)", {"text", "json"}),
       rule_of(SweepSize::rules(), "at_limits"), rule_of(SweepSize::rules(), "cycles")},
      SweepSize::rules(false),
  });
  return rules;
}

CheckRequest CheckRequest::read(const Options& options) {
  CheckRequest r;
  r.format = read_text(options, rule_of(rules(), "format")).value_or("text");
  const SweepSize sweep = SweepSize::read(options);  // the same rules for at_limits and cycles
  r.max_steps = sweep.max_steps;
  r.at_limits = sweep.at_limits;
  r.cycles = sweep.cycles;
  return r;
}

std::shared_ptr<const Mechanism> CheckRequest::mechanism(std::shared_ptr<const Mechanism> loaded) const {
  AnalysisOptions options;
  options.at_limits = at_limits;
  options.cycles = cycles;
  return with_sweep_options(std::move(loaded), options);
}

// ----------------------------------------------------------------------------------- solve

const std::vector<OptionRule>& SolveRequest::rules() {
  static const std::vector<OptionRule> rules = joined({
      SweepSize::rules(),
      {integer_rule("order",
                    "highest time derivative: 0 positions, 1 velocities, 2 accelerations (default), 3 jerk, "
                    "up to 5",
                    0, 5),
       choice("format", "csv (default), json, or table (aligned, for reading)", {"csv", "json", "table"}),
       names("columns", "only these columns, comma-separated names or globs, e.g. 'crank,rocker.*,B.v*'"),
       flag("dynamics",
            "add inverse dynamics: the force at every joint, every driver's torque or force, energies "
            "(N, N m, J whatever the length unit; order at least 2)")},
  });
  return rules;
}

SolveRequest SolveRequest::read(const Options& options) {
  SolveRequest r;
  r.sweep = SweepSize::read(options);
  r.order = static_cast<int>(read_integer(options, rule_of(rules(), "order")).value_or(2));
  r.format = read_text(options, rule_of(rules(), "format")).value_or("csv");
  r.columns = read_names(options, rule_of(rules(), "columns"));
  r.dynamics = read_flag(options, rule_of(rules(), "dynamics"));
  return r;
}

AnalysisOptions SolveRequest::analysis_options() const {
  AnalysisOptions options;
  sweep.apply(options);
  options.order = order;
  options.dynamics = dynamics;
  // A pattern that may name `cond` (which of them do needs the mechanism): its estimates are cheap.
  options.condition =
      std::any_of(columns.begin(), columns.end(), [](const std::string& p) { return glob_match(p, "cond"); });
  return options;
}

void SolveRequest::explain_column_error(const Mechanism& mechanism, const std::string& problem) const {
  // A force or torque column asked for without dynamics: say so rather than list the others.
  if (!dynamics && column_needs(mechanism, columns, order, false).dynamics)
    throw OptionError("columns", literal(problem) +
                                     ": the force and torque columns come from the inverse dynamics, add "
                                     "{dynamics}");
  std::string listed;
  for (const std::string& name : column_names(column_catalogue(mechanism, order, dynamics)))
    listed += (listed.empty() ? "" : ", ") + name;
  throw OptionError("columns", literal(problem + "; the columns are: " + listed));
}

// The library's select_columns and TableStream::select say which pattern matched nothing (an
// Error of kind BadInput); the request adds what the user can do about it.
ResultTable SolveRequest::table(const Analysis& analysis) const {
  ResultTable table = result_table(analysis, columns_on_request(*analysis.mechanism));
  if (columns.empty()) return table;
  try {
    return select_columns(table, columns);
  } catch (const Error& e) {
    explain_column_error(*analysis.mechanism, e.message());
  }
}

ColumnTable SolveRequest::columns_of(const Analysis& analysis) const {
  return columns_of(*analysis.mechanism, result_columns(analysis, columns_on_request(*analysis.mechanism)));
}

ColumnTable SolveRequest::columns_of(const Mechanism& mechanism, const ColumnTable& table) const {
  if (columns.empty()) return table;
  try {
    return select_columns(table, columns);
  } catch (const Error& e) {
    explain_column_error(mechanism, e.message());
  }
}

ColumnsOnRequest SolveRequest::columns_on_request(const Mechanism& mechanism) const {
  return nbar::columns_on_request(mechanism, columns);
}

void SolveRequest::select(const Mechanism& mechanism, TableStream& stream) const {
  if (columns.empty()) return;
  try {
    stream.select(columns);
  } catch (const Error& e) {
    explain_column_error(mechanism, e.message());
  }
}

// ---------------------------------------------------------------------------------- stress

const std::vector<OptionRule>& StressRequest::rules() {
  static const std::vector<OptionRule> rules = joined({
      SweepSize::rules(),
      {choice("method",
              "beam (default: quick, beam theory on cross-sections, for slender links between joints) or fe "
              "(plane-stress finite elements: the peaks at pin holes, fillets and in plates)",
              {"beam", "fe"}),
       integer_rule("sections", "beam: cross-sections per link, at least (default 200)", kMinSectionsPerLink,
                    kMaxSectionsPerLink),
       positive_number("mesh_size",
                       "fe: element edge far from holes and corners, in the model's length unit "
                       "(default: a twentieth of each plate's size; finer around holes)"),
       choice("format", "table (default), csv or json", {"table", "csv", "json"}),
       text("section_profile",
            "instead, every section of BODY at one step: N, V, M, sigma, tau, von Mises (with {method} fe: "
            "integrated over cuts of the finite-element field)"),
       integer_rule("step", "the step for {section_profile} (default 0)", 0, kIntMax),
       names("at",
             "fe: the stresses of the {section_profile} body at a point, X,Y (model length unit) or a point's "
             "name; several: X1,Y1,X2,Y2,..."),
       names("along",
             "fe: the stresses along a line of the {section_profile} body, X1,Y1,X2,Y2 or P1,P2 (points' names)"),
       text("around_hole",
            "fe: the stresses around a round hole's edge against the angle: a point at its centre (e.g. A) or its "
            "number from 1, as BODY:HOLE or with {section_profile} BODY"),
       choice("coordinates",
              "where {at} and {along} are given and components point: body (default: x along the link from its "
              "first point, y to its left) or model (the drawing's coordinates)",
              {"body", "model"}),
       text("export_mesh",
            "fe: write each link's mesh and stresses into directory DIR, at {step} or at its peak's step: "
            "BODY-stepK.vtu (VTK, for ParaView), BODY-stepK-nodes.csv and BODY-stepK-elements.csv"),
       positive_number("radius",
                       "with {around_hole}: the stresses on a circle of this radius about the hole's centre (model "
                       "length unit) instead of its edge"),
       integer_rule("samples",
                    "points along {along} or around {radius}, or cuts of an fe {section_profile} (default 101)", 2,
                    100000)},
      {integer_rule("segments_per_hole", "fe: edges around each round hole, at least (default 48)", 8, 1e6),
       positive_number("edge_size",
                       "fe: element edge along holes, arcs and re-entrant corners, at most, in the model's length "
                       "unit (default: 2 pi r / 48 at a hole, scaled down with {mesh_size} below the default size)"),
       flag("converge",
            "fe: refine every plate's mesh, halving its element sizes, until every link's peak changes by less than "
            "{tolerance}; prints each mesh's nodes and peaks"),
       number_rule("tolerance",
                   "with {converge}: the largest change of a peak from one mesh to the next, % (default 1)", 0, 50)},
  });
  return rules;
}

StressRequest StressRequest::read(const Options& options) {
  StressRequest r;
  r.sweep = SweepSize::read(options);
  r.method =
      read_text(options, rule_of(rules(), "method")).value_or("beam") == "fe" ? StressMethod::fe : StressMethod::beam;
  r.sections = static_cast<int>(read_integer(options, rule_of(rules(), "sections")).value_or(200));
  r.mesh_size = read_number(options, rule_of(rules(), "mesh_size"));
  r.format = read_text(options, rule_of(rules(), "format")).value_or("table");
  r.section_profile = read_text(options, rule_of(rules(), "section_profile")).value_or("");
  r.step = optional_int(read_integer(options, rule_of(rules(), "step")));
  r.read_field_query(options);
  if (r.step && r.section_profile.empty() && r.export_mesh.empty())
    throw OptionError("step", "needs {section_profile} or {export_mesh}");
  if (r.mesh_size && r.method != StressMethod::fe)
    throw OptionError("mesh_size", "is the finite elements' element size: give {method} fe too");
  read_fe_mesh_options(options, r);
  return r;
}

void StressRequest::read_field_query(const Options& options) {
  at = read_names(options, rule_of(rules(), "at"));
  along = read_names(options, rule_of(rules(), "along"));
  around_hole = read_text(options, rule_of(rules(), "around_hole")).value_or("");
  const std::optional<std::string> frame = read_text(options, rule_of(rules(), "coordinates"));
  coordinates = frame.value_or("body");
  const std::optional<long long> count = read_integer(options, rule_of(rules(), "samples"));
  samples = static_cast<int>(count.value_or(101));
  export_mesh = read_text(options, rule_of(rules(), "export_mesh")).value_or("");
  if (!export_mesh.empty() && method != StressMethod::fe)
    throw OptionError("export_mesh", "writes the finite-element meshes: give {method} fe too", true);
  radius = read_number(options, rule_of(rules(), "radius"));
  if (radius && around_hole.empty()) throw OptionError("radius", "needs {around_hole}");
  const auto given = [](bool v) { return v ? 1 : 0; };
  const int queries = given(!at.empty()) + given(!along.empty()) + given(!around_hole.empty());
  const char* query_key = !at.empty() ? "at" : !along.empty() ? "along" : "around_hole";
  if (queries > 1) throw OptionError(query_key, "give one of {at}, {along} and {around_hole}");
  if (queries == 1 && method != StressMethod::fe)
    throw OptionError(query_key, "reads the finite-element field: give {method} fe too", true);
  if (const std::size_t colon = around_hole.find(':'); colon != std::string::npos) {
    const std::string body = around_hole.substr(0, colon);
    if (!section_profile.empty() && section_profile != body)
      throw OptionError("around_hole", literal("names body '" + body + "', but ") + "{section_profile} is '" +
                                           literal(section_profile) + "'");
    section_profile = body;
    around_hole = around_hole.substr(colon + 1);
  }
  if (queries == 1 && section_profile.empty())
    throw OptionError(query_key, "needs the body: give {section_profile} BODY");
  if (frame && at.empty() && along.empty()) throw OptionError("coordinates", "applies to {at} and {along}");
  if (count && along.empty() && !radius && !(method == StressMethod::fe && !section_profile.empty() && queries == 0))
    throw OptionError("samples", "counts the points of {along} or the cuts of a {method} fe {section_profile}");
}

void StressRequest::read_fe_mesh_options(const Options& options, StressRequest& r) {
  r.segments_per_hole = optional_int(read_integer(options, rule_of(rules(), "segments_per_hole")));
  r.edge_size = read_number(options, rule_of(rules(), "edge_size"));
  r.converge = read_flag(options, rule_of(rules(), "converge"));
  const std::optional<double> tolerance = read_number(options, rule_of(rules(), "tolerance"));
  if (tolerance && !(*tolerance > 0))
    throw OptionError("tolerance", "must be above 0 %, not " + number_text(*tolerance));
  if (tolerance) r.tolerance = *tolerance / 100;
  for (const char* key : {"segments_per_hole", "edge_size", "converge"})
    if (options.has(key) && r.method != StressMethod::fe)
      throw OptionError(key, "is for finite elements: give {method} fe too");
  if (tolerance && !r.converge) throw OptionError("tolerance", "needs {converge}");
}

FeConvergence StressRequest::convergence(const Analysis& analysis, const RunControl& control) const {
  if (!analysis.stress || !analysis.stress->fe || !analysis.dynamics)
    throw Error(ErrorKind::BadInput, "a convergence study needs the finite-element stresses of the analysis");
  return converge_fe_peaks(analysis.dynamics->solver, analysis.stress->fe->options(), analysis.stress->fe_peaks,
                           analysis.sweep, analysis.dynamics->samples, tolerance, 8, control);
}

AnalysisOptions StressRequest::analysis_options(const Model& model) const {
  AnalysisOptions options;
  sweep.apply(options);
  options.stress = true;
  options.sections = sections;
  if (method == StressMethod::fe) {
    use_finite_elements(options, model, mesh_size);
    if (segments_per_hole) options.fe.segments_per_hole = *segments_per_hole;
    if (edge_size) options.fe.edge_size = *edge_size * model.units.length_scale;
  }
  return options;
}

ResultTable StressRequest::section_profile_table(const Analysis& analysis) const {
  const int body = analysis.model().find_body(section_profile);
  if (body < 0) throw OptionError("section_profile", literal("'" + section_profile + "' is not a body of the model"));
  if (method == StressMethod::fe) {
    if (!analysis.stress || !analysis.stress->fe || !analysis.stress->fe->analysed(body))
      throw OptionError("section_profile", literal("'" + section_profile + "' has no plate to analyse"));
    return field_query_table(analysis, body, solved_step(analysis.sweep, step.value_or(0)));
  }
  if (!analysis.stress || !analysis.stress->links || !analysis.stress->links->analysed(body))
    throw OptionError("section_profile", literal("'" + section_profile + "' has no shape to cut"));
  return nbar::section_profile_table(analysis, body, solved_step(analysis.sweep, step.value_or(0)));
}

std::vector<StressRequest::MeshExport> StressRequest::mesh_exports(const Analysis& analysis) const {
  std::vector<MeshExport> out;
  if (export_mesh.empty() || !analysis.stress || !analysis.stress->fe) return out;
  const Model& model = analysis.model();
  const int only = section_profile.empty() ? -1 : model.find_body(section_profile);
  if (!section_profile.empty() && (only < 0 || !analysis.stress->fe->analysed(only)))
    throw OptionError("section_profile", literal("'" + section_profile + "' has no plate to export"));
  const std::optional<int> at = step ? std::optional<int>(solved_step(analysis.sweep, *step)) : std::nullopt;
  for (const FePeak& peak : analysis.stress->fe_peaks) {
    if (only >= 0 && peak.body != only) continue;
    MeshExport e;
    e.body = peak.body;
    e.step = at.value_or(std::max(peak.step, 0));
    e.stem = model.bodies[peak.body].name + "-step" + std::to_string(e.step);
    out.push_back(std::move(e));
  }
  return out;
}

namespace {

std::optional<double> parse_number(const std::string& text) {
  try {
    std::size_t used = 0;
    const double v = std::stod(text, &used);
    if (used == text.size() && std::isfinite(v)) return v;
  } catch (const std::exception&) {
  }
  return std::nullopt;
}

// The points of `key`'s values in `frame` (model units): pairs of numbers, or points' names.
std::vector<Eigen::Vector2d> query_points(const Model& model, int body, QueryFrame frame,
                                          const std::vector<std::string>& values, const std::string& key) {
  std::vector<Eigen::Vector2d> out;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (const int point = model.find_point(values[i]); point >= 0) {
      out.push_back(query_point(model, body, frame, model.points[point].position));
      continue;
    }
    const std::optional<double> x = parse_number(values[i]);
    const std::optional<double> y = i + 1 < values.size() ? parse_number(values[i + 1]) : std::nullopt;
    if (!x || !y)
      throw OptionError(key, literal("'" + values[i] + "' is neither a point of the model nor the X of an X,Y pair"));
    out.emplace_back(*x, *y);
    ++i;
  }
  return out;
}

// The hole named by `text`: a point of the model inside one of the body's round holes, or the
// hole's number from 1.
int hole_of(const Model& model, int body, const std::string& text) {
  if (const int point = model.find_point(text); point >= 0) {
    const int hole = hole_at_point(model, body, point);
    if (hole < 0)
      throw OptionError("around_hole",
                        literal("point '" + text + "' is not in a round hole of '" + model.bodies[body].name + "'"));
    return hole;
  }
  const std::optional<double> number = parse_number(text);
  const int holes = model.bodies[body].shape ? static_cast<int>(model.bodies[body].shape->circle_holes.size()) : 0;
  if (!number || *number != std::floor(*number) || *number < 1 || *number > holes)
    throw OptionError("around_hole",
                      literal("'" + text + "' is neither a point in a round hole of '" + model.bodies[body].name +
                              "' nor a hole's number (" +
                              (holes == 0 ? std::string("it has none") : "1 to " + std::to_string(holes)) + ")"));
  return static_cast<int>(*number) - 1;
}

}  // namespace

// The core's errors about a point off the plate become errors at the option that gave it.
ResultTable StressRequest::field_query_table(const Analysis& analysis, int body, int step) const {
  const Model& model = analysis.model();
  const QueryFrame frame = coordinates == "model" ? QueryFrame::model : QueryFrame::body;
  const std::string key = !at.empty() ? "at" : !along.empty() ? "along" : "section_profile";
  try {
    if (!around_hole.empty())
      return fe_hole_table(analysis, body, step, hole_of(model, body, around_hole), frame, radius, samples);
    if (!at.empty()) return fe_points_table(analysis, body, step, query_points(model, body, frame, at, "at"), frame);
    if (!along.empty()) {
      const std::vector<Eigen::Vector2d> ends = query_points(model, body, frame, along, "along");
      if (ends.size() != 2) throw OptionError("along", "must be two points: X1,Y1,X2,Y2 or P1,P2");
      return fe_line_table(analysis, body, step, ends[0], ends[1], samples, frame);
    }
    return fe_section_table(analysis, body, step, samples);
  } catch (const OptionError&) {
    throw;
  } catch (const Error& e) {
    if (e.kind() != ErrorKind::BadInput) throw;
    throw OptionError(key, literal(e.message()));
  }
}

// ------------------------------------------------------------------------------ stress probe

const std::vector<OptionRule>& StressProbeRequest::rules() {
  static const std::vector<OptionRule> rules = joined({
      SweepSize::rules(),
      {integer_rule("step", "the step drawn (default 0)", 0, kIntMax),
       number_rule("x", "the point in the drawing at {step}: x, in the model's coordinates and length unit",
                   -std::numeric_limits<double>::max(), std::numeric_limits<double>::max()),
       number_rule("y", "the point in the drawing at {step}: y, in the model's coordinates and length unit",
                   -std::numeric_limits<double>::max(), std::numeric_limits<double>::max()),
       positive_number("mesh_size",
                       "element edge far from holes and corners, in the model's length unit (default: a "
                       "twentieth of each plate's size; finer around holes), as the stress map's")},
  });
  return rules;
}

StressProbeRequest StressProbeRequest::read(const Options& options) {
  StressProbeRequest r;
  r.sweep = SweepSize::read(options);
  r.mesh_size = read_number(options, rule_of(rules(), "mesh_size"));
  r.step = optional_int(read_integer(options, rule_of(rules(), "step"))).value_or(0);
  for (int k = 0; k < 2; ++k) {
    const char* key = k == 0 ? "x" : "y";
    const std::optional<double> v = read_number(options, rule_of(rules(), key));
    if (!v) throw OptionError(key, "is needed: the point of the drawing to read the stress at, {x} and {y}");
    r.at[k] = *v;
  }
  return r;
}

AnalysisOptions StressProbeRequest::analysis_options(const Model& model) const {
  AnalysisOptions options;
  sweep.apply(options);
  options.stress = true;
  use_finite_elements(options, model, mesh_size);
  return options;
}

StressProbeRequest::Answer StressProbeRequest::probe(const Analysis& analysis) const {
  const Model& model = analysis.model();
  Answer answer;
  answer.link = plate_under(analysis, solved_step(analysis.sweep, step), at * model.units.length_scale);
  if (answer.link)
    answer.stresses = fe_points_table(analysis, answer.link->body, step, {answer.link->at}, QueryFrame::model);
  return answer;
}

// ------------------------------------------------------------------------------------ draw

const std::vector<OptionRule>& DrawRequest::rules() {
  static const std::vector<OptionRule> rules = joined({
      {choice("format", "svg (default) or png; the web app's scene", {"svg", "png", "scene"}),
       integer_rule("step",
                    "draw this sample of the sweep (default 0, the start, unless every point lies on one line "
                    "there: then the most open pose)",
                    0, kIntMax),
       number_rule("at", "draw where the first driver has this value (model units; a time for time laws)",
                   -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity())},
      SweepSize::rules(),
      picture_rules(kDrawingLimits),
      stress_map_rules("colour every link with a shape by its von Mises stress at the drawn step (finite elements, "
                       "as `nbar stress {method} fe`), with a colour legend and each link's peak marked"),
  });
  return rules;
}

DrawRequest DrawRequest::read(const Options& options) {
  DrawRequest r;
  r.format = read_text(options, rule_of(rules(), "format")).value_or("svg");
  r.step = optional_int(read_integer(options, rule_of(rules(), "step")));
  r.at = read_number(options, rule_of(rules(), "at"));
  r.sweep = SweepSize::read(options);
  r.picture = read_picture(options, rules(), kDrawingLimits);
  r.stress = read_flag(options, rule_of(rules(), "stress"));
  r.mesh_size = read_number(options, rule_of(rules(), "mesh_size"));
  if (r.step && r.at) throw OptionError("at", "give {step} or {at}, not both");
  if (r.stress && r.at)
    throw OptionError("at", "{stress} colours a solved step of the sweep: give {step} instead of {at}");
  if (r.format == "scene" && r.at) throw OptionError("at", "a scene is drawn at a solved step: give {step}, not {at}");
  return r;
}

AnalysisOptions DrawRequest::analysis_options(const Model& model) const {
  AnalysisOptions options;
  sweep.apply(options);
  options.order = 0;  // positions are all a picture needs
  if (stress) {
    options.stress = true;
    use_finite_elements(options, model, mesh_size);
  }
  return options;
}

int DrawRequest::drawn_step(const Analysis& analysis) const {
  return solved_step(analysis.sweep, step.value_or(render::default_drawn_step(*analysis.mechanism, analysis.sweep)));
}

DrawRequest::Pose DrawRequest::pose(const Analysis& analysis, const RunControl& control) const {
  const Mechanism& mech = *analysis.mechanism;
  if (at) return {std::nullopt, render::sample_points(mech, pose_at(mech, *at, 0, control))};
  const int drawn = drawn_step(analysis);
  return {drawn, render::sample_points(mech, analysis.sweep.samples[static_cast<std::size_t>(drawn)])};
}

// --------------------------------------------------------------------------------- animate

const std::vector<OptionRule>& AnimateRequest::rules() {
  static const std::vector<OptionRule> rules = joined({
      {choice("format", "gif, svg, html (default) or mp4 (with ffmpeg)", {"gif", "svg", "html", "mp4"}),
       number_rule("fps", "frames per second (default 24)", 0.1, 120.0),
       integer_rule("frames", "number of frames, evenly spaced over the sweep (default: every sample, at most 120)", 1,
                    100000)},
      SweepSize::rules(),
      picture_rules(kAnimationLimits),
      stress_map_rules("GIF and MP4: colour every link with a shape by its von Mises stress in every frame (finite "
                       "elements, one colour scale for the whole sweep), each link's peak marked"),
  });
  return rules;
}

AnimateRequest AnimateRequest::read(const Options& options) {
  AnimateRequest r;
  r.format = read_text(options, rule_of(rules(), "format")).value_or("html");
  r.fps = read_number(options, rule_of(rules(), "fps")).value_or(24.0);
  r.frames = optional_int(read_integer(options, rule_of(rules(), "frames")));
  r.sweep = SweepSize::read(options);
  r.picture = read_picture(options, rules(), kAnimationLimits);
  r.stress = read_flag(options, rule_of(rules(), "stress"));
  r.mesh_size = read_number(options, rule_of(rules(), "mesh_size"));
  return r;
}

AnalysisOptions AnimateRequest::analysis_options(const Model& model) const {
  AnalysisOptions options;
  sweep.apply(options);
  options.order = 0;
  if (stress) {
    options.stress = true;
    use_finite_elements(options, model, mesh_size);
  }
  return options;
}

// ------------------------------------------------------------------------------------ plot

const std::vector<OptionRule>& PlotRequest::rules() {
  static const std::vector<OptionRule> rules = [] {
    OptionRule y_range = rule("y_range", OptionKind::Numbers, "a fixed y range LO,HI instead of one covering the data");
    y_range.count = 2;
    return joined({
        {choice("format", "svg (default) or png", {"svg", "png"}),
         names("y", "columns to plot: names or globs, comma-separated, e.g. 'rocker.omega,B.v*'"),
         text("x", "the column along the x axis (default: the first driver's, or t when a driver follows a time law)"),
         integer_rule("order", "highest time derivative to solve, 0 to 5 (default: 2, or what the columns need)", 0, 5),
         flag("dynamics",
              "add the inverse-dynamics columns (joint forces, driver torques and forces, energies); on by "
              "itself when a column asked for needs it"),
         y_range, text("title", "the title at the top (default: the model's name)"),
         integer_rule("width", "picture width in pixels (default 900)", kPlotLimits.min_width, kPlotLimits.max_width),
         integer_rule("height", "picture height in pixels (default 520)", kPlotLimits.min_height,
                      kPlotLimits.max_height)},
        SweepSize::rules(),
    });
  }();
  return rules;
}

PlotRequest PlotRequest::read(const Options& options) {
  PlotRequest r;
  r.format = read_text(options, rule_of(rules(), "format")).value_or("svg");
  r.y = read_names(options, rule_of(rules(), "y"));
  if (r.y.empty()) throw OptionError("y", "missing: the columns to plot");
  r.x = read_text(options, rule_of(rules(), "x")).value_or("");
  r.order = optional_int(read_integer(options, rule_of(rules(), "order")));
  r.dynamics = read_flag(options, rule_of(rules(), "dynamics"));
  const std::vector<double> range = read_numbers(options, rule_of(rules(), "y_range"));
  if (!range.empty()) {
    if (!(std::abs(range[0]) <= 1e300 && std::abs(range[1]) <= 1e300 && range[0] < range[1]))
      throw OptionError("y_range", "LO and HI must be finite numbers with LO < HI");
    r.y_range = std::make_pair(range[0], range[1]);
  }
  r.title = read_text(options, rule_of(rules(), "title")).value_or("");
  r.width = static_cast<int>(read_integer(options, rule_of(rules(), "width")).value_or(kPlotLimits.default_width));
  r.height = static_cast<int>(read_integer(options, rule_of(rules(), "height")).value_or(kPlotLimits.default_height));
  r.sweep = SweepSize::read(options);
  return r;
}

AnalysisOptions PlotRequest::analysis_options(const Mechanism& mechanism) const {
  const std::string x_pattern = x.empty() ? default_abscissa(mechanism.model()) : x;
  std::vector<std::string> patterns = y;
  patterns.push_back(x_pattern);
  const ColumnNeeds needs = column_needs(mechanism, patterns, order, dynamics);
  if (needs.unmatched >= 0)
    throw OptionError(needs.unmatched < static_cast<int>(y.size()) ? "y" : "x", literal(needs.message));
  AnalysisOptions options;
  sweep.apply(options);
  options.order = needs.order;
  options.dynamics = needs.dynamics;
  options.condition = needs.condition;
  return options;
}

render::PlotSpec PlotRequest::plot(const Analysis& analysis, const std::string& fallback_title) const {
  const Model& m = analysis.model();
  const std::string x_pattern = x.empty() ? default_abscissa(m) : x;
  std::vector<std::string> patterns = y;
  patterns.push_back(x_pattern);
  const ResultTable table = result_table(analysis, nbar::columns_on_request(*analysis.mechanism, patterns));
  const ResultTable x_column = select_columns(table, {x_pattern});
  if (x_column.columns.size() != 1) {
    std::string listed;
    for (const std::string& c : x_column.columns) listed += (listed.empty() ? "" : ", ") + c;
    throw OptionError("x", literal("'" + x_pattern + "' matches " + std::to_string(x_column.columns.size()) +
                                   " columns (" + listed + "); name one"));
  }
  render::PlotSpec spec;
  spec.title = !title.empty() ? title : !m.name.empty() ? m.name : fallback_title;
  if (y_range) {
    spec.y_lo = y_range->first;
    spec.y_hi = y_range->second;
  }
  spec.width = width;
  spec.height = height;
  render::set_plot_data(spec, x_column, select_columns(table, y));
  return spec;
}

// ---------------------------------------------------------------------------------- report

const std::vector<OptionRule>& ReportRequest::rules() {
  static const std::vector<OptionRule> rules = joined({
      SweepSize::rules(),
      {integer_rule("frames", "animation frames (default 72)", render::kMinReportFrames, render::kMaxReportFrames),
       choice("stress_method",
              "the stresses' method, as `nbar stress {method}`: beam (default) or fe (links coloured by their "
              "finite-element von Mises stress)",
              {"beam", "fe"}),
       positive_number("mesh_size",
                       "with {stress_method} fe: element edge far from holes, in the model's length unit")},
  });
  return rules;
}

ReportRequest ReportRequest::read(const Options& options) {
  ReportRequest r;
  r.sweep = SweepSize::read(options);
  r.frames = static_cast<int>(read_integer(options, rule_of(rules(), "frames")).value_or(72));
  r.stress_method = read_text(options, rule_of(rules(), "stress_method")).value_or("beam") == "fe" ? StressMethod::fe
                                                                                                   : StressMethod::beam;
  r.mesh_size = read_number(options, rule_of(rules(), "mesh_size"));
  if (r.mesh_size && r.stress_method != StressMethod::fe)
    throw OptionError("mesh_size", "is the finite elements' element size: give {stress_method} fe too");
  return r;
}

AnalysisOptions ReportRequest::analysis_options(const ModelSummary& summary, const Model& model) const {
  AnalysisOptions options = render::report_analysis_options(summary);
  sweep.apply(options);
  if (stress_method == StressMethod::fe) use_finite_elements(options, model, mesh_size);
  return options;
}

// --------------------------------------------------------------------------------- explain

namespace {
// The options of the run whose equations of motion `explain --simulate` shows.
const std::vector<std::string> kExplainRunKeys = {"dt", "rtol", "at_toggle"};
}  // namespace

const std::vector<OptionRule>& ExplainRequest::rules() {
  static const std::vector<OptionRule> rules = [] {
    std::vector<OptionRule> out = joined({
        {integer_rule("step", "the sample of the sweep to explain (default 0, the start)", 0, kIntMax)},
        SweepSize::rules(),
        {choice("format",
                "text (default), markdown (with LaTeX maths, for Jupyter), latex or json (with {simulate}: text or "
                "json)",
                {"text", "markdown", "latex", "json"}),
         flag("simulate",
              "the equations of motion of the simulation (as `nbar simulate`: M, Phi_q, Q by origin, gamma and the "
              "accelerations and multipliers they give) at the time {at}, instead of the sweep's method"),
         number_rule("at", "with {simulate}: the time, s, from 0 (the start) to 1e6", 0.0, kMaxTime)},
    });
    // The run's options, said as options of the run to {at}.
    for (const std::string& key : kExplainRunKeys) {
      OptionRule rule = rule_of(SimulateRequest::rules(), key);
      if (key == "dt") rule.help = "time between the rows of the run to {at}, s (default: a hundredth of {at})";
      rule.help = "with {simulate}: " + rule.help;
      out.push_back(rule);
    }
    return out;
  }();
  return rules;
}

ExplainRequest ExplainRequest::read(const Options& options) {
  ExplainRequest r;
  r.step = static_cast<int>(read_integer(options, rule_of(rules(), "step")).value_or(0));
  r.sweep = SweepSize::read(options);
  r.format = read_text(options, rule_of(rules(), "format")).value_or("text");
  r.simulate = read_flag(options, rule_of(rules(), "simulate"));
  const std::optional<double> at = read_number(options, rule_of(rules(), "at"));
  Options run(options.text_values());
  for (const std::string& key : kExplainRunKeys)
    if (const Value* value = options.find(key)) {
      if (!r.simulate) throw OptionError(key, "is an option of a simulation: give {simulate} too");
      run.set(key, *value);
    }
  if (!r.simulate) {
    if (at) throw OptionError("at", "is the time of a simulation's equations of motion: give {simulate} too");
    return r;
  }
  if (!at) throw OptionError("at", "give the time of the simulation to explain, in s, e.g. {simulate} {at} 0.5");
  if (options.find("step")) throw OptionError("step", "is a sample of the sweep; with {simulate} give {at}");
  if (r.format != "text" && r.format != "json")
    throw OptionError("format", "with {simulate} must be text or json, not '" + literal(r.format) + "'");
  r.at = *at;
  r.run = SimulateRequest::read(run);
  return r;
}

ExplainOptions ExplainRequest::explain_options() const {
  ExplainOptions options;
  options.step = step;
  options.steps = sweep.steps;
  options.max_steps = sweep.max_steps;
  return options;
}

// The run to `at` is `nbar simulate --to at` with the same options (the model's `simulation:`
// filling in what is not given); at 0 it does not integrate, and only its other options count.
EquationsOfMotionAt ExplainRequest::equations_of_motion(const Mechanism& mechanism, const RunControl& control) const {
  SimulateRequest to_at = run;
  to_at.to = at > 0.0 ? at : 1.0;
  if (at > 0.0) SimulateRequest::check_rows(to_at.to, to_at.dt);
  return equations_of_motion_at(mechanism, at, to_at.simulation_options(mechanism), control);
}

void ExplainRequest::write(std::ostream& out, const Mechanism& mechanism, const EquationsOfMotionAt& equations) const {
  if (format == "json")
    out << io::json_text(io::equations_of_motion_json(mechanism, equations), 2) << '\n';
  else
    out << render_equations_of_motion(mechanism, equations);
}

// ---------------------------------------------------------------------------------- export

const std::vector<OptionRule>& ExportRequest::rules() {
  static const std::vector<OptionRule> rules{
      choice("format",
             "dxf (AutoCAD R12 ASCII DXF, in the model's length unit, one layer per link) or svg (default: one "
             "group per link, true size in mm)",
             {"svg", "dxf"}),
      number_rule("at",
                  "place the plates where the first driver has this value (model units; a time for time laws); "
                  "default: as drawn in the model file",
                  -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()),
  };
  return rules;
}

ExportRequest ExportRequest::read(const Options& options) {
  ExportRequest r;
  r.format = read_text(options, rule_of(rules(), "format")).value_or("svg");
  r.at = read_number(options, rule_of(rules(), "at"));
  return r;
}

std::vector<Eigen::Vector2d> ExportRequest::points(const Mechanism& mechanism, const RunControl& control) const {
  if (at) return point_positions(mechanism, pose_at(mechanism, *at, 0, control).taylor.col(0));
  std::vector<Eigen::Vector2d> drawn;
  for (const Point& p : mechanism.model().points) drawn.push_back(p.position);
  return drawn;
}

std::string ExportRequest::plates(const Mechanism& mechanism, const std::vector<Eigen::Vector2d>& points) const {
  return format == "dxf" ? io::cutting_dxf(mechanism, points) : io::cutting_svg(mechanism, points);
}

// ----------------------------------------------------------------------------------- simulate

const std::vector<OptionRule>& SimulateRequest::rules() {
  static const std::vector<OptionRule> rules = {
      positive_number("to", "the simulated time, s (required unless the model's `simulation:` gives it)"),
      positive_number("dt", "time between output rows, s (default: a hundredth of --to)"),
      number_rule("rtol", "relative tolerance of the integrator (default 1e-8), from 1e-14 to 0.01", 1e-14, 0.01),
      positive_integer("max_steps", "most integration steps before the run stops (default 10000000)"),
      choice("format", "csv (default), json (with the step statistics and constraint drift), or table",
             {"csv", "json", "table"}),
      names("columns", "only these columns, comma-separated names or globs, e.g. 'crank,energy.*'"),
      text("stop_when",
           "end the run where a column crosses a value, in the column's unit, e.g. 'slider.x > 200' "
           "(located to 1e-12 s)"),
      choice("at_toggle",
             "where the constraints become singular (a toggle): stop (default), or reverse every speed and go on",
             {"stop", "reverse"}),
      integer_rule("threads",
                   "1: the whole run on one thread; 2 (default where the machine has two cores): the output rows "
                   "made on a second while the integration goes on (the answer is the same, to the last bit)",
                   1, 2),
  };
  return rules;
}

SimulateRequest SimulateRequest::read(const Options& options) {
  SimulateRequest r;
  r.to = read_number(options, rule_of(rules(), "to")).value_or(0.0);
  r.dt = read_number(options, rule_of(rules(), "dt"));
  if (r.to > 0.0) check_rows(r.to, r.dt);
  const std::optional<double> rtol = read_number(options, rule_of(rules(), "rtol"));
  r.rtol = rtol.value_or(1e-8);
  r.rtol_given = rtol.has_value();
  r.max_steps = static_cast<long>(read_integer(options, rule_of(rules(), "max_steps")).value_or(10'000'000));
  r.format = read_text(options, rule_of(rules(), "format")).value_or("csv");
  r.columns = read_names(options, rule_of(rules(), "columns"));
  if (const std::optional<std::string> stop = read_text(options, rule_of(rules(), "stop_when"))) {
    r.stop_when = parse_stop_condition(*stop);
    if (!r.stop_when)
      throw OptionError("stop_when", "must be a column, < or > and a number, e.g. 'slider.x > 200', not " +
                                         literal("'" + *stop + "'"));
  }
  const std::optional<std::string> at_toggle = read_text(options, rule_of(rules(), "at_toggle"));
  r.at_toggle = at_toggle.value_or("stop") == "reverse" ? AtToggle::reverse : AtToggle::stop;
  r.at_toggle_given = at_toggle.has_value();
  r.threads = static_cast<unsigned>(read_integer(options, rule_of(rules(), "threads")).value_or(0));
  return r;
}

void SimulateRequest::check_rows(double to, std::optional<double> dt) {
  if (to / dt.value_or(to / 100) + 1 > kMaxRows)
    throw OptionError(
        "dt", "gives more than " + number_text(kMaxRows) + " rows over " + number_text(to) + " s; give a larger {dt}");
}

// The options with what the command leaves unset taken from the model's `simulation:` section.
// A stop condition from the model names a column checked here, so that a typo is shown at its
// line in the file.
SimulationOptions SimulateRequest::simulation_options(const Mechanism& mechanism) const {
  const SimulationSpec& spec = mechanism.model().simulation;
  SimulationOptions options = simulation_options();
  if (!(to > 0.0)) {
    if (!spec.end_time) throw OptionError("to", "give the simulated time in seconds, e.g. {to} 2");
    options.end_time = *spec.end_time;
    if (!dt && spec.output_step) options.output_step = *spec.output_step;
    check_rows(options.end_time, options.output_step > 0 ? std::optional<double>(options.output_step) : std::nullopt);
  } else if (!dt && spec.output_step) {
    options.output_step = *spec.output_step;
    check_rows(options.end_time, options.output_step);
  }
  if (!rtol_given && spec.relative_tolerance) options.relative_tolerance = *spec.relative_tolerance;
  if (!at_toggle_given && spec.reverse_at_toggle)
    options.at_toggle = *spec.reverse_at_toggle ? AtToggle::reverse : AtToggle::stop;
  if (!stop_when && spec.stop_when) {
    options.stop_when = parse_stop_condition(*spec.stop_when);
    const std::vector<std::string> names = simulation_table(mechanism, Simulation{}).columns;
    if (std::find(names.begin(), names.end(), options.stop_when->column) == names.end()) {
      const std::string& column = options.stop_when->column;
      const std::string owner = column.substr(0, column.find('.'));
      std::string listed;
      for (const std::string& name : names)
        if (name.substr(0, name.find('.')) == owner) listed += (listed.empty() ? "" : ", ") + name;
      throw Error(ErrorKind::InvalidModel,
                  "the stop condition '" + *spec.stop_when + "' names no column '" + column + "'" +
                      (listed.empty() ? std::string(" (the columns are those of `nbar simulate`'s table)")
                                      : "; the columns of " + owner + " are " + listed),
                  {EntityRef::Kind::Simulation, 1, -1});
    }
  }
  // The columns asked for are checked before the run, not after it: a typo in --columns waited
  // for the whole run (7 s for a long one) to be told. Their names do not depend on the rows.
  if (!columns.empty()) table(mechanism, Simulation{});
  return options;
}

SimulationOptions SimulateRequest::simulation_options() const {
  SimulationOptions options;
  options.end_time = to;
  options.output_step = dt.value_or(0.0);
  options.relative_tolerance = rtol;
  options.max_steps = max_steps;
  options.stop_when = stop_when;
  options.at_toggle = at_toggle;
  options.threads = threads;
  return options;
}

ResultTable SimulateRequest::table(const Mechanism& mechanism, const Simulation& simulation) const {
  ResultTable table = simulation_table(mechanism, simulation);
  if (columns.empty()) return table;
  try {
    return select_columns(table, columns);
  } catch (const Error& e) {
    throw OptionError("columns", literal(e.message()));
  }
}

void SimulateRequest::write(std::ostream& out, const Mechanism& mechanism, const Simulation& simulation,
                            const ResultTable& table, std::size_t table_width) const {
  if (format == "json") {
    io::write_simulation_json(out, mechanism, simulation, table);
  } else if (format == "table") {
    io::write_text_table(out, table, table_width);
    for (const SimulationEvent& event : simulation.events) out << "Event: " << event.message << '\n';
    if (!simulation.complete)
      out << "Stopped early: " << simulation.stop_reason << " (the last row is at "
          << number_text(simulation.time_reached()) << " s)\n";
  } else {
    io::write_csv(out, table);
  }
}

SweepResult simulated_motion(const Simulation& simulation) {
  SweepResult motion;
  motion.order = 2;
  motion.samples = simulation.samples;
  motion.complete = simulation.complete;
  motion.stop_reason = simulation.stop_reason;
  motion.solved = motion.samples.size();
  return motion;
}

Analysis simulated_analysis(std::shared_ptr<const Mechanism> mechanism, const Simulation& simulation) {
  Analysis analysis;
  analysis.mechanism = std::move(mechanism);
  analysis.sweep = simulated_motion(simulation);
  return analysis;
}

namespace {
// The options of a run that a drawn motion takes from `nbar simulate` (not its table's).
const std::vector<std::string> kRunKeys = {"to", "dt", "rtol", "stop_when", "at_toggle"};
}  // namespace

const std::vector<OptionRule>& SimulatedMotionRequest::rules() {
  static const std::vector<OptionRule> rules = [] {
    std::vector<OptionRule> out = {
        flag("simulate",
             "the motion under the loads with the free drivers released (as `nbar simulate`), not the "
             "sweep; give {to}")};
    for (const std::string& key : kRunKeys) out.push_back(rule_of(SimulateRequest::rules(), key));
    return out;
  }();
  return rules;
}

SimulatedMotionRequest SimulatedMotionRequest::read(const Options& options) {
  SimulatedMotionRequest r;
  const bool simulate = read_flag(options, rule_of(rules(), "simulate"));
  Options run(options.text_values());
  for (const std::string& key : kRunKeys) {
    const Value* value = options.find(key);
    if (!value) continue;
    if (!simulate) throw OptionError(key, "is an option of a simulation: give {simulate} too");
    run.set(key, *value);
  }
  if (simulate) r.simulation = SimulateRequest::read(run);
  return r;
}

}  // namespace nbar::request
