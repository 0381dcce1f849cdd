#include "nbar/io/summary_writer.hpp"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "json_text.hpp"
#include "nbar/kinematics/continuation.hpp"
#include "nbar/model/bar_width.hpp"

namespace nbar::io {

namespace {

std::string join(const std::vector<std::string>& items, const std::string& separator = ", ") {
  std::string s;
  for (std::size_t i = 0; i < items.size(); ++i) s += (i ? separator : "") + items[i];
  return s;
}

std::string length_text(const Model& m, double si) {
  return fmt::format("{:.6g} {}", si / m.units.length_scale, m.units.length);
}

std::string plural(std::size_t n) { return n == 1 ? "" : "s"; }

void write_structure(std::ostream& out, const Model& m, const ModelSummary& s, const std::string& source) {
  out << "Model: " << (m.name.empty() ? std::string("(unnamed)") : m.name) << "  [" << source << "]\n";
  out << "Units: length " << m.units.length << ", angle " << m.units.angle << ", time s\n";
  out << fmt::format("Points: {} ({} fixed: {}; {} moving: {})\n", s.ground_points.size() + s.moving_points.size(),
                     s.ground_points.size(), join(s.ground_points), s.moving_points.size(), join(s.moving_points));
  out << "Bodies: " << m.bodies.size() << '\n';
  for (const BodySummary& b : s.bodies) {
    const std::string extra =
        b.length ? "  length " + length_text(m, *b.length) + (b.length_given ? " (given)" : "") : std::string();
    out << fmt::format("  {:<12} [{}]{}\n", b.name, join(b.points), extra);
  }
  out << "Joints: " << s.joints.size() << '\n';
  for (const std::string& j : s.joints) out << "  " << j << '\n';
}

void write_mobility(std::ostream& out, const ModelSummary& s) {
  const MobilityReport& mob = s.mobility;
  out << fmt::format(
      "Degrees of freedom: {} (Gruebler-Kutzbach count {}; {} coordinates, {} constraint equations of rank {})\n",
      mob.dof, mob.grubler, mob.coordinates, mob.constraint_rows, mob.rank);
  if (mob.grubler != mob.dof)
    out << "  note: the count and the true mobility differ: the linkage has special geometry (redundant constraints)\n";
  if (s.redundant.empty()) {
    out << "Redundant constraints: none\n";
  } else {
    out << "Redundant constraints: " << s.redundant.size()
        << " (these depend on the others; the choice among a dependent set is arbitrary)\n";
    for (const std::string& label : s.redundant) out << "  " << label << '\n';
  }
  out << "Drivers: " << s.drivers.size() << '\n';
  for (const std::string& d : s.drivers) out << "  " << d << '\n';
}

void write_kinetics(std::ostream& out, const Model& m, const ModelSummary& s) {
  if (!s.has_mass_data && !s.has_loads) return;
  const double unit = m.units.length_scale;
  out << fmt::format("Mass properties (mass kg, centre of mass in {}, inertia about it kg m^2, plate area {}^2):\n",
                     m.units.length, m.units.length);
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    const BodySummary& b = s.bodies[i];
    const MassProperties& mp = b.mass;
    const std::string area =
        mp.from_shape || m.bodies[i].shape ? fmt::format("  area {:.6g}", mp.area / (unit * unit)) : "";
    if (mp.mass > 0.0)
      out << fmt::format("  {:<12} mass {:.6g}  cg ({:.6g}, {:.6g})  inertia {:.6g}{}  [{}]\n", b.name, mp.mass,
                         mp.cg.x() / unit, mp.cg.y() / unit, mp.inertia, area, b.mass_source);
    else  // no centre of mass to speak of
      out << fmt::format("  {:<12} mass 0{}  [{}]\n", b.name, area, b.mass_source);
  }
  out << fmt::format("Loads: gravity ({:.6g}, {:.6g}) m/s^2, {} point force{}, {} torque{}, {} spring{}\n",
                     m.gravity.x(), m.gravity.y(), m.point_loads.size(), plural(m.point_loads.size()), m.torques.size(),
                     plural(m.torques.size()), m.springs.size(), plural(m.springs.size()));
}

void write_start(std::ostream& out, const Model& m, const ModelSummary& s) {
  if (!s.assembly) {
    if (s.assembly_error && s.assembly_error->kind() == ErrorKind::CannotAssemble)
      out << "Assembly at the start: FAILED\n";
    return;
  }
  std::vector<std::string> at;
  for (std::size_t d = 0; d < s.assembly->driver_values.size(); ++d)
    at.push_back(m.drivers[d].name + " = " + format_driver_value(m, static_cast<int>(d), s.assembly->driver_values[d]));
  out << fmt::format("Assembly at the start ({}): converged, residual {:.3g} {}\n", join(at),
                     s.assembly->residual / m.units.length_scale, m.units.length);
  if (s.assembly->passed_singularity)
    out << "  warning: reaching the start from the drawn pose passed a singular position\n";
  if (s.loops.empty()) {
    out << "Four-bar loops: none\n";
    return;
  }
  out << "Four-bar loops: " << s.loops.size() << '\n';
  for (const LoopSummary& l : s.loops) {
    out << "  " << l.loop.name << ": " << l.description << '\n';
    out << fmt::format("    at the start: {} branch, transmission angle {:.4g} {}\n", l.branch,
                       l.transmission_angle / m.units.angle_scale, m.units.angle);
    if (const auto& t = l.transmission_over_turn)
      out << fmt::format(
          "    over the input's full turn: transmission angle from {:.4g} to {:.4g} {}, design value {:.4g} {} "
          "(nearest a dead point: the smallest of mu and its supplement)\n",
          t->min / m.units.angle_scale, t->max / m.units.angle_scale, m.units.angle, t->design / m.units.angle_scale,
          m.units.angle);
    if (l.toggle_from && l.toggle_to)
      out << fmt::format("    the input turns only between its toggle positions, {:.6g} {} and {:.6g} {}\n",
                         *l.toggle_from / m.units.angle_scale, m.units.angle, *l.toggle_to / m.units.angle_scale,
                         m.units.angle);
    if (l.rocker) out << "    " << l.rocker->description << '\n';
  }
}

// Whether a four-bar loop's closed form (the toggle line above) already gives this limit: its
// input is the driven body and its toggle the limit's value.
bool given_by_a_loop(const Model& m, const ModelSummary& s, const PathSingularity& limit, int driver) {
  const Driver& drv = m.drivers[driver];
  if (drv.kind != DriverKind::Angle || drv.relative_to >= 0) return false;
  const double x = limit.driver_values[driver];
  for (const LoopSummary& l : s.loops) {
    if (l.loop.input != drv.body || !l.toggle_from || !l.toggle_to) continue;
    for (const double toggle : {*l.toggle_from, *l.toggle_to})
      if (std::abs(std::remainder(x - toggle, 2.0 * std::numbers::pi)) <= 1e-6) return true;
  }
  return false;
}

// The singular positions the sweep's path meets: change points inside the sweep's range, and the
// first limit each way.
std::vector<std::pair<std::string, const PathSingularity*>> met_on_path(const PathLimits& l) {
  std::vector<std::pair<std::string, const PathSingularity*>> met;
  const double lo = std::min(l.start_parameter, l.end_parameter), hi = std::max(l.start_parameter, l.end_parameter);
  for (const auto& [name, reach] : {std::pair{"ahead", &l.ahead}, std::pair{"behind", &l.behind}})
    for (const PathSingularity& s : reach->singularities)
      if (s.kind == PathSingularityKind::Limit || (s.parameter >= lo && s.parameter <= hi)) met.emplace_back(name, &s);
  return met;
}

// The limits of the whole mechanism, said when they add to the loops' closed forms above: a
// limit no loop's toggle gives (a dyad of a six-bar, a cylinder), or a search that could not decide.
void write_limits(std::ostream& out, const Model& m, const ModelSummary& s) {
  if (s.limits_error) {
    out << "Limits of the whole mechanism: the search failed: " << *s.limits_error << '\n';
    return;
  }
  if (!s.limits || !s.limits->searched) return;
  const PathLimits& l = *s.limits;
  const int d = l.driver;
  const auto met = met_on_path(l);
  const bool news = !l.ahead.undecided.empty() || !l.behind.undecided.empty() ||
                    std::any_of(met.begin(), met.end(), [&](const auto& e) {
                      return e.second->kind == PathSingularityKind::Limit && !given_by_a_loop(m, s, *e.second, d);
                    });
  if (!news) return;
  const auto value = [&](double si) {
    return fmt::format("{:.10g} {}", si / (m.drivers[d].is_angular() ? m.units.angle_scale : m.units.length_scale),
                       m.drivers[d].is_angular() ? m.units.angle : m.units.length);
  };
  out << "Limits of the whole mechanism on the sweep's path (" << m.drivers[d].name
      << ", ahead the way the sweep goes):\n";
  for (const auto& [way, singular] : met) {
    const bool limit = singular->kind == PathSingularityKind::Limit;
    out << fmt::format("  {}: {} at {} = {}: {}{}\n", way, limit ? "limit" : "change point", m.drivers[d].name,
                       value(singular->driver_values[d]), singular->involved,
                       l.stop && singular == l.ahead.limit() ? "; the sweep stops there"
                       : limit                               ? ""
                                                             : "; branches cross, the sweep passes on its branch");
  }
  for (const auto& [way, reach] : {std::pair{"ahead", &l.ahead}, std::pair{"behind", &l.behind}}) {
    if (!reach->undecided.empty()) out << "  " << way << ": the search could not decide: " << reach->undecided << '\n';
    if (reach->turns_fully) out << "  " << way << ": no limit over a full turn\n";
  }
}

// Slider-cranks and quick-returns: stroke, dead centres, swing and time ratio.
void write_crank_mechanisms(std::ostream& out, const ModelSummary& s) {
  if (!s.slider_cranks.empty()) {
    out << "Slider-cranks: " << s.slider_cranks.size() << '\n';
    for (const SliderCrankSummary& f : s.slider_cranks) out << "  " << f.description << '\n';
  }
  if (!s.quick_returns.empty()) {
    out << "Quick-returns: " << s.quick_returns.size() << '\n';
    for (const QuickReturnSummary& f : s.quick_returns) out << "  " << f.description << '\n';
  }
}

using Json = nlohmann::ordered_json;

Json optional_number(const std::optional<double>& v, double scale) { return v ? Json(*v / scale) : Json(nullptr); }

Json bodies_json(const Model& m, const ModelSummary& s) {
  const double unit = m.units.length_scale;
  Json bodies = Json::array();
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    const BodySummary& b = s.bodies[i];
    const MassProperties& mp = b.mass;
    Json mass = {{"mass", mp.mass},
                 {"cg", {mp.cg.x() / unit, mp.cg.y() / unit}},
                 {"inertia", mp.inertia},
                 {"area", mp.from_shape || m.bodies[i].shape ? Json(mp.area / (unit * unit)) : Json(nullptr)},
                 {"source", b.mass_source}};
    bodies.push_back({{"name", b.name},
                      {"points", b.points},
                      {"length", optional_number(b.length, unit)},
                      {"length_given", b.length_given},
                      {"default_bar_width", default_bar_width(m, static_cast<int>(i))},
                      {"mass", mass}});
  }
  return bodies;
}

