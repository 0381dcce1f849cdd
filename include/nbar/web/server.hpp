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
  int max_jobs = 2;                // computations at once; more are answered 503
  int threads = 8;                 // connections served at once
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
