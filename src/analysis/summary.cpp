#include "nbar/analysis/summary.hpp"

#include <fmt/format.h>

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
    case DriverKind::Slide:
      what = "slide of " + m.bodies[m.sliders[drv.slider].body].name + " along its guide";
      break;
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
  for (int p : b.points) s.points.push_back(m.points[p].name);
  if (b.points.size() >= 2) {
    s.length = b.length.value_or((m.points[b.points[1]].position - m.points[b.points[0]].position).norm());
    s.length_given = b.length.has_value();
  }
  s.mass = mass_properties(b);
  s.mass_source = b.inertia ? "given" : b.shape ? (b.material ? b.material->name : "shape, no material") : "none";
  return s;
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
                     m.points[s.along[0]].name + "-" + m.points[s.along[1]].name);
  for (const Slot& s : m.slots)
    joints.push_back("slot " + m.points[s.point].name + " in " + m.points[s.along[0]].name + "-" +
                     m.points[s.along[1]].name);
  return joints;
}

// Assembles at the start of the sweep and classifies every four-bar loop in that pose.
void summarize_start(const Mechanism& mech, ModelSummary& out) {
  State state(mech);
  try {
    AssemblySummary a;
    a.driver_values = sweep_start_values(mech);
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
    out.loops.push_back(std::move(l));
  }
}

}  // namespace

ModelSummary summarize(const Mechanism& mech) {
  const Model& m = mech.model();
  ModelSummary s;
  for (const Point& p : m.points) (p.ground ? s.ground_points : s.moving_points).push_back(p.name);
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
  for (int r : s.mobility.redundant) s.redundant.push_back(mech.rows()[r].label);
  for (std::size_t d = 0; d < m.drivers.size(); ++d) s.drivers.push_back(describe_driver(m, static_cast<int>(d)));
  summarize_start(mech, s);
  return s;
}

}  // namespace nbar