Json transmission_over_turn_json(const Model& m, const std::optional<TransmissionOverTurn>& t) {
  if (!t) return nullptr;
  const double unit = m.units.angle_scale;
  return {{"min", t->min / unit}, {"max", t->max / unit}, {"design", t->design / unit}};
}

Json rocker_json(const Model& m, const std::optional<RockerSwing>& r) {
  if (!r) return nullptr;
  const double angle = m.units.angle_scale;
  return Json{{"swing", r->swing / angle},
              {"rocker_stretched", r->rocker_stretched / angle},
              {"rocker_folded", r->rocker_folded / angle},
              {"crank_stretched", r->crank_stretched / angle},
              {"crank_folded", r->crank_folded / angle},
              {"turn_to_stretched", r->turn_to_stretched / angle},
              {"turn_to_folded", r->turn_to_folded / angle},
              {"time_ratio", r->time_ratio},
              {"description", r->description}};
}

Json loops_json(const Model& m, const ModelSummary& s) {
  const double unit = m.units.length_scale;
  const auto name = [&](int body) { return body < 0 ? std::string("ground") : m.bodies[body].name; };
  Json loops = Json::array();
  for (const LoopSummary& l : s.loops) {
    const GrashofReport& g = l.grashof;
    loops.push_back({{"name", l.loop.name},
                     {"frame", name(l.loop.frame)},
                     {"input", name(l.loop.input)},
                     {"coupler", name(l.loop.coupler)},
                     {"output", name(l.loop.output)},
                     {"grashof", grashof_name(g.kind, g.input_turns_fully)},
                     {"lengths",
                      {{"frame", g.frame / unit},
                       {"input", g.input / unit},
                       {"coupler", g.coupler / unit},
                       {"output", g.output / unit}}},
                     {"grashof_margin", g.margin / unit},
                     {"input_turns_fully", g.input_turns_fully},
                     {"output_turns_fully", g.output_turns_fully},
                     {"description", l.description},
                     {"branch", l.branch},
                     {"transmission_angle", l.transmission_angle / m.units.angle_scale},
                     {"transmission_over_turn", transmission_over_turn_json(m, l.transmission_over_turn)},
                     {"toggles", l.toggle_from && l.toggle_to ? Json::array({*l.toggle_from / m.units.angle_scale,
                                                                             *l.toggle_to / m.units.angle_scale})
                                                              : Json(nullptr)},
                     {"rocker", rocker_json(m, l.rocker)}});
  }
  return loops;
}

