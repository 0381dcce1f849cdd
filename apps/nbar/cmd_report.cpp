// nbar report: one self-contained HTML file about a mechanism.
#include <fstream>

#include "commands.hpp"
#include "common.hpp"
#include "nbar/analysis/summary.hpp"
#include "nbar/render/report.hpp"
#include "validators.hpp"

namespace nbar::cli {

namespace {

struct ReportArgs {
  std::string model, output;
  std::optional<int> steps;
  int max_steps = nbar::kDefaultMaxSweepSamples;
  int frames = 72;
  std::string method = "beam";
  std::optional<double> mesh_size;
};

int run_report(const ReportArgs& args) {
  if (args.output.size() < 5 || args.output.substr(args.output.size() - 5) != ".html") {
    std::cerr << "error: -o " << args.output << ": the report is an HTML file: name it FILE.html\n";
    return kBadUsage;
  }
  Loaded loaded;
  if (int code = load(args.model, loaded)) return code;
  const ModelSummary summary = summarize(*loaded.mechanism, args.max_steps);
  AnalysisOptions options = render::report_analysis_options(summary);
  options.steps = args.steps;
  options.max_steps = args.max_steps;
  if (args.method == "fe") use_finite_elements(options, loaded.mechanism->model(), args.mesh_size);
  Analysis analysis;
  if (int code = analyse_model(args.model, loaded, options, analysis)) return code;
  render::ReportOptions report;
  report.source = args.model;
  report.frames = args.frames;
  const std::string html = render::html_report(analysis, summary, report);
  std::ofstream out(args.output);
  if (out << html) out.close();  // a full disk fails here, after the page was taken
  if (!out) {
    std::cerr << "error: " << cannot_write_message(args.output) << '\n';
    return kBadUsage;
  }
  print_warnings(analysis.warnings());
  return finish(loaded, analysis.sweep);
}

}  // namespace

Command add_report_command(CLI::App& app) {
  auto args = std::make_shared<ReportArgs>();
  CLI::App* sub = app.add_subcommand("report", "One self-contained HTML report: summary, animation, coupler paths, "
                                               "angle/velocity/acceleration/jerk plots, and forces and stresses when "
                                               "the model has masses, loads and shapes");
  sub->add_option("MODEL", args->model, "model file (YAML or JSON)")->required();
  sub->add_option("-o,--output", args->output, "FILE.html")->check(nbar::cli::output_file())->required();
  sub->add_option("--steps", args->steps, "samples of the sweep (overrides the model's sweep)")->check(nbar::cli::positive());
  sub->add_option("--max-steps", args->max_steps, kMaxStepsHelp)->check(nbar::cli::positive());
  sub->add_option("--frames", args->frames, "animation frames (default 72)")->check(nbar::cli::in_range(nbar::render::kMinReportFrames, nbar::render::kMaxReportFrames));
  sub->add_option("--stress-method", args->method,
                  "the stresses' method, as `nbar stress --method`: beam (default) or fe (links coloured by their "
                  "finite-element von Mises stress)")
      ->check(CLI::IsMember({"beam", "fe"}));
  sub->add_option("--mesh-size", args->mesh_size, "with --stress-method fe: element edge far from holes, in the "
                                                  "model's length unit")
      ->check(nbar::cli::positive());
  return {sub, [args] { return run_report(*args); }};
}

}  // namespace nbar::cli
