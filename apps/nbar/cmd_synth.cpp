// nbar synth: four-bars from a task file (five-point and nine-point path generation, Burmester motion
// generation, Freudenstein function generation), checked with the kinematics engine, ranked,
// printed as a table or JSON and exported as model files. docs/synthesis.md. The work is the
// library's (synthesis/run.hpp, io/synthesis_writer.hpp); this file reads options and prints.
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <optional>

#include <mutex>

#include "commands.hpp"
#include "common.hpp"
#include "io/yaml_support.hpp"
#include "nbar/io/synthesis_task.hpp"
#include "nbar/request/synthesis_request.hpp"
#include "request_flags.hpp"
#include "terminal_progress.hpp"
#include "validators.hpp"

namespace nbar::cli {

namespace {

using io::SynthesisKind;
using io::SynthesisTask;

// A task key given as an option instead of in a file: --input-range 90,150.
struct TaskOption {
  const char* key;   // in the task file
  const char* flag;  // on the command line
  const char* help;
  std::string value;
};

struct SynthArgs {
  std::string kind, file, output, export_dir, curves;
  std::optional<double> timeout;
  std::vector<TaskOption> task_options{
      {"name", "--name", "the task's title (names the exported models)", {}},
      {"units", "--units", "e.g. '{length: mm, angle: deg}'", {}},
      {"pivots", "--pivots", "five-point: the fixed pivots, e.g. '{a: [0, 0], b: [1, 0]}'", {}},
      {"points",
       "--points",
       "five-point: the 5 points '[[x, y], ...]'; nine-point: the 9 points; path: 10 or more; function: the number "
       "of precision points",
       {}},
      {"curve", "--curve-csv", "path: a CSV file of the target points (x, y a line)", {}},
      {"constraints", "--constraints", "path: e.g. '{crank: true, min_transmission: 30, lengths: [10, 200]}'", {}},
      {"nine_point_starts",
       "--nine-point-starts",
       "path: subsets of nine targets solved for starting designs (slow)",
       {}},
      {"poses", "--poses", "burmester: '[{point: [x, y], angle: a}, ...]'", {}},
      {"fixed_pivots", "--fixed-pivots", "burmester, 3 poses: '{a: [x, y], b: [x, y]}'", {}},
      {"moving_pivots", "--moving-pivots", "burmester, 3 poses: '{a: [x, y], b: [x, y]}'", {}},
      {"curves", "--window", "burmester, 4 poses: where the curves are traced, '{radius: R, step: S}'", {}},
      {"samples", "--samples", "burmester, 4 poses: dyads taken along the curves", {}},
      {"function", "--function", "function: y = f(x), e.g. 'log10(x)'", {}},
      {"x", "--x", "function: the range of x, e.g. 1,2", {}},
      {"input_range", "--input-range", "function: input angles at the ends of the range, e.g. 90,150", {}},
      {"output_range", "--output-range", "function: output angles at f of the ends, e.g. 60,120", {}},
      {"spacing", "--spacing", "function: chebyshev or even", {}},
      {"frame", "--frame", "function: length of the frame link", {}},
  };
  std::unique_ptr<RequestFlags> flags;  // the request's options: format, all, top, threads, seed
};

// The method named on the command line (CLI11 has checked it is one of them).
SynthesisKind kind_named(const std::string& name) {
  for (const SynthesisKind kind : {SynthesisKind::FivePoint, SynthesisKind::Burmester, SynthesisKind::Function,
                                   SynthesisKind::NinePoint, SynthesisKind::Path})
    if (io::to_string(kind) == name) return kind;
  throw Error(ErrorKind::BadInput, "no synthesis method '" + name + "'");
}

// The task options as a task file, one key a line, so that the file's checks and messages
// serve them too: a message about line k is about the option of that line.
class OptionTask {
 public:
  explicit OptionTask(const SynthArgs& args) {
    text_ = "task: " + args.kind + "\n";
    for (const TaskOption& o : args.task_options) {
      if (o.value.empty()) continue;
      std::string value = o.value;
      // Where the option's own text starts on its line (1-based), or 0 when it was quoted
      // (its characters shift where it holds quotes or backslashes).
      int first = static_cast<int>(std::string(o.key).size()) + 3;
      // Text that is not UTF-8 is left as it is: the task reader reports it at this option's line.
      if ((std::string(o.key) == "function" || std::string(o.key) == "name") && !io::yaml::first_invalid_utf8(value)) {
        value = nlohmann::json(value).dump();  // a quoted YAML string
        first = 0;
      } else if (value.find(',') != std::string::npos && value.front() != '[' && value.front() != '{') {
        value = "[" + value + "]";  // 1,2 for [1, 2]
        ++first;
      }
      lines_.push_back({&o, first});
      text_ += std::string(o.key) + ": " + value + "\n";
    }
  }
  bool empty() const { return lines_.empty(); }
  // --curve-csv names the user's own file, read from the current directory.
  SynthesisTask parse() const { return io::parse_synthesis_task(text_, kFile, io::CurveFiles::read); }
  // "--points: message", "--points at character 9: message" when the problem is inside the
  // option's text (as a file's line:column), or the message when it concerns no single option.
  std::string explain(const Error& e) const {
    const int line = e.mark().line;
    if (e.file() != kFile) return e.what();
    if (line < 2 || line - 2 >= static_cast<int>(lines_.size())) return "task options: " + e.message();
    const Line& l = lines_[line - 2];
    const int character = l.first > 0 ? e.mark().column - l.first + 1 : 0;
    if (character > 1 && character <= static_cast<int>(l.option->value.size()))
      return std::string(l.option->flag) + " at character " + std::to_string(character) + ": " + e.message();
    return std::string(l.option->flag) + ": " + e.message();
  }