Json singularity_json(const Mechanism& mech, const PathSingularity& s, int driver) {
  const Model& m = mech.model();
  const auto in_units = [&](int d, double si) {
    return si / (m.drivers[d].is_angular() ? m.units.angle_scale : m.units.length_scale);
  };
  Json values = Json::object();
  for (std::size_t d = 0; d < s.driver_values.size(); ++d)
    values[m.drivers[d].name] = in_units(static_cast<int>(d), s.driver_values[d]);
  Json bodies = Json::array(), rows = Json::array();
  for (int b : s.bodies) bodies.push_back(m.bodies[b].name);
  for (int r : s.rows) rows.push_back(mech.row_label(r));
  return Json{{"kind", s.kind == PathSingularityKind::Limit ? "limit" : "change_point"},
              {"value", in_units(driver, s.driver_values[driver])},
              {"driver_values", values},
              {"bodies", bodies},
              {"loop", s.loop >= 0 ? Json(mech.four_bar_loops()[s.loop].name) : Json(nullptr)},
              {"constraints", rows},
              {"involved", s.involved}};
}

// The whole mechanism's limits on the sweep's path (null when not searched).
Json limits_json(const Mechanism& mech, const ModelSummary& s) {
  if (!s.limits || !s.limits->searched) return nullptr;
  const PathLimits& l = *s.limits;
  const Model& m = mech.model();
  const double scale = m.drivers[l.driver].is_angular() ? m.units.angle_scale : m.units.length_scale;
  Json ahead = Json::array(), behind = Json::array();
  for (const auto& [way, singular] : met_on_path(l))
    (std::string(way) == "ahead" ? ahead : behind).push_back(singularity_json(mech, *singular, l.driver));
  const auto undecided = [](const PathReach& r) { return r.undecided.empty() ? Json(nullptr) : Json(r.undecided); };
  return Json{{"driver", m.drivers[l.driver].name},
              {"stop", l.stop ? Json(l.stop->driver_values[l.driver] / scale) : Json(nullptr)},
              {"ahead", ahead},
              {"behind", behind},
              {"turns_fully_ahead", l.ahead.turns_fully},
              {"turns_fully_behind", l.behind.turns_fully},
              {"undecided", {{"ahead", undecided(l.ahead)}, {"behind", undecided(l.behind)}}}};
}

