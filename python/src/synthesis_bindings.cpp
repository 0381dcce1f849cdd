// Synthesis from Python: a task (read from the same YAML or JSON a task file holds, so every
// check and message is the CLI's), one run, and the CLI's JSON, table and model files.
#include <pybind11/stl.h>

#include <sstream>

#include "bindings.hpp"
#include "nbar/io/synthesis_task.hpp"
#include "nbar/io/synthesis_writer.hpp"
#include "nbar/synthesis/run.hpp"

namespace nbar::python {

namespace {

struct PySynthesis {
  synthesis::SynthesisTask task;
  synthesis::SynthesisOutcome outcome;

  io::SynthesisListing listing(bool all, int top, const std::string& export_dir = {}) const {
    io::SynthesisListing l;
    l.all = all;
    l.shown = synthesis::shown_rows(outcome, all, top);
    l.export_dir = export_dir;
    return l;
  }
};

std::shared_ptr<PySynthesis> run(const synthesis::SynthesisTask& task, unsigned threads, std::uint64_t seed,
                                 std::optional<double> timeout) {
  auto out = std::make_shared<PySynthesis>();
  out->task = task;
  synthesis::SynthesisRunOptions options;
  options.threads = threads;
  options.seed = seed;
  run_interruptible(options.control, timeout, [&] { out->outcome = synthesis::run_synthesis(task, options); });
  return out;
}

std::string table(const PySynthesis& s, bool all, int top) {
  std::ostringstream out;
  io::write_synthesis_table(out, s.task, s.outcome, s.listing(all, top));
  return out.str();
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
      .def_property_readonly("notes", [](const PySynthesis& s) { return s.outcome.notes; })
      .def_property_readonly("task", [](const PySynthesis& s) { return s.task; })
      .def(
          "shown", [](const PySynthesis& s, bool all, int top) { return synthesis::shown_rows(s.outcome, all, top); },
          py::arg("all") = false, py::arg("top") = 0)
      .def(
          "json",
          [](const PySynthesis& s, bool all, int top) {
            return io::synthesis_json(s.task, s.outcome, s.listing(all, top));
          },
          py::arg("all") = false, py::arg("top") = 0)
      .def("table", &table, py::arg("all") = false, py::arg("top") = 0)
      .def(
          "design_yaml",
          [](const PySynthesis& s, int row, int rank) { return io::design_model_yaml(s.task, s.outcome, row, rank); },
          py::arg("row"), py::arg("rank"))
      .def(
          "export",
          [](const PySynthesis& s, const std::string& dir, bool all, int top) {
            io::export_designs(s.task, s.outcome, s.listing(all, top, dir));
          },
          py::arg("dir"), py::arg("all") = false, py::arg("top") = 0)
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
  m.def("synthesize", &run, py::arg("task"), py::arg("threads") = 0, py::arg("seed") = 1,
        py::arg("timeout") = std::nullopt);
}

}  // namespace nbar::python
