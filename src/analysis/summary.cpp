#include "nbar/analysis/summary.hpp"
#include "nbar/analysis/summary_facts.hpp"
#include "nbar/model/geometry.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "nbar/analysis/cylinders.hpp"
#include "nbar/kinematics/continuation.hpp"
#include "nbar/kinematics/sweep.hpp"

namespace nbar {

namespace {

std::string join(const std::vector<std::string>& items, const std::string& separator) {
  std::string s;
  for (std::size_t i = 0; i < items.size(); ++i) s += (i ? separator : "") + items[i];
  return s;
}

std::string describe_driver(const Model& m, int d) {
  const Driver& drv = m.drivers[d];
  std::string what;
  switch (drv.kind) {
    case DriverKind::Angle:
      what = "angle of " + m.bodies[drv.body].name +
             (drv.relative_to < 0 ? std::string(" (from +x)") : " relative to " + m.bodies[drv.relative_to].name);
      break;
    case DriverKind::Distance:
      what = "distance " + m.points[drv.points[0]].name + "-" + m.points[drv.points[1]].name;
      break;
    case DriverKind::Slide: what = "slide of " + m.bodies[m.sliders[drv.slider].body].name + " along its guide"; break;
  }
  const double rate_scale = drv.is_angular() ? m.units.angle_scale : m.units.length_scale;
  const std::string unit = drv.is_angular() ? m.units.angle : m.units.length;
  if (drv.law) return fmt::format("{}: {}, law {}(t) = {} {}", drv.name, what, drv.name, drv.law->text(), unit);
  std::string motion;
  if (drv.from) motion += ", " + format_driver_value(m, d, *drv.from);
  if (drv.to) motion += " to " + format_driver_value(m, d, *drv.to);
  motion += fmt::format(", speed {:.6g} {}/s", drv.speed / rate_scale, unit);
  if (drv.accel != 0.0) motion += fmt::format(", accel {:.6g} {}/s^2", drv.accel / rate_scale, unit);
  return drv.name + ": " + what + motion;
}

BodySummary summarize_body(const Model& m, const Body& b) {
  BodySummary s;
  s.name = b.name;
  for (int p : b.points)
    if (!m.points[p].guide_direction) s.points.push_back(m.points[p].name);
  if (b.points.size() >= 2) {
    s.length = b.length.value_or((m.points[b.points[1]].position - m.points[b.points[0]].position).norm());
    s.length_given = b.length.has_value();
  }
  s.mass = mass_properties(b);
  s.mass_source = b.inertia ? "given" : b.shape ? (b.material ? b.material->name : "shape, no material") : "none";
  return s;
}

// A guide's line as the model file gave it: two points, or a point and the angle in the drawing
// (the reader's second point only sets the direction: the user never named it).
std::string guide_text(const Model& m, const std::array<int, 2>& along) {
  const Point &through = m.points[along[0]], &direction = m.points[along[1]];
  if (!direction.guide_direction) return through.name + "-" + direction.name;
  const Eigen::Vector2d d = direction.position - through.position;
  return fmt::format("the line through {} at {:.6g} {}", through.name, std::atan2(d.y(), d.x()) / m.units.angle_scale,
                     m.units.angle);
}

// Revolute pairs at shared points, then sliders and slots.
std::vector<std::string> describe_joints(const Model& m) {
  std::vector<std::string> joints;
  for (std::size_t p = 0; p < m.points.size(); ++p) {
    std::vector<std::string> at;
    if (m.points[p].ground) at.push_back("ground");
    for (const Body& b : m.bodies)
      for (int q : b.points)
        if (q == static_cast<int>(p)) at.push_back(b.name);
    if (at.size() >= 2) joints.push_back("revolute " + m.points[p].name + " (" + join(at, "/") + ")");
  }
  for (const Slider& s : m.sliders)
    joints.push_back("slider " + m.bodies[s.body].name + " at " + m.points[s.point].name + " along " +
                     guide_text(m, s.along));
  for (const Slot& s : m.slots) joints.push_back("slot " + m.points[s.point].name + " in " + guide_text(m, s.along));
  return joints;
}

double angle_of(const Eigen::Vector2d& v) { return std::atan2(v.y(), v.x()); }

// The sweep's path meets a limit of the whole mechanism before its end (limits.hpp): the sweep
// would stop there. Said with the limit's true value, and the range the input has, whichever loop
// or dyad sets it; never a limit the path does not meet.
void warn_about_input_limits(const Mechanism& mech, ModelSummary& out) {
  if (!out.limits || !out.limits->stop) return;
  const Model& m = mech.model();
  if (m.drivers.size() == 1 && m.drivers[0].at_limits == AtLimits::Reverse) return;  // it turns back there
  const PathLimits& l = *out.limits;
  const PathSingularity& stop = *l.stop;
  const SweepPath plan = sweep_path(mech, std::nullopt, kDefaultMaxSweepSamples, false);
  std::vector<Series> start, end;
  plan.drivers(l.start_parameter, 1, start);
  plan.drivers(l.end_parameter, 1, end);
  int d = 0;
  while (d + 1 < static_cast<int>(start.size()) && start[d].value() == end[d].value()) ++d;
  const Driver& drv = m.drivers[d];
  const auto value = [&](double si) { return format_driver_value(m, d, si); };
  const std::string who = stop.loop >= 0 ? "loop " + mech.four_bar_loops()[stop.loop].name : "the mechanism";
  std::string range;
  if (const PathSingularity* back = l.behind.limit()) {
    const double a = std::min(back->driver_values[d], stop.driver_values[d]);
    const double b = std::max(back->driver_values[d], stop.driver_values[d]);
    range = fmt::format("only between {} and {}", value(a), value(b));
  } else {
    range = "only up to " + value(stop.driver_values[d]);
  }
  out.warnings.push_back(
      {"input_limited", -1,
       fmt::format("the sweep asks {} to {} {}, from {} to {}, but {} lets it {} {} (limit positions): the sweep "
                   "will stop at {}: {}",
                   drv.name, drv.is_angular() ? "turn" : "move", value(std::abs(end[d].value() - start[d].value())),
                   value(start[d].value()), value(end[d].value()), who, drv.is_angular() ? "turn" : "move", range,
                   value(stop.driver_values[d]), stop.involved)});
}

// A rocking driver's turns over one cycle of its path, or that it never turns back.
void describe_rocking(const Mechanism& mech, double work_budget, ModelSummary& out) {
  const Model& m = mech.model();
  if (m.drivers.size() != 1 || m.drivers[0].at_limits != AtLimits::Reverse) return;
  const std::string name = "driver '" + m.drivers[0].name + "'";
  try {
    const RockingPlan plan = plan_rocking(mech, work_budget);
    if (!plan.reverses) {
      out.rocking = name + " never reverses: " + plan.never_reverses;
      out.warnings.push_back({"never_reverses", -1,
                              name + " never reverses (`at_limits: reverse`): " + plan.never_reverses +
                                  ", so the sweep runs from its start to its end as usual"});
      return;
    }
    std::string turns;
    for (std::size_t i = 0; i < plan.turns.size(); ++i)
      turns += (i ? ", then " : "") + format_driver_value(m, 0, plan.turns[i].driver_values[0]) + " (" +
               plan.turns[i].involved + ")";
    out.rocking =
        name + " turns back at " + turns +
        (plan.closed ? "; a cycle (back to the start's pose) is " + format_driver_value(m, 0, plan.circuit_travel) +
                           " of travel, " + fmt::format("{:.6g}", plan.circuit_travel / plan.speed) + " s"
                     : "; then its path turns fully and it goes on that way");
  } catch (const Error& e) {
    out.rocking = e.message();
    out.warnings.push_back({"cannot_rock", -1, e.message()});
  }
}

// The limits of the whole mechanism, searched on the sweep's own path from its start.
void find_limits(const Mechanism& mech, double work_budget, ModelSummary& out) {
  try {
    LimitSearchOptions options;
    options.work_budget = work_budget;
    out.limits = find_path_limits(mech, options);
  } catch (const Error& e) {
    out.limits_error = e.message();
  }
}

// Angle drivers asked to turn more than a few times: most often degrees written with
// `angle: rad`.
void warn_about_many_turns(const Model& m, ModelSummary& out) {
  constexpr double kTurn = 2 * std::numbers::pi;
  for (std::size_t d = 0; d < m.drivers.size(); ++d) {
    const Driver& drv = m.drivers[d];
    if (!drv.is_angular() || drv.law || !drv.from || !drv.to) continue;
    const double turns = std::abs(*drv.to - *drv.from) / kTurn;
    if (turns <= 4.0) continue;
    std::string hint;
    if (m.units.angle == "rad")
      hint = fmt::format(" (the model's angle unit is rad: for {} degrees, write `units: {{angle: deg}}`)",
                         fmt::format("{:.6g}", std::abs(*drv.to - *drv.from) / m.units.angle_scale));
    out.warnings.push_back({"many_turns", -1,
                            fmt::format("the sweep turns {} {:.4g} times, from {} to {}{}", drv.name, turns,
                                        format_driver_value(m, static_cast<int>(d), *drv.from),
                                        format_driver_value(m, static_cast<int>(d), *drv.to), hint)});
  }
}

// A plate whose body's points lie off it was most likely drawn elsewhere or in the part's own
// frame (a DXF part file): its mass, centre of mass and stresses would belong to another place.
void warn_about_points_off_plates(const Model& m, std::vector<Warning>& out) {
  for (const Body& b : m.bodies) {
    if (!b.shape || b.shape->outline.size() < 3) continue;
    const Region straight = straight_edged(*b.shape);  // arcs bulge past their vertices
    Eigen::Vector2d low = straight.outline[0], high = low;
    for (const Eigen::Vector2d& v : straight.outline) {
      low = low.cwiseMin(v);
      high = high.cwiseMax(v);
    }
    const double size = (high - low).norm();
    for (int p : b.points) {
      const double off = distance_outside_outline(*b.shape, m.points[p].position);
      if (!(off > 1e-3 * size)) continue;
      const double unit = m.units.length_scale;
      out.push_back({"point_off_plate", -1,
                     fmt::format("point {} of body {} lies {:.6g} {} outside its plate, which spans x from {:.6g} to "
                                 "{:.6g} and y from {:.6g} to {:.6g} {}: is the plate drawn in another place or frame "
                                 "than the body?",
                                 m.points[p].name, b.name, off / unit, m.units.length, low.x() / unit, high.x() / unit,
                                 low.y() / unit, high.y() / unit, m.units.length)});
    }
  }
}

// The input angles of the toggle positions of a loop on the ground whose input cannot turn
// fully, in the measure of the input's angle driver when it has one (from +x), else of the
// input's direction from its first point to its second.
void add_input_toggles(const Mechanism& mech, const std::vector<Eigen::Vector2d>& p, LoopSummary& l) {
  const FourBarLoop& loop = l.loop;
  const Model& m = mech.model();
  if (loop.frame >= 0 || l.grashof.input_turns_fully || m.bodies[loop.input].points.size() < 2) return;
  const Body& body = m.bodies[loop.input];
  const double offset = std::remainder(
      angle_of(p[body.points[1]] - p[body.points[0]]) - angle_of(p[loop.a] - p[loop.o2]), 2 * std::numbers::pi);
  const InputLimits limits = input_limits(l.grashof.frame, l.grashof.input, l.grashof.coupler, l.grashof.output,
                                          angle_of(p[loop.o4] - p[loop.o2]), angle_of(p[loop.a] - p[loop.o2]));
  if (limits.full || !limits.closes) return;
  // Near the driver's start value when driven (the same turn), else as the drawing has it.
  double shift = 0.0;
  for (const Driver& d : m.drivers)
    if (d.kind == DriverKind::Angle && d.body == loop.input && d.relative_to < 0 && d.from)
      shift = 2 * std::numbers::pi *
              std::round((*d.from - (angle_of(p[loop.a] - p[loop.o2]) + offset)) / (2 * std::numbers::pi));
  l.toggle_from = limits.from + offset + shift;
  l.toggle_to = limits.to + offset + shift;
}

// Every law at the times the sweep reaches (at most kLawSamples of them, evenly picked), so
// that a law undefined inside the sweep, like 1/(t-1) over 0..2 s, is found before solving.
// Driver laws need their first two derivatives too (velocities and accelerations).
void check_laws_over_sweep(const Mechanism& mech, ModelSummary& out) {
  constexpr double kLawSamples = 20000;
  const Model& m = mech.model();
  bool any_law = !m.point_loads.empty() || !m.torques.empty();
  for (const Driver& d : m.drivers) any_law = any_law || d.law.has_value();
  if (!any_law || !(sweep_sample_count(m) <= 1e6)) return;  // a sweep too large is refused by the sweep itself
  std::vector<double> times;
  try {
    times = sweep_path(mech).times;
  } catch (const Error&) {
    return;  // the sweep's own error, which solving reports
  }
  const std::size_t stride = std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(times.size() / kLawSamples)));
  const auto check = [&](const Law& law, EntityRef::Kind kind, std::size_t index, int which, double t, int terms) {
    try {
      if (terms > 1)
        (void)law.series(t, terms);
      else
        (void)law.value(t);
    } catch (const Error& e) {
      out.law_error = Error(e.kind(), e.message(), EntityRef{kind, static_cast<int>(index), which});
    }
  };
  std::vector<double> picked;
  for (std::size_t k = 0; k < times.size(); k += stride) picked.push_back(times[k]);
  if (!times.empty() && (times.size() - 1) % stride != 0) picked.push_back(times.back());
  for (const double t : picked) {
    if (out.law_error) break;
    for (std::size_t d = 0; d < m.drivers.size() && !out.law_error; ++d)
      if (m.drivers[d].law) check(*m.drivers[d].law, EntityRef::Kind::Driver, d, 0, t, 3);
    for (std::size_t i = 0; i < m.point_loads.size() && !out.law_error; ++i) {
      check(m.point_loads[i].fx, EntityRef::Kind::PointLoad, i, 0, t, 1);
      if (!out.law_error) check(m.point_loads[i].fy, EntityRef::Kind::PointLoad, i, 1, t, 1);
    }
    for (std::size_t i = 0; i < m.torques.size() && !out.law_error; ++i)
      check(m.torques[i].torque, EntityRef::Kind::Torque, i, 0, t, 1);
  }
}

