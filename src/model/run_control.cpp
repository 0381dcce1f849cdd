#include "nbar/model/run_control.hpp"

namespace nbar {

CancelToken::CancelToken() : shared_(std::make_shared<Shared>()) {}

void CancelToken::cancel() const { shared_->flag.store(true, std::memory_order_relaxed); }

void CancelToken::set_deadline(Clock::time_point deadline) { shared_->deadline = deadline; }

void CancelToken::set_time_budget(std::chrono::duration<double> budget) {
  // A budget the clock cannot count to (an infinite one, or 1e12 s: the clock's nanoseconds
  // overflow past about 292 years) is no deadline at all; converted, it would wrap into the past
  // and stop the run at once. Half the room left keeps the conversion's rounding clear of it.
  const Clock::time_point now = Clock::now();
  const std::chrono::duration<double> room = Clock::time_point::max() - now;
  if (!(budget < 0.5 * room)) {
    shared_->deadline.reset();
    return;
  }
  set_deadline(now + std::chrono::duration_cast<Clock::duration>(budget));
}

bool CancelToken::deadline_passed() const { return shared_->deadline && Clock::now() >= *shared_->deadline; }

bool CancelToken::cancelled() const { return shared_->flag.load(std::memory_order_relaxed) || deadline_passed(); }

bool RunControl::should_stop(const char* stage, long done, long total) const {
  if (token.cancelled()) return true;
  return on_progress && !on_progress(Progress{stage, done, total});
}

void RunControl::checkpoint(const char* stage, long done, long total) const {
  if (should_stop(stage, done, total)) throw_stopped(stage);
}

void RunControl::throw_stopped(const char* stage) const {
  throw Error(ErrorKind::Cancelled, token.deadline_passed()
                                        ? std::string("stopped: the time budget ran out during the ") + stage
                                        : std::string("cancelled during the ") + stage);
}

}  // namespace nbar
