// The web server's JSON API, without any transport: a request (method, path, body) in, a
// response (status, content type, body) out. The HTTP layer (server.hpp) only routes bytes to
// handle_api; the tests call it directly. It is a front-end like the CLI: it parses the request,
// calls the library and writes the answer with the library's own writers (docs/web-api.md).
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "nbar/model/run_control.hpp"

namespace nbar::web {

// What one request may ask for. Requests over a limit are answered 413 (kind "limit_exceeded",
// with the limit's name and value); see docs/web-api.md.
struct Limits {
  std::size_t max_body_bytes = 1 << 20;  // 1 MiB
  int max_points = 2000;                 // points of a model
  int max_bodies = 1000;                 // bodies of a model
  int max_steps = 100001;                // samples of a sweep (the model's or `steps`)
  double max_table_values = 5e6;         // solve and plot: samples x columns of the table
  int max_sections = 2000;               // stress: cross-sections per link
  int max_fe_nodes = 50000;              // stress by finite elements: nodes of a link's mesh
  int max_explain_points = 200;          // explain: points of the model (Phi_q is written whole)
  int max_explain_bodies = 100;          // explain: bodies (every pair's instant centre)
  int max_frames = 360;                  // animations and reports
  int max_pixels = 2048;                 // width and height of a picture, each
  double max_animation_pixels = 250e6;   // frames x width x height of an animation
  int max_synthesis_top = 200;           // synthesis: designs listed
  unsigned max_synthesis_threads = 2;    // synthesis: path-tracking threads per request
  double max_curve_samples = 3000;       // burmester, 4 poses: curves.radius / curves.step
  double time_budget_seconds = 30;       // wall time of one request's computation
};

// A cap on the computations running at once: a counting semaphore whose waiters are served in
// the order they came, each for at most its own wait, and at most `max_waiting` of them.
class JobSlots {
 public:
  explicit JobSlots(int slots, int max_waiting = 256) : free_(slots), total_(slots), max_waiting_(max_waiting) {}
  // Holds a slot until destroyed.
  class Slot {
   public:
    Slot() = default;
    explicit Slot(JobSlots* owner) : owner_(owner) {}
    Slot(Slot&& other) noexcept : owner_(std::exchange(other.owner_, nullptr)) {}
    Slot& operator=(Slot&& other) noexcept {
      if (this != &other) {
        release();
        owner_ = std::exchange(other.owner_, nullptr);
      }
      return *this;
    }
    Slot(const Slot&) = delete;
    Slot& operator=(const Slot&) = delete;
    ~Slot() { release(); }
    explicit operator bool() const { return owner_ != nullptr; }

   private:
    void release() {
      if (owner_) owner_->give_back();
      owner_ = nullptr;
    }
    JobSlots* owner_ = nullptr;
  };
  // A held slot, or an empty one when all are taken (or others are waiting for one).
  Slot try_acquire() { return acquire(std::chrono::duration<double>(0)); }
  // A held slot as soon as one is free and every earlier waiter has had one; an empty one when
  // none came within `max_wait` or `max_waiting` requests are already waiting.
  Slot acquire(std::chrono::duration<double> max_wait);
  int in_use() const;
  int waiting() const;
  int total() const { return total_; }

 private:
  void give_back();
  mutable std::mutex mutex_;
  std::condition_variable freed_;
  std::deque<std::uint64_t> queue_;  // tickets of the waiters, first come first
  std::uint64_t next_ticket_ = 0;
  int free_;
  const int total_;
  const int max_waiting_;
};

struct ServerConfig {
  Limits limits;
  // Shared by every request of one server. Heavy computations (synthesis, stresses, reports,
  // animations, sweeps whose table is over `light_table_values`) take a slot of `jobs`; light
  // ones (checks, explanations, drawings, small solves and plots) one of `light_jobs`, so that
  // a class's quick solves never queue behind a synthesis. A computation waits for its slot at
  // most `queue_wait_seconds`, then it is answered 503 with Retry-After.
  std::shared_ptr<JobSlots> jobs = std::make_shared<JobSlots>(2);
  std::shared_ptr<JobSlots> light_jobs = std::make_shared<JobSlots>(2);
  double light_table_values = 50000;  // samples x columns of a light sweep
  double queue_wait_seconds = 10;
  int retry_after_seconds = 2;  // the Retry-After of a 503
  // Called at every checkpoint of a request's computation (sweep samples, stages, synthesis
  // paths, animation frames, report sections, the explanation's parts); returning false stops
  // it as a passed deadline does (504). For tests; empty in `nbar serve`.
  std::function<bool(const Progress&)> on_progress;
};

struct ApiRequest {
  std::string method;  // "GET", "POST", ...
  std::string path;    // decoded, without the query: "/api/solve"
  std::string body;
  // The HTTP Accept-Language header, if any: the answer's messages are in its first language
  // that nbar speaks, unless the body's "lang" says another (docs/web-api.md).
  std::string accept_language = {};
};

struct ApiResponse {
  int status = 200;
  std::string content_type = "application/json";
  std::string body;
  std::vector<std::pair<std::string, std::string>> headers;  // extra headers (Retry-After...)
};

// Every endpoint: /api/... as docs/web-api.md says, and the embedded static files at other
// paths. Never throws.
ApiResponse handle_api(const ApiRequest& request, const ServerConfig& config);

// The error answer for a status the HTTP layer decides itself (a body over the limit before it
// is read, a malformed request): {"error": {"kind": ..., "message": ...}}.
ApiResponse error_response(int status, const std::string& message);
// The 413 of a body over `max_body_bytes` as handle_api answers it, with the limit's name and value.
ApiResponse body_too_large_response(const std::string& message, std::size_t max_body_bytes);
// The 503 of an answer refused because the server already holds `max_bytes` of answers that
// their clients have not read (limit "held_answers"), with Retry-After.
ApiResponse held_answers_response(const std::string& message, std::size_t max_bytes, int retry_after_seconds);

}  // namespace nbar::web
