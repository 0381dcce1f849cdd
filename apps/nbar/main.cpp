// nbar: the command-line front-end. It only translates between the terminal and the core.
//
// Exit codes: 0 success; 1 invalid model; 2 bad usage; 3 cannot assemble at the start;
// 4 sweep stopped early (the rows solved so far are written).
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <iostream>
#include <new>
#include <optional>
#include <sstream>
#include <string>

#include "commands.hpp"
#include "common.hpp"
#include "nbar/analysis/columns.hpp"
#include "nbar/analysis/summary.hpp"
#include "nbar/analysis/table_stream.hpp"
#include "nbar/io/results_writer.hpp"
#include "nbar/io/summary_writer.hpp"
#include "nbar/io/yaml_support.hpp"
#include "nbar/version.hpp"
#include "validators.hpp"

namespace {

using namespace nbar::cli;


int run_check(const std::string& path, const std::string& format, int max_steps) {
  Loaded loaded;
  if (int code = load(path, loaded)) return code;
  const nbar::ModelSummary summary = nbar::summarize(*loaded.mechanism, max_steps);
  if (format == "json")
    std::cout << nbar::io::summary_json(*loaded.mechanism, summary, loaded.file.source);
  else
    nbar::io::write_summary_text(std::cout, *loaded.mechanism, summary, path);
  if (summary.assembly_error) return fail(path, nbar::io::located(loaded.file.source, *summary.assembly_error));
  if (summary.law_error) return fail(path, nbar::io::located(loaded.file.source, *summary.law_error));
  return kOk;
}

struct SolveArgs {
  std::string model;
  std::optional<int> steps;
  int max_steps = nbar::kDefaultMaxSweepSamples;
  int order = 2;
  std::string format = "csv";
  std::string output;
  std::vector<std::string> columns;
  bool dynamics = false;
};

void print_column_error(const Loaded& loaded, const SolveArgs& args, const std::invalid_argument& e) {
  // A force or torque column asked for without --dynamics: say so rather than list the others.
  if (!args.dynamics && nbar::column_needs(*loaded.mechanism, args.columns, args.order, false).dynamics) {
    std::cerr << "error: --columns: " << e.what() << ": the force and torque columns come from the inverse dynamics, "
              << "add --dynamics\n";
    return;
  }
  std::cerr << "error: --columns: " << e.what() << "; the columns are: "
            << join(nbar::column_names(nbar::column_catalogue(*loaded.mechanism, args.order, args.dynamics))) << '\n';
}

// CSV is streamed: rows are written as the sweep solves them and none is kept, so memory does
// not grow with the number of steps (TableStream runs a long sweep twice for that). JSON and the
// text table need every row at once (the text table sizes its columns over all rows).
int solve_to_csv(const SolveArgs& args, const Loaded& loaded, const nbar::AnalysisOptions& options) {
  std::optional<nbar::TableStream> stream;
  try {
    stream.emplace(loaded.mechanism, options);
    stream->measure();
  } catch (const nbar::Error& e) {
    return fail(args.model, nbar::io::located(loaded.file.source, e));
  }
  if (!args.columns.empty()) {
    try {
      stream->select(args.columns);
    } catch (const std::invalid_argument& e) {
      print_column_error(loaded, args, e);
      return kBadUsage;
    }
  }
  Output output;
  if (!output.open(args.output)) return kBadUsage;
  std::ostream& out = output.stream();
  {
    nbar::io::CsvWriter csv(out, stream->columns());
    try {
      stream->rows([&](const double* row) { csv.row(row); });
    } catch (const nbar::Error& e) {  // the first pass has met every error already
      return fail(args.model, nbar::io::located(loaded.file.source, e));
    }
  }
  if (!output.finish()) return kBadUsage;
  print_warnings(stream->warnings());
  return finish(loaded, stream->sweep());
}

int run_solve(const SolveArgs& args) {
  Loaded loaded;
  if (int code = load(args.model, loaded)) return code;
  nbar::AnalysisOptions options;
  options.steps = args.steps;
  options.max_steps = args.max_steps;
  options.order = args.order;
  options.dynamics = args.dynamics;
  if (args.format == "csv") return solve_to_csv(args, loaded, options);
  nbar::Analysis analysis;
  if (int code = analyse_model(args.model, loaded, options, analysis)) return code;
  nbar::ResultTable table = nbar::result_table(analysis);
  if (!args.columns.empty()) {
    try {
      table = nbar::select_columns(table, args.columns);
    } catch (const std::invalid_argument& e) {
      print_column_error(loaded, args, e);
      return kBadUsage;
    }
  }

  Output output;
  if (!output.open(args.output)) return kBadUsage;
  std::ostream& out = output.stream();
  nbar::io::write_table(out, args.format, analysis, table, analysis.dynamics ? &*analysis.dynamics : nullptr,
                        terminal_width());
  if (!output.finish()) return kBadUsage;
  print_warnings(analysis.warnings());
  return finish(loaded, analysis.sweep);
}

struct StressArgs {
  std::string model;
  std::optional<int> steps;
  int max_steps = nbar::kDefaultMaxSweepSamples;
  int sections = 200;
  std::string method = "beam";
  std::optional<double> mesh_size;
  std::string format = "table";
  std::string output;
  std::string profile_body;
  std::optional<int> profile_step;
};

// Every section of one body at one step.
int write_section_profile(const StressArgs& args, const nbar::Analysis& analysis, std::ostream& out) {
  const int body = analysis.model().find_body(args.profile_body);
  if (body < 0 || !analysis.stress->links->analysed(body)) {
    std::cerr << "error: --section-profile: '" << args.profile_body
              << (body < 0 ? "' is not a body of the model\n" : "' has no shape to cut\n");
    return kBadUsage;
  }
  const int step = args.profile_step.value_or(0);
  if (!check_step(step, analysis.sweep)) return kBadUsage;
  const nbar::ResultTable t = nbar::section_profile_table(analysis, body, step);
  nbar::io::write_table(out, args.format, analysis, t);
  return kOk;
}

int run_stress(const StressArgs& args) {
  Loaded loaded;
  if (int code = load(args.model, loaded)) return code;
  nbar::AnalysisOptions options;
  options.steps = args.steps;
  options.max_steps = args.max_steps;
  options.stress = true;
  options.sections = args.sections;
  if (args.method == "fe") use_finite_elements(options, loaded.mechanism->model(), args.mesh_size);
  if (args.method == "fe" && !args.profile_body.empty()) {
    std::cerr << "error: --section-profile cuts sections, which the beam method has: leave out --method fe\n";
    return kBadUsage;
  }
  nbar::Analysis analysis;
  if (int code = analyse_model(args.model, loaded, options, analysis)) return code;

  Output output;
  if (!output.open(args.output)) return kBadUsage;
  std::ostream& out = output.stream();
  if (!args.profile_body.empty()) {
    if (int code = write_section_profile(args, analysis, out)) return code;
  } else {
    nbar::io::write_stress_report(out, args.format, analysis);
  }
  if (!output.finish()) return kBadUsage;
  return finish(loaded, analysis.sweep);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"nbar: analysis of planar linkages (n-bar mechanisms)"};
  app.set_version_flag("--version", std::string("nbar ") + nbar::kVersion);
  app.require_subcommand(1);
  app.footer(
      "Exit codes: 0 success, 1 invalid model, 2 bad usage, 3 cannot assemble at the start,\n"
      "            4 sweep stopped early (the rows solved so far are written), 5 stopped by synth --timeout.\n"
      "Limits: a sweep has at most 10000000 samples (--max-steps of every command that sweeps), model files at most\n"
      "        16 MB, names at most 256 characters, models at most 20000 moving points.\n"
      "Model files: see docs/model-format.md.");

