// A simulation run by a command (simulate, and animate and report with --simulate): its progress
// on a terminal, its errors at their place in the model file, and the exit code of a run that
// stopped early, said once for every command.
#pragma once

#include <iostream>
#include <string>

#include "common.hpp"
#include "nbar/dynamics/forward_dynamics.hpp"
#include "nbar/request/requests.hpp"
#include "request_flags.hpp"
#include "terminal_progress.hpp"

namespace nbar::cli {

// Runs the simulation the request asks for; the exit code says what went wrong (0 when it ran,
// even if it stopped early: finish_simulation says so after the rows are written).
inline int simulate_model(const std::string& path, const Loaded& loaded, const request::SimulateRequest& request,
                          Simulation& out) {
  TerminalProgress progress;
  RunControl control;
  control.on_progress = [&progress](const Progress& p) {
    progress.update(static_cast<int>(p.done), static_cast<int>(p.total), "simulate");
    return true;
  };
  SimulationOptions options;
  try {
    options = request.simulation_options(*loaded.mechanism);
  } catch (const request::OptionError& e) {  // no --to, and none in the model: as a flag's problem
    std::cerr << e.spelled(spell_flag) << "\nRun with --help for more information.\n";
    return kBadUsage;
  } catch (const Error& e) {
    return fail(path, io::located(loaded.file.source, e));
  }
  try {
    out = simulate(*loaded.mechanism, options, control);
  } catch (const Error& e) {
    progress.clear();
    return fail(path, io::located(loaded.file.source, e));
  }
  progress.clear();
  print_warnings(out.warnings);
  return kOk;
}

// After the rows (or the frames, or the page) are written: a run that stopped early is said at
// the entity concerned, exit code 4.
inline int finish_simulation(const std::string& path, const Loaded& loaded, const Simulation& simulation) {
  if (simulation.complete) return kOk;
  const Error stop(ErrorKind::StoppedAtLimit, "the simulation stopped early: " + simulation.stop_reason,
                   simulation.stop_where);
  fail(path, io::located(loaded.file.source, stop));
  return kStoppedEarly;
}

}  // namespace nbar::cli
