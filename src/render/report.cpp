#include "nbar/render/report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "nbar/analysis/columns.hpp"
#include "nbar/dynamics/dynamics_table.hpp"
#include "nbar/kinematics/table.hpp"
#include "nbar/model/units.hpp"
#include "nbar/render/animation.hpp"
#include "nbar/render/drawing.hpp"
#include "nbar/render/plot.hpp"
#include "nbar/render/stress_map.hpp"
#include "nbar/stress/link_stress.hpp"
#include "nbar/version.hpp"

namespace nbar::render {

namespace {

constexpr const char* kStyle = R"(
body { font-family: system-ui, sans-serif; color: #222; margin: 0 auto; max-width: 980px; padding: 0 12px 40px; line-height: 1.45; }
h1 { font-size: 1.6em; margin: 18px 0 4px; }
h2 { font-size: 1.25em; border-bottom: 1px solid #ccc; padding-bottom: 3px; margin-top: 28px; }
p.meta { color: #666; margin-top: 0; }
.scroll { overflow-x: auto; }
table { border-collapse: collapse; margin: 8px 0; font-size: 0.92em; }
th, td { border: 1px solid #ddd; padding: 3px 8px; text-align: left; vertical-align: top; }
th { background: #f4f4f4; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
svg { width: 100%; height: auto; display: block; }
iframe { width: 100%; height: 640px; border: 1px solid #ddd; display: block; }
.warn { color: #a40; }
.narrow { display: none; }
.peaks { display: grid; grid-template-columns: repeat(auto-fit, minmax(min(100%, 400px), 1fr)); gap: 12px; }
.peaks figure { margin: 0; }
.peaks figcaption { font-size: 0.92em; color: #444; }
table.facts th { width: 11em; }
@media (max-width: 600px) {
  .wide { display: none; }
  .narrow { display: block; }
  body { padding: 0 8px 32px; }
  table { font-size: 0.82em; }
  th, td { padding: 2px 5px; }
  table.facts th { width: auto; }
}
)";

// The animation's frame as tall as the page in it, at any width: the page has a fixed part
// (title, controls) and a drawing that scales with the width.
constexpr const char* kFitFrames = R"(<script>
(function () {
  function fit() {
    document.querySelectorAll("iframe").forEach(function (f) {
      var main = f.contentDocument && f.contentDocument.querySelector("main");
      if (main) f.style.height = Math.ceil(main.getBoundingClientRect().height) + 4 + "px";
    });
  }
  window.addEventListener("load", fit);
  window.addEventListener("resize", fit);
  document.querySelectorAll("iframe").forEach(function (f) { f.addEventListener("load", fit); });
})();
</script>
)";

// Phone screens get pictures drawn for their width, so that the text in them stays readable
// (a 900 px plot shrunk to 370 px would have 5 px text).
constexpr int kNarrowWidth = 440;

std::string esc(const std::string& s) { return xml_escape(s); }

std::string short_number(double v, int digits = 4) { return fmt::format("{:.{}g}", v + 0.0, digits); }

std::vector<double> column(const ResultTable& t, const std::string& name) {
  const auto it = std::find(t.columns.begin(), t.columns.end(), name);
  std::vector<double> out;
  if (it == t.columns.end()) return out;
  const std::size_t c = static_cast<std::size_t>(it - t.columns.begin());
  for (const auto& row : t.rows) out.push_back(row[c]);
  return out;
}

std::string unit_of(const ResultTable& t, const std::string& name) {
  const auto it = std::find(t.columns.begin(), t.columns.end(), name);
  return it == t.columns.end() ? "" : t.units[static_cast<std::size_t>(it - t.columns.begin())];
}

std::string plot_svg(const PlotSpec& spec) {
  SvgCanvas wide(spec.width, spec.height);
  draw_plot(wide, spec);
  PlotSpec small = spec;
  small.width = kNarrowWidth;
  small.height = 400;
  SvgCanvas narrow(small.width, small.height);
  draw_plot(narrow, small);
  return "<div class=\"wide\">" + wide.element() + "</div><div class=\"narrow\">" + narrow.element() + "</div>\n";
}

// A drawing at its own size for wide screens and at kNarrowWidth for phones (or only at
// kNarrowWidth, for pictures side by side).
std::string drawing_html(const Analysis& analysis, int step, const DrawOptions& options, bool small_only = false) {
  std::string out;
  for (const bool narrow : {false, true}) {
    if (small_only && !narrow) continue;
    DrawOptions o = options;
    if (narrow) o.width = kNarrowWidth, o.height = kNarrowWidth * 4 / 5, o.margin = 16;
    SvgCanvas canvas(o.width, o.height);
    draw_sample(canvas, *analysis.mechanism, analysis.sweep, step, o);
    if (small_only) return canvas.element() + "\n";
    out += std::string("<div class=\"") + (narrow ? "narrow" : "wide") + "\">" + canvas.element() + "</div>";
  }
  return out + "\n";
}

struct Html {
  std::string out;
  Html& operator<<(const std::string& s) {
    out += s;
    return *this;
  }
};

// The x axis of every plot: the first driver, or the time.
struct Axis {
  std::string name, unit;
  std::vector<double> values;
};

PlotSpec plot_against(const Axis& x, const std::string& title) {
  PlotSpec spec;
  spec.title = title;
  spec.x_name = x.name;
  spec.x_unit = x.unit;
  spec.x = x.values;
  return spec;
}

void write_head(Html& h, const Model& m, const ReportOptions& options) {
  h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
    << "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">"
    << "<title>" << esc(m.name.empty() ? "nbar report" : m.name) << "</title><style>" << kStyle
    << "</style></head><body>\n";
  h << "<h1>" << esc(m.name.empty() ? "Mechanism" : m.name) << "</h1>\n<p class=\"meta\">" << esc(options.source)
    << " &middot; lengths in " << esc(m.units.length) << ", angles in " << esc(m.units.angle)
    << ", forces in N &middot; report by nbar " << kVersion << "</p>\n";
}

void write_model_table(Html& h, const Analysis& analysis, const ModelSummary& summary, bool simulated) {
  const Model& m = analysis.model();
  const SweepResult& sweep = analysis.sweep;
  h << "<section id=\"summary\"><h2>Model</h2><div class=\"scroll\"><table>\n";
  h << "<tr><th>Degrees of freedom</th><td>" << std::to_string(summary.mobility.dof) << " (Gruebler-Kutzbach count "
    << std::to_string(summary.mobility.grubler) << ")</td></tr>\n";
  std::string redundant = summary.redundant.empty() ? "none" : "";
  for (const std::string& label : summary.redundant) redundant += (redundant.empty() ? "" : "; ") + esc(label);
  h << "<tr><th>Redundant constraints</th><td>" << redundant << "</td></tr>\n";
  h << "<tr><th>Bodies, points</th><td>" << std::to_string(m.bodies.size()) << ", " << std::to_string(m.points.size())
    << "</td></tr>\n";
  std::string drivers;
  for (const Driver& d : m.drivers) drivers += (drivers.empty() ? "" : "; ") + esc(d.name);
  h << "<tr><th>Drivers</th><td>" << (drivers.empty() ? "none" : drivers) << "</td></tr>\n";
  h << "<tr><th>" << (simulated ? "Simulation" : "Sweep") << "</th><td>" << std::to_string(sweep.samples.size())
    << (simulated ? " rows in time" : " samples")
    << (sweep.complete ? "" : "; <span class=\"warn\">stopped early: " + esc(sweep.stop_reason) + "</span>")
    << "</td></tr>\n";
  for (const Warning& w : analysis.warnings())
    h << "<tr><th>Warning</th><td class=\"warn\">" << esc(w.message) << "</td></tr>\n";
  h << "</table></div>\n";
}

// One small table of facts per loop, not one wide table: the Grashof description is long, and
// a column of it on a phone would be a word wide.
void write_loops_table(Html& h, const Analysis& analysis, const ModelSummary& summary, const ResultTable& table) {
  const Model& m = analysis.model();
  if (summary.loops.empty() || analysis.sweep.samples.empty()) return;
  h << "<h3>Four-bar loops</h3>\n";
  for (std::size_t l = 0; l < summary.loops.size(); ++l) {
    const LoopSummary& loop = summary.loops[l];
    const std::vector<double> mu = column(table, loop.loop.name + ".mu");
    const auto [lo, hi] = std::minmax_element(mu.begin(), mu.end());
    // A simulation's motion has no branch of its own: it goes where the loads take it.
    const std::vector<std::string>& branches = analysis.sweep.branches;
    const std::string branch =
        l < branches.size() ? "</td></tr>\n<tr><th>Branch</th><td>" + esc(branches[l]) : std::string();
    h << "<table class=\"facts\"><tr><th>Loop</th><td>" << esc(loop.loop.name) << "</td></tr>\n<tr><th>Grashof</th><td>"
      << esc(loop.description) << branch << "</td></tr>\n<tr><th>Transmission angle</th><td>"
      << (mu.empty() ? "" : short_number(*lo) + " to " + short_number(*hi) + " " + esc(m.units.angle))
      << "</td></tr></table>\n";
  }
}

void write_bodies_table(Html& h, const Model& m, const ModelSummary& summary) {
  h << "<h3>Bodies</h3><div class=\"scroll\"><table><tr><th>Body</th><th>Points</th><th>Length [" << esc(m.units.length)
    << "]</th><th>Mass [kg]</th><th>Inertia [kg m&sup2;]</th></tr>\n";
  for (const BodySummary& b : summary.bodies) {
    std::string points;
    for (const std::string& p : b.points) points += (points.empty() ? "" : ", ") + esc(p);
    const MassProperties& mp = b.mass;
    h << "<tr><td>" << esc(b.name) << "</td><td>" << points << "</td><td class=\"num\">"
      << (b.length ? short_number(*b.length / m.units.length_scale, 6) : "") << "</td><td class=\"num\">"
      << (mp.mass > 0 ? short_number(mp.mass) : "") << "</td><td class=\"num\">"
      << (mp.mass > 0 ? short_number(mp.inertia) : "") << "</td></tr>\n";
  }
  h << "</table></div></section>\n";
}

// The drawing options of the report's pictures; the coupler points (on one moving body only)
// are traced.
DrawOptions report_drawing(const Model& m) {
  DrawOptions draw;
  draw.width = 800;
  draw.height = 560;
  for (std::size_t p = 0; p < m.points.size(); ++p) {
    int links = m.points[p].ground ? 1 : 0;
    for (const Body& b : m.bodies)
      links += static_cast<int>(std::count(b.points.begin(), b.points.end(), static_cast<int>(p)));
    if (!m.points[p].ground && links == 1) draw.traces.push_back(static_cast<int>(p));
  }
  return draw;
}

void write_motion(Html& h, const Analysis& analysis, const DrawOptions& draw, const ReportOptions& options) {
  h << "<section id=\"motion\"><h2>Motion</h2>\n";
  Animation animation(analysis.mechanism, analysis.sweep, draw, options.frames);
  animation.set_control(options.control);
  h << "<iframe title=\"animation\" srcdoc=\"" << esc(animation.html_animation()) << "\"></iframe>\n";
  if (!draw.traces.empty()) {
    h << "<h3>Paths of the coupler points</h3>\n";
    DrawOptions paths = draw;
    paths.labels = true;
    h << drawing_html(analysis, 0, paths);
  }
  h << "</section>\n";
}

void write_kinematics(Html& h, const Analysis& analysis, const ResultTable& table, const Axis& x) {
  const char* quantities[][2] = {
      {"angle", "Angle"}, {"omega", "Angular velocity"}, {"alpha", "Angular acceleration"}, {"jerk", "Angular jerk"}};
  h << "<section id=\"kinematics\"><h2>Angles, angular velocities, accelerations and jerk</h2>\n";
  for (int q = 0; q <= std::min(analysis.sweep.order, 3); ++q) {
    PlotSpec spec = plot_against(x, quantities[q][1]);
    for (const Body& b : analysis.model().bodies) {
      const std::string name = b.name + "." + quantities[q][0];
      const std::vector<double> y = column(table, name);
      if (!y.empty()) spec.series.push_back({b.name, unit_of(table, name), y});
    }
    if (!spec.series.empty()) h << plot_svg(spec);
  }
  h << "</section>\n";
}

void write_forces(Html& h, const Analysis& analysis, const ResultTable& table, const Axis& x) {
  const DynamicsStage& dynamics = *analysis.dynamics;
  h << "<section id=\"forces\"><h2>Forces</h2>\n";
  if (!dynamics.unique)
    h << "<p class=\"warn\">Redundant constraints: the joint forces shown are the minimum-norm set.</p>";
  PlotSpec efforts = plot_against(x, "Driver efforts");
  for (const Driver& d : analysis.model().drivers) {
    const std::string name = d.name + (d.kind == DriverKind::Angle ? ".torque" : ".force");
    efforts.series.push_back({name, unit_of(table, name), column(table, name)});
  }
  if (!efforts.series.empty()) h << plot_svg(efforts);
  PlotSpec joints = plot_against(x, "Joint forces (magnitude)");
  h << "<div class=\"scroll\"><table><tr><th>Joint force</th><th>Largest [N]</th><th>at " << esc(x.name) << " ["
    << esc(x.unit) << "]</th></tr>\n";
  for (const JointForceColumn& force : joint_force_columns(*dynamics.solver)) {
    std::vector<double> magnitude;
    for (const DynamicsResult& r : dynamics.samples) {
      const Eigen::Vector2d& f = r.pin_forces[force.joint_link];
      magnitude.push_back(std::hypot(f.x(), f.y()));
    }
    const auto peak = std::max_element(magnitude.begin(), magnitude.end());
    if (peak == magnitude.end()) continue;
    h << "<tr><td>" << esc(force.name) << "</td><td class=\"num\">" << short_number(*peak) << "</td><td class=\"num\">"
      << short_number(x.values[static_cast<std::size_t>(peak - magnitude.begin())]) << "</td></tr>\n";
    joints.series.push_back({force.name, "N", magnitude});
  }
  h << "</table></div>\n";
  if (!joints.series.empty()) h << plot_svg(joints);
  h << "</section>\n";
}

void write_stresses(Html& h, const Analysis& analysis, const DrawOptions& draw, const Axis& x) {
  const Model& m = analysis.model();
  h << "<section id=\"stresses\"><h2>Stresses</h2><div class=\"scroll\"><table><tr><th>Link</th>"
    << "<th>Largest von Mises [MPa]</th><th>at " << esc(x.name) << " [" << esc(x.unit) << "]</th><th>x, y ["
    << esc(m.units.length) << "]</th><th>&sigma;, &tau; [MPa]</th><th>Safety factor</th></tr>\n";
  std::vector<std::pair<const StressPeak*, double>> drawn;
  for (const StressPeak& p : analysis.stress->peaks) {
    const double at = p.step >= 0 ? x.values[static_cast<std::size_t>(p.step)] : 0.0;
    h << "<tr><td>" << esc(m.bodies[p.body].name) << "</td><td class=\"num\">"
      << short_number(to_megapascal(p.at.von_mises)) << "</td><td class=\"num\">" << short_number(at)
      << "</td><td class=\"num\">" << short_number(p.at.where.x() / m.units.length_scale) << ", "
      << short_number(p.at.where.y() / m.units.length_scale) << "</td><td class=\"num\">"
      << short_number(to_megapascal(p.at.sigma)) << ", " << short_number(to_megapascal(p.at.tau))
      << "</td><td class=\"num\">" << (p.safety_factor ? short_number(*p.safety_factor, 3) : "") << "</td></tr>\n";
    drawn.emplace_back(&p, at);
  }
  h << "</table></div><p>Each link's largest stress is marked in the pose where it occurs. Beam theory on the net "
    << "sections, no stress concentration factors: see docs/kinetics.md.</p>\n<div class=\"peaks\">\n";
  for (const auto& [peak, at] : drawn) {
    DrawOptions marked = draw;
    marked.traces.clear();
    marked.markers.push_back({peak->body, peak->at.where, short_number(to_megapascal(peak->at.von_mises), 3) + " MPa"});
    h << "<figure>" << drawing_html(analysis, std::max(peak->step, 0), marked, true) << "<figcaption>"
      << esc(m.bodies[peak->body].name) << ": " << short_number(to_megapascal(peak->at.von_mises), 3) << " MPa at "
      << esc(x.name) << " = " << short_number(at) << " " << esc(x.unit) << "</figcaption></figure>\n";
  }
  h << "</div></section>\n";
}

// By finite elements: each link's peak over the sweep with its mesh and numerical checks, and
// each link coloured by von Mises in the pose of its peak, on the sweep's one scale.
void write_fe_stresses(Html& h, const Analysis& analysis, const DrawOptions& draw, const Axis& x) {
  const Model& m = analysis.model();
  const double length = m.units.length_scale;
  h << "<section id=\"stresses\"><h2>Stresses (finite elements)</h2><div class=\"scroll\"><table><tr><th>Link</th>"
    << "<th>Largest von Mises [MPa]</th><th>at " << esc(x.name) << " [" << esc(x.unit) << "]</th><th>x, y ["
    << esc(m.units.length) << "]</th><th>Safety factor</th><th>Nodes, elements</th><th>Unbalance, reaction</th></tr>\n";
  for (const FePeak& p : analysis.stress->fe_peaks) {
    const double at = p.step >= 0 ? x.values[static_cast<std::size_t>(p.step)] : 0.0;
    const Eigen::Vector2d where = body_frame_point(m, p.body, p.at);
    h << "<tr><td>" << esc(m.bodies[p.body].name) << "</td><td class=\"num\">"
      << short_number(to_megapascal(p.von_mises)) << "</td><td class=\"num\">" << short_number(at)
      << "</td><td class=\"num\">" << short_number(where.x() / length) << ", " << short_number(where.y() / length)
      << "</td><td class=\"num\">" << (p.safety_factor ? short_number(*p.safety_factor, 3) : "")
      << "</td><td class=\"num\">" << std::to_string(p.nodes) << ", " << std::to_string(p.elements)
      << "</td><td class=\"num\">" << short_number(p.load_unbalance, 2) << ", " << short_number(p.support_reaction, 2)
      << "</td></tr>\n";
  }
  h << "</table></div><p>Plane-stress 6-node triangles on each link's plate; pin forces as bearing pressures on "
    << "their holes, torques as shear around theirs, d'Alembert forces as body forces. Each link is coloured by von "
    << "Mises in the pose of its largest stress, on one scale for the sweep, its peak marked: see "
    << "docs/kinetics.md.</p>\n<div class=\"peaks\">\n";
  const double scale = sweep_stress_scale(analysis);
  for (const FePeak& p : analysis.stress->fe_peaks) {
    const int step = std::max(p.step, 0);
    DrawOptions mapped = draw;
    mapped.traces.clear();
    add_stress_maps(mapped, analysis, step, scale);
    // Only this link's peak is marked: the figure is about it.
    std::erase_if(mapped.markers, [&](const Marker& mk) { return mk.body != p.body; });
    const double at = x.values[static_cast<std::size_t>(step)];
    h << "<figure>" << drawing_html(analysis, step, mapped, true) << "<figcaption>" << esc(m.bodies[p.body].name)
      << ": " << esc(stress_text(p.von_mises)) << " at " << esc(x.name) << " = " << short_number(at) << " "
      << esc(x.unit) << "</figcaption></figure>\n";
  }
  h << "</div></section>\n";
}

// A simulation's run: where it ended and why, its events, the integrator's report, and its
// energies against time (the balance shows the integration error).
void write_simulation(Html& h, const Analysis& analysis, const Simulation& simulation, const Axis& x) {
  const Model& m = analysis.model();
  const SimulationStatistics& stats = simulation.statistics;
  h << "<section id=\"simulation\"><h2>Simulation</h2>\n<p>The motion under the loads, the drivers marked free "
       "released "
    << "(forward dynamics, as <code>nbar simulate</code>): " << kSimulationMethod
    << "; see docs/dynamics.md.</p>\n<div class=\"scroll\"><table class=\"facts\">\n";
  std::string free;
  for (int d : simulation.free_drivers)
    free += (free.empty() ? "" : ", ") + esc(m.drivers[static_cast<std::size_t>(d)].name);
  h << "<tr><th>Free drivers</th><td>" << (free.empty() ? "none" : free) << "</td></tr>\n";
  const double end = simulation.samples.empty() ? 0.0 : simulation.samples.back().time;
  h << "<tr><th>Simulated</th><td>" << short_number(end, 6) << " s, " << std::to_string(simulation.samples.size())
    << " rows"
    << (simulation.complete ? "" : "; <span class=\"warn\">stopped early: " + esc(simulation.stop_reason) + "</span>")
    << "</td></tr>\n";
  for (const SimulationEvent& e : simulation.events)
    h << "<tr><th>Event at " << short_number(e.time, 8) << " s</th><td>" << esc(e.message) << "</td></tr>\n";
  h << "<tr><th>Integration steps</th><td>" << std::to_string(stats.accepted_steps) << " accepted, "
    << std::to_string(stats.rejected_steps) << " rejected; " << short_number(stats.smallest_step) << " to "
    << short_number(stats.largest_step) << " s</td></tr>\n";
  const double unit = m.units.length_scale;
  h << "<tr><th>Constraint drift</th><td>" << short_number(stats.drift.position / unit, 3) << " " << esc(m.units.length)
    << ", " << short_number(stats.drift.velocity / unit, 3) << " " << esc(m.units.length) << "/s, "
    << short_number(stats.drift.acceleration / unit, 3) << " " << esc(m.units.length) << "/s&sup2;</td></tr>\n";
  h << "<tr><th>Largest energy error</th><td>" << short_number(stats.largest_energy_error, 3)
    << " J</td></tr>\n</table></div>\n";
  const ResultTable table = simulation_table(*analysis.mechanism, simulation);
  PlotSpec energy = plot_against(x, "Energies");
  for (const std::string& name : table.columns)
    if (name.starts_with("energy."))
      energy.series.push_back({name.substr(7), unit_of(table, name), column(table, name)});
  if (!energy.series.empty()) h << plot_svg(energy);
  h << "</section>\n";
}

}  // namespace

AnalysisOptions report_analysis_options(const ModelSummary& summary) {
  AnalysisOptions options;
  options.order = 3;  // jerk is plotted
  options.dynamics = summary.has_kinetics();
  options.stress = summary.has_kinetics() && summary.has_stress_links;
  return options;
}

std::string html_report(const Analysis& analysis, const ModelSummary& summary, const ReportOptions& options) {
  if (options.frames < kMinReportFrames || options.frames > kMaxReportFrames)
    throw Error(ErrorKind::BadInput, fmt::format("a report's animation has {} to {} frames, not {}", kMinReportFrames,
                                                 kMaxReportFrames, options.frames));
  const Model& m = analysis.model();
  const ResultTable table = result_table(analysis);
  Axis x;
  x.name = options.simulation ? "t" : default_abscissa(m);  // t for a sweep in time
  x.values = column(table, x.name);
  x.unit = unit_of(table, x.name);

  Html h;
  write_head(h, m, options);
  write_model_table(h, analysis, summary, options.simulation != nullptr);
  write_loops_table(h, analysis, summary, table);
  write_bodies_table(h, m, summary);
  if (analysis.sweep.samples.empty()) {
    h << "</body></html>\n";
    return h.out;
  }
  const DrawOptions draw = report_drawing(m);
  const RunControl& control = options.control;
  control.checkpoint("report", 0, 4);
  write_motion(h, analysis, draw, options);
  control.checkpoint("report", 1, 4);
  write_kinematics(h, analysis, table, x);
  if (options.simulation) write_simulation(h, analysis, *options.simulation, x);
  control.checkpoint("report", 2, 4);
  if (analysis.dynamics) write_forces(h, analysis, table, x);
  control.checkpoint("report", 3, 4);
  if (analysis.stress && analysis.stress->method == StressMethod::fe)
    write_fe_stresses(h, analysis, draw, x);
  else if (analysis.stress)
    write_stresses(h, analysis, draw, x);
  h << kFitFrames << "</body></html>\n";
  return h.out;
}

}  // namespace nbar::render