  std::string check_model, check_format = "text";
  int check_max_steps = nbar::kDefaultMaxSweepSamples;
  CLI::App* check = app.add_subcommand("check", "Summarise a model: bodies, joints, degrees of freedom, redundant "
                                                "constraints, drivers, assembly at the start, Grashof class of "
                                                "every four-bar loop");
  check->add_option("MODEL", check_model, "model file (YAML or JSON)")->required();
  check->add_option("--format", check_format, "text (default) or json (the same summary as data, in the model's units)")
      ->check(CLI::IsMember({"text", "json"}));
  // check runs no sweep of the model's size (its law and cylinder checks sample a bounded
  // number of poses), but it says whether the sweep would be refused, at this limit.
  check->add_option("--max-steps", check_max_steps, kMaxStepsHelp)->check(nbar::cli::positive());

  SolveArgs solve_args;
  CLI::App* solve = app.add_subcommand("solve", "Sweep the drivers and write positions, velocities, accelerations "
                                                "and higher derivatives of every point and body");
  solve->add_option("MODEL", solve_args.model, "model file (YAML or JSON)")->required();
  solve->add_option("--steps", solve_args.steps, "number of samples, ends included (overrides the model's sweep)")
      ->check(nbar::cli::positive());
  solve->add_option("--max-steps", solve_args.max_steps, kMaxStepsHelp)->check(nbar::cli::positive());
  solve->add_option("--order", solve_args.order, "highest time derivative: 0 positions, 1 velocities, 2 "
                                                 "accelerations (default), 3 jerk, up to 5")
      ->check(nbar::cli::in_range(0, 5));
  solve->add_option("--format", solve_args.format, "csv (default), json, or table (aligned, for reading)")
      ->check(CLI::IsMember({"csv", "json", "table"}));
  solve->add_option("--columns", solve_args.columns,
                    "only these columns, comma-separated names or globs, e.g. 'crank,rocker.*,B.v*'")
      ->delimiter(',');
  solve->add_option("-o,--output", solve_args.output, "write to FILE instead of standard output")
      ->check(nbar::cli::output_file());

