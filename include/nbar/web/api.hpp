// The web server's JSON API, without any transport: a request (method, path, body) in, a
// response (status, content type, body) out. The HTTP layer (server.hpp) only routes bytes to
// handle_api; the tests call it directly. It is a front-end like the CLI: it parses the request,
// calls the library and writes the answer with the library's own writers (docs/web-api.md).
#pragma once

#include <atomic>
#include <cstddef>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

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

// A cap on the computations running at once: a counting semaphore that never waits.
class JobSlots {
 public:
  explicit JobSlots(int slots) : free_(slots), total_(slots) {}
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
  // A held slot, or an empty one when all are taken.
  Slot try_acquire() {
    const std::lock_guard lock(mutex_);
    if (free_ <= 0) return Slot();
    --free_;
    return Slot(this);
  }
  int in_use() const {
    const std::lock_guard lock(mutex_);
    return total_ - free_;
  }
  int total() const { return total_; }

 private:
  void give_back() {
    const std::lock_guard lock(mutex_);
    ++free_;
  }
  mutable std::mutex mutex_;
  int free_;
  const int total_;
};

struct ServerConfig {
  Limits limits;
  // Shared by every request of one server; computations over the cap are answered 503.
  std::shared_ptr<JobSlots> jobs = std::make_shared<JobSlots>(2);
  int retry_after_seconds = 2;  // the Retry-After of a 503
};

struct ApiRequest {
  std::string method;  // "GET", "POST", ...
  std::string path;    // decoded, without the query: "/api/solve"
  std::string body;
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

}  // namespace nbar::web
