#include "nbar/dynamics/dynamics_table.hpp"

#include <cmath>

namespace nbar {

namespace {

std::string link_name(const Model& m, int link) { return link < 0 ? std::string("ground") : m.bodies[link].name; }

struct ForceColumns {
  std::size_t joint_link;  // index into InverseDynamics::joint_links()
  int receiver;            // body whose axis gives along/across, or -1
};

}  // namespace

DynamicsSummary append_dynamics(const Mechanism& mech, const SweepResult& sweep, ResultTable& table) {
  const Model& m = mech.model();
  const InverseDynamics dynamics(mech);
  DynamicsSummary summary;
  auto add = [&](std::string name, std::string unit) {
    table.columns.push_back(std::move(name));
    table.units.push_back(std::move(unit));
  };

  // Which pin forces to show: with two links at a joint, the force the first exerts on the
  // second (equal to the pin's force on the second); with more, the pin's force on each.
  std::vector<ForceColumns> forces;
  const auto& links = dynamics.joint_links();
  for (std::size_t i = 0; i < links.size();) {
    std::size_t end = i;
    while (end < links.size() && links[end].point == links[i].point) ++end;
    const std::string& point = m.points[links[i].point].name;
    auto add_force = [&](std::size_t k, const std::string& prefix) {
      const int receiver = links[k].link >= 0 && m.bodies[links[k].link].points.size() >= 2 ? links[k].link : -1;
      forces.push_back({k, receiver});
      add(prefix + ".Fx", "N");
      add(prefix + ".Fy", "N");
      if (receiver >= 0) {
        add(prefix + ".along", "N");
        add(prefix + ".across", "N");
      }
    };
    if (end - i == 2) {
      add_force(i + 1, point + "." + link_name(m, links[i].link) + ">" + link_name(m, links[i + 1].link));
    } else {
      for (std::size_t k = i; k < end; ++k) add_force(k, point + ".pin>" + link_name(m, links[k].link));
    }
    i = end;
  }
  for (const Slider& s : m.sliders) {
    add(m.bodies[s.body].name + ".slider.N", "N");
    add(m.bodies[s.body].name + ".slider.M", "N m");
  }
  for (const Slot& s : m.slots) add(m.points[s.point].name + ".slot.N", "N");
  for (const Driver& d : m.drivers) {
    if (d.kind == DriverKind::Angle)
      add(d.name + ".torque", "N m");
    else
      add(d.name + ".force", "N");
  }
  add("energy.kinetic", "J");
  add("energy.potential", "J");

  for (std::size_t row = 0; row < sweep.samples.size(); ++row) {
    const Sample& sample = sweep.samples[row];
    const DynamicsResult r = dynamics.solve(sample);
    summary.unique = summary.unique && r.unique;
    summary.max_residual = std::max(summary.max_residual, r.residual);
    std::vector<double>& out = table.rows[row];
    for (const ForceColumns& f : forces) {
      const Eigen::Vector2d& force = r.pin_forces[f.joint_link];
      out.push_back(force.x());
      out.push_back(force.y());
      if (f.receiver >= 0) {
        const auto& pts = m.bodies[f.receiver].points;
        const Motion2 a = point_motion(mech, sample, pts[0]), b = point_motion(mech, sample, pts[1]);
        const Eigen::Vector2d axis = Eigen::Vector2d(b.x[0] - a.x[0], b.y[0] - a.y[0]).normalized();
        out.push_back(force.dot(axis));
        out.push_back(axis.x() * force.y() - axis.y() * force.x());
      }
    }
    for (std::size_t s = 0; s < m.sliders.size(); ++s) {
      out.push_back(r.slider_normal[s]);
      out.push_back(r.slider_couple[s]);
    }
    for (double n : r.slot_normal) out.push_back(n);
    for (double e : r.driver_effort) out.push_back(e);
    out.push_back(r.kinetic_energy);
    out.push_back(r.potential_energy);
  }
  if (!summary.unique)
    summary.warnings.push_back(
        "the mechanism has redundant constraints: its joint forces are not unique (statically indeterminate); "
        "the minimum-norm set is given");
  return summary;
}

}  // namespace nbar
