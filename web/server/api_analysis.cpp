// The analysis endpoints: check, solve, stress, report and explain.
#include <cmath>

#include "api_internal.hpp"
#include "endpoints.hpp"
#include "io/explain_writer.hpp"
#include "io/json_text.hpp"
#include "nbar/analysis/explain.hpp"
#include "nbar/analysis/summary.hpp"
#include "nbar/io/results_writer.hpp"
#include "nbar/io/summary_writer.hpp"
#include "nbar/render/report.hpp"
#include "nbar/request/outline_request.hpp"
#include "nbar/request/requests.hpp"

namespace nbar::web {

ApiResponse api_check(Job& job, const std::string& text) {
  const RequestBody body(text, {"model"});
  load_model(job, body.text("model", true));
  const ModelSummary summary = summarize(*job.mechanism);
  job.checkpoint("check");
  return answer(io::summary_json(*job.mechanism, summary, job.file->source));
}

ApiResponse api_solve(Job& job, const std::string& text) {
  const RequestBody body(text, request::SolveRequest::rules(), {"model"});
  const auto solve = read_request<request::SolveRequest>(body, {"model"}, true);
  load_model(job, body.text("model", true));
  check_sweep_size(job, solve.sweep.steps);
  const AnalysisOptions options = solve.analysis_options();
  check_table_size(job, options);
  const Analysis analysis = run_analysis(job, options);
  const ResultTable table = solve.table(analysis);
  return answer(write([&](std::ostream& out) {
                  io::write_table(out, solve.format, analysis, table, analysis.dynamics ? &*analysis.dynamics : nullptr,
                                  io::kTextTableWidth);
                }),
                text_type(solve.format));
}

ApiResponse api_stress(Job& job, const std::string& text) {
  const RequestBody body(text, request::StressRequest::rules(), {"model"});
  const auto stress = read_request<request::StressRequest>(body, {"model"}, true);
  load_model(job, body.text("model", true));
  check_sweep_size(job, stress.sweep.steps);
  check_limit("sections", static_cast<double>(stress.sections), job.limits.max_sections,
              "the number of sections per link");
  check_limit("samples", static_cast<double>(stress.samples), job.limits.max_sections,
              "the number of points or cuts of a stress profile");
  // The server writes no file: a mesh export is the command line's and Python's.
  if (!stress.export_mesh.empty())
    throw request::OptionError("export_mesh", "writes files, which the web API does not (use the command line)", true);
  AnalysisOptions options = stress.analysis_options(job.mechanism->model());
  options.fe.max_nodes = job.limits.max_fe_nodes;
  const Analysis analysis = run_analysis(job, options);
  if (stress.converge) {
    // The meshes refine until the next one would pass the server's node limit.
    const FeConvergence convergence = stress.convergence(analysis, job.control);
    return answer(
        write([&](std::ostream& out) { io::write_fe_convergence(out, stress.format, analysis, convergence); }),
        text_type(stress.format));
  }
  if (!stress.profile_asked())
    return answer(write([&](std::ostream& out) { io::write_stress_report(out, stress.format, analysis); }),
                  text_type(stress.format));
  const ResultTable profile = stress.section_profile_table(analysis);
  return answer(write([&](std::ostream& out) { io::write_table(out, stress.format, analysis, profile); }),
                text_type(stress.format));
}

namespace {

// {"step", "x", "y", "link"} and, on a link, "model_x", "model_y" (the point where the model draws
// the link) and the stresses there by their column names; "units" for both.
std::string stress_probe_json(const Analysis& analysis, const request::StressProbeRequest& probe,
                              const request::StressProbeRequest::Answer& answer) {
  const Model& model = analysis.model();
  nlohmann::ordered_json j;
  j["step"] = probe.step;
  j["x"] = probe.at.x();
  j["y"] = probe.at.y();
  j["link"] = answer.link ? nlohmann::ordered_json(model.bodies[answer.link->body].name) : nlohmann::ordered_json();
  if (answer.link) {
    const ResultTable& t = answer.stresses;
    for (std::size_t c = 0; c < t.columns.size(); ++c) {
      const std::string key = t.columns[c] == "x" ? "model_x" : t.columns[c] == "y" ? "model_y" : t.columns[c];
      j[key] = t.rows.at(0).at(c);
    }
  }
  j["units"] = {{"length", model.units.length}, {"stress", "MPa"}, {"angle", model.units.angle}};
  return io::json_text(j, 2) + "\n";
}

}  // namespace

ApiResponse api_stress_probe(Job& job, const std::string& text) {
  const RequestBody body(text, request::StressProbeRequest::rules(), {"model"});
  // The model first: a broken model is told at its line, as every endpoint tells it, before the
  // point it was to be read at is asked for.
  load_model(job, body.text("model", true));
  const auto probe = read_request<request::StressProbeRequest>(body, {"model"});
  check_sweep_size(job, probe.sweep.steps);
  AnalysisOptions options = probe.analysis_options(job.mechanism->model());
  options.fe.max_nodes = job.limits.max_fe_nodes;
  const Analysis analysis = run_analysis(job, options);
  return answer(stress_probe_json(analysis, probe, probe.probe(analysis)));
}

ApiResponse api_report(Job& job, const std::string& text) {
  const RequestBody body(text, request::ReportRequest::rules(), {"model"});
  const auto report_request = read_request<request::ReportRequest>(body, {"model"});
  load_model(job, body.text("model", true));
  check_limit("frames", static_cast<double>(report_request.frames), job.limits.max_frames, "the number of frames");
  check_sweep_size(job, report_request.sweep.steps);
  const ModelSummary summary = summarize(*job.mechanism, report_request.sweep.max_steps);
  AnalysisOptions options = report_request.analysis_options(summary, job.mechanism->model());
  options.fe.max_nodes = job.limits.max_fe_nodes;
  check_table_size(job, options);
  job.start(Weight::Heavy);
  const Analysis analysis = run_analysis(job, options);
  job.checkpoint("report");
  render::ReportOptions report;
  report.source = kModelFile;
  report.frames = report_request.frames;
  report.control = job.control;
  return answer_html(render::html_report(analysis, summary, report));
}

namespace {

// `simulate` and `at`: the equations of motion at that time of the simulation `nbar simulate`
// runs, its rows (at / dt + 1) within the server's sample limit as /api/simulate's are.
ApiResponse explain_motion(Job& job, const request::ExplainRequest& r) {
  const double step = r.run.dt.value_or(job.mechanism->model().simulation.output_step.value_or(r.at / 100));
  check_limit("steps", r.at > 0 ? std::floor(r.at / step + 1e-9) + 1 : 1, job.limits.max_steps,
              "the number of rows of the simulation (at / dt + 1)");
  job.start(Weight::Heavy);
  const EquationsOfMotionAt equations = r.equations_of_motion(*job.mechanism, job.control);
  return answer(write([&](std::ostream& out) { r.write(out, *job.mechanism, equations); }),
                r.format == "json" ? "application/json" : "text/plain; charset=utf-8");
}

}  // namespace

ApiResponse api_explain(Job& job, const std::string& text) {
  const RequestBody body(text, request::ExplainRequest::rules(), {"model"});
  const auto explain_request = read_request<request::ExplainRequest>(body, {"model"}, true);
  load_model(job, body.text("model", true));
  // The explanation writes Phi_q whole and every pair of links' instant centre: small models.
  const Model& m = job.mechanism->model();
  check_limit("explain_points", static_cast<double>(m.points.size()), job.limits.max_explain_points,
              "the number of points of a model to explain");
  check_limit("explain_bodies", static_cast<double>(m.bodies.size()), job.limits.max_explain_bodies,
              "the number of bodies of a model to explain");
  if (explain_request.simulate) return explain_motion(job, explain_request);
  check_sweep_size(job, explain_request.sweep.steps);
  ExplainOptions options = explain_request.explain_options();
  options.control = job.control;
  job.start(Weight::Light);
  const Explanation ex = explain(job.mechanism, options);
  job.checkpoint("explain");
  const std::string& format = explain_request.format;
  if (format == "json") return answer(io::json_text(io::explanation_json(ex), 2) + '\n');
  const ExplainFormat f = format == "markdown" ? ExplainFormat::Markdown
                          : format == "latex"  ? ExplainFormat::Latex
                                               : ExplainFormat::Text;
  return answer(render_explanation(ex, f), format == "markdown" ? "text/markdown; charset=utf-8"
                                           : format == "latex"  ? "application/x-latex; charset=utf-8"
                                                                : "text/plain; charset=utf-8");
}

}  // namespace nbar::web

