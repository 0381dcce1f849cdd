// The commands, each in its own file. Each adds its subcommand and options to the app and
// returns the subcommand with the function that runs it (returning the exit code).
#pragma once

#include "command_line.hpp"

#include <functional>
#include <utility>
#include <vector>

namespace nbar::cli {

using Command = std::pair<Subcommand*, std::function<int()>>;
using AddCommand = Command (*)(CommandLine&);

Command add_check_command(CommandLine& app);        // cmd_check.cpp
Command add_solve_command(CommandLine& app);        // cmd_solve.cpp
Command add_simulate_command(CommandLine& app);     // cmd_simulate.cpp
Command add_equilibrium_command(CommandLine& app);  // cmd_equilibrium.cpp
Command add_stress_command(CommandLine& app);       // cmd_stress.cpp
Command add_draw_command(CommandLine& app);         // cmd_draw.cpp
Command add_plot_command(CommandLine& app);         // cmd_plot.cpp
Command add_animate_command(CommandLine& app);      // cmd_animate.cpp
Command add_report_command(CommandLine& app);       // cmd_report.cpp
Command add_synth_command(CommandLine& app);        // cmd_synth.cpp
Command add_explain_command(CommandLine& app);      // cmd_explain.cpp
Command add_serve_command(CommandLine& app);        // cmd_serve.cpp
Command add_export_command(CommandLine& app);       // cmd_export.cpp
Command add_import_command(CommandLine& app);       // cmd_import.cpp

// In the order they appear in --help.
inline std::vector<AddCommand> all_commands() {
  return {&add_check_command,  &add_solve_command, &add_simulate_command, &add_equilibrium_command,
          &add_stress_command, &add_draw_command,  &add_plot_command,     &add_animate_command,
          &add_report_command, &add_synth_command, &add_explain_command,  &add_export_command,
          &add_import_command, &add_serve_command};
}

}  // namespace nbar::cli
