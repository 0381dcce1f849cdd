// A simulation run by a command (simulate, and animate and report with --simulate): its progress
// on a terminal, its errors at their place in the model file, and the exit code of a run that
// stopped early, said once for every command.
#pragma once

#include <atomic>
#include <csignal>
#include <iostream>
#include <string>

#include "common.hpp"
#include "nbar/dynamics/forward_dynamics.hpp"
#include "nbar/request/requests.hpp"
#include "request_flags.hpp"
#include "terminal_progress.hpp"

namespace nbar::cli {

// While a run lasts, Ctrl-C (SIGINT) cancels it instead of ending the program, so that the rows
// so far are written; a second Ctrl-C ends the program as usual (the handler resets itself).
class InterruptCancels {
 public:
  explicit InterruptCancels(const CancelToken& token) {
    sigaction(SIGINT, nullptr, &previous_);
    if (previous_.sa_handler == SIG_IGN) return;  // started ignoring it (nohup, a background job): keep that
    target_.store(&token);
    struct sigaction action {};
    action.sa_handler = on_interrupt;
    action.sa_flags = SA_RESETHAND;
    sigemptyset(&action.sa_mask);
    sigaction(SIGINT, &action, nullptr);
    installed_ = true;
  }
  ~InterruptCancels() {
    if (!installed_) return;
    sigaction(SIGINT, &previous_, nullptr);
    target_.store(nullptr);
  }
  InterruptCancels(const InterruptCancels&) = delete;
  InterruptCancels& operator=(const InterruptCancels&) = delete;

 private:
  static void on_interrupt(int) {
    if (const CancelToken* token = target_.load()) token->cancel();  // an atomic store: safe here
  }
  static inline std::atomic<const CancelToken*> target_{nullptr};
  struct sigaction previous_ {};
  bool installed_ = false;
};

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
    const InterruptCancels interrupt(control.token);
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
// the entity concerned, exit code 4; one cancelled (Ctrl-C) says where it got to, exit code 5.
inline int finish_simulation(const std::string& path, const Loaded& loaded, const Simulation& simulation) {
  if (simulation.complete) return kOk;
  if (simulation.cancelled) {  // by Ctrl-C: one line saying where, exit code 5
    const std::size_t rows = simulation.samples.size();
    return fail(path, Error(ErrorKind::Cancelled, "the simulation stopped early: " + simulation.stop_reason + "; the " +
                                                      std::to_string(rows) + (rows == 1 ? " row" : " rows") +
                                                      " up to there are written"));
  }
  const Error stop(ErrorKind::StoppedAtLimit, "the simulation stopped early: " + simulation.stop_reason,
                   simulation.stop_where);
  fail(path, io::located(loaded.file.source, stop));
  return kStoppedEarly;
}

}  // namespace nbar::cli
