// A command's progress as a bar on standard error ("synthesis  [#####     ] 120/300"), only when
// that is a terminal (a pipe or a file gets nothing), cleared when the work ends. Callbacks may come
// from worker threads (a synthesis tracks its paths on every core).
#pragma once

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <iostream>
#include <mutex>
#include <string>

namespace nbar::cli {

class TerminalProgress {
 public:
  TerminalProgress() : enabled_(::isatty(STDERR_FILENO) == 1) {}
  TerminalProgress(const TerminalProgress&) = delete;
  TerminalProgress& operator=(const TerminalProgress&) = delete;
  ~TerminalProgress() { clear(); }
  void update(int done, int total, const char* what) {
    if (!enabled_ || total <= 0) return;
    const std::lock_guard lock(mutex_);
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(static_cast<long>(kWidth) * std::min(done, total) / total);
    if (filled == last_filled_ && done != total) return;
    last_filled_ = filled;
    std::cerr << fmt::format("\r{:<10} [{}{}] {}/{}", what, std::string(filled, '#'), std::string(kWidth - filled, ' '),
                             done, total)
              << std::flush;
    shown_ = true;
  }
  void clear() {
    const std::lock_guard lock(mutex_);
    if (shown_) std::cerr << '\r' << std::string(70, ' ') << '\r' << std::flush;
    shown_ = false;
    last_filled_ = -1;
  }

 private:
  bool enabled_;
  bool shown_ = false;
  int last_filled_ = -1;
  std::mutex mutex_;
};

}  // namespace nbar::cli
