// nbar stress: every shaped link's largest stress, or one link's sections at one step.
#include "commands.hpp"
#include "common.hpp"
#include "nbar/request/requests.hpp"
#include "request_flags.hpp"
#include "validators.hpp"

namespace nbar::cli {

namespace {

struct StressCommand {
  std::string model;
  std::string output;
  std::unique_ptr<RequestFlags> flags;
};

int run_stress(const StressCommand& command) {
  request::StressRequest request;
  if (!read_request(*command.flags, request)) return kBadUsage;
  Loaded loaded;
  if (int code = load(command.model, loaded)) return code;
  Analysis analysis;
  if (int code = analyse_model(command.model, loaded, request.analysis_options(loaded.mechanism->model()), analysis))
    return code;
  ResultTable profile;
  if (request.profile_asked()) {
    try {
      profile = request.section_profile_table(analysis);
    } catch (const request::OptionError& e) {
      print_option_error(e);
      return kBadUsage;
    }
  }
  Output output;
  if (!output.open(command.output)) return kBadUsage;
  if (request.profile_asked())
    io::write_table(output.stream(), request.format, analysis, profile);
  else
    io::write_stress_report(output.stream(), request.format, analysis);
  if (!output.finish()) return kBadUsage;
  return finish(loaded, analysis.sweep);
}

}  // namespace

Command add_stress_command(CLI::App& app) {
  auto command = std::make_shared<StressCommand>();
  CLI::App* sub = app.add_subcommand("stress",
                                     "Stresses in every link that has a shape: the largest von Mises "
                                     "stress over the sweep, where and when, and the safety factor");
  sub->add_option("MODEL", command->model, "model file (YAML or JSON)")->required();
  command->flags = std::make_unique<RequestFlags>(*sub, request::StressRequest::rules());
  command->flags->add({"steps", "max_steps", "method", "sections", "mesh_size", "format"});
  sub->add_option("-o,--output", command->output, "write to FILE instead of standard output")
      ->check(nbar::cli::output_file());
  command->flags->add({"section_profile", "step"});
  command->flags->add({"at", "along", "around_hole", "coordinates", "radius", "samples"});
  return {sub, [command] { return run_stress(*command); }};
}

}  // namespace nbar::cli
