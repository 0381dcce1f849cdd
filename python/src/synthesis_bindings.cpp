// Synthesis from Python: a task (read from the same YAML or JSON a task file holds, so every
// check and message is the CLI's), one run, and the CLI's JSON, table and model files.
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "nbar/io/synthesis_task.hpp"
#include "nbar/io/synthesis_writer.hpp"
#include "nbar/request/synthesis_request.hpp"
#include "nbar/synthesis/run.hpp"

namespace nbar::python {

namespace {

struct PySynthesis {
  synthesis::SynthesisTask task;
  request::SynthesisRequest request;  // the listing's `all` and `top`
  synthesis::SynthesisOutcome outcome;

  std::string answer(const std::string& format) const {
    request::SynthesisRequest as = request;
    as.format = format;
    return as.answer(task, outcome, request.listing(outcome));
  }
};

// Python's keyword arguments as the request layer reads them: None is absent; a bool, an int, a
// float or a str as it is (numpy's scalars are made Python's by nbar.synth).
request::Options options_of(const py::dict& keywords) {
  request::Options options;
  for (const auto& [key_object, value] : keywords) {
    const std::string key = py::str(key_object);
    if (value.is_none()) continue;
    if (py::isinstance<py::bool_>(value)) {
      options.set(key, value.cast<bool>());
    } else if (py::isinstance<py::int_>(value)) {
      try {
        options.set(key, value.cast<long long>());
      } catch (const py::cast_error&) {  // beyond a long long: a number out of every rule's range
        options.set(key, value.cast<double>());
      }
    } else if (py::isinstance<py::float_>(value)) {
      options.set(key, value.cast<double>());
    } else if (py::isinstance<py::str>(value)) {
      options.set(key, value.cast<std::string>());
    } else {
      throw request::OptionError(key, request::literal("must be a number, True or False, or a text, not " +
                                                       std::string(py::str(py::repr(value)))));
    }
  }
  return options;
}

// The method a task's `task:` names; five-point (whose options are every method's) for a name the
// task reader is to refuse.
synthesis::SynthesisKind kind_named(const std::string& name) {
  for (const synthesis::SynthesisKind kind :
       {synthesis::SynthesisKind::FivePoint, synthesis::SynthesisKind::Burmester, synthesis::SynthesisKind::Function,
        synthesis::SynthesisKind::NinePoint, synthesis::SynthesisKind::Path})
    if (synthesis::to_string(kind) == name) return kind;
  return synthesis::SynthesisKind::FivePoint;
}

std::shared_ptr<PySynthesis> run(const synthesis::SynthesisTask& task, const py::dict& options,
                                 std::optional<double> timeout) {
  auto out = std::make_shared<PySynthesis>();
  out->task = task;
  out->request = request::SynthesisRequest::read(task.kind, options_of(options));
  synthesis::SynthesisRunOptions run = out->request.run_options();
  run_interruptible(run.control, timeout, [&] { out->outcome = synthesis::run_synthesis(task, run); });
  return out;
}

}  // namespace

void bind_synthesis(py::module_& m) {
  py::class_<synthesis::SynthesisTask>(m, "SynthesisTask", "A synthesis task, as a task file says it")
      .def_property_readonly("kind", [](const synthesis::SynthesisTask& t) { return synthesis::to_string(t.kind); })
      .def_property_readonly("name", [](const synthesis::SynthesisTask& t) { return t.name; })
      .def_property_readonly("file", [](const synthesis::SynthesisTask& t) { return t.file; })
      .def_property_readonly("length_unit", [](const synthesis::SynthesisTask& t) { return t.units.length; })
      .def_property_readonly("angle_unit", [](const synthesis::SynthesisTask& t) { return t.units.angle; });

  py::class_<PySynthesis, std::shared_ptr<PySynthesis>>(m, "SynthesisOutcome", "Every design of one task, ranked")
      .def_property_readonly("method", [](const PySynthesis& s) { return s.outcome.method; })
      .def_property_readonly("notes",
                             [](const PySynthesis& s) {
                               std::vector<std::string> notes;
                               for (const std::string& n : s.outcome.notes) notes.push_back(in_python_words(n));
                               return notes;
                             })
      .def_property_readonly("task", [](const PySynthesis& s) { return s.task; })
      .def("shown", [](const PySynthesis& s) { return s.request.listing(s.outcome).shown; })
      // (solutions, real ones, real ones without defects), as the table's second line counts them.
      .def("counts",
           [](const PySynthesis& s) {
             int real = 0, clean = 0;
             for (const auto& r : s.outcome.rows) {
               real += r.real;
               clean += r.real && r.check.defect_free();
             }
             return py::make_tuple(s.outcome.rows.size(), real, clean);
           })
      .def("json", [](const PySynthesis& s) { return s.answer("json"); })
      .def("table", [](const PySynthesis& s) { return in_python_words(s.answer("table")); })
      .def(
          "design_yaml",
          [](const PySynthesis& s, int row, int rank) { return io::design_model_yaml(s.task, s.outcome, row, rank); },
          py::arg("row"), py::arg("rank"))
      .def("design_files",
           [](const PySynthesis& s) { return io::design_files(s.task, s.outcome, s.request.listing(s.outcome)); })
      .def(
          "export",
          [](const PySynthesis& s, const std::string& dir) {
            io::export_designs(s.task, s.outcome, s.request.listing(s.outcome, dir));
          },
          py::arg("dir"))
      .def(
          "write_curves",
          [](const PySynthesis& s, const std::string& path) {
            if (!s.outcome.curves)
              throw Error(ErrorKind::BadInput, "only Burmester synthesis through four poses has curves");
            io::write_burmester_curves(path, s.task, *s.outcome.curves);
          },
          py::arg("path"));

  // Python runs in the user's own process: a dict's `curve` names the user's file, read from the
  // current directory.
  m.def(
      "parse_task",
      [](const std::string& text, const std::string& name) {
        return io::parse_synthesis_task(text, name, io::CurveFiles::read);
      },
      py::arg("text"), py::arg("name") = "<task>");
  m.def("load_task", &io::load_synthesis_task, py::arg("path"));
  // The options are the request's (nbar/request/synthesis_request.hpp): all, top, threads, seed.
  // The options checked before the task is read, as the command line and the web server check
  // them: `kind` is the task's `task:` when it is known before reading it.
  m.def(
      "check_synthesis_options",
      [](const std::string& kind, const py::dict& options) {
        request::SynthesisRequest::read(kind_named(kind), options_of(options));
      },
      py::arg("kind"), py::arg("options"));
  m.def("synthesize", &run, py::arg("task"), py::arg("options") = py::dict(), py::arg("timeout") = std::nullopt);
}

}  // namespace nbar::python
