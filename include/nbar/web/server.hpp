// `nbar serve`: the JSON API (api.hpp) and the embedded static files over HTTP, with
// cpp-httplib. This layer only moves bytes: every answer comes from handle_api.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>

#include "nbar/web/api.hpp"

namespace nbar::web {

struct ServeOptions {
  std::string host = "127.0.0.1";  // only this machine unless told otherwise
  int port = 8080;                 // 0: any free port (bound_port() says which)
  int max_jobs = 2;                // heavy computations at once (ServerConfig::jobs)
  int light_jobs = 0;              // light computations at once; 0: one per core, at least 2
  double queue_wait_seconds = 10;  // a computation waits this long for a slot, then 503
  int threads = 256;               // requests served at once (each one holds a thread)
  int keep_alive_seconds = 5;      // an idle connection is closed after this
  // Slow and idle clients (web/server/connection_front.hpp): a request must arrive whole (its
  // header and body) within `request_read_seconds` of its first byte, else 408; a client address
  // keeps at most `max_connections_per_address` open (more are refused 503), and past
  // `max_connections` in all the one that has waited longest without a whole request is closed.
  double request_read_seconds = 10;
  int max_connections = 4096;  // at most the descriptors the process may open, less 64
  int max_connections_per_address = 256;
  // Answers written to clients that do not read them: each is held in memory until it is sent
  // or the write deadline (30 s) passes. Past these many bytes held in all, or from one client
  // address, a further answer over 64 KiB is refused 503 (limit "held_answers") instead of held;
  // a lone answer is never refused, whatever its size.
  std::size_t max_held_answer_bytes = std::size_t{512} << 20;
  std::size_t max_held_answer_bytes_per_address = std::size_t{192} << 20;
  Limits limits;
};

class HttpServer {
 public:
  explicit HttpServer(const ServeOptions& options);
  ~HttpServer();
  HttpServer(const HttpServer&) = delete;
  HttpServer& operator=(const HttpServer&) = delete;

  // Binds the socket; false (with a message in `error`) when it cannot.
  bool bind(std::string& error);
  int bound_port() const;
  // Serves until stop(), from the calling thread.
  void listen();
  // From any thread.
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace nbar::web
