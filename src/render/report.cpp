#include "nbar/render/report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "nbar/dynamics/dynamics_table.hpp"
#include "nbar/kinematics/table.hpp"
#include "nbar/render/animation.hpp"
#include "nbar/render/drawing.hpp"
#include "nbar/render/plot.hpp"
#include "nbar/stress/link_stress.hpp"

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
iframe { width: 100%; aspect-ratio: 10 / 9; height: auto; border: 1px solid #ddd; }
.warn { color: #a40; }
)";

std::string esc(const std::string& s) { return xml_escape(s); }

std::string num(double v, int digits = 4) { return fmt::format("{:.{}g}", v + 0.0, digits); }

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
  SvgCanvas canvas(spec.width, spec.height);
  draw_plot(canvas, spec);
  return canvas.element();
}

struct Html {
  std::string out;
  Html& operator<<(const std::string& s) {
    out += s;
    return *this;
  }
};

}  // namespace

std::string html_report(const Mechanism& mech, const SweepResult& sweep, const ReportOptions& options) {
  const Model& m = mech.model();
  const MobilityReport& mob = mech.mobility();
  ResultTable table = make_table(mech, sweep);

  bool has_mass = false;
  for (const Body& b : m.bodies) has_mass = has_mass || mass_properties(b).mass > 0.0;
  const bool has_loads = !m.gravity.isZero() || !m.point_loads.empty() || !m.torques.empty() || !m.springs.empty();
  const bool kinetics = (has_mass || has_loads) && sweep.order >= 2 && !sweep.samples.empty();
  DynamicsSummary dynamics;
  if (kinetics) dynamics = append_dynamics(mech, sweep, table);

  // The x axis of every plot: the first driver, or the time.
  const std::string x_name = m.drivers.empty() ? "t" : m.drivers[0].name;
  const std::vector<double> x = column(table, x_name);
  const std::string x_unit = unit_of(table, x_name);

  Html h;
  h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
    << "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">"
    << "<title>" << esc(m.name.empty() ? "nbar report" : m.name) << "</title><style>" << kStyle << "</style></head><body>\n";
  h << "<h1>" << esc(m.name.empty() ? "Mechanism" : m.name) << "</h1>\n<p class=\"meta\">"
    << esc(options.source) << " &middot; lengths in " << esc(m.units.length) << ", angles in " << esc(m.units.angle)
    << ", forces in N &middot; report by nbar 0.1.0</p>\n";

  // Summary.
  h << "<section id=\"summary\"><h2>Model</h2><div class=\"scroll\"><table>\n";
  h << "<tr><th>Degrees of freedom</th><td>" << std::to_string(mob.dof) << " (Gruebler-Kutzbach count "
    << std::to_string(mob.grubler) << ")</td></tr>\n";
  std::string redundant = mob.redundant.empty() ? "none" : "";
  for (int r : mob.redundant) redundant += (redundant.empty() ? "" : "; ") + esc(mech.rows()[r].label);
  h << "<tr><th>Redundant constraints</th><td>" << redundant << "</td></tr>\n";
  h << "<tr><th>Bodies, points</th><td>" << std::to_string(m.bodies.size()) << ", " << std::to_string(m.points.size())
    << "</td></tr>\n";
  std::string drivers;
  for (const Driver& d : m.drivers) drivers += (drivers.empty() ? "" : "; ") + esc(d.name);
  h << "<tr><th>Drivers</th><td>" << (drivers.empty() ? "none" : drivers) << "</td></tr>\n";
  h << "<tr><th>Sweep</th><td>" << std::to_string(sweep.samples.size()) << " samples"
    << (sweep.complete ? "" : "; <span class=\"warn\">stopped early: " + esc(sweep.stop_reason) + "</span>")
    << "</td></tr>\n";
  for (const std::string& w : sweep.warnings) h << "<tr><th>Warning</th><td class=\"warn\">" << esc(w) << "</td></tr>\n";
  for (const std::string& w : dynamics.warnings)
    h << "<tr><th>Warning</th><td class=\"warn\">" << esc(w) << "</td></tr>\n";
  h << "</table></div>\n";

  const auto& loops = mech.four_bar_loops();
  if (!loops.empty() && !sweep.samples.empty()) {
    const auto start = sample_points(mech, sweep.samples.front());
    h << "<h3>Four-bar loops</h3><div class=\"scroll\"><table><tr><th>Loop</th><th>Grashof</th><th>Branch</th>"
      << "<th>Transmission angle</th></tr>\n";
    for (std::size_t l = 0; l < loops.size(); ++l) {
      const GrashofReport g = classify_grashof(loops[l], start, mech.tolerance());
      const std::vector<double> mu = column(table, loops[l].name + ".mu");
      const auto [lo, hi] = std::minmax_element(mu.begin(), mu.end());
      h << "<tr><td>" << esc(loops[l].name) << "</td><td>" << esc(describe(g, loops[l], m)) << "</td><td>"
        << esc(sweep.branches[l]) << "</td><td>" << (mu.empty() ? "" : num(*lo) + " to " + num(*hi) + " " + esc(m.units.angle))
        << "</td></tr>\n";
    }
    h << "</table></div>\n";
  }

  h << "<h3>Bodies</h3><div class=\"scroll\"><table><tr><th>Body</th><th>Points</th><th>Length ["
    << esc(m.units.length) << "]</th><th>Mass [kg]</th><th>Inertia [kg m&sup2;]</th></tr>\n";
  for (const Body& b : m.bodies) {
    std::string points;
    for (int p : b.points) points += (points.empty() ? "" : ", ") + esc(m.points[p].name);
    const double length = b.points.size() >= 2 ? b.length.value_or((m.points[b.points[1]].position -
                                                                     m.points[b.points[0]].position).norm())
                                               : 0.0;
    const MassProperties mp = mass_properties(b);
    h << "<tr><td>" << esc(b.name) << "</td><td>" << points << "</td><td class=\"num\">"
      << (b.points.size() >= 2 ? num(length / m.units.length_scale, 6) : "") << "</td><td class=\"num\">"
      << (mp.mass > 0 ? num(mp.mass) : "") << "</td><td class=\"num\">" << (mp.mass > 0 ? num(mp.inertia) : "")
      << "</td></tr>\n";
  }
  h << "</table></div></section>\n";

  if (sweep.samples.empty()) {
    h << "</body></html>\n";
    return h.out;
  }

  // Motion.
  DrawOptions draw;
  draw.width = 800;
  draw.height = 560;
  for (std::size_t p = 0; p < m.points.size(); ++p) {
    int links = m.points[p].ground ? 1 : 0;
    for (const Body& b : m.bodies) links += static_cast<int>(std::count(b.points.begin(), b.points.end(), static_cast<int>(p)));
    if (!m.points[p].ground && links == 1) draw.traces.push_back(static_cast<int>(p));  // a coupler point
  }
  h << "<section id=\"motion\"><h2>Motion</h2>\n";
  const Animation animation(mech, sweep, draw, options.frames);
  h << "<iframe title=\"animation\" srcdoc=\"" << esc(animation.html_animation()) << "\"></iframe>\n";
  if (!draw.traces.empty()) {
    h << "<h3>Paths of the coupler points</h3>\n";
    DrawOptions paths = draw;
    paths.labels = true;
    SvgCanvas canvas(paths.width, paths.height);
    draw_sample(canvas, mech, sweep, 0, paths);
    h << canvas.element();
  }
  h << "</section>\n";

  // Kinematics of the bodies.
  const char* quantities[][2] = {{"angle", "Angle"}, {"omega", "Angular velocity"}, {"alpha", "Angular acceleration"},
                                 {"jerk", "Angular jerk"}};
  h << "<section id=\"kinematics\"><h2>Angles, angular velocities, accelerations and jerk</h2>\n";
  for (int q = 0; q <= std::min(sweep.order, 3); ++q) {
    PlotSpec spec;
    spec.title = quantities[q][1];
    spec.x_name = x_name;
    spec.x_unit = x_unit;
    spec.x = x;
    for (const Body& b : m.bodies) {
      const std::string name = b.name + "." + quantities[q][0];
      const std::vector<double> y = column(table, name);
      if (!y.empty()) spec.series.push_back({b.name, unit_of(table, name), y});
    }
    if (!spec.series.empty()) h << plot_svg(spec);
  }
  h << "</section>\n";

  if (kinetics) {
    h << "<section id=\"forces\"><h2>Forces</h2>\n";
    if (!dynamics.unique) h << "<p class=\"warn\">Redundant constraints: the joint forces shown are the minimum-norm set.</p>";
    PlotSpec efforts;
    efforts.title = "Driver efforts";
    efforts.x_name = x_name;
    efforts.x_unit = x_unit;
    efforts.x = x;
    for (const Driver& d : m.drivers) {
      const std::string name = d.name + (d.kind == DriverKind::Angle ? ".torque" : ".force");
      efforts.series.push_back({name, unit_of(table, name), column(table, name)});
    }
    if (!efforts.series.empty()) h << plot_svg(efforts);
    // Joint force magnitudes from the x, y columns.
    PlotSpec joints;
    joints.title = "Joint forces (magnitude)";
    joints.x_name = x_name;
    joints.x_unit = x_unit;
    joints.x = x;
    h << "<div class=\"scroll\"><table><tr><th>Joint force</th><th>Largest [N]</th><th>at " << esc(x_name) << " ["
      << esc(x_unit) << "]</th></tr>\n";
    for (const std::string& c : table.columns) {
      if (c.size() < 3 || c.compare(c.size() - 3, 3, ".Fx") != 0) continue;
      const std::string base = c.substr(0, c.size() - 3);
      const std::vector<double> fx = column(table, c), fy = column(table, base + ".Fy");
      std::vector<double> magnitude(fx.size());
      for (std::size_t i = 0; i < fx.size(); ++i) magnitude[i] = std::hypot(fx[i], fy[i]);
      const auto peak = std::max_element(magnitude.begin(), magnitude.end());
      if (peak == magnitude.end()) continue;
      h << "<tr><td>" << esc(base) << "</td><td class=\"num\">" << num(*peak) << "</td><td class=\"num\">"
        << num(x[static_cast<std::size_t>(peak - magnitude.begin())]) << "</td></tr>\n";
      joints.series.push_back({base, "N", magnitude});
    }
    h << "</table></div>\n";
    if (!joints.series.empty()) h << plot_svg(joints);
    h << "</section>\n";

    const InverseDynamics inverse(mech);
    const LinkStress stress(inverse, options.sections);
    bool any = false;
    for (std::size_t b = 0; b < m.bodies.size(); ++b) any = any || stress.analysed(static_cast<int>(b));
    if (any) {
      const auto peaks = stress_peaks(inverse, stress, sweep);
      h << "<section id=\"stresses\"><h2>Stresses</h2><div class=\"scroll\"><table><tr><th>Link</th>"
        << "<th>Largest von Mises [MPa]</th><th>at " << esc(x_name) << " [" << esc(x_unit) << "]</th><th>x, y ["
        << esc(m.units.length) << "]</th><th>&sigma;, &tau; [MPa]</th><th>Safety factor</th></tr>\n";
      DrawOptions marked = draw;
      marked.traces.clear();
      for (const StressPeak& p : peaks) {
        const double at = p.step >= 0 ? x[static_cast<std::size_t>(p.step)] : 0.0;
        h << "<tr><td>" << esc(m.bodies[p.body].name) << "</td><td class=\"num\">" << num(p.at.von_mises / 1e6)
          << "</td><td class=\"num\">" << num(at) << "</td><td class=\"num\">"
          << num(p.at.where.x() / m.units.length_scale) << ", " << num(p.at.where.y() / m.units.length_scale)
          << "</td><td class=\"num\">" << num(p.at.sigma / 1e6) << ", " << num(p.at.tau / 1e6) << "</td><td class=\"num\">"
          << (p.safety_factor ? num(*p.safety_factor, 3) : "") << "</td></tr>\n";
        marked.markers.push_back({p.body, p.at.where, num(p.at.von_mises / 1e6, 3) + " MPa"});
      }
      h << "</table></div><p>Each link's largest stress is marked (in the starting pose). Beam theory on the net "
        << "sections, no stress concentration factors: see docs/kinetics.md.</p>\n";
      SvgCanvas canvas(marked.width, marked.height);
      draw_sample(canvas, mech, sweep, 0, marked);
      h << canvas.element() << "</section>\n";
    }
  }
  h << "</body></html>\n";
  return h.out;
}

}  // namespace nbar::render
