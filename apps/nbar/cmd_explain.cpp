// nbar explain: the method, step by step, at one sample of the sweep (Gruebler count, q, Phi,
// Phi_q, Newton's iterations, the velocity and acceleration systems, the instant centres), as
// text, Markdown, LaTeX or JSON, and optionally a drawing with the instant centres marked.

#include "commands.hpp"
#include "common.hpp"
#include "io/explain_writer.hpp"
#include "io/json_text.hpp"
#include "nbar/analysis/explain.hpp"
#include "nbar/render/pictures.hpp"
#include "nbar/request/requests.hpp"
#include "request_flags.hpp"
#include "simulation_run.hpp"
#include "validators.hpp"

namespace nbar::cli {

namespace {

struct ExplainCommand {
  std::string model, output, draw;
  std::unique_ptr<RequestFlags> flags;
};

// The pose with its finite instant centres marked.
int draw_centres(const std::string& path, const Explanation& ex) {
  int off_picture = 0;
  try {
    const bool written = extension(path) == "svg" ? write_file(path, render::instant_centres_svg(ex, &off_picture))
                                                  : write_file(path, render::instant_centres_png(ex, &off_picture));
    if (!written) return kBadUsage;
  } catch (const Error& e) {
    std::cerr << "error: " << said(e) << '\n';
    return exit_code(e.kind());
  }
  if (off_picture > 0)
    std::cerr << "note: --draw: " << off_picture << " instant centre" << (off_picture == 1 ? " lies" : "s lie")
              << " too far from the mechanism to draw\n";
  return kOk;
}

// --simulate: the equations of motion at --at, from the simulation `nbar simulate` runs.
int explain_motion(const ExplainCommand& command, const request::ExplainRequest& request, const Loaded& loaded) {
  EquationsOfMotionAt equations;
  try {
    RunControl control;
    const InterruptCancels interrupt(control.token);
    equations = request.equations_of_motion(*loaded.mechanism, control);
  } catch (const request::OptionError& e) {
    print_option_error(e);
    return kBadUsage;
  } catch (const Error& e) {
    return fail(command.model, nbar::io::located(loaded.file.source, e));
  }
  Output output;
  if (!output.open(command.output)) return kBadUsage;
  if (request.format == "json") output.json_answer();
  request.write(output.stream(), *loaded.mechanism, equations);
  return output.finish() ? kOk : kBadUsage;
}

// The explanation with its rows' labels in the language asked, as the web API says them in
// explain's JSON. Newton's start stays English here: the text says it inside an English sentence
// of its own ("from step 4's pose with the drivers at..."), which the catalogue does not hold.
Explanation said(Explanation ex) {
  for (EquationRow& row : ex.equations) row.label = say(row.label);
  return ex;
}

int run_explain(const ExplainCommand& command) {
  if (!command.draw.empty() && extension(command.draw) != "svg" && extension(command.draw) != "png") {
    std::cerr << "error: --draw " << command.draw << ": the picture's format comes from its extension: .svg or .png\n";
    return kBadUsage;
  }
  request::ExplainRequest request;
  if (!read_request(*command.flags, request)) return kBadUsage;
  if (request.simulate && !command.draw.empty()) {
    std::cerr << "error: --draw draws the sweep's instant centres: it is not an option of --simulate\n";
    return kBadUsage;
  }
  Loaded loaded;
  if (int code = load(command.model, loaded)) return code;
  if (request.simulate) return explain_motion(command, request, loaded);
  Explanation ex;
  try {
    ex = explain(loaded.mechanism, request.explain_options());
  } catch (const Error& e) {
    return fail(command.model, nbar::io::located(loaded.file.source, e));
  }
  Output output;
  if (!output.open(command.output)) return kBadUsage;
  if (request.format == "json") output.json_answer();
  std::ostream& out = output.stream();
  if (request.format == "json")
    out << io::json_text(io::explanation_json(ex), 2) << '\n';
  else
    out << render_explanation(said(ex), request.format == "markdown" ? ExplainFormat::Markdown
                                  : request.format == "latex"  ? ExplainFormat::Latex
                                                               : ExplainFormat::Text);
  if (!output.finish()) return kBadUsage;
  if (!command.draw.empty()) return draw_centres(command.draw, ex);
  return kOk;
}

}  // namespace

Command add_explain_command(CommandLine& app) {
  auto command = std::make_shared<ExplainCommand>();
  Subcommand* sub = app.add_subcommand("explain",
                                       "The method step by step at one sample: Gruebler count, q, the "
                                       "constraint equations and their Jacobian, Newton's iterations, the "
                                       "velocity and acceleration systems, the instant centres");
  sub->add_option("MODEL", command->model, "model file (YAML or JSON)")->required();
  command->flags = std::make_unique<RequestFlags>(*sub, request::ExplainRequest::rules());
  command->flags->add({"step", "steps", "max_steps", "format", "simulate", "at", "dt", "rtol", "at_toggle"});
  sub->add_option("-o,--output", command->output, "write to FILE instead of standard output")
      ->check(nbar::cli::output_file());
  sub->add_option("--draw", command->draw, "also draw the pose with its instant centres marked: FILE.svg or FILE.png");
  return {sub, [command] { return run_explain(*command); }};
}

}  // namespace nbar::cli
