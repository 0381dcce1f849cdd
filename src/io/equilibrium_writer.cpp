#include "nbar/io/equilibrium_writer.hpp"

#include <nlohmann/json.hpp>

#include <fmt/format.h>

#include "json_text.hpp"

namespace nbar::io {

namespace {

// A free driver's value in the model's units, with the unit.
double in_model_units(const Model& m, int driver, double value) {
  return m.drivers[driver].is_angular() ? value / m.units.angle_scale : value / m.units.length_scale;
}
const std::string& unit_of(const Model& m, int driver) {
  return m.drivers[driver].is_angular() ? m.units.angle : m.units.length;
}
// The SI unit of a generalised force on a driver.
const char* force_unit(const Model& m, int driver) { return m.drivers[driver].is_angular() ? "N m" : "N"; }

std::string stiffness_units(const Model& m, const Equilibrium& e) {
  bool angular = false, linear = false;
  for (int d : e.free_drivers) (m.drivers[d].is_angular() ? angular : linear) = true;
  if (angular && linear) return "SI, mixed: N m/rad, N/rad, N and N/m";
  return angular ? "N m/rad" : "N/m";
}

}  // namespace

void write_equilibrium_summary(std::ostream& out, const Mechanism& mechanism, const Equilibrium& equilibrium) {
  const Model& m = mechanism.model();
  const char* meaning = equilibrium.stability == Stability::stable     ? "a small push is pulled back"
                        : equilibrium.stability == Stability::unstable ? "a small push moves it away"
                                                                       : "a small push moves it as far as it goes";
  out << "Equilibrium: " << to_string(equilibrium.stability) << " (" << meaning << "), found in "
      << equilibrium.iterations << " Newton iteration" << (equilibrium.iterations == 1 ? "" : "s") << '\n';
  for (std::size_t i = 0; i < equilibrium.free_drivers.size(); ++i) {
    const int d = equilibrium.free_drivers[i];
    out << fmt::format("  {} = {:.10g} {}  (generalised force left {:.3g} {})\n", m.drivers[d].name,
                       in_model_units(m, d, equilibrium.pose.driver_values[d]), unit_of(m, d), equilibrium.forces[i],
                       force_unit(m, d));
  }
  out << "Stiffness eigenvalues (" << stiffness_units(m, equilibrium) << "):";
  for (double v : equilibrium.eigenvalues) out << fmt::format(" {:.6g}", v);
  out << '\n';
}

void write_equilibrium_json(std::ostream& out, const Mechanism& mechanism, const Equilibrium& equilibrium,
                            const ResultTable& table) {
  const Model& m = mechanism.model();
  nlohmann::ordered_json j;
  j["model"] = m.name;
  j["units"] = {{"length", m.units.length}, {"angle", m.units.angle}, {"force", "N"}, {"torque", "N m"}};
  nlohmann::ordered_json free = nlohmann::ordered_json::object();
  nlohmann::ordered_json forces = nlohmann::ordered_json::object();
  for (std::size_t i = 0; i < equilibrium.free_drivers.size(); ++i) {
    const int d = equilibrium.free_drivers[i];
    free[m.drivers[d].name] = in_model_units(m, d, equilibrium.pose.driver_values[d]);
    forces[m.drivers[d].name] = equilibrium.forces[i];
  }
  j["free_drivers"] = free;
  j["stability"] = to_string(equilibrium.stability);
  j["stiffness_eigenvalues"] = equilibrium.eigenvalues;
  std::vector<std::vector<double>> stiffness;
  for (Eigen::Index r = 0; r < equilibrium.stiffness.rows(); ++r) {
    stiffness.emplace_back();
    for (Eigen::Index c = 0; c < equilibrium.stiffness.cols(); ++c)
      stiffness.back().push_back(equilibrium.stiffness(r, c));
  }
  j["stiffness"] = stiffness;
  j["stiffness_units"] = stiffness_units(m, equilibrium);
  j["residual"] = equilibrium.residual;
  j["generalised_forces"] = forces;
  j["iterations"] = equilibrium.iterations;
  j["columns"] = table.columns;
  j["column_units"] = table.units;
  j["row"] = table.rows.front();
  put_warnings(j, equilibrium.warnings);
  out << json_text(j, 1) << '\n';
}

}  // namespace nbar::io
