// The static equilibrium (nbar equilibrium) from Python, through its request as on the command line.
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "nbar/request/equilibrium_request.hpp"

namespace nbar::python {

namespace {

// Model.equilibrium's answer: plain data in the model's units (the stiffness in SI).
py::dict equilibrium(std::shared_ptr<PyModel> model, std::optional<long long> max_iterations,
                     std::optional<double> timeout) {
  request::Options given;
  if (max_iterations) given.set("max_iterations", *max_iterations);
  const request::EquilibriumRequest request = request::EquilibriumRequest::read(given);
  RunControl control;
  Equilibrium found;
  run_interruptible(control, timeout, [&] {
    try {
      found = find_equilibrium(*model->mechanism, request.equilibrium_options(), control);
    } catch (const Error& e) {
      throw located(*model, e);
    }
  });
  const Model& m = model->mechanism->model();
  const ResultTable table = request.table(*model->mechanism, found);
  py::dict free, forces, pose, units;
  for (std::size_t i = 0; i < found.free_drivers.size(); ++i) {
    const Driver& d = m.drivers[found.free_drivers[i]];
    const double value = found.pose.driver_values[found.free_drivers[i]];
    free[py::str(d.name)] = d.is_angular() ? value / m.units.angle_scale : value / m.units.length_scale;
    forces[py::str(d.name)] = found.forces[i];
  }
  for (std::size_t c = 0; c < table.columns.size(); ++c) {
    pose[py::str(table.columns[c])] = table.rows.front()[c];
    units[py::str(table.columns[c])] = table.units[c];
  }
  std::vector<std::vector<double>> stiffness;
  for (Eigen::Index r = 0; r < found.stiffness.rows(); ++r) {
    stiffness.emplace_back();
    for (Eigen::Index c = 0; c < found.stiffness.cols(); ++c) stiffness.back().push_back(found.stiffness(r, c));
  }
  py::dict out;
  out["free_drivers"] = free;
  out["stability"] = to_string(found.stability);
  out["eigenvalues"] = found.eigenvalues;
  out["stiffness"] = stiffness;
  out["residual"] = found.residual;
  out["forces"] = forces;
  out["iterations"] = found.iterations;
  out["pose"] = pose;
  out["units"] = units;
  out["warnings"] = warning_list(found.warnings);
  return out;
}

}  // namespace

void bind_equilibrium(py::module_& m) {
  m.def("equilibrium", &equilibrium, py::arg("model"), py::arg("max_iterations") = std::nullopt,
        py::arg("timeout") = std::nullopt);
}

}  // namespace nbar::python