 private:
  static constexpr const char* kFile = "<options>";
  struct Line {
    const TaskOption* option;
    int first;  // the column of the option's first character, 0 when unknown
  };
  std::string text_;
  std::vector<Line> lines_;
};

// An option's value becomes one line of the task text: a line break (or another control
// character) in it would add keys of its own, so it is refused, naming the option.
bool options_are_one_line(const SynthArgs& args) {
  for (const TaskOption& o : args.task_options) {
    const auto control = std::find_if(o.value.begin(), o.value.end(),
                                      [](char c) { return static_cast<unsigned char>(c) < 0x20 && c != '\t'; });
    if (control == o.value.end()) continue;
    std::cerr << "error: " << o.flag << ": the value holds a line break or another control character (at character "
              << (control - o.value.begin()) + 1 << "); give it on one line\n";
    return false;
  }
  return true;
}

int run_synth(const SynthArgs& args) {
  request::SynthesisRequest request;
  try {
    request = request::SynthesisRequest::read(kind_named(args.kind), args.flags->options());
  } catch (const request::OptionError& e) {
    std::cerr << e.spelled(spell_flag) << "\nRun with --help for more information.\n";
    return kBadUsage;
  }
  if (!options_are_one_line(args)) return kBadUsage;
  const OptionTask options(args);
  if (!options.empty() && !args.file.empty()) {
    std::cerr << "error: give a task file or task options (--points, --poses, --function...), not both\n";
    return kBadUsage;
  }
  if (options.empty() && args.file.empty()) {
    std::cerr << "error: nbar synth " << args.kind << " needs a task file (or task options); see docs/synthesis.md\n";
    return kBadUsage;
  }
  // Problems in a file are an invalid model (1); in options, bad usage (2).
  const int bad_task = options.empty() ? kInvalidModel : kBadUsage;
  SynthesisTask task;
  try {
    task = options.empty() ? io::load_synthesis_task(args.file) : options.parse();
  } catch (const Error& e) {
    std::cerr << "error: " << options.explain(e) << '\n';
    return bad_task;
  }
  if (io::to_string(task.kind) != args.kind) {
    std::cerr << "error: " << args.file << ": this is a " << io::to_string(task.kind) << " task: run `nbar synth "
              << io::to_string(task.kind) << " " << args.file << "`\n";
    return kBadUsage;
  }
  if (!args.curves.empty() && !(task.kind == SynthesisKind::Burmester && task.poses.size() == 4)) {
    std::cerr << "error: --curves applies to burmester tasks with 4 poses\n";
    return kBadUsage;
  }
  TerminalProgress progress;
  synthesis::SynthesisRunOptions run = request.run_options();
  if (args.timeout) run.control.token.set_time_budget(std::chrono::duration<double>(*args.timeout));
  run.control.on_progress = [&progress](const nbar::Progress& p) {
    progress.update(static_cast<int>(p.done), static_cast<int>(p.total), p.stage);
    return true;
  };
  synthesis::SynthesisOutcome outcome;
  io::SynthesisListing listing;
  try {
    outcome = synthesis::run_synthesis(task, run);
    progress.clear();
    if (outcome.curves && !args.curves.empty()) io::write_burmester_curves(args.curves, task, *outcome.curves);
    listing = request.listing(outcome, args.export_dir);
    Output output;
    if (!output.open(args.output)) return kBadUsage;
    if (request.format == "json") output.json_answer();
    if (!args.export_dir.empty()) io::export_designs(task, outcome, listing);
    output.stream() << request.answer(task, outcome, listing);
    if (!output.finish()) return kBadUsage;
  } catch (const Error& e) {
    progress.clear();
    if (e.kind() == ErrorKind::InvalidModel) {  // the solvers' complaints about the task itself
      std::cerr << "error: " << options.explain(e) << '\n';
      return bad_task;
    }
    std::cerr << "error: " << say(e.message()) << '\n';
    return exit_code(e.kind());
  }
  return kOk;
}

}  // namespace

Command add_synth_command(CommandLine& app) {
  static SynthArgs args;
  Subcommand* synth = app.add_subcommand(
      "synth",
      "Synthesise four-bars from a task file: five-point and nine-point path generation, Burmester motion "
      "generation, function generation or a best fit through many path points; every real solution is checked for "
      "defects and ranked");
  synth->add_option("TASK", args.kind, "five-point, nine-point, burmester, function or path")
      ->required()
      ->check(one_of({"five-point", "nine-point", "burmester", "function", "path"}));
  synth->add_option("FILE", args.file, "task file (YAML; see docs/synthesis.md), or the task options below");
  // Every method's options; one a method does not take is refused by its request.
  args.flags = std::make_unique<RequestFlags>(*synth, request::SynthesisRequest::rules(SynthesisKind::FivePoint));
  args.flags->add({"format"});
  synth->add_option("-o,--output", args.output, "write the table or JSON to FILE instead of standard output")
      ->check(nbar::cli::output_file());
  synth->add_option("--export", args.export_dir, "write every design listed as DIR/design-01.yaml, ... (model files)");
  args.flags->add({"all", "top", "threads"});
  synth
      ->add_option("--timeout", args.timeout,
                   "give up after SECONDS, exit 5 (a nine-point task on a conic or with five points on a line can "
                   "take minutes)")
      ->check(nbar::cli::positive());
  args.flags->add({"seed"});
  synth->add_option("--curves", args.curves,
                    "burmester, 4 poses: write the centre- and circle-point curves to FILE (.csv, .json or .svg)");
  for (TaskOption& o : args.task_options) synth->add_option(o.flag, o.value, o.help)->group("Task (instead of a file)");
  return {synth, [] { return run_synth(args); }};
}

}  // namespace nbar::cli
