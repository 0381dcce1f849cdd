// `nbar serve`: the JSON API (api.hpp) and the embedded static files over HTTP, with
// cpp-httplib. This layer only moves bytes: every answer comes from handle_api.
#pragma once

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
  int threads = 256;               // connections served at once (each one holds a thread)
  int keep_alive_seconds = 5;      // an idle connection gives its thread back after this
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
