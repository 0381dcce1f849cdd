// Stopping long computations from outside: a shared cancellation flag with an optional deadline,
// and a progress callback that may ask to stop. Sweeps, stresses and synthesis call
// RunControl::checkpoint between units of work; it throws Error(ErrorKind::Cancelled). The web
// server gives each request a deadline; Python maps Ctrl-C to cancel().
#pragma once

#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "nbar/model/diagnostics.hpp"

namespace nbar {

class CancelToken {
 public:
  using Clock = std::chrono::steady_clock;

  CancelToken();
  // Copies share one flag: cancelling any copy cancels them all. Thread-safe.
  void cancel() const;
  void set_deadline(Clock::time_point deadline);
  // After `budget` from now.
  void set_time_budget(std::chrono::duration<double> budget);
  bool cancelled() const;  // cancel() was called or the deadline has passed
  bool deadline_passed() const;

 private:
  struct Shared {
    std::atomic<bool> flag{false};
    std::optional<Clock::time_point> deadline;
  };
  std::shared_ptr<Shared> shared_;
};

struct Progress {
  const char* stage = "";  // "sweep", "dynamics", "stress", "paths", "checking"
  long done = 0;
  long total = 0;
};

struct RunControl {
  CancelToken token;
  // Called at checkpoints; returning false stops the run (Error of kind Cancelled). May be
  // called from worker threads (synthesis paths), so it must be thread-safe there.
  std::function<bool(const Progress&)> on_progress;

  // Throws Error(ErrorKind::Cancelled) when the token is cancelled, its deadline has passed or
  // on_progress returns false.
  void checkpoint(const char* stage, long done, long total) const;
  // The same test without throwing.
  bool should_stop(const char* stage, long done, long total) const;
  // The error checkpoint throws, for a caller that saw should_stop() and cleaned up first (it
  // must not ask again: on_progress may answer differently the second time).
  [[noreturn]] void throw_stopped(const char* stage) const;
};

}  // namespace nbar
