#include "nbar/dynamics/dynamics_table.hpp"

#include <array>

#include <cmath>

namespace nbar {

namespace {

std::string link_or_ground_name(const Model& m, int link) {
  return link < 0 ? std::string("ground") : m.bodies[link].name;
}

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
      add_force(i + 1,
                point + "." + link_or_ground_name(m, links[i].link) + ">" + link_or_ground_name(m, links[i + 1].link));
    } else {
      for (std::size_t k = i; k < end; ++k) add_force(k, point + ".pin>" + link_or_ground_name(m, links[k].link));
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
  for (const Driver& d : m.drivers)
    columns.push_back(
        {d.name + (d.kind == DriverKind::Angle ? ".torque" : ".force"), d.kind == DriverKind::Angle ? "N m" : "N"});
  columns.push_back({"energy.kinetic", "J"});
  columns.push_back({"energy.potential", "J"});
  return columns;
}

namespace {

// One sample's dynamics columns, value j at out[j * stride] (see make_column_table).
void fill_dynamics_row(const Mechanism& mech, const std::vector<JointForceColumn>& forces, const Sample& sample,
                       const DynamicsResult& r, double* out, std::ptrdiff_t stride) {
  const Model& m = mech.model();
  std::ptrdiff_t j = 0;
  auto put = [&](double v) { out[stride * j++] = v; };
  std::array<double, Series::kCapacity> ax{}, ay{}, bx{}, by{};
  for (const JointForceColumn& f : forces) {
    const Eigen::Vector2d& force = r.pin_forces[f.joint_link];
    put(force.x());
    put(force.y());
    if (f.receiver >= 0) {
      const auto& pts = m.bodies[f.receiver].points;
      point_derivatives(mech, sample, pts[0], ax.data(), ay.data());
      point_derivatives(mech, sample, pts[1], bx.data(), by.data());
      const Eigen::Vector2d axis = Eigen::Vector2d(bx[0] - ax[0], by[0] - ay[0]).normalized();
      put(force.dot(axis));
      put(axis.x() * force.y() - axis.y() * force.x());
    }
  }
  for (std::size_t s = 0; s < m.sliders.size(); ++s) {
    put(r.slider_normal[s]);
    put(r.slider_couple[s]);
  }
  for (double n : r.slot_normal) put(n);
  for (double e : r.driver_effort) put(e);
  put(r.kinetic_energy);
  put(r.potential_energy);
}

template <class Table>
void name_dynamics_columns(const InverseDynamics& dynamics, Table& table) {
  for (ColumnName& c : dynamics_columns(dynamics)) {
    table.columns.push_back(std::move(c.name));
    table.units.push_back(std::move(c.unit));
  }
}

}  // namespace

DynamicsRows::DynamicsRows(const InverseDynamics& dynamics)
    : dynamics_(dynamics), forces_(joint_force_columns(dynamics)), count_(dynamics_columns(dynamics).size()) {}

void DynamicsRows::fill(const Sample& sample, const DynamicsResult& result, double* out, std::ptrdiff_t stride) const {
  fill_dynamics_row(dynamics_.mechanism(), forces_, sample, result, out, stride);
}

void append_dynamics_columns(const InverseDynamics& dynamics, const SweepResult& sweep,
                             const std::vector<DynamicsResult>& results, ResultTable& table) {
  const std::size_t first = table.columns.size();
  name_dynamics_columns(dynamics, table);
  const std::vector<JointForceColumn> forces = joint_force_columns(dynamics);
  for (std::size_t row = 0; row < sweep.samples.size(); ++row) {
    std::vector<double>& out = table.rows[row];
    out.resize(table.columns.size());
    fill_dynamics_row(dynamics.mechanism(), forces, sweep.samples[row], results[row], out.data() + first, 1);
  }
}

void append_dynamics_columns(const InverseDynamics& dynamics, const SweepResult& sweep,
                             const std::vector<DynamicsResult>& results, ColumnTable& table) {
  const auto first = static_cast<Eigen::Index>(table.columns.size());
  name_dynamics_columns(dynamics, table);
  const auto samples = static_cast<std::ptrdiff_t>(sweep.samples.size());
  table.values.conservativeResize(samples, static_cast<Eigen::Index>(table.columns.size()));
  const std::vector<JointForceColumn> forces = joint_force_columns(dynamics);
  for (std::ptrdiff_t r = 0; r < samples; ++r)
    fill_dynamics_row(dynamics.mechanism(), forces, sweep.samples[r], results[r],
                      table.values.data() + first * samples + r, samples);
}

}  // namespace nbar