void crank_mechanisms_json(const Model& m, const ModelSummary& s, Json& j) {
  const double length = m.units.length_scale, angle = m.units.angle_scale;
  Json sliders = Json::array();
  for (const SliderCrankSummary& f : s.slider_cranks) {
    Json one = {{"crank", f.crank},
                {"rod", f.rod},
                {"slider", f.slider},
                {"crank_length", f.crank_length / length},
                {"rod_length", f.rod_length / length},
                {"offset", f.offset / length},
                {"crank_turns_fully", f.crank_turns_fully}};
    if (f.crank_turns_fully) {
      one["stroke"] = f.stroke / length;
      one["dead_centres"] = {{"outer", f.outer_dead_centre / angle}, {"inner", f.inner_dead_centre / angle}};
      one["outstroke_turn"] = f.outstroke_turn / angle;
      one["return_turn"] = f.return_turn / angle;
      one["time_ratio"] = f.time_ratio;
    }
    one["description"] = f.description;
    sliders.push_back(one);
  }
  j["slider_cranks"] = sliders;
  Json quick = Json::array();
  for (const QuickReturnSummary& f : s.quick_returns) {
    Json one = {{"crank", f.crank},
                {"arm", f.arm},
                {"crank_length", f.crank_length / length},
                {"pivot_distance", f.pivot_distance / length},
                {"arm_turns_fully", f.arm_turns_fully}};
    if (!f.arm_turns_fully) {
      one["swing"] = f.swing / angle;
      one["limits"] = {f.limit_from / angle, f.limit_to / angle};
      one["slow_turn"] = f.slow_turn / angle;
      one["fast_turn"] = f.fast_turn / angle;
      one["time_ratio"] = f.time_ratio;
    }
    one["description"] = f.description;
    quick.push_back(one);
  }
  j["quick_returns"] = quick;
}

}  // namespace

