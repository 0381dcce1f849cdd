// nbar simulate: the motion under the loads, with the free drivers released (forward dynamics).
#include "commands.hpp"
#include "common.hpp"
#include "nbar/dynamics/forward_dynamics.hpp"
#include "nbar/request/requests.hpp"
#include "request_flags.hpp"
#include "simulation_run.hpp"
#include "validators.hpp"

namespace nbar::cli {

namespace {

struct SimulateCommand {
  std::string model;
  std::string output;
  std::unique_ptr<RequestFlags> flags;
};

int run_simulate(const SimulateCommand& command) {
  request::SimulateRequest request;
  if (!read_request(*command.flags, request)) return kBadUsage;
  Loaded loaded;
  if (int code = load(command.model, loaded)) return code;
  Simulation simulation;
  if (int code = simulate_model(command.model, loaded, request, simulation)) return code;
  ResultTable table;
  try {
    table = request.table(*loaded.mechanism, simulation);
  } catch (const request::OptionError& e) {
    print_option_error(e);
    return kBadUsage;
  }
  Output output;
  if (!output.open(command.output)) return kBadUsage;
  if (request.format == "json") output.json_answer();
  // A table says the events and the stop after its rows: in the language asked, as the JSON's are.
  if (request.format == "table") {
    for (SimulationEvent& event : simulation.events) event.message = say(event.message);
    simulation.stop_reason = say(simulation.stop_reason);
  }
  request.write(output.stream(), *loaded.mechanism, simulation, table, terminal_width());
  // The events: in the JSON's "events"; after a table; on standard error beside a CSV, which stays
  // rows only.
  if (request.format == "csv")
    for (const SimulationEvent& event : simulation.events)
      std::cerr << command.model << ": event: " << say(event.message) << '\n';
  if (!output.finish()) return kBadUsage;
  // The rows so far are written; the reason is said at the entity concerned.
  return finish_simulation(command.model, loaded, simulation);
}

}  // namespace

Command add_simulate_command(CommandLine& app) {
  auto command = std::make_shared<SimulateCommand>();
  Subcommand* sub =
      app.add_subcommand("simulate",
                         "Let the mechanism move under its loads (forward dynamics), the drivers "
                         "marked free released: positions, velocities, accelerations and energies in time");
  sub->add_option("MODEL", command->model, "model file (YAML or JSON)")->required();
  command->flags = std::make_unique<RequestFlags>(*sub, request::SimulateRequest::rules());
  command->flags->add({"to", "dt", "rtol", "max_steps", "format", "columns", "stop_when", "at_toggle", "threads"});
  sub->add_option("-o,--output", command->output, "write to FILE instead of standard output")
      ->check(nbar::cli::output_file());
  return {sub, [command] { return run_simulate(*command); }};
}

}  // namespace nbar::cli
