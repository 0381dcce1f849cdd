// Jobs one thread hands to a second, done there one after another in the order given: a
// simulation's output rows made while its integration goes on (forward_dynamics.cpp). Without a
// second thread (one asked for, one core, WebAssembly without threads) each job is done at once
// on the caller's, by the same code, so the answers are the same either way.
//
// The caller fills the slot next_slot() gives and publishes it with submit(); drain() waits until
// every job published is done. The thread starts at the first job, or at start_early() (which a
// simulation calls before its start, so that the thread's creation overlaps with it). A job that
// throws stops the jobs after it (they are skipped) and its exception
// is thrown again to the caller by every later next_slot() or drain(): the caller sees it where a
// run on one thread would have, before anything it does after the job's rows.
//
// Waiting spins for a few microseconds before it sleeps: jobs come every few microseconds (a
// four-bar's steps), and a sleep and wake-up for each cost as much as the job; longer spins only
// took the core from another process (50 us made a four-bar's run a fifth slower than on one
// thread with a busy process beside it, 5 us as fast as one thread, and as fast as 50 us alone).
// The ring is deep so that where the two threads share a core with other processes, the caller
// can run ahead for a whole time slice (64 jobs kept it waiting for most of each).
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif
#if defined(__linux__) && !defined(__EMSCRIPTEN__)
#include <sched.h>
#endif

namespace nbar {

#if defined(__EMSCRIPTEN__) && !defined(__EMSCRIPTEN_PTHREADS__)
inline constexpr bool kSecondThreadPossible = false;
#else
inline constexpr bool kSecondThreadPossible = true;
#endif

// The cores this process may run on: those of its CPU affinity where the system says (taskset, a
// container's cpuset), which std::thread::hardware_concurrency() does not count.
inline unsigned usable_cores() {
#if defined(__linux__) && !defined(__EMSCRIPTEN__)
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof(set), &set) == 0) return static_cast<unsigned>(CPU_COUNT(&set));
#endif
  return std::thread::hardware_concurrency();
}

template <class Job>
class OrderedWorker {
 public:
  // `work` is called with each job, on the second thread when `threaded` (and the platform has
  // threads), else in submit(). `capacity`: jobs published and not yet done at most.
  OrderedWorker(std::function<void(Job&)> work, bool threaded, std::size_t capacity)
      : work_(std::move(work)), ring_(1), capacity_(capacity), start_wanted_(threaded && kSecondThreadPossible) {}
  OrderedWorker(const OrderedWorker&) = delete;
  OrderedWorker& operator=(const OrderedWorker&) = delete;
  ~OrderedWorker() {
    if (!thread_.joinable()) return;
    failed_ = true;  // the jobs still out are skipped: their answer is being thrown away
    stopping_ = true;
    wake();
    thread_.join();
  }

  // Starts the thread now rather than at the first job (where the caller would wait for its
  // creation), if it is to have one.
  void start_early() {
    if (start_wanted_) start();
  }

  bool threaded() const { return thread_.joinable(); }
  // Jobs published and not yet done (always 0 without the thread).
  std::size_t waiting() const { return threaded() ? submitted_.load() - done_.load() : 0; }

  // The slot for the next job, once there is room; throws a job's exception (see above).
  Job& next_slot() {
    if (start_wanted_) start();
    if (!threaded()) return ring_[0].job;
    if (failed_) drain();
    const std::size_t next = submitted_.load();
    wait_until([&] { return next - done_.load() < ring_.size(); });
    return ring_[next % ring_.size()].job;
  }

  // Publishes the slot next_slot() gave, filled.
  void submit() {
    if (!threaded()) {
      work_(ring_[0].job);
      return;
    }
    submitted_.store(submitted_.load() + 1);
    wake();
  }

  // Waits until every job published is done; throws the first exception one threw.
  void drain() {
    if (!threaded()) return;
    const std::size_t all = submitted_.load();
    wait_until([&] { return done_.load() == all; });
    if (failed_) {
      std::exception_ptr error;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        error = error_;
      }
      if (error) std::rethrow_exception(error);
    }
  }

 private:
  void start() {
    start_wanted_ = false;
    if constexpr (kSecondThreadPossible) {
      try {
        ring_ = std::vector<Slot>(std::max<std::size_t>(capacity_, 1));
        thread_ = std::thread([this] { serve(); });
      } catch (const std::system_error&) {
        ring_.resize(1);  // no thread to be had: the jobs are done on the caller's
      }
    }
  }

  void serve() {
    for (;;) {
      wait_until([&] { return done_.load() < submitted_.load() || stopping_.load(); });
      const std::size_t at = done_.load();
      if (at == submitted_.load()) return;  // stopping, nothing left
      if (!failed_) {
        try {
          work_(ring_[at % ring_.size()].job);
        } catch (...) {
          std::lock_guard<std::mutex> lock(mutex_);
          error_ = std::current_exception();
          failed_ = true;
        }
      }
      done_.store(at + 1);
      wake();
    }
  }

  // Spins, then sleeps, until `ready` holds. The counters are sequentially consistent: a waker
  // that sees no sleeper changed them before the sleeper's own check of `ready`.
  template <class Ready>
  void wait_until(const Ready& ready) {
    const auto spin_until = std::chrono::steady_clock::now() + std::chrono::microseconds(5);
    for (int i = 0; !ready(); ++i) {
      pause();
      if (i % 64 == 63 && std::chrono::steady_clock::now() > spin_until) {
        std::unique_lock<std::mutex> lock(mutex_);
        ++sleepers_;
        woken_.wait(lock, ready);
        --sleepers_;
        return;
      }
    }
  }
  void wake() {
    if (sleepers_.load() == 0) return;
    std::lock_guard<std::mutex> lock(mutex_);
    woken_.notify_all();
  }
  static void pause() {
#if defined(__x86_64__) || defined(__i386__)
    _mm_pause();
#else
    std::this_thread::yield();
#endif
  }

  // Each thread's writes on a cache line of their own: a line both write goes back and forth
  // between the cores at every job.
  struct alignas(64) Slot {
    Job job;
  };
  std::function<void(Job&)> work_;
  std::vector<Slot> ring_;  // one slot until the thread starts
  std::size_t capacity_ = 1;
  alignas(64) std::atomic<std::size_t> submitted_{0};  // written by the caller
  alignas(64) std::atomic<std::size_t> done_{0};       // written by the second thread
  std::atomic<bool> failed_{false};
  alignas(64) std::atomic<bool> stopping_{false};
  std::atomic<int> sleepers_{0};
  std::mutex mutex_;
  std::condition_variable woken_;
  std::exception_ptr error_;  // under mutex_
  bool start_wanted_ = false;
  std::thread thread_;
};

}  // namespace nbar
