// The job slots: a semaphore with a first-come-first-served queue and a bounded wait.
#include <algorithm>

#include "nbar/web/api.hpp"

namespace nbar::web {

JobSlots::Slot JobSlots::acquire(std::chrono::duration<double> max_wait) {
  std::unique_lock lock(mutex_);
  if (queue_.empty() && free_ > 0) {
    --free_;
    return Slot(this);
  }
  if (max_wait.count() <= 0 || static_cast<int>(queue_.size()) >= max_waiting_) return Slot();
  const std::uint64_t ticket = next_ticket_++;
  queue_.push_back(ticket);
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(max_wait);
  const bool served = freed_.wait_until(lock, deadline, [&] { return free_ > 0 && queue_.front() == ticket; });
  if (served) {
    queue_.pop_front();
    --free_;
    // The next waiter may find a slot too.
    if (free_ > 0 && !queue_.empty()) freed_.notify_all();
    return Slot(this);
  }
  queue_.erase(std::find(queue_.begin(), queue_.end(), ticket));
  // The waiter behind this one may now be first.
  freed_.notify_all();
  return Slot();
}

int JobSlots::in_use() const {
  const std::lock_guard lock(mutex_);
  return total_ - free_;
}

int JobSlots::waiting() const {
  const std::lock_guard lock(mutex_);
  return static_cast<int>(queue_.size());
}

void JobSlots::give_back() {
  {
    const std::lock_guard lock(mutex_);
    ++free_;
  }
  freed_.notify_all();
}

}  // namespace nbar::web
