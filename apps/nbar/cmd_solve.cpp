// nbar solve: the sweep's columns as CSV (streamed), JSON or an aligned table.
#include <optional>

#include "commands.hpp"
#include "common.hpp"
#include "nbar/analysis/table_stream.hpp"
#include "nbar/request/requests.hpp"
#include "request_flags.hpp"
#include "validators.hpp"

namespace nbar::cli {

namespace {

struct SolveCommand {
  std::string model;
  std::string output;
  std::unique_ptr<RequestFlags> flags;
};

// CSV is streamed: rows are written as the sweep solves them and none is kept, so memory does
// not grow with the number of steps (TableStream runs a long sweep twice for that). JSON and the
// text table need every row at once (the text table sizes its columns over all rows).
int solve_to_csv(const SolveCommand& command, const request::SolveRequest& request, const Loaded& loaded) {
  std::optional<TableStream> stream;
  try {
    stream.emplace(loaded.mechanism, request.analysis_options(), request.columns_on_request(*loaded.mechanism));
    stream->measure();
  } catch (const Error& e) {
    return fail(command.model, io::located(loaded.file.source, e));
  }
  try {
    request.select(*loaded.mechanism, *stream);
  } catch (const request::OptionError& e) {
    print_option_error(e);
    return kBadUsage;
  }
  Output output;
  if (!output.open(command.output)) return kBadUsage;
  {
    io::CsvWriter csv(output.stream(), stream->columns());
    try {
      stream->rows([&](const double* row) { csv.row(row); });
    } catch (const Error& e) {  // the first pass has met every error already
      return fail(command.model, io::located(loaded.file.source, e));
    }
  }
  if (!output.finish()) return kBadUsage;
  print_warnings(stream->warnings());
  return finish(loaded, stream->sweep());
}

int run_solve(const SolveCommand& command) {
  request::SolveRequest request;
  if (!read_request(*command.flags, request)) return kBadUsage;
  Loaded loaded;
  if (int code = load(command.model, loaded)) return code;
  if (request.format == "csv") return solve_to_csv(command, request, loaded);
  Analysis analysis;
  if (int code = analyse_model(command.model, loaded, request.analysis_options(), analysis)) return code;
  ResultTable table;
  try {
    table = request.table(analysis);
  } catch (const request::OptionError& e) {
    print_option_error(e);
    return kBadUsage;
  }
  Output output;
  if (!output.open(command.output)) return kBadUsage;
  if (request.format == "json") output.json_answer();
  io::write_table(output.stream(), request.format, analysis, table, analysis.dynamics ? &*analysis.dynamics : nullptr,
                  terminal_width());
  if (!output.finish()) return kBadUsage;
  print_warnings(analysis.warnings());
  return finish(loaded, analysis.sweep);
}

}  // namespace

Command add_solve_command(CommandLine& app) {
  auto command = std::make_shared<SolveCommand>();
  Subcommand* sub = app.add_subcommand("solve",
                                       "Sweep the drivers and write positions, velocities, accelerations "
                                       "and higher derivatives of every point and body");
  sub->add_option("MODEL", command->model, "model file (YAML or JSON)")->required();
  command->flags = std::make_unique<RequestFlags>(*sub, request::SolveRequest::rules());
  command->flags->add({"steps", "max_steps", "at_limits", "cycles", "order", "format", "columns"});
  sub->add_option("-o,--output", command->output, "write to FILE instead of standard output")
      ->check(nbar::cli::output_file());
  command->flags->add({"dynamics"});
  return {sub, [command] { return run_solve(*command); }};
}

}  // namespace nbar::cli
