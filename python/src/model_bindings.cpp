// Models: loading, compiling, what `nbar check` says, the column catalogue.
#include <pybind11/stl.h>

#include <algorithm>
#include <filesystem>
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
  d["limits"] = json["limits"];
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
  d["condition"] = n.condition;
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

std::string names_of(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

int point_named(const Model& m, const std::string& name) {
  std::vector<std::string> names;
  for (std::size_t i = 0; i < m.points.size(); ++i) {
    if (m.points[i].name == name) return static_cast<int>(i);
    names.push_back(m.points[i].name);
  }
  throw Error(ErrorKind::BadInput, "no point '" + name + "'; the points are " + names_of(names));
}

Body& body_named(Model& m, const std::string& name) {
  std::vector<std::string> names;
  for (Body& b : m.bodies) {
    if (b.name == name) return b;
    names.push_back(b.name);
  }
  throw Error(ErrorKind::BadInput, "no body '" + name + "'; the bodies are " + names_of(names));
}

// Moves a point of the drawing. A shape is drawn around its body's points in the starting pose:
// moving one of them would leave the outline where it was, so that is refused.
void move_point(Model& m, const std::string& name, const std::array<double, 2>& xy) {
  const int index = point_named(m, name);
  for (const Body& b : m.bodies)
    if (b.shape && std::find(b.points.begin(), b.points.end(), index) != b.points.end())
      throw Error(ErrorKind::BadInput, "point '" + name + "' is on body '" + b.name +
                                           "', whose shape is drawn around its points: edit the model file instead");
  m.points[static_cast<std::size_t>(index)].position = Eigen::Vector2d(xy[0], xy[1]) * m.units.length_scale;
}

void set_length(Model& m, const std::string& name, double length) {
  Body& body = body_named(m, name);
  if (body.points.size() != 2)
    throw Error(ErrorKind::BadInput, "body '" + name + "' has " + std::to_string(body.points.size()) +
                                         " points: only a body of two points has a length");
  if (body.shape)
    throw Error(ErrorKind::BadInput,
                "body '" + name + "' has a shape drawn around its points: edit the model file instead");
  body.length = length * m.units.length_scale;
}

// The model with `points` moved and `lengths` set (model units), validated and compiled as a model
// file is: an invalid result is a ModelError at the edited entity's place in the original text.
PyModel edited(const PyModel& base, const std::vector<std::pair<std::string, std::array<double, 2>>>& points,
               const std::vector<std::pair<std::string, double>>& lengths) {
  io::LoadedModel file = base.file;
  for (const auto& [name, xy] : points) move_point(file.model, name, xy);
  for (const auto& [name, length] : lengths) set_length(file.model, name, length);
  try {
    validate(file.model);
  } catch (const ModelError& e) {
    throw io::ModelFileError(file.source.file, file.source.find(e.where()), e.message());
  }
  PyModel out = compile_model(std::move(file));
  out.import_dir = base.import_dir;
  out.moved_points = base.moved_points;
  out.moved_points.insert(out.moved_points.end(), points.begin(), points.end());
  out.set_lengths = base.set_lengths;
  out.set_lengths.insert(out.set_lengths.end(), lengths.begin(), lengths.end());
  return out;
}

// A pickled model: its text, its file's name and folder (for its imports) and the edits made
// since; unpickling parses and compiles it again, so a model crosses to another process as a few
// kilobytes of text.
py::tuple model_state(const PyModel& p) {
  return py::make_tuple(p.file.text, p.file.source.file, p.import_dir, p.moved_points, p.set_lengths);
}

std::shared_ptr<PyModel> model_from_state(const py::tuple& state) {
  if (state.size() != 5) throw Error(ErrorKind::BadInput, "not a pickled nbar model");
  const auto text = state[0].cast<std::string>();
  const auto name = state[1].cast<std::string>();
  const auto import_dir = state[2].cast<std::string>();
  PyModel base =
      compile_model(import_dir.empty() ? io::parse_model(text, name) : io::parse_model(text, name, import_dir));
  base.import_dir = import_dir;
  return std::make_shared<PyModel>(edited(base,
                                          state[3].cast<std::vector<std::pair<std::string, std::array<double, 2>>>>(),
                                          state[4].cast<std::vector<std::pair<std::string, double>>>()));
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
      .def("yaml", [](const PyModel& p) { return io::model_yaml(p.file.model); })
      .def(
          "edited",
          [](const PyModel& p, const std::vector<std::pair<std::string, std::array<double, 2>>>& points,
             const std::vector<std::pair<std::string, double>>& lengths) {
            return std::make_shared<PyModel>(edited(p, points, lengths));
          },
          py::arg("points"), py::arg("lengths"))
      .def(py::pickle(&model_state, &model_from_state));

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
      [](const std::string& path) {
        auto model = std::make_shared<PyModel>(compile_model(io::load_model_file(path)));
        // Absolute: a process that unpickles the model may run in another folder.
        model->import_dir = std::filesystem::absolute(path).parent_path().string();
        return model;
      },
      py::arg("path"));
  m.def(
      "loads",
      [](const std::string& text, const std::string& name) {
        return std::make_shared<PyModel>(compile_model(io::parse_model(text, name)));
      },
      py::arg("text"), py::arg("name") = "<string>");
}

}  // namespace nbar::python
