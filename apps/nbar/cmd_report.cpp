// nbar report: one self-contained HTML file about a mechanism.
#include <fstream>

#include "commands.hpp"
#include "common.hpp"
#include "nbar/analysis/summary.hpp"
#include "nbar/render/report.hpp"
#include "nbar/request/requests.hpp"
#include "request_flags.hpp"
#include "validators.hpp"

namespace nbar::cli {

namespace {

struct ReportCommand {
  std::string model, output;
  std::unique_ptr<RequestFlags> flags;
};

int run_report(const ReportCommand& command) {
  if (command.output.size() < 5 || command.output.substr(command.output.size() - 5) != ".html") {
    std::cerr << "error: -o " << command.output << ": the report is an HTML file: name it FILE.html\n";
    return kBadUsage;
  }
  request::ReportRequest request;
  if (!read_request(*command.flags, request)) return kBadUsage;
  Loaded loaded;
  if (int code = load(command.model, loaded)) return code;
  const ModelSummary summary = summarize(*loaded.mechanism, request.sweep.max_steps);
  Analysis analysis;
  if (int code =
          analyse_model(command.model, loaded, request.analysis_options(summary, loaded.mechanism->model()), analysis))
    return code;
  render::ReportOptions report;
  report.source = command.model;
  report.frames = request.frames;
  const std::string html = render::html_report(analysis, summary, report);
  std::ofstream out(command.output);
  if (out << html) out.close();  // a full disk fails here, after the page was taken
  if (!out) {
    std::cerr << "error: " << cannot_write_message(command.output) << '\n';
    return kBadUsage;
  }
  print_warnings(analysis.warnings());
  return finish(loaded, analysis.sweep);
}

}  // namespace

Command add_report_command(CLI::App& app) {
  auto command = std::make_shared<ReportCommand>();
  CLI::App* sub = app.add_subcommand("report",
                                     "One self-contained HTML report: summary, animation, coupler paths, "
                                     "angle/velocity/acceleration/jerk plots, and forces and stresses when "
                                     "the model has masses, loads and shapes");
  sub->add_option("MODEL", command->model, "model file (YAML or JSON)")->required();
  sub->add_option("-o,--output", command->output, "FILE.html")->check(nbar::cli::output_file())->required();
  command->flags = std::make_unique<RequestFlags>(*sub, request::ReportRequest::rules());
  command->flags->add({"steps", "max_steps", "frames", "stress_method", "mesh_size"});
  return {sub, [command] { return run_report(*command); }};
}

}  // namespace nbar::cli
