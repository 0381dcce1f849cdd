// The analysis pipeline from Python: one call runs the stages, then tables as numpy arrays,
// the CLI's JSON and stress report, pictures, animations and the report render what it kept.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <sstream>
#include <thread>

#include "bindings.hpp"
#include "nbar/analysis/columns.hpp"
#include "nbar/analysis/pose.hpp"
#include "nbar/analysis/summary.hpp"
#include "nbar/dynamics/forward_dynamics.hpp"
#include "nbar/io/fe_export.hpp"
#include "nbar/io/results_writer.hpp"
#include "nbar/render/animation.hpp"
#include "nbar/render/pictures.hpp"
#include "nbar/render/report.hpp"
#include "nbar/request/requests.hpp"

namespace nbar::python {

namespace {

struct PyAnalysis {
  std::shared_ptr<PyModel> model;
  Analysis analysis;
};

// The analysis options from Python's arguments, read by the same requests as the command line's
// `solve` and `stress` (nbar/request): the same ranges, defaults, unit conversions and messages.
AnalysisOptions analysis_options(const Model& model, std::optional<int> steps, int order, bool dynamics, bool stress,
                                 int sections, std::optional<int> max_steps, const std::string& method,
                                 std::optional<double> mesh_size, const std::optional<std::string>& at_limits,
                                 std::optional<int> cycles, std::optional<int> segments_per_hole = std::nullopt,
                                 std::optional<double> edge_size = std::nullopt) {
  request::Options sweep;
  if (steps) sweep.set("steps", static_cast<long long>(*steps));
  if (max_steps) sweep.set("max_steps", static_cast<long long>(*max_steps));
  if (at_limits) sweep.set("at_limits", *at_limits);
  if (cycles) sweep.set("cycles", static_cast<long long>(*cycles));
  request::Options solve = sweep;
  solve.set("order", static_cast<long long>(order));
  solve.set("dynamics", dynamics);
  AnalysisOptions options = request::SolveRequest::read(solve).analysis_options();
  request::Options stresses = sweep;
  stresses.set("method", method);
  stresses.set("sections", static_cast<long long>(sections));
  if (mesh_size) stresses.set("mesh_size", *mesh_size);
  if (segments_per_hole) stresses.set("segments_per_hole", static_cast<long long>(*segments_per_hole));
  if (edge_size) stresses.set("edge_size", *edge_size);
  const AnalysisOptions stress_options = request::StressRequest::read(stresses).analysis_options(model);
  if (stress) {
    options.stress = true;
    options.sections = stress_options.sections;
    options.stress_method = stress_options.stress_method;
    options.fe = stress_options.fe;
  }
  return options;
}

std::shared_ptr<PyAnalysis> run_analysis(std::shared_ptr<PyModel> model, std::optional<int> steps, int order,
                                         bool dynamics, bool stress, int sections, std::optional<double> timeout,
                                         std::optional<int> max_steps, const std::string& method,
                                         std::optional<double> mesh_size, const std::optional<std::string>& at_limits,
                                         std::optional<int> cycles, std::optional<int> segments_per_hole,
                                         std::optional<double> edge_size, bool condition) {
  auto out = std::make_shared<PyAnalysis>();
  out->model = model;
  AnalysisOptions options =
      analysis_options(model->mechanism->model(), steps, order, dynamics, stress, sections, max_steps, method,
                       mesh_size, at_limits, cycles, segments_per_hole, edge_size);
  options.condition = condition;
  run_interruptible(options.control, timeout, [&] {
    try {
      out->analysis = analyse(model->mechanism, options);
    } catch (const Error& e) {
      throw located(*model, e);
    }
  });
  return out;
}

// Many models' sweeps at once: `threads` workers (0: one per hardware thread, never more than
// models) take the next model in turn, with the GIL released throughout. Each item of the answer
// is the model's Analysis, or the nbar.errors instance its analysis raised (placed in its own
// file), so that the caller can say which model failed. A timeout or Ctrl-C cancels them all.
py::list run_many(const std::vector<std::shared_ptr<PyModel>>& models, std::optional<int> steps, int order,
                  bool dynamics, std::optional<int> max_steps, unsigned threads, std::optional<double> timeout,
                  bool condition) {
  std::vector<AnalysisOptions> options;
  for (const auto& model : models) {
    options.push_back(analysis_options(model->mechanism->model(), steps, order, dynamics, false, 200, max_steps, "beam",
                                       std::nullopt, std::nullopt, std::nullopt));
    options.back().condition = condition;  // the `cond` column's estimates, as solve() asks them
  }
  RunControl control;
  std::vector<std::shared_ptr<PyAnalysis>> done(models.size());
  std::vector<std::optional<Error>> failed(models.size());
  run_interruptible(control, timeout, [&] {
    std::atomic<std::size_t> next{0};
    const auto work = [&] {
      for (std::size_t i = next++; i < models.size(); i = next++) {
        options[i].control = control;  // a copy shares the token: a cancel reaches every worker
        try {
          auto out = std::make_shared<PyAnalysis>();
          out->model = models[i];
          out->analysis = analyse(models[i]->mechanism, options[i]);
          done[i] = std::move(out);
        } catch (const Error& e) {
          failed[i] = located(*models[i], e);
        } catch (const std::exception& e) {
          failed[i] = internal_error(e);
        }
      }
    };
    const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
    const std::size_t count = std::min<std::size_t>(threads == 0 ? hardware : threads, models.size());
    std::vector<std::thread> workers;
    for (std::size_t k = 1; k < count; ++k) workers.emplace_back(work);
    work();
    for (std::thread& w : workers) w.join();
  });
  py::list out;
  for (std::size_t i = 0; i < models.size(); ++i) out.append(failed[i] ? python_error(*failed[i]) : py::cast(done[i]));
  return out;
}

// The columns matching `patterns`, or an error at `columns` that lists them, as `nbar solve
// --columns` gives.
request::SolveRequest column_request(const PyAnalysis& a, const std::optional<std::vector<std::string>>& patterns) {
  request::SolveRequest solve;
  if (patterns) solve.columns = *patterns;
  solve.order = a.analysis.sweep.order;
  solve.dynamics = a.analysis.dynamics.has_value();
  return solve;
}

// Column names, units and one numpy array per column. The arrays are views into one matrix the
// table was built in, which they keep alive: nothing is copied after the sweep's table.
py::tuple as_arrays(ColumnTable table) {
  auto* values = new Eigen::MatrixXd(std::move(table.values));
  py::capsule owner(values, [](void* p) { delete static_cast<Eigen::MatrixXd*>(p); });
  const auto rows = static_cast<py::ssize_t>(values->rows());
  py::list arrays;
  for (Eigen::Index c = 0; c < values->cols(); ++c)
    arrays.append(
        py::array_t<double>({rows}, {static_cast<py::ssize_t>(sizeof(double))}, values->col(c).data(), owner));
  return py::make_tuple(table.columns, table.units, arrays);
}

py::tuple as_arrays(const ResultTable& rows) {
  ColumnTable table;
  table.columns = rows.columns;
  table.units = rows.units;
  table.values.resize(static_cast<Eigen::Index>(rows.rows.size()), static_cast<Eigen::Index>(rows.columns.size()));
  for (std::size_t r = 0; r < rows.rows.size(); ++r)
    for (std::size_t c = 0; c < rows.columns.size(); ++c)
      table.values(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = rows.rows[r][c];
  return as_arrays(std::move(table));
}

}  // namespace

py::list warning_list(const std::vector<Warning>& warnings) {
  py::list out;
  for (const Warning& w : warnings) out.append(py::make_tuple(w.code, w.step, w.message));
  return out;
}

namespace {

// A picture's options as the request layer reads them (the same as `nbar draw`'s and
// `nbar animate`'s flags).
request::Options picture_options(const std::string& format, bool labels, const std::vector<std::string>& traces,
                                 int width, int height, const std::string& title) {
  request::Options options;
  options.set("format", format);
  options.set("labels", labels);
  options.set("trace", traces);
  options.set("width", static_cast<long long>(width));
  options.set("height", static_cast<long long>(height));
  options.set("title", title);
  return options;
}

py::object draw(const PyAnalysis& a, const std::string& format, std::optional<int> step, std::optional<double> at,
                bool labels, const std::vector<std::string>& traces, int width, int height, const std::string& title) {
  request::Options options = picture_options(format, labels, traces, width, height, title);
  if (step) options.set("step", static_cast<long long>(*step));
  if (at) options.set("at", *at);
  const request::DrawRequest request = request::DrawRequest::read(options);
  if (request.format == "scene") throw request::OptionError("format", "must be one of svg, png, not 'scene'");
  const Mechanism& mech = *a.model->mechanism;
  const render::DrawOptions draw = request.picture.draw_options(mech.model());
  std::vector<Eigen::Vector2d> points;
  try {
    points = request.pose(a.analysis).points;
  } catch (const request::OptionError&) {
    throw;
  } catch (const Error& e) {
    throw located(*a.model, e);
  }
  if (request.format == "svg") return py::str(render::drawing_svg(mech, a.analysis.sweep, points, draw));
  const std::vector<std::uint8_t> png = render::drawing_png(mech, a.analysis.sweep, points, draw);
  return py::bytes(reinterpret_cast<const char*>(png.data()), png.size());
}

// The animation of a motion (a sweep, or a simulation's rows) by `nbar animate`'s request.
py::object animate_motion(const PyModel& model, const SweepResult& motion, const std::string& format, int frames,
                          double fps, bool labels, const std::vector<std::string>& traces, int width, int height,
                          const std::string& title) {
  request::Options options = picture_options(format, labels, traces, width, height, title);
  options.set("fps", fps);
  if (frames != 0) options.set("frames", static_cast<long long>(frames));  // 0: every sample, at most 120
  const request::AnimateRequest request = request::AnimateRequest::read(options);
  const render::DrawOptions draw = request.picture.draw_options(model.file.model);
  const render::Animation animation(model.mechanism, motion, draw, request.frames.value_or(0), request.fps);
  const auto as_bytes = [](const std::vector<std::uint8_t>& b) {
    return py::bytes(reinterpret_cast<const char*>(b.data()), b.size());
  };
  if (request.format == "html") return py::str(animation.html_animation());
  if (request.format == "svg") return py::str(animation.svg_animation());
  if (request.format == "gif") return as_bytes(animation.gif_bytes());
  return as_bytes(animation.mp4_bytes());
}

py::object animate(const PyAnalysis& a, const std::string& format, int frames, double fps, bool labels,
                   const std::vector<std::string>& traces, int width, int height, const std::string& title) {
  return animate_motion(*a.model, a.analysis.sweep, format, frames, fps, labels, traces, width, height, title);
}

// The page, whether the sweep reached its end, and why not (the report of a stopped sweep is
// written all the same, as `nbar report` writes it before exiting 4).
py::tuple report(std::shared_ptr<PyModel> model, int frames, std::optional<double> timeout) {
  request::Options given;
  given.set("frames", static_cast<long long>(frames));
  const request::ReportRequest request = request::ReportRequest::read(given);
  const ModelSummary summary = summarize(*model->mechanism);
  AnalysisOptions options = request.analysis_options(summary, model->mechanism->model());
  Analysis analysis;
  run_interruptible(options.control, timeout, [&] {
    try {
      analysis = analyse(model->mechanism, options);
    } catch (const Error& e) {
      throw located(*model, e);
    }
  });
  render::ReportOptions report;
  report.source = model->file.source.file;
  report.frames = request.frames;
  const std::string page = render::html_report(analysis, summary, report);
  return py::make_tuple(page, analysis.complete(),
                        analysis.complete() ? py::object(py::none()) : py::object(py::str(analysis.sweep.stop_reason)));
}

std::string stress_report(const PyAnalysis& a, const std::string& format) {
  if (!a.analysis.stress) throw Error(ErrorKind::BadInput, "the analysis has no stress stage: run it with stress=True");
  std::ostringstream out;
  io::write_stress_report(out, format, a.analysis);
  return out.str();
}

// The request's options for one link at one step, by the analysis's own stress method.
request::Options profile_options(const PyAnalysis& a, const std::string& body_name, int step) {
  if (!a.analysis.stress) throw Error(ErrorKind::BadInput, "the analysis has no stress stage: run it with stress=True");
  request::Options options;
  options.set("section_profile", body_name);
  options.set("step", static_cast<long long>(step));
  if (a.analysis.stress->method == StressMethod::fe) options.set("method", std::string("fe"));
  return options;
}

py::tuple section_profile(const PyAnalysis& a, const std::string& body_name, int step) {
  return as_arrays(request::StressRequest::read(profile_options(a, body_name, step)).section_profile_table(a.analysis));
}

// The finite-element field at points, along a line or around a hole (`nbar stress --at`, `--along`,
// `--around-hole`), as numpy arrays.
py::tuple stress_field(const PyAnalysis& a, const std::string& body_name, int step,
                       const std::optional<std::vector<std::string>>& at,
                       const std::optional<std::vector<std::string>>& along,
                       const std::optional<std::string>& around_hole, std::optional<double> radius,
                       const std::optional<std::string>& coordinates, std::optional<int> samples) {
  request::Options options = profile_options(a, body_name, step);
  if (at) options.set("at", *at);
  if (along) options.set("along", *along);
  if (around_hole) options.set("around_hole", *around_hole);
  if (radius) options.set("radius", *radius);
  if (coordinates) options.set("coordinates", *coordinates);
  if (samples) options.set("samples", static_cast<long long>(*samples));
  return as_arrays(request::StressRequest::read(options).section_profile_table(a.analysis));
}

// A simulation (nbar simulate) as Python holds it: the run, and the request that chose its
// options and picks its columns.
struct PySimulation {
  std::shared_ptr<PyModel> model;
  request::SimulateRequest request;
  Simulation simulation;
  bool interrupted = false;  // by Ctrl-C (the rows so far are kept)
};

// Python's arguments read by the command line's rules (request::SimulateRequest): the same
// ranges, defaults and messages as `nbar simulate`'s flags.
std::shared_ptr<PySimulation> run_simulation(std::shared_ptr<PyModel> model, std::optional<double> to,
                                             std::optional<double> dt, std::optional<double> rtol,
                                             std::optional<long long> max_steps, std::optional<std::string> stop_when,
                                             std::optional<std::string> at_toggle, std::optional<long long> threads,
                                             std::optional<double> timeout) {
  request::Options given;
  if (to) given.set("to", *to);
  if (dt) given.set("dt", *dt);
  if (rtol) given.set("rtol", *rtol);
  if (max_steps) given.set("max_steps", *max_steps);
  if (stop_when) given.set("stop_when", *stop_when);
  if (at_toggle) given.set("at_toggle", *at_toggle);
  if (threads) given.set("threads", *threads);
  auto out = std::make_shared<PySimulation>();
  out->model = model;
  out->request = request::SimulateRequest::read(given);
  SimulationOptions options;
  try {
    options = out->request.simulation_options(*model->mechanism);  // with the model's `simulation:`
  } catch (const request::OptionError&) {
    throw;
  } catch (const Error& e) {
    throw located(*model, e);
  }
  RunControl control;
  try {
    run_interruptible(control, timeout, [&] {
      try {
        out->simulation = simulate(*model->mechanism, options, control);
      } catch (const Error& e) {
        throw located(*model, e);
      }
    });
  } catch (py::error_already_set& e) {
    // Ctrl-C: the run kept its rows; Model.simulate raises KeyboardInterrupt with them attached.
    if (!e.matches(PyExc_KeyboardInterrupt) || out->simulation.samples.empty()) throw;
    out->interrupted = true;
  }
  return out;
}

// The columns matching `patterns` (every column without them), or an error at `columns`.
ResultTable simulation_columns(const PySimulation& s, const std::optional<std::vector<std::string>>& patterns) {
  request::SimulateRequest picked = s.request;
  picked.columns = patterns.value_or(std::vector<std::string>{});
  return picked.table(*s.model->mechanism, s.simulation);
}

void bind_simulation(py::module_& m) {
  py::class_<PySimulation, std::shared_ptr<PySimulation>>(m, "Simulation", "One run of the forward dynamics")
      .def_property_readonly("complete", [](const PySimulation& s) { return s.simulation.complete; })
      .def_property_readonly("stop_reason", [](const PySimulation& s) { return s.simulation.stop_reason; })
      .def_property_readonly("cancelled", [](const PySimulation& s) { return s.simulation.cancelled; })
      .def_property_readonly("interrupted", [](const PySimulation& s) { return s.interrupted; })
      .def_property_readonly("time_reached", [](const PySimulation& s) { return s.simulation.time_reached(); })
      // Where the command line places the stop: the line and column of the entity concerned.
      .def_property_readonly("stop_place",
                             [](const PySimulation& s) {
                               const SourceMark at = s.model->file.source.find(s.simulation.stop_where);
                               return !s.simulation.complete && at.line > 0
                                          ? py::object(py::make_tuple(at.line, at.column))
                                          : py::object(py::none());
                             })
      .def_property_readonly("samples", [](const PySimulation& s) { return s.simulation.samples.size(); })
      // A Result's fields that a sweep has and a simulation has not: no branches, no change points.
      .def_property_readonly("warnings", [](const PySimulation& s) { return warning_list(s.simulation.warnings); })
      .def_property_readonly("branches", [](const PySimulation&) { return py::list(); })
      .def_property_readonly("transmission_angles", [](const PySimulation&) { return py::dict(); })
      .def_property_readonly("forces_unique", [](const PySimulation&) { return py::none(); })
      .def_property_readonly("max_residual",
                             [](const PySimulation& s) {
                               return s.simulation.statistics.drift.position / s.model->file.model.units.length_scale;
                             })
      .def_property_readonly(
          "statistics",
          [](const PySimulation& s) {
            const SimulationStatistics& st = s.simulation.statistics;
            const double length = s.model->file.model.units.length_scale;
            return py::dict(py::arg("accepted_steps") = st.accepted_steps,
                            py::arg("rejected_steps") = st.rejected_steps, py::arg("evaluations") = st.evaluations,
                            py::arg("smallest_step") = st.smallest_step, py::arg("largest_step") = st.largest_step,
                            py::arg("largest_energy_error") = st.largest_energy_error,
                            py::arg("drift") = py::dict(py::arg("position") = st.drift.position / length,
                                                        py::arg("velocity") = st.drift.velocity / length,
                                                        py::arg("acceleration") = st.drift.acceleration / length));
          })
      .def_property_readonly(
          "events",
          [](const PySimulation& s) {
            py::list out;
            for (const SimulationEvent& e : s.simulation.events)
              out.append(py::dict(py::arg("kind") = e.kind == SimulationEvent::Kind::toggle ? "toggle" : "stop_when",
                                  py::arg("time") = e.time, py::arg("row") = e.row, py::arg("message") = e.message));
            return out;
          })
      .def(
          "table",
          [](const PySimulation& s, const std::optional<std::vector<std::string>>& columns) {
            return as_arrays(simulation_columns(s, columns));
          },
          py::arg("columns") = std::nullopt)
      .def(
          "json",
          [](const PySimulation& s, const std::optional<std::vector<std::string>>& columns) {
            std::ostringstream out;
            io::write_simulation_json(out, *s.model->mechanism, s.simulation, simulation_columns(s, columns));
            return out.str();
          },
          py::arg("columns") = std::nullopt)
      // `nbar animate --simulate`: every row a frame's pose at its time (request::simulated_motion).
      .def(
          "animate",
          [](const PySimulation& s, const std::string& format, int frames, double fps, bool labels,
             const std::vector<std::string>& traces, int width, int height, const std::string& title) {
            return animate_motion(*s.model, request::simulated_motion(s.simulation), format, frames, fps, labels,
                                  traces, width, height, title);
          },
          py::arg("format") = "html", py::arg("frames") = 0, py::arg("fps") = 24.0, py::arg("labels") = false,
          py::arg("traces") = std::vector<std::string>{}, py::arg("width") = 900, py::arg("height") = 640,
          py::arg("title") = "");
  m.def("simulate", &run_simulation, py::arg("model"), py::arg("to") = std::nullopt, py::arg("dt") = std::nullopt,
        py::arg("rtol") = std::nullopt, py::arg("max_steps") = std::nullopt, py::arg("stop_when") = std::nullopt,
        py::arg("at_toggle") = std::nullopt, py::arg("threads") = std::nullopt, py::arg("timeout") = std::nullopt);
}

// One link's mesh and field at one step as a .vtu document (`nbar stress --export-mesh`).
std::string fe_vtu(const PyAnalysis& a, const std::string& body_name, int step) {
  request::Options options = profile_options(a, body_name, step);
  options.set("export_mesh", std::string("."));
  const auto meshes = request::StressRequest::read(options).mesh_exports(a.analysis);
  if (meshes.empty()) throw Error(ErrorKind::BadInput, "the analysis has no finite-element stresses: method='fe'");
  std::ostringstream out;
  io::write_fe_vtu(out, a.analysis, meshes.front().body, meshes.front().step);
  return out.str();
}

// The convergence study of `nbar stress --method fe --converge` from this analysis's meshes, as
// the command's JSON: `tolerance` in %.
std::string fe_convergence(const PyAnalysis& a, double tolerance, std::optional<double> timeout) {
  request::Options options;
  options.set("method", std::string("fe"));
  options.set("converge", true);
  options.set("tolerance", tolerance);
  const request::StressRequest request = request::StressRequest::read(options);
  FeConvergence convergence;
  RunControl control;
  run_interruptible(control, timeout, [&] {
    try {
      convergence = request.convergence(a.analysis, control);
    } catch (const Error& e) {
      throw located(*a.model, e);
    }
  });
  std::ostringstream out;
  io::write_fe_convergence(out, "json", a.analysis, convergence);
  return out.str();
}

}  // namespace

// The Analysis object: what each stage left, and the tables, pictures and reports made of it.
static void bind_analysis_class(py::module_& m) {
  py::class_<PyAnalysis, std::shared_ptr<PyAnalysis>>(m, "Analysis", "The stages of one analysis, run once and kept")
      .def_property_readonly("complete", [](const PyAnalysis& a) { return a.analysis.complete(); })
      .def_property_readonly("stop_reason", [](const PyAnalysis& a) { return a.analysis.sweep.stop_reason; })
      .def_property_readonly("samples", [](const PyAnalysis& a) { return a.analysis.sweep.samples.size(); })
      .def_property_readonly("order", [](const PyAnalysis& a) { return a.analysis.sweep.order; })
      .def_property_readonly(
          "max_residual",
          [](const PyAnalysis& a) { return a.analysis.sweep.max_residual / a.analysis.model().units.length_scale; })
      .def_property_readonly("branches", [](const PyAnalysis& a) { return a.analysis.sweep.branches; })
      .def_property_readonly("transmission_angles",
                             [](const PyAnalysis& a) {
                               const double unit = a.analysis.model().units.angle_scale;
                               py::dict out;
                               for (const TransmissionExtremes& mu : transmission_extremes(a.analysis))
                                 out[py::str(mu.loop)] = py::dict(
                                     py::arg("min") = mu.min / unit, py::arg("min_step") = mu.min_step,
                                     py::arg("max") = mu.max / unit, py::arg("max_step") = mu.max_step,
                                     py::arg("design") = mu.design / unit, py::arg("design_step") = mu.design_step);
                               return out;
                             })
      .def_property_readonly("warnings", [](const PyAnalysis& a) { return warning_list(a.analysis.warnings()); })
      .def_property_readonly("has_dynamics", [](const PyAnalysis& a) { return a.analysis.dynamics.has_value(); })
      .def_property_readonly("has_stress", [](const PyAnalysis& a) { return a.analysis.stress.has_value(); })
      .def_property_readonly("forces_unique",
                             [](const PyAnalysis& a) {
                               return a.analysis.dynamics ? py::object(py::bool_(a.analysis.dynamics->unique))
                                                          : py::none();
                             })
      .def(
          "table",
          [](const PyAnalysis& a, const std::optional<std::vector<std::string>>& columns) {
            return as_arrays(column_request(a, columns).columns_of(a.analysis));
          },
          py::arg("columns") = std::nullopt)
      .def(
          "json",
          [](const PyAnalysis& a, const std::optional<std::vector<std::string>>& columns) {
            std::ostringstream out;
            io::write_json(out, a.analysis, column_request(a, columns).table(a.analysis),
                           a.analysis.dynamics ? &*a.analysis.dynamics : nullptr);
            return out.str();
          },
          py::arg("columns") = std::nullopt)
      .def("stress_report", &stress_report, py::arg("format") = "json")
      .def("section_profile", &section_profile, py::arg("body"), py::arg("step"))
      .def("stress_field", &stress_field, py::arg("body"), py::arg("step") = 0, py::arg("at") = std::nullopt,
           py::arg("along") = std::nullopt, py::arg("around_hole") = std::nullopt, py::arg("radius") = std::nullopt,
           py::arg("coordinates") = std::nullopt, py::arg("samples") = std::nullopt)
      .def("fe_vtu", &fe_vtu, py::arg("body"), py::arg("step") = 0)
      .def("fe_convergence", &fe_convergence, py::arg("tolerance") = 1.0, py::arg("timeout") = std::nullopt)
      .def("draw", &draw, py::arg("format") = "svg", py::arg("step") = std::nullopt, py::arg("at") = std::nullopt,
           py::arg("labels") = false, py::arg("traces") = std::vector<std::string>{}, py::arg("width") = 900,
           py::arg("height") = 640, py::arg("title") = "")
      .def("animate", &animate, py::arg("format") = "html", py::arg("frames") = 0, py::arg("fps") = 24.0,
           py::arg("labels") = false, py::arg("traces") = std::vector<std::string>{}, py::arg("width") = 900,
           py::arg("height") = 640, py::arg("title") = "");
}

void bind_analysis(py::module_& m) {
  bind_analysis_class(m);
  m.def("analyse_many", &run_many, py::arg("models"), py::arg("steps") = std::nullopt, py::arg("order") = 2,
        py::arg("dynamics") = false, py::arg("max_steps") = std::nullopt, py::arg("threads") = 0u,
        py::arg("timeout") = std::nullopt, py::arg("condition") = false);
  m.def("analyse", &run_analysis, py::arg("model"), py::arg("steps") = std::nullopt, py::arg("order") = 2,
        py::arg("dynamics") = false, py::arg("stress") = false, py::arg("sections") = 200,
        py::arg("timeout") = std::nullopt, py::arg("max_steps") = std::nullopt, py::arg("method") = "beam",
        py::arg("mesh_size") = std::nullopt, py::arg("at_limits") = std::nullopt, py::arg("cycles") = std::nullopt,
        py::arg("segments_per_hole") = std::nullopt, py::arg("edge_size") = std::nullopt, py::arg("condition") = false);
  // For bench/python: the same solve timed inside C++ (the sweep, then the sweep and its column
  // table), the reference Python's own cost is measured against.
  m.def(
      "_time_in_cpp",
      [](std::shared_ptr<PyModel> model, int steps, int order) {
        py::gil_scoped_release release;
        AnalysisOptions options;
        options.steps = steps;
        options.order = order;
        const auto start = std::chrono::steady_clock::now();
        const Analysis analysis = analyse(model->mechanism, options);
        const auto swept = std::chrono::steady_clock::now();
        const ColumnTable table = result_columns(analysis);
        const auto tabled = std::chrono::steady_clock::now();
        const std::chrono::duration<double> sweep = swept - start, total = tabled - start;
        return std::make_pair(sweep.count(), table.values.size() > 0 ? total.count() : 0.0);
      },
      py::arg("model"), py::arg("steps"), py::arg("order") = 2);
  m.def("report", &report, py::arg("model"), py::arg("frames") = 72, py::arg("timeout") = std::nullopt);
  bind_simulation(m);
}

}  // namespace nbar::python
