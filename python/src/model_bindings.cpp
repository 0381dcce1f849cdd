// Models: loading, compiling, what `nbar check` says, the column catalogue.
#include <pybind11/stl.h>

#include <sstream>

#include "bindings.hpp"
#include "nbar/analysis/columns.hpp"
#include "nbar/analysis/summary.hpp"
#include "nbar/io/model_export.hpp"
#include "nbar/io/summary_writer.hpp"
#include "nbar/kinematics/table.hpp"

namespace nbar::python {

namespace {

// What `nbar check` prints, as plain data in the model's units. The bodies, the loops, the
// slider-cranks and the quick-returns are the JSON summary's (`nbar check --format json`, the
// web API's): one rendering of them for every front-end.
py::dict summary_dict(const PyModel& model) {
  const Mechanism& mech = *model.mechanism;
  const ModelSummary s = summarize(mech);
  const Units& u = mech.model().units;
  const py::object json = py::module_::import("json").attr("loads")(io::summary_json(mech, s, model.file.source));
  py::dict d;
  d["ground_points"] = s.ground_points;
  d["moving_points"] = s.moving_points;
  d["joints"] = s.joints;
  d["dof"] = s.mobility.dof;
  d["gruebler"] = s.mobility.grubler;
  d["coordinates"] = s.mobility.coordinates;
  d["constraints"] = s.mobility.constraint_rows;
  d["rank"] = s.mobility.rank;
  d["redundant"] = s.redundant;
  d["drivers"] = s.drivers;
  d["bodies"] = json["bodies"];
  d["has_kinetics"] = s.has_kinetics();
  d["has_stress_links"] = s.has_stress_links;
  if (s.assembly) {
    py::list values;
    for (std::size_t i = 0; i < s.assembly->driver_values.size(); ++i) {
      const bool angular = mech.model().drivers[i].is_angular();
      values.append(s.assembly->driver_values[i] / (angular ? u.angle_scale : u.length_scale));
    }
    d["assembly"] =
        py::dict(py::arg("driver_values") = values, py::arg("residual") = s.assembly->residual / u.length_scale,
                 py::arg("passed_singularity") = s.assembly->passed_singularity);
  } else {
    d["assembly"] = py::none();
  }
  d["assembly_error"] = s.assembly_error ? py::object(py::str(located(model, *s.assembly_error).what())) : py::none();
  d["loops"] = json["loops"];
  d["slider_cranks"] = json["slider_cranks"];
  d["quick_returns"] = json["quick_returns"];
  py::list warnings;
  for (const Warning& w : s.warnings) warnings.append(py::make_tuple(w.code, w.step, w.message));
  d["warnings"] = warnings;
  std::ostringstream text;
  io::write_summary_text(text, mech, s, model.file.source.file);
  d["text"] = text.str();
  return d;
}

py::list catalogue(const PyModel& model, int max_order, bool dynamics) {
  py::list out;
  for (const ColumnInfo& c : column_catalogue(*model.mechanism, max_order, dynamics)) {
    const char* stage = c.stage == Stage::Sweep ? "sweep" : c.stage == Stage::Dynamics ? "dynamics" : "stress";
    out.append(py::make_tuple(c.name, c.unit, stage, c.order));
  }
  return out;
}

py::dict needs(const PyModel& model, const std::vector<std::string>& patterns, std::optional<int> order,
               bool dynamics) {
  const ColumnNeeds n = column_needs(*model.mechanism, patterns, order, dynamics);
  py::dict d;
  d["order"] = n.order;
  d["dynamics"] = n.dynamics;
  d["unmatched"] = n.unmatched;
  d["message"] = n.message;
  return d;
}

py::list point_list(const Model& m) {
  py::list points;
  for (const Point& p : m.points)
    points.append(
        py::make_tuple(p.name, p.position.x() / m.units.length_scale, p.position.y() / m.units.length_scale, p.ground));
  return points;
}

py::list body_points(const Model& m) {
  py::list bodies;
  for (const Body& b : m.bodies) {
    std::vector<std::string> names;
    for (int p : b.points) names.push_back(m.points[p].name);
    bodies.append(py::make_tuple(b.name, names));
  }
  return bodies;
}

}  // namespace

PyModel compile_model(io::LoadedModel loaded) {
  PyModel model;
  model.file = std::move(loaded);
  try {
    model.mechanism = std::make_shared<const Mechanism>(model.file.model);
  } catch (const ModelError& e) {
    throw io::ModelFileError(model.file.source.file, model.file.source.find(e.where()), e.message());
  }
  return model;
}

void bind_model(py::module_& m) {
  py::class_<PyModel, std::shared_ptr<PyModel>>(m, "CompiledModel", "A model file, parsed, validated and compiled")
      .def_property_readonly("name", [](const PyModel& p) { return p.file.model.name; })
      .def_property_readonly("file", [](const PyModel& p) { return p.file.source.file; })
      .def_property_readonly("sweep_stop_place",
                             [](const PyModel& p) {
                               const SourceMark at = p.file.source.sweep_stop();
                               return at.line > 0 ? py::object(py::make_tuple(at.line, at.column))
                                                  : py::object(py::none());
                             })
      .def_property_readonly("length_unit", [](const PyModel& p) { return p.file.model.units.length; })
      .def_property_readonly("angle_unit", [](const PyModel& p) { return p.file.model.units.angle; })
      .def_property_readonly("points", [](const PyModel& p) { return point_list(p.file.model); })
      .def_property_readonly("bodies", [](const PyModel& p) { return body_points(p.file.model); })
      .def_property_readonly("drivers",
                             [](const PyModel& p) {
                               std::vector<std::string> names;
                               for (const Driver& d : p.file.model.drivers) names.push_back(d.name);
                               return names;
                             })
      .def_property_readonly("has_time_law", [](const PyModel& p) { return p.file.model.has_time_law(); })
      .def_property_readonly("default_abscissa", [](const PyModel& p) { return default_abscissa(p.file.model); })
      .def("summary", &summary_dict)
      .def("catalogue", &catalogue, py::arg("max_order") = 5, py::arg("dynamics") = true)
      .def("needs", &needs, py::arg("patterns"), py::arg("order") = std::nullopt, py::arg("dynamics") = false)
      .def("yaml", [](const PyModel& p) { return io::model_yaml(p.file.model); });

  // Which of `columns` the names or globs `patterns` pick, in the order `solve --columns` and
  // `plot --y` use: (indices, "") or ([], the message naming a pattern that matches nothing).
  m.def(
      "pick_columns",
      [](const std::vector<std::string>& columns, const std::vector<std::string>& patterns) {
        try {
          return py::make_tuple(pick_columns(columns, patterns), std::string());
        } catch (const Error& e) {
          return py::make_tuple(std::vector<std::size_t>{}, std::string(e.what()));
        }
      },
      py::arg("columns"), py::arg("patterns"));

  m.def(
      "load",
      [](const std::string& path) { return std::make_shared<PyModel>(compile_model(io::load_model_file(path))); },
      py::arg("path"));
  m.def(
      "loads",
      [](const std::string& text, const std::string& name) {
        return std::make_shared<PyModel>(compile_model(io::parse_model(text, name)));
      },
      py::arg("text"), py::arg("name") = "<string>");
}

}  // namespace nbar::python
