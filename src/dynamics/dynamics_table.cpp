#include "nbar/dynamics/dynamics_table.hpp"

#include <cmath>

namespace nbar {

namespace {

std::string link_name(const Model& m, int link) { return link < 0 ? std::string("ground") : m.bodies[link].name; }

}  // namespace

std::vector<JointForceColumn> joint_force_columns(const InverseDynamics& dynamics) {
  const Model& m = dynamics.mechanism().model();
  const auto& links = dynamics.joint_links();
  std::vector<JointForceColumn> forces;
  for (std::size_t i = 0; i < links.size();) {
    std::size_t end = i;
    while (end < links.size() && links[end].point == links[i].point) ++end;
    const std::string& point = m.points[links[i].point].name;
    const auto add_force = [&](std::size_t k, const std::string& name) {
      const int receiver = links[k].link >= 0 && m.bodies[links[k].link].points.size() >= 2 ? links[k].link : -1;
      forces.push_back({name, k, receiver});
    };
    if (end - i == 2) {
      add_force(i + 1, point + "." + link_name(m, links[i].link) + ">" + link_name(m, links[i + 1].link));
    } else {
      for (std::size_t k = i; k < end; ++k) add_force(k, point + ".pin>" + link_name(m, links[k].link));
    }
    i = end;
  }
  return forces;
}

std::vector<ColumnName> dynamics_columns(const InverseDynamics& dynamics) {
  const Model& m = dynamics.mechanism().model();
  std::vector<ColumnName> columns;
  for (const JointForceColumn& f : joint_force_columns(dynamics)) {
    columns.push_back({f.name + ".Fx", "N"});
    columns.push_back({f.name + ".Fy", "N"});
    if (f.receiver >= 0) {
      columns.push_back({f.name + ".along", "N"});
      columns.push_back({f.name + ".across", "N"});
    }
  }
  for (const Slider& s : m.sliders) {
    columns.push_back({m.bodies[s.body].name + ".slider.N", "N"});
    columns.push_back({m.bodies[s.body].name + ".slider.M", "N m"});
  }
  for (const Slot& s : m.slots) columns.push_back({m.points[s.point].name + ".slot.N", "N"});
  for (const Driver& d : m.drivers) columns.push_back({d.name + (d.kind == DriverKind::Angle ? ".torque" : ".force"),
                                                       d.kind == DriverKind::Angle ? "N m" : "N"});
  columns.push_back({"energy.kinetic", "J"});
  columns.push_back({"energy.potential", "J"});
  return columns;
}

void append_dynamics_columns(const InverseDynamics& dynamics, const SweepResult& sweep,
                             const std::vector<DynamicsResult>& results, ResultTable& table) {
  const Mechanism& mech = dynamics.mechanism();
  const Model& m = mech.model();
  for (ColumnName& c : dynamics_columns(dynamics)) {
    table.columns.push_back(std::move(c.name));
    table.units.push_back(std::move(c.unit));
  }
  const std::vector<JointForceColumn> forces = joint_force_columns(dynamics);
  for (std::size_t row = 0; row < sweep.samples.size(); ++row) {
    const Sample& sample = sweep.samples[row];
    const DynamicsResult& r = results[row];
    std::vector<double>& out = table.rows[row];
    for (const JointForceColumn& f : forces) {
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
}

}  // namespace nbar
