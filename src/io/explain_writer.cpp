#include "explain_writer.hpp"

#include <cmath>

namespace nbar::io {

namespace {

using nlohmann::json;

// A finite number, or 0 for anything else (the explanation holds none, but JSON must never
// carry NaN).
double finite(double v) { return std::isfinite(v) ? v : 0.0; }

json vector_json(const Eigen::VectorXd& v) {
  json a = json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) a.push_back(finite(v[i]));
  return a;
}

json matrix_json(const Eigen::MatrixXd& m) {
  json rows = json::array();
  for (Eigen::Index r = 0; r < m.rows(); ++r) rows.push_back(vector_json(m.row(r).transpose()));
  return rows;
}

json system_json(const LinearSystem& s) { return {{"rhs", vector_json(s.rhs)}, {"solution", vector_json(s.solution)}}; }

}  // namespace

json explanation_json(const Explanation& ex) {
  const Model& m = ex.mechanism->model();
  json j;
  j["model"] = m.name;
  j["step"] = ex.step;
  j["time"] = finite(ex.time);
  j["units"] = {{"length", m.units.length}, {"angle", m.units.angle}, {"time", "s"}};
  json drivers = json::array();
  for (std::size_t d = 0; d < m.drivers.size(); ++d)
    drivers.push_back({{"name", m.drivers[d].name},
                       {"kind", m.drivers[d].is_angular() ? "angle" : "length"},
                       {"value", finite(ex.driver_values[d])}});
  j["drivers"] = drivers;
  j["count"] = {{"links", ex.count.links},
                {"lower_pairs", ex.count.lower_pairs},
                {"higher_pairs", ex.count.higher_pairs},
                {"dof", ex.count.dof},
                {"mobility", ex.count.mobility}};
  json q = json::array();
  for (const Coordinate& c : ex.coordinates)
    q.push_back(
        {{"name", c.name}, {"symbol", c.symbol}, {"point", m.points[c.point].name}, {"axis", c.axis == 0 ? "x" : "y"}});
  j["coordinates"] = q;
  json rows = json::array();
  for (const EquationRow& e : ex.equations) {
    json d = json::array();
    for (const auto& entry : e.jacobian)
      d.push_back({{"column", entry.column}, {"text", entry.text}, {"latex", entry.latex}});
    rows.push_back({{"label", e.label},
                    {"kind", e.kind},
                    {"text", e.text},
                    {"latex", e.latex},
                    {"jacobian", d},
                    {"driver", e.driver},
                    {"scale", finite(e.scale)}});
  }
  j["equations"] = rows;
  json newton = json::array();
  for (const NewtonIteration& it : ex.newton) {
    json k = {{"iteration", it.iteration}, {"q", vector_json(it.q)}, {"residual", finite(it.residual)}};
    if (it.dq.size()) k["dq"] = vector_json(it.dq);
    newton.push_back(k);
  }
  j["newton"] = {{"start", ex.start}, {"converged", ex.converged}, {"iterations", newton}};
  j["q"] = vector_json(ex.q);
  j["residual"] = finite(ex.residual);
  j["matches_sweep"] = ex.matches_sweep;
  j["sweep_difference"] = finite(ex.sweep_difference);
  j["jacobian"] = matrix_json(ex.jacobian);
  j["velocity"] = system_json(ex.velocity);
  j["acceleration"] = system_json(ex.acceleration);
  json centres = json::array();
  for (const InstantCentre& c : ex.centres) {
    json k = {{"name", c.name},
              {"links", {c.body_a < 0 ? "ground" : m.bodies[c.body_a].name, m.bodies[c.body_b].name}},
              {"primary", c.at_joint},
              {"at_infinity", c.at_infinity},
              {"indeterminate", c.indeterminate}};
    if (c.at_infinity)
      k["direction"] = {finite(c.direction.x()), finite(c.direction.y())};
    else if (!c.indeterminate)
      k["position"] = {finite(c.position.x()), finite(c.position.y())};
    centres.push_back(k);
  }
  j["centres"] = centres;
  // The stresses at the pose: von Mises in MPa (`unit`), `at` along the link in the model's length.
  json stresses = json::array();
  for (const StressPeak& p : ex.stresses)
    stresses.push_back({{"body", m.bodies[p.body].name},
                        {"von_mises", finite(to_megapascal(p.at.von_mises))},
                        {"unit", "MPa"},
                        {"at", finite(p.at.position / m.units.length_scale)},
                        {"safety_factor", p.safety_factor ? json(finite(*p.safety_factor)) : json(nullptr)}});
  j["stresses"] = stresses;
  j["notes"] = ex.notes;
  return j;
}

json equations_of_motion_json(const Mechanism& mechanism, const EquationsOfMotionAt& e) {
  json j;
  j["model"] = mechanism.model().name;
  j["time"] = finite(e.time);
  j["units"] = {{"q", "m"},         {"velocity", "m/s"},       {"mass", "kg"},      {"forces", "N"},
                {"gamma", "m/s^2"}, {"acceleration", "m/s^2"}, {"multipliers", "N"}};
  j["system"] = "[M Phi_q^T; Phi_q 0] [acceleration; multipliers] = [forces; gamma]";
  j["free_drivers"] = e.free_drivers;
  j["coordinates"] = e.coordinates;
  j["rows"] = e.row_labels;
  j["q"] = vector_json(e.q);
  j["velocity"] = vector_json(e.velocity);
  j["mass"] = matrix_json(e.mass);
  j["jacobian"] = matrix_json(e.jacobian);
  j["forces"] = {{"gravity", vector_json(e.gravity)},
                 {"given", vector_json(e.applied)},
                 {"springs", vector_json(e.springs)},
                 {"friction", vector_json(e.friction)},
                 {"total", vector_json(e.forces)}};
  j["gamma"] = vector_json(e.gamma);
  j["acceleration"] = vector_json(e.acceleration);
  j["multipliers"] = vector_json(e.multipliers);
  j["residual"] = finite(e.residual);
  j["simulated_acceleration"] = vector_json(e.simulated_acceleration);
  j["accepted_steps"] = e.accepted_steps;
  return j;
}

}  // namespace nbar::io
