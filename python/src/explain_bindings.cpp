// The step-by-step explanation (nbar/analysis/explain.hpp) from Python: every part as numpy
// arrays and plain data, and the documents render_explanation writes.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "io/explain_writer.hpp"
#include "nbar/analysis/explain.hpp"
#include "nbar/render/pictures.hpp"
#include "nbar/request/requests.hpp"

namespace nbar::python {

namespace {

ExplainFormat format_of(const std::string& name) {
  if (name == "text") return ExplainFormat::Text;
  if (name == "markdown") return ExplainFormat::Markdown;
  if (name == "latex") return ExplainFormat::Latex;
  throw Error(ErrorKind::BadInput, "an explanation is rendered as text, markdown or latex, not '" + name + "'");
}

py::dict system_dict(const LinearSystem& s) {
  return py::dict(py::arg("matrix") = s.matrix, py::arg("rhs") = s.rhs, py::arg("solution") = s.solution);
}

py::list equation_list(const Explanation& e) {
  py::list rows;
  for (const EquationRow& r : e.equations) {
    py::list derivatives;
    for (const EquationRow::Derivative& d : r.jacobian) derivatives.append(py::make_tuple(d.column, d.text, d.latex));
    py::dict d;
    d["label"] = r.label;
    d["kind"] = r.kind;
    d["text"] = r.text;
    d["latex"] = r.latex;
    d["jacobian"] = derivatives;
    d["driver"] = r.driver;
    d["scale"] = r.scale;
    rows.append(d);
  }
  return rows;
}

py::list centre_list(const Explanation& e) {
  py::list centres;
  for (const InstantCentre& c : e.centres) {
    py::dict d;
    d["name"] = c.name;
    d["bodies"] = py::make_tuple(c.body_a, c.body_b);
    d["at_infinity"] = c.at_infinity;
    d["position"] = c.at_infinity ? py::object(py::none()) : py::object(py::make_tuple(c.position.x(), c.position.y()));
    d["direction"] =
        c.at_infinity ? py::object(py::make_tuple(c.direction.x(), c.direction.y())) : py::object(py::none());
    d["at_joint"] = c.at_joint;
    d["indeterminate"] = c.indeterminate;
    centres.append(d);
  }
  return centres;
}

// Each shaped link's largest von Mises stress at the pose, as explain's JSON gives it: MPa, the
// place along the link in the model's length unit.
py::list stress_list(const Explanation& e) {
  const Model& m = e.mechanism->model();
  py::list stresses;
  for (const StressPeak& p : e.stresses) {
    py::dict d;
    d["body"] = m.bodies[p.body].name;
    d["von_mises"] = to_megapascal(p.at.von_mises);
    d["unit"] = "MPa";
    d["at"] = p.at.position / m.units.length_scale;
    d["safety_factor"] = p.safety_factor ? py::object(py::float_(*p.safety_factor)) : py::object(py::none());
    stresses.append(d);
  }
  return stresses;
}

py::list newton_list(const Explanation& e) {
  py::list iterations;
  for (const NewtonIteration& it : e.newton)
    iterations.append(py::dict(py::arg("iteration") = it.iteration, py::arg("q") = it.q,
                               py::arg("residual") = it.residual, py::arg("dq") = it.dq));
  return iterations;
}

// The equations of motion at a time, with the model and the request that made them.
struct PyEquationsOfMotion {
  std::shared_ptr<PyModel> model;
  request::ExplainRequest request;
  EquationsOfMotionAt equations;
};

void bind_explanation(py::module_& m) {
  py::class_<Explanation, std::shared_ptr<Explanation>>(m, "NativeExplanation")
      .def_readonly("step", &Explanation::step)
      .def_readonly("time", &Explanation::time)
      .def_readonly("driver_values", &Explanation::driver_values)
      .def_property_readonly("count",
                             [](const Explanation& e) {
                               return py::dict(py::arg("links") = e.count.links,
                                               py::arg("lower_pairs") = e.count.lower_pairs,
                                               py::arg("higher_pairs") = e.count.higher_pairs,
                                               py::arg("dof") = e.count.dof, py::arg("mobility") = e.count.mobility);
                             })
      .def_property_readonly("coordinates",
                             [](const Explanation& e) {
                               std::vector<std::string> names;
                               for (const Coordinate& c : e.coordinates) names.push_back(c.name);
                               return names;
                             })
      .def_property_readonly("equations", &equation_list)
      .def_property_readonly("newton", &newton_list)
      .def_readonly("converged", &Explanation::converged)
      .def_readonly("start", &Explanation::start)
      .def_readonly("jacobian", &Explanation::jacobian)
      .def_readonly("q", &Explanation::q)
      .def_property_readonly("velocity", [](const Explanation& e) { return system_dict(e.velocity); })
      .def_property_readonly("acceleration", [](const Explanation& e) { return system_dict(e.acceleration); })
      .def_property_readonly("centres", &centre_list)
      .def_property_readonly("stresses", &stress_list)
      .def_readonly("residual", &Explanation::residual)
      .def_readonly("matches_sweep", &Explanation::matches_sweep)
      .def_readonly("sweep_difference", &Explanation::sweep_difference)
      .def_readonly("notes", &Explanation::notes)
      .def("json", [](const Explanation& e) { return io::explanation_json(e).dump(2); })
      .def(
          "centres_picture",
          [](const Explanation& e, const std::string& format) -> py::object {
            if (format == "svg") return py::str(render::instant_centres_svg(e));
            if (format == "png") {
              const std::vector<std::uint8_t> png = render::instant_centres_png(e);
              return py::bytes(reinterpret_cast<const char*>(png.data()), png.size());
            }
            throw Error(ErrorKind::BadInput, "a picture's format is svg or png, not '" + format + "'");
          },
          py::arg("format") = "svg")
      .def(
          "render",
          [](const Explanation& e, const std::string& format) { return render_explanation(e, format_of(format)); },
          py::arg("format") = "text");

}

// `explain(simulate=True, at=T)`: the equations of motion, read by the command line's request.
void bind_equations_of_motion(py::module_& m) {
  py::class_<PyEquationsOfMotion, std::shared_ptr<PyEquationsOfMotion>>(m, "NativeEquationsOfMotion")
      .def_property_readonly("time", [](const PyEquationsOfMotion& e) { return e.equations.time; })
      .def_property_readonly("q", [](const PyEquationsOfMotion& e) { return e.equations.q; })
      .def_property_readonly("velocity", [](const PyEquationsOfMotion& e) { return e.equations.velocity; })
      .def_property_readonly("coordinates", [](const PyEquationsOfMotion& e) { return e.equations.coordinates; })
      .def_property_readonly("rows", [](const PyEquationsOfMotion& e) { return e.equations.row_labels; })
      .def_property_readonly("free_drivers", [](const PyEquationsOfMotion& e) { return e.equations.free_drivers; })
      .def_property_readonly("mass", [](const PyEquationsOfMotion& e) { return e.equations.mass; })
      .def_property_readonly("jacobian", [](const PyEquationsOfMotion& e) { return e.equations.jacobian; })
      .def_property_readonly("forces",
                             [](const PyEquationsOfMotion& e) {
                               const EquationsOfMotionAt& q = e.equations;
                               return py::dict(py::arg("gravity") = q.gravity, py::arg("given") = q.applied,
                                               py::arg("springs") = q.springs, py::arg("friction") = q.friction,
                                               py::arg("total") = q.forces);
                             })
      .def_property_readonly("gamma", [](const PyEquationsOfMotion& e) { return e.equations.gamma; })
      .def_property_readonly("acceleration", [](const PyEquationsOfMotion& e) { return e.equations.acceleration; })
      .def_property_readonly("multipliers", [](const PyEquationsOfMotion& e) { return e.equations.multipliers; })
      .def_property_readonly("residual", [](const PyEquationsOfMotion& e) { return e.equations.residual; })
      .def_property_readonly("simulated_acceleration",
                             [](const PyEquationsOfMotion& e) { return e.equations.simulated_acceleration; })
      .def("render",
           [](const PyEquationsOfMotion& e) { return render_equations_of_motion(*e.model->mechanism, e.equations); })
      .def("json", [](const PyEquationsOfMotion& e) {
        return io::equations_of_motion_json(*e.model->mechanism, e.equations).dump(2);
      });
  m.def(
      "explain_motion",
      [](std::shared_ptr<PyModel> model, double at, std::optional<double> dt, std::optional<double> rtol,
         std::optional<std::string> at_toggle, std::optional<double> timeout) {
        request::Options given;
        given.set("simulate", true);
        given.set("at", at);
        if (dt) given.set("dt", *dt);
        if (rtol) given.set("rtol", *rtol);
        if (at_toggle) given.set("at_toggle", *at_toggle);
        auto out = std::make_shared<PyEquationsOfMotion>();
        out->model = model;
        out->request = request::ExplainRequest::read(given);
        RunControl control;
        run_interruptible(control, timeout, [&] {
          try {
            out->equations = out->request.equations_of_motion(*model->mechanism, control);
          } catch (const request::OptionError&) {
            throw;
          } catch (const Error& e) {
            throw located(*model, e);
          }
        });
        return out;
      },
      py::arg("model"), py::arg("at"), py::arg("dt") = std::nullopt, py::arg("rtol") = std::nullopt,
      py::arg("at_toggle") = std::nullopt, py::arg("timeout") = std::nullopt);
}

void bind_explain_step(py::module_& m) {
  m.def(
      "explain",
      [](std::shared_ptr<PyModel> model, int step, std::optional<int> steps) {
        request::Options given;
        given.set("step", static_cast<long long>(step));
        if (steps) given.set("steps", static_cast<long long>(*steps));
        ExplainOptions options = request::ExplainRequest::read(given).explain_options();
        auto out = std::make_shared<Explanation>();
        RunControl control;
        run_interruptible(control, std::nullopt, [&] {
          try {
            *out = explain(model->mechanism, options);
          } catch (const Error& e) {
            throw located(*model, e);
          }
        });
        return out;
      },
      py::arg("model"), py::arg("step") = 0, py::arg("steps") = std::nullopt);
}

}  // namespace

void bind_explain(py::module_& m) {
  bind_explanation(m);
  bind_equations_of_motion(m);
  bind_explain_step(m);
}

}  // namespace nbar::python