  solve->add_flag("--dynamics", solve_args.dynamics,
                  "add inverse dynamics: the force at every joint, every driver's torque or force, energies "
                  "(N, N m, J whatever the length unit; order at least 2)");

  StressArgs stress_args;
  CLI::App* stress = app.add_subcommand("stress", "Stresses in every link that has a shape: the largest von Mises "
                                                  "stress over the sweep, where and when, and the safety factor");
  stress->add_option("MODEL", stress_args.model, "model file (YAML or JSON)")->required();
  stress->add_option("--steps", stress_args.steps, "number of samples, ends included (overrides the model's sweep)")
      ->check(nbar::cli::positive());
  stress->add_option("--max-steps", stress_args.max_steps, kMaxStepsHelp)->check(nbar::cli::positive());
  stress->add_option("--method", stress_args.method,
                     "beam (default: quick, beam theory on cross-sections, for slender links between joints) or fe "
                     "(plane-stress finite elements: the peaks at pin holes, fillets and in plates)")
      ->check(CLI::IsMember({"beam", "fe"}));
  stress->add_option("--sections", stress_args.sections, "beam: cross-sections per link, at least (default 200)")
      ->check(nbar::cli::in_range(nbar::kMinSectionsPerLink, nbar::kMaxSectionsPerLink));
  stress->add_option("--mesh-size", stress_args.mesh_size,
                     "fe: element edge far from holes and corners, in the model's length unit (default: a twentieth "
                     "of each plate's size; finer around holes)")
      ->check(nbar::cli::positive());
  stress->add_option("--format", stress_args.format, "table (default), csv or json")
      ->check(CLI::IsMember({"table", "csv", "json"}));
  stress->add_option("-o,--output", stress_args.output, "write to FILE instead of standard output")
      ->check(nbar::cli::output_file());
  CLI::Option* profile = stress->add_option("--section-profile", stress_args.profile_body,
                                            "instead, every section of BODY at one step: N, V, M, sigma, tau, von Mises");
  stress->add_option("--step", stress_args.profile_step, "the step for --section-profile (default 0)")->needs(profile);

  // Commands defined in their own files (commands.hpp).
  std::vector<std::pair<CLI::App*, std::function<int()>>> more;
  for (const auto& add : nbar::cli::more_commands()) more.push_back(add(app));

  // A first argument that is neither an option nor a command: say so, with the nearest command
  // (CLI11 alone says only that a subcommand is required).
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands({})) names.push_back(sub->get_name());
  if (argc > 1 && argv[1][0] != '-' && std::find(names.begin(), names.end(), argv[1]) == names.end()) {
    const auto close = nbar::io::yaml::suggestion(argv[1], names);
    std::cerr << "error: '" << argv[1] << "' is not an nbar command (the commands are: " << join(names) << ")"
              << (close ? "; did you mean '" + *close + "'?" : std::string()) << "\n";
    return kBadUsage;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kOk : kBadUsage;
  }
  // Each command reports what it expects; anything else still ends in a message and an exit
  // code, never an abort.
  try {
    if (check->parsed()) return run_check(check_model, check_format, check_max_steps);
    if (solve->parsed()) return run_solve(solve_args);
    if (stress->parsed()) return run_stress(stress_args);
    for (const auto& [command, run] : more)
      if (command->parsed()) return run();
  } catch (const nbar::Error& e) {
    return fail("", e);
  } catch (const std::bad_alloc&) {
    // Within the limits a run can still outgrow the machine: every sample is kept.
    std::cerr << "error: out of memory: ask for fewer steps (--steps) or a smaller model\n";
    return kBadUsage;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << '\n';
    return kBadUsage;
  }
  return kBadUsage;
}