namespace nbar::web {

namespace {

Json outline_json(const request::Outline& o) {
  Json points = Json::array(), bodies = Json::array(), guides = Json::array();
  for (const auto& p : o.points) points.push_back({{"name", p.name}, {"x", p.x}, {"y", p.y}, {"ground", p.ground}});
  for (const auto& b : o.bodies) bodies.push_back({{"name", b.name}, {"points", b.points}});
  for (const auto& g : o.guides)
    guides.push_back({{"kind", g.kind}, {"body", g.body}, {"point", g.point}, {"line", g.line}});
  Json mobility = {{"gruebler", o.count.dof},
                   {"links", o.count.links},
                   {"lower_pairs", o.count.lower_pairs},
                   {"higher_pairs", o.count.higher_pairs},
                   {"dof", o.mobility ? Json(o.mobility->dof) : Json(nullptr)},
                   {"drivers", o.drivers}};
  Json problem = nullptr;
  if (!o.problem.empty()) {
    problem = {{"message", o.problem}};
    if (o.problem_at.line > 0) {
      problem["line"] = o.problem_at.line;
      problem["column"] = o.problem_at.column;
    }
  }
  return {{"model", o.name},
          {"units", {{"length", o.units.length}, {"angle", o.units.angle}}},
          {"points", points},
          {"bodies", bodies},
          {"guides", guides},
          {"joints", o.joints},
          {"mobility", mobility},
          {"problem", problem},
          {"immobile", o.immobile.empty() ? Json(nullptr) : Json(o.immobile)}};
}

}  // namespace

// A model being built, drawn by the app's tools as it grows (request/outline_request.hpp).
ApiResponse api_outline(Job& job, const std::string& text) {
  const RequestBody body(text, {"model"});
  const std::string model = body.text("model", true);
  const request::Outline outline = request::outline_model(model, kModelFile);
  check_limit("points", static_cast<double>(outline.points.size()), job.limits.max_points, "the number of points");
  check_limit("bodies", static_cast<double>(outline.bodies.size()), job.limits.max_bodies, "the number of bodies");
  job.checkpoint("outline");
  return answer(outline_json(outline).dump(2) + '\n');
}

}  // namespace nbar::web
