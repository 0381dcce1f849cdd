// The commands, each in its own file. Each adds its subcommand and options to the app and
// returns the subcommand with the function that runs it (returning the exit code).
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <utility>
#include <vector>

namespace nbar::cli {

using Command = std::pair<CLI::App*, std::function<int()>>;
using AddCommand = Command (*)(CLI::App&);

Command add_check_command(CLI::App& app);        // cmd_check.cpp
Command add_solve_command(CLI::App& app);        // cmd_solve.cpp
Command add_simulate_command(CLI::App& app);     // cmd_simulate.cpp
Command add_equilibrium_command(CLI::App& app);  // cmd_equilibrium.cpp
Command add_stress_command(CLI::App& app);       // cmd_stress.cpp
Command add_draw_command(CLI::App& app);         // cmd_draw.cpp
Command add_plot_command(CLI::App& app);         // cmd_plot.cpp
Command add_animate_command(CLI::App& app);      // cmd_animate.cpp
Command add_report_command(CLI::App& app);       // cmd_report.cpp
Command add_synth_command(CLI::App& app);        // cmd_synth.cpp
Command add_explain_command(CLI::App& app);      // cmd_explain.cpp
Command add_serve_command(CLI::App& app);        // cmd_serve.cpp
Command add_export_command(CLI::App& app);       // cmd_export.cpp
Command add_import_command(CLI::App& app);       // cmd_import.cpp

// In the order they appear in --help.
inline std::vector<AddCommand> all_commands() {
  return {&add_check_command,  &add_solve_command, &add_simulate_command, &add_equilibrium_command,
          &add_stress_command, &add_draw_command,  &add_plot_command,     &add_animate_command,
          &add_report_command, &add_synth_command, &add_explain_command,  &add_export_command,
          &add_import_command, &add_serve_command};
}

}  // namespace nbar::cli
