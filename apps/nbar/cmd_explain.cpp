// nbar explain: the method, step by step, at one sample of the sweep (Gruebler count, q, Phi,
// Phi_q, Newton's iterations, the velocity and acceleration systems, the instant centres), as
// text, Markdown, LaTeX or JSON, and optionally a drawing with the instant centres marked.

#include "commands.hpp"
#include "common.hpp"
#include "nbar/analysis/explain.hpp"
#include "nbar/io/json_text.hpp"
#include "nbar/io/explain_writer.hpp"
#include "nbar/render/pictures.hpp"
#include "validators.hpp"

namespace nbar::cli {

namespace {

struct ExplainArgs {
  std::string model, output, format = "text", draw;
  int step = 0;
  std::optional<int> steps;
  int max_steps = nbar::kDefaultMaxSweepSamples;
};

std::string extension(const std::string& path) {
  const auto dot = path.rfind('.');
  return dot == std::string::npos ? "" : path.substr(dot + 1);
}

// The pose with its finite instant centres marked.
int draw_centres(const ExplainArgs& args, const Explanation& ex) {
  int off_picture = 0;
  try {
    const bool written = extension(args.draw) == "svg"
                             ? write_file(args.draw, render::instant_centres_svg(ex, &off_picture))
                             : write_file(args.draw, render::instant_centres_png(ex, &off_picture));
    if (!written) return kBadUsage;
  } catch (const std::runtime_error& e) {
    std::cerr << "error: " << e.what() << '\n';
    return kBadUsage;
  }
  if (off_picture > 0)
    std::cerr << "note: --draw: " << off_picture << " instant centre" << (off_picture == 1 ? " lies" : "s lie")
              << " too far from the mechanism to draw\n";
  return kOk;
}

int run_explain(const ExplainArgs& args) {
  if (!args.draw.empty() && extension(args.draw) != "svg" && extension(args.draw) != "png") {
    std::cerr << "error: --draw " << args.draw << ": the picture's format comes from its extension: .svg or .png\n";
    return kBadUsage;
  }
  Loaded loaded;
  if (int code = load(args.model, loaded)) return code;
  ExplainOptions options;
  options.step = args.step;
  options.steps = args.steps;
  options.max_steps = args.max_steps;
  Explanation ex;
  try {
    ex = explain(loaded.mechanism, options);
  } catch (const Error& e) {
    return fail(args.model, e);
  }
  Output output;
  if (!output.open(args.output)) return kBadUsage;
  std::ostream& out = output.stream();
  if (args.format == "json")
    out << io::json_text(io::explanation_json(ex), 2) << '\n';
  else
    out << render_explanation(ex, args.format == "markdown" ? ExplainFormat::Markdown
                                  : args.format == "latex"  ? ExplainFormat::Latex
                                                            : ExplainFormat::Text);
  if (!output.finish()) return kBadUsage;
  if (!args.draw.empty()) return draw_centres(args, ex);
  return kOk;
}

}  // namespace

Command add_explain_command(CLI::App& app) {
  auto args = std::make_shared<ExplainArgs>();
  CLI::App* sub = app.add_subcommand("explain", "The method step by step at one sample: Gruebler count, q, the "
                                                "constraint equations and their Jacobian, Newton's iterations, the "
                                                "velocity and acceleration systems, the instant centres");
  sub->add_option("MODEL", args->model, "model file (YAML or JSON)")->required();
  sub->add_option("--step", args->step, "the sample of the sweep to explain (default 0, the start)")
      ->check(nbar::cli::non_negative());
  sub->add_option("--steps", args->steps, "samples of the sweep, ends included (overrides the model's sweep)")
      ->check(nbar::cli::positive());
  sub->add_option("--max-steps", args->max_steps, kMaxStepsHelp)->check(nbar::cli::positive());
  sub->add_option("--format", args->format, "text (default), markdown (with LaTeX maths, for Jupyter), latex or json")
      ->check(CLI::IsMember({"text", "markdown", "latex", "json"}));
  sub->add_option("-o,--output", args->output, "write to FILE instead of standard output")
      ->check(nbar::cli::output_file());
  sub->add_option("--draw", args->draw, "also draw the pose with its instant centres marked: FILE.svg or FILE.png");
  return {sub, [args] { return run_explain(*args); }};
}

}  // namespace nbar::cli