// Assembles at the start of the sweep and classifies every four-bar loop in that pose.
void summarize_start(const Mechanism& mech, int max_steps, double work_budget, ModelSummary& out) {
  State state(mech);
  try {
    AssemblySummary a;
    a.driver_values = sweep_start_values(mech, max_steps);
    const AssemblyReport report = assemble(mech, state, a.driver_values);
    a.residual = report.residual;
    a.passed_singularity = report.passed_singularity;
    out.assembly = a;
  } catch (const Error& e) {
    out.assembly_error = e;
    return;
  } catch (const std::exception& e) {
    out.assembly_error = Error(ErrorKind::CannotAssemble, e.what());
    return;
  }
  const auto points = point_positions(mech, state.q);
  for (const FourBarLoop& loop : mech.four_bar_loops()) {
    LoopSummary l;
    l.loop = loop;
    l.grashof = classify_grashof(loop, points, mech.tolerance());
    l.description = describe(l.grashof, loop, mech.model());
    l.branch = branch_name(branch_sign(loop, points));
    l.transmission_angle = transmission_angle(loop, points);
    if (loop.frame < 0 && l.grashof.input_turns_fully)
      l.transmission_over_turn =
          transmission_over_full_turn(l.grashof.frame, l.grashof.input, l.grashof.coupler, l.grashof.output);
    add_input_toggles(mech, points, l);
    add_rocker_swing(mech, points, l);
    out.loops.push_back(std::move(l));
  }
  find_limits(mech, work_budget, out);
  warn_about_input_limits(mech, out);
  describe_rocking(mech, work_budget, out);
}

}  // namespace