std::string summary_json(const Mechanism& mechanism, const ModelSummary& s, const SourceMap& source) {
  const Model& m = mechanism.model();
  const MobilityReport& mob = s.mobility;
  Json j;
  j["model"] = m.name;
  j["source"] = source.file;
  j["units"] = {{"length", m.units.length}, {"angle", m.units.angle}, {"time", "s"}};
  j["points"] = {{"count", s.ground_points.size() + s.moving_points.size()},
                 {"ground", s.ground_points},
                 {"moving", s.moving_points}};
  j["bodies"] = bodies_json(m, s);
  j["joints"] = s.joints;
  j["dof"] = {{"gruebler", mob.grubler},
              {"mobility", mob.dof},
              {"coordinates", mob.coordinates},
              {"constraint_equations", mob.constraint_rows},
              {"rank", mob.rank},
              {"redundant_constraints", s.redundant}};
  j["drivers"] = s.drivers;
  j["kinetics"] = {{"has_masses", s.has_masses},
                   {"has_mass_data", s.has_mass_data},
                   {"has_shapes", s.has_shapes},
                   {"has_loads", s.has_loads},
                   {"has_stress_links", s.has_stress_links},
                   {"gravity", {m.gravity.x(), m.gravity.y()}},
                   {"point_forces", m.point_loads.size()},
                   {"torques", m.torques.size()},
                   {"springs", m.springs.size()}};
  if (s.assembly) {
    Json values = Json::object();
    for (std::size_t d = 0; d < s.assembly->driver_values.size(); ++d)
      values[m.drivers[d].name] =
          s.assembly->driver_values[d] / (m.drivers[d].is_angular() ? m.units.angle_scale : m.units.length_scale);
    j["assembly"] = {{"converged", true},
                     {"driver_values", values},
                     {"residual", s.assembly->residual / m.units.length_scale},
                     {"passed_singularity", s.assembly->passed_singularity}};
  } else {
    j["assembly"] = nullptr;
  }
  if (s.assembly_error) {
    const Error& e = *s.assembly_error;
    const SourceMark mark = e.file().empty() ? source.find(e.where()) : e.mark();
    Json error = {{"kind", to_string(e.kind())}, {"message", e.message()}};
    if (mark.line > 0) {
      error["line"] = mark.line;
      error["column"] = mark.column;
    }
    j["assembly_error"] = error;
  } else {
    j["assembly_error"] = nullptr;
  }
  if (s.law_error) {  // only when there is one, so that the answer for a sound model is unchanged
    const Error& e = *s.law_error;
    const SourceMark mark = source.find(e.where());
    Json error = {{"kind", to_string(e.kind())}, {"message", e.message()}};
    if (mark.line > 0) {
      error["line"] = mark.line;
      error["column"] = mark.column;
    }
    j["law_error"] = error;
  }
  j["loops"] = loops_json(m, s);
  crank_mechanisms_json(m, s, j);
  j["limits"] = limits_json(mechanism, s);
  if (s.limits_error) j["limits_error"] = *s.limits_error;
  if (s.rocking) j["rocking"] = *s.rocking;
  return json_text(j, 2) + '\n';
}

void write_summary_text(std::ostream& out, const Mechanism& mechanism, const ModelSummary& summary,
                        const std::string& source) {
  const Model& m = mechanism.model();
  write_structure(out, m, summary, source);
  write_mobility(out, summary);
  write_kinetics(out, m, summary);
  write_start(out, m, summary);
  write_limits(out, m, summary);
  if (summary.rocking) out << "Rocking: " << *summary.rocking << '\n';
  write_crank_mechanisms(out, summary);
  if (!summary.warnings.empty()) {
    out << "Warnings: " << summary.warnings.size() << '\n';
    for (const Warning& w : summary.warnings) out << "  warning: " << w.message << '\n';
  }
}

}  // namespace nbar::io
