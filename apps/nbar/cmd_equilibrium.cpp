// nbar equilibrium: where the free drivers come to rest under the model's loads (statics).
#include "commands.hpp"
#include "common.hpp"
#include "nbar/io/equilibrium_writer.hpp"
#include "nbar/request/equilibrium_request.hpp"
#include "request_flags.hpp"
#include "validators.hpp"

namespace nbar::cli {

namespace {

struct EquilibriumCommand {
  std::string model;
  std::string output;
  std::unique_ptr<RequestFlags> flags;
};

int run_equilibrium(const EquilibriumCommand& command) {
  request::EquilibriumRequest request;
  if (!read_request(*command.flags, request)) return kBadUsage;
  Loaded loaded;
  if (int code = load(command.model, loaded)) return code;
  Equilibrium equilibrium;
  try {
    equilibrium = find_equilibrium(*loaded.mechanism, request.equilibrium_options());
  } catch (const Error& e) {
    return fail(command.model, io::located(loaded.file.source, e));
  }
  ResultTable table;
  try {
    table = request.table(*loaded.mechanism, equilibrium);
  } catch (const request::OptionError& e) {
    print_option_error(e);
    return kBadUsage;
  }
  print_warnings(equilibrium.warnings);
  Output output;
  if (!output.open(command.output)) return kBadUsage;
  if (request.format == "json") output.json_answer();
  if (request.format == "json") {
    io::write_equilibrium_json(output.stream(), *loaded.mechanism, equilibrium, table);
  } else if (request.format == "csv") {
    io::write_csv(output.stream(), table);
  } else {
    io::write_text_table(output.stream(), table, terminal_width());
    io::write_equilibrium_summary(output.stream(), *loaded.mechanism, equilibrium);
  }
  return output.finish() ? kOk : kBadUsage;
}

}  // namespace

Command add_equilibrium_command(CommandLine& app) {
  auto command = std::make_shared<EquilibriumCommand>();
  Subcommand* sub = app.add_subcommand("equilibrium",
                                       "Where the drivers marked free come to rest under the loads (statics): their "
                                       "values, every point and body, the residual force and the stability");
  sub->add_option("MODEL", command->model, "model file (YAML or JSON)")->required();
  command->flags = std::make_unique<RequestFlags>(*sub, request::EquilibriumRequest::rules());
  command->flags->add({"format", "columns", "max_iterations"});
  sub->add_option("-o,--output", command->output, "write to FILE instead of standard output")
      ->check(nbar::cli::output_file());
  return {sub, [command] { return run_equilibrium(*command); }};
}

}  // namespace nbar::cli
