// nbar report: one self-contained HTML file about a mechanism.
#include <fstream>

#include "commands.hpp"
#include "common.hpp"
#include "nbar/analysis/summary.hpp"
#include "nbar/render/report.hpp"
#include "nbar/request/requests.hpp"
#include "request_flags.hpp"
#include "simulation_run.hpp"
#include "validators.hpp"

namespace nbar::cli {

namespace {

struct ReportCommand {
  std::string model, output;
  std::unique_ptr<RequestFlags> flags;
  std::unique_ptr<RequestFlags> motion_flags;  // --simulate and its run's options
};

// The page, written; false (said) when it cannot be.
bool write_report(const std::string& path, const std::string& html) {
  std::ofstream out(path);
  if (out << html) out.close();  // a full disk fails here, after the page was taken
  if (!out) {
    std::cerr << "error: " << cannot_write_message(path) << '\n';
    return false;
  }
  return true;
}

// --simulate: the report of the simulation's motion (no forces or stresses: those are the sweep's).
int report_simulation(const ReportCommand& command, const request::ReportRequest& request,
                      const request::SimulateRequest& run, const Loaded& loaded) {
  if (request.stress_method == StressMethod::fe) {
    print_option_error(request::OptionError("stress_method", "colours the sweep's stresses: not with {simulate}"));
    return kBadUsage;
  }
  const ModelSummary summary = summarize(*loaded.mechanism, request.sweep.max_steps);
  Simulation simulation;
  if (int code = simulate_model(command.model, loaded, run, simulation)) return code;
  render::ReportOptions report;
  report.source = command.model;
  report.frames = request.frames;
  report.simulation = &simulation;
  std::string html;
  try {
    html = render::html_report(request::simulated_analysis(loaded.mechanism, simulation), summary, report);
  } catch (const Error& e) {
    return fail(command.model, nbar::io::located(loaded.file.source, e));
  }
  if (!write_report(command.output, html)) return kBadUsage;
  return finish_simulation(command.model, loaded, simulation);
}

int run_report(const ReportCommand& command) {
  if (command.output.size() < 5 || command.output.substr(command.output.size() - 5) != ".html") {
    std::cerr << "error: -o " << command.output << ": the report is an HTML file: name it FILE.html\n";
    return kBadUsage;
  }
  request::ReportRequest request;
  if (!read_request(*command.flags, request)) return kBadUsage;
  request::SimulatedMotionRequest motion;
  if (!read_request(*command.motion_flags, motion)) return kBadUsage;
  Loaded loaded;
  if (int code = load(command.model, loaded)) return code;
  if (motion.simulation) return report_simulation(command, request, *motion.simulation, loaded);
  const ModelSummary summary = summarize(*loaded.mechanism, request.sweep.max_steps);
  Analysis analysis;
  if (int code =
          analyse_model(command.model, loaded, request.analysis_options(summary, loaded.mechanism->model()), analysis))
    return code;
  render::ReportOptions report;
  report.source = command.model;
  report.frames = request.frames;
  if (!write_report(command.output, render::html_report(analysis, summary, report))) return kBadUsage;
  print_warnings(analysis.warnings());
  return finish(loaded, analysis.sweep);
}

}  // namespace

Command add_report_command(CommandLine& app) {
  auto command = std::make_shared<ReportCommand>();
  Subcommand* sub = app.add_subcommand("report",
                                       "One self-contained HTML report: summary, animation, coupler paths, "
                                       "angle/velocity/acceleration/jerk plots, and forces and stresses when "
                                       "the model has masses, loads and shapes");
  sub->add_option("MODEL", command->model, "model file (YAML or JSON)")->required();
  sub->add_option("-o,--output", command->output, "FILE.html")->check(nbar::cli::output_file())->required();
  command->flags = std::make_unique<RequestFlags>(*sub, request::ReportRequest::rules());
  command->flags->add({"steps", "max_steps", "frames", "stress_method", "mesh_size"});
  command->motion_flags = std::make_unique<RequestFlags>(*sub, request::SimulatedMotionRequest::rules());
  command->motion_flags->add({"simulate", "to", "dt", "rtol", "stop_when", "at_toggle"});
  return {sub, [command] { return run_report(*command); }};
}

}  // namespace nbar::cli