std::vector<std::string> joint_descriptions(const Model& model) { return describe_joints(model); }

std::vector<Warning> check_before_sweep(const Mechanism& mech) {
  ModelSummary s;
  warn_about_many_turns(mech.model(), s);
  warn_about_points_off_plates(mech.model(), s.warnings);
  check_laws_over_sweep(mech, s);
  if (s.law_error) throw *s.law_error;
  return s.warnings;
}

ModelSummary summarize(const Mechanism& mech, int max_steps, double limit_search_work) {
  const Model& m = mech.model();
  ModelSummary s;
  // The reader's guide points (a guide by a point and an angle) are not the user's: not listed.
  for (const Point& p : m.points)
    if (!p.guide_direction) (p.ground ? s.ground_points : s.moving_points).push_back(p.name);
  for (const Body& b : m.bodies) {
    s.bodies.push_back(summarize_body(m, b));
    s.has_masses = s.has_masses || s.bodies.back().mass.mass > 0.0;
    s.has_shapes = s.has_shapes || b.shape.has_value();
    s.has_mass_data = s.has_mass_data || b.inertia.has_value() || b.shape.has_value();
    s.has_stress_links = s.has_stress_links || (b.shape && b.thickness > 0.0 && b.points.size() >= 2);
  }
  s.has_loads = !m.gravity.isZero() || !m.point_loads.empty() || !m.torques.empty() || !m.springs.empty();
  s.joints = describe_joints(m);
  s.mobility = mech.mobility();
  for (int r : s.mobility.redundant) s.redundant.push_back(mech.row_label(r));
  for (std::size_t d = 0; d < m.drivers.size(); ++d) s.drivers.push_back(describe_driver(m, static_cast<int>(d)));
  warn_about_many_turns(m, s);
  warn_about_points_off_plates(m, s.warnings);
  summarize_crank_mechanisms(m, s);
  summarize_start(mech, max_steps, limit_search_work, s);
  if (s.assembly)
    for (Warning& w : cylinder_warnings(mech)) s.warnings.push_back(std::move(w));
  check_laws_over_sweep(mech, s);
  return s;
}

}  // namespace nbar
