// A simulation run by a command (simulate, and animate and report with --simulate): its progress
// on a terminal, its errors at their place in the model file, and the exit code of a run that
// stopped early, said once for every command.
#pragma once

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <iostream>
#include <string>

#include "common.hpp"
#include "nbar/dynamics/forward_dynamics.hpp"
#include "nbar/request/requests.hpp"
#include "request_flags.hpp"

namespace nbar::cli {

// "simulate [######      ] 120/300 rows" on standard error while the run goes, only when it is a
// terminal (a pipe or a file gets nothing), cleared when the run ends.
class SimulationProgress {
 public:
  SimulationProgress() : enabled_(::isatty(STDERR_FILENO) == 1) {}
  SimulationProgress(const SimulationProgress&) = delete;
  SimulationProgress& operator=(const SimulationProgress&) = delete;
  ~SimulationProgress() { clear(); }
  void update(long done, long total) {
    if (!enabled_ || total <= 0) return;
    constexpr long kWidth = 30;
    const long filled = kWidth * std::min(done, total) / total;
    if (filled == last_filled_) return;
    last_filled_ = filled;
    std::cerr << fmt::format("\rsimulate [{}{}] {}/{} rows", std::string(static_cast<std::size_t>(filled), '#'),
                             std::string(static_cast<std::size_t>(kWidth - filled), ' '), done, total)
              << std::flush;
    shown_ = true;
  }
  void clear() {
    if (shown_) std::cerr << '\r' << std::string(70, ' ') << '\r' << std::flush;
    shown_ = false;
    last_filled_ = -1;
  }

 private:
  bool enabled_;
  bool shown_ = false;
  long last_filled_ = -1;
};

// Runs the simulation the request asks for; the exit code says what went wrong (0 when it ran,
// even if it stopped early: finish_simulation says so after the rows are written).
inline int simulate_model(const std::string& path, const Loaded& loaded, const request::SimulateRequest& request,
                          Simulation& out) {
  SimulationProgress progress;
  RunControl control;
  control.on_progress = [&progress](const Progress& p) {
    progress.update(p.done, p.total);
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
