// nbar check: the model's summary, as text or JSON.
#include "commands.hpp"
#include "common.hpp"
#include "nbar/analysis/summary.hpp"
#include "nbar/io/summary_writer.hpp"
#include "nbar/request/requests.hpp"
#include "request_flags.hpp"

namespace nbar::cli {

namespace {

struct CheckCommand {
  std::string model;
  std::unique_ptr<RequestFlags> flags;
};

// The summary with the prose the web API translates in the check's JSON (its joints, the loops',
// rockers', slider-cranks' and quick-returns' descriptions, its warnings) in the language asked;
// names, numbers and the text's own headings stay as they are.
ModelSummary said(ModelSummary s) {
  for (std::string& joint : s.joints) joint = say(joint);
  for (LoopSummary& loop : s.loops) {
    loop.description = say(loop.description);
    if (loop.rocker) loop.rocker->description = say(loop.rocker->description);
  }
  for (SliderCrankSummary& f : s.slider_cranks) f.description = say(f.description);
  for (QuickReturnSummary& f : s.quick_returns) f.description = say(f.description);
  for (Warning& w : s.warnings) w.message = say(w.message);
  return s;
}

int run_check(const CheckCommand& command) {
  request::CheckRequest request;
  if (!read_request(*command.flags, request)) return kBadUsage;
  Loaded loaded;
  if (int code = load(command.model, loaded)) return code;
  const std::shared_ptr<const Mechanism> mechanism = request.mechanism(loaded.mechanism);
  const ModelSummary summary = summarize(*mechanism, request.max_steps);
  Output output;
  output.open("");
  if (request.format == "json") output.json_answer();
  if (request.format == "json")
    output.stream() << io::summary_json(*mechanism, summary, loaded.file.source);
  else
    io::write_summary_text(output.stream(), *mechanism, said(summary), command.model);
  if (!output.finish()) return kBadUsage;
  if (summary.assembly_error) return fail(command.model, io::located(loaded.file.source, *summary.assembly_error));
  if (summary.law_error) return fail(command.model, io::located(loaded.file.source, *summary.law_error));
  return kOk;
}

}  // namespace

Command add_check_command(CommandLine& app) {
  auto command = std::make_shared<CheckCommand>();
  Subcommand* sub = app.add_subcommand("check",
                                       "Summarise a model: bodies, joints, degrees of freedom, redundant "
                                       "constraints, drivers, assembly at the start, Grashof class of "
                                       "every four-bar loop");
  sub->add_option("MODEL", command->model, "model file (YAML or JSON)")->required();
  // check runs no sweep of the model's size (its law and cylinder checks sample a bounded
  // number of poses), but it says whether the sweep would be refused, at max_steps.
  command->flags = std::make_unique<RequestFlags>(*sub, request::CheckRequest::rules());
  command->flags->add({"format", "at_limits", "cycles", "max_steps"});
  return {sub, [command] { return run_check(*command); }};
}

}  // namespace nbar::cli
