// nbar: the command-line front-end. It only translates between the terminal and the core.
//
// Exit codes: 0 success; 1 invalid model; 2 bad usage; 3 cannot assemble at the start;
// 4 sweep stopped early (the rows solved so far are written).
#include <algorithm>
#include <iostream>
#include <new>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "common.hpp"
#include "io/yaml_support.hpp"
#include "language.hpp"
#include "nbar/version.hpp"

int main(int argc, char** argv) {
  using namespace nbar::cli;
  CommandLine app{"nbar: analysis of planar linkages (n-bar mechanisms)"};
  app.set_version_flag("--version", std::string("nbar ") + nbar::kVersion);
  app.require_subcommand(1);
  app.footer(
      "Exit codes: 0 success, 1 invalid model, 2 bad usage, 3 cannot assemble at the start,\n"
      "            4 sweep stopped early (the rows solved so far are written), 5 stopped by synth --timeout.\n"
      "Limits: a sweep has at most 10000000 samples (--max-steps of every command that sweeps), model files at most\n"
      "        16 MB, names at most 256 characters, models at most 20000 moving points.\n"
      "Model files: see docs/model-format.md.");

  std::vector<nbar::cli::Command> commands;
  for (const auto& add : nbar::cli::all_commands()) commands.push_back(add(app));

  // A first argument that is neither an option nor a command: say so, with the nearest command
  // (CLI11 alone says only that a subcommand is required).
  const std::vector<std::string> names = app.subcommand_names();
  if (argc > 1 && argv[1][0] != '-' && std::find(names.begin(), names.end(), argv[1]) == names.end()) {
    const auto close = nbar::io::yaml::suggestion(argv[1], names);
    std::cerr << "error: '" << argv[1] << "' is not an nbar command (the commands are: " << join(names) << ")"
              << (close ? "; did you mean '" + *close + "'?" : std::string()) << "\n";
    return kBadUsage;
  }
  if (const std::optional<int> code = app.parse(argc, argv)) {
    // --help and --version write to standard output: a full disk or a closed pipe is a failure
    // to report, as every command reports it.
    if (*code == 0) return Output().finish() ? kOk : kBadUsage;
    return kBadUsage;
  }
  if (!choose_language(app.language_given())) return kBadUsage;
  // Each command reports what it expects; anything else still ends in a message and an exit
  // code, never an abort.
  try {
    for (const auto& [command, run] : commands)
      if (command->parsed()) return run();
  } catch (const nbar::Error& e) {
    return fail("", e);
  } catch (const std::bad_alloc&) {
    // Within the limits a run can still outgrow the machine: every sample is kept.
    std::cerr << "error: out of memory: ask for fewer steps (--steps) or a smaller model\n";
    return kBadUsage;
  } catch (const std::exception& e) {
    // A last resort: the library throws nbar::Error only, so this is a defect to report.
    std::cerr << "error: internal error: " << e.what() << " (please report it)\n";
    return kBadUsage;
  }
  return kBadUsage;
}
