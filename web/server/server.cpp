// HTTP with cpp-httplib: every request goes to handle_api, whose answer is sent as it is. The
// only decisions taken here are those httplib takes before the body is read (a body far over
// the limit, a malformed request); they are answered with the API's JSON errors too.
#include "nbar/web/server.hpp"

#include <arpa/inet.h>
#include <httplib.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <optional>
#include <string>
#include <thread>

namespace nbar::web {

struct HttpServer::Impl {
  ServeOptions options;
  ServerConfig config;
  httplib::Server server;
  int port = -1;
  std::atomic<bool> listening{false}, stopping{false};
};

namespace {

// httplib 0.11 listens with a backlog of 5: a burst of new connections (a class's browsers, or
// nginx's one connection per request) overflows it, and each dropped SYN costs its client a
// 1 s retransmission. Listening again on the bound socket raises the backlog; httplib does not
// hand the socket out, so it is found among the process's descriptors by its port.
// A body whose length two headers tell differently (RFC 9112, 6.3): a proxy in front may frame
// it one way and this server another, which is how requests are smuggled past the proxy. Such a
// request is refused and its connection closed, before the body is read.
std::optional<std::string> framing_error(const httplib::Request& req) {
  const std::size_t lengths = req.get_header_value_count("Content-Length");
  const bool chunked = req.has_header("Transfer-Encoding");
  if (chunked && lengths > 0)
    return "a request with both Transfer-Encoding and Content-Length has no single length; send one of them";
  for (std::size_t i = 1; i < lengths; ++i)
    if (req.get_header_value("Content-Length", i) != req.get_header_value("Content-Length", 0))
      return "the request's Content-Length headers disagree; send one";
  if (chunked && req.get_header_value_count("Transfer-Encoding") > 1)
    return "the request has several Transfer-Encoding headers; send one";
  return std::nullopt;
}

// The connection of a request, found by its two ends (httplib does not hand sockets to
// handlers), or -1.
int socket_of(const httplib::Request& req) {
  const auto same_end = [](const sockaddr_storage& end, const std::string& address, int port) {
    char text[INET6_ADDRSTRLEN] = {};
    if (end.ss_family == AF_INET) {
      const auto& v4 = reinterpret_cast<const sockaddr_in&>(end);
      return ntohs(v4.sin_port) == port && ::inet_ntop(AF_INET, &v4.sin_addr, text, sizeof text) && address == text;
    }
    if (end.ss_family == AF_INET6) {
      const auto& v6 = reinterpret_cast<const sockaddr_in6&>(end);
      return ntohs(v6.sin6_port) == port && ::inet_ntop(AF_INET6, &v6.sin6_addr, text, sizeof text) && address == text;
    }
    return false;
  };
  const auto options = std::filesystem::directory_options::skip_permission_denied;
  std::error_code ignored;
  for (const auto& entry : std::filesystem::directory_iterator("/proc/self/fd", options, ignored)) {
    const std::string name = entry.path().filename().string();
    if (name.empty() || name.find_first_not_of("0123456789") != std::string::npos || name.size() > 9) continue;
    const int fd = std::stoi(name);
    sockaddr_storage peer{}, local{};
    socklen_t peer_size = sizeof peer, local_size = sizeof local;
    if (::getpeername(fd, reinterpret_cast<sockaddr*>(&peer), &peer_size) == 0 &&
        ::getsockname(fd, reinterpret_cast<sockaddr*>(&local), &local_size) == 0 &&
        same_end(peer, req.remote_addr, req.remote_port) && same_end(local, req.local_addr, req.local_port))
      return fd;
  }
  return -1;
}

// httplib 0.11 keeps a connection open after an answer whatever its Connection header says, and
// reads the next request from where this one's headers ended: a body left unread would be taken
// for the next request (a smuggled one). Once the answer is written (httplib calls its logger
// then), the connection is closed the way servers close one with unread input: the answer is
// ended (FIN), what the client still sends is read and dropped for a moment, then reading is shut
// so that httplib's next read sees the end. Closing at once would answer the unread bytes with a
// reset, which can destroy the answer before the client reads it.
void close_after_answer(const httplib::Request& req) {
  const int fd = socket_of(req);
  if (fd < 0) return;
  ::shutdown(fd, SHUT_WR);
  char sink[16384];
  const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(500);
  for (pollfd p{fd, POLLIN, 0}; std::chrono::steady_clock::now() < until; p.revents = 0) {
    if (::poll(&p, 1, 50) <= 0) continue;
    if (::recv(fd, sink, sizeof sink, MSG_DONTWAIT) <= 0) break;
  }
  ::shutdown(fd, SHUT_RD);
}

void raise_listen_backlog(int port) {
  for (int fd = 0; fd < 4096; ++fd) {
    int listening = 0;
    socklen_t size = sizeof listening;
    if (::getsockopt(fd, SOL_SOCKET, SO_ACCEPTCONN, &listening, &size) != 0 || !listening) continue;
    sockaddr_storage address{};
    socklen_t length = sizeof address;
    if (::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length) != 0) continue;
    const int bound = address.ss_family == AF_INET    ? ntohs(reinterpret_cast<sockaddr_in*>(&address)->sin_port)
                      : address.ss_family == AF_INET6 ? ntohs(reinterpret_cast<sockaddr_in6*>(&address)->sin6_port)
                                                      : -1;
    if (bound == port) ::listen(fd, SOMAXCONN);
  }
}

// httplib 0.11 compresses an answer for a client that accepts br (every browser) with brotli at
// its best quality, about 1 MB/s: a 100 000-step sweep (78 MB of JSON) held a core for three
// minutes after the run's time budget, outside the job slots, and each of a class's browsers
// spent a second on app.js. gzip at zlib's default level is some thirty times faster for a few
// per cent more bytes. httplib reads the request's Accept-Encoding when it writes the answer,
// so the handler takes br out of it first (the request is httplib's own non-const object,
// handed to handlers as const).
void without_brotli(const httplib::Request& req) {
  auto& headers = const_cast<httplib::Headers&>(req.headers);
  const auto [first, last] = headers.equal_range("Accept-Encoding");
  for (auto it = first; it != last; ++it) {
    std::string kept;
    std::size_t start = 0;
    while (start <= it->second.size()) {
      std::size_t end = it->second.find(',', start);
      if (end == std::string::npos) end = it->second.size();
      std::string token = it->second.substr(start, end - start);
      token.erase(0, token.find_first_not_of(" \t"));
      const std::string name = token.substr(0, token.find_first_of(" \t;"));
      if (!name.empty() && name != "br") kept += (kept.empty() ? "" : ", ") + token;
      start = end + 1;
    }
    it->second = kept;
  }
}

void send(const ApiResponse& answer, httplib::Response& res) {
  res.status = answer.status;
  for (const auto& [name, value] : answer.headers) res.set_header(name, value);
  res.set_header("X-Content-Type-Options", "nosniff");
  res.set_header("Cache-Control", "no-store");
  res.set_content(answer.body, answer.content_type);
}

}  // namespace

HttpServer::HttpServer(const ServeOptions& options) : impl_(std::make_unique<Impl>()) {
  impl_->options = options;
  impl_->config.limits = options.limits;
  impl_->config.jobs = std::make_shared<JobSlots>(std::max(1, options.max_jobs));
  const int cores = static_cast<int>(std::thread::hardware_concurrency());
  impl_->config.light_jobs =
      std::make_shared<JobSlots>(options.light_jobs > 0 ? options.light_jobs : std::max(2, cores));
  impl_->config.queue_wait_seconds = options.queue_wait_seconds;
  httplib::Server& server = impl_->server;
  const int threads = std::max(2, options.threads);
  server.new_task_queue = [threads] { return new httplib::ThreadPool(static_cast<std::size_t>(threads)); };
  // Bodies up to twice the limit are read, so that handle_api answers them with its own 413;
  // httplib refuses larger ones from their Content-Length alone.
  server.set_payload_max_length(options.limits.max_body_bytes * 2);
  // SO_REUSEADDR but not httplib's SO_REUSEPORT: a second server on a port in use fails to
  // bind instead of sharing it silently.
  server.set_socket_options([](socket_t sock) {
    int yes = 1;
    ::setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
  });
  // httplib serves a connection on one thread from its first request to its close, so an idle
  // keep-alive connection holds a thread: there are many threads (they mostly sleep), and an
  // idle connection is closed after a few seconds. Behind nginx every request comes on a
  // connection of its own.
  if (options.keep_alive_seconds > 0) {
    server.set_keep_alive_timeout(options.keep_alive_seconds);
    server.set_keep_alive_max_count(100);
  } else {
    server.set_keep_alive_max_count(1);  // "Connection: close" after every answer
  }
  // Headers and body go out in separate writes: without this, Nagle's algorithm holds the body
  // until the client's delayed acknowledgement, 40 ms on Linux, on every kept-alive request.
  server.set_tcp_nodelay(true);
  server.set_read_timeout(10, 0);
  server.set_write_timeout(30, 0);
  // httplib inflates a gzip or deflate body whole before its size is checked (1 MB of gzipped
  // zeros became 1 GB in memory), and the API's bodies are small JSON: it takes them as sent. The
  // check runs before the body is read; the connection closes, its unread body with it.
  server.set_pre_routing_handler([](const httplib::Request& req, httplib::Response& res) {
    const auto refuse = [&res](int status, const std::string& message) {
      send(error_response(status, message), res);
      res.set_header("Connection", "close");
      return httplib::Server::HandlerResponse::Handled;
    };
    if (const std::optional<std::string> framing = framing_error(req)) return refuse(400, *framing);
    const std::string encoding = req.get_header_value("Content-Encoding");
    if (encoding.empty() || encoding == "identity") return httplib::Server::HandlerResponse::Unhandled;
    return refuse(415, "this server reads bodies as they are sent, without Content-Encoding (here '" +
                           encoding.substr(0, 40) + "')");
  });
  // Refused before their bodies were read (above): closed once answered.
  server.set_logger([](const httplib::Request& req, const httplib::Response& res) {
    if (!req.body.empty() || res.get_header_value("Connection") != "close") return;
    bool unread_body = req.has_header("Transfer-Encoding");
    for (std::size_t i = 0; i < req.get_header_value_count("Content-Length"); ++i)
      unread_body = unread_body || req.get_header_value("Content-Length", i) != "0";
    if (unread_body) close_after_answer(req);
  });
  const ServerConfig* config = &impl_->config;
  const auto handler = [config](const httplib::Request& req, httplib::Response& res) {
    without_brotli(req);
    send(handle_api(ApiRequest{req.method, req.path, req.body}, *config), res);
  };
  const char* everything = R"(/.*)";
  server.Get(everything, handler);
  server.Post(everything, handler);
  server.Put(everything, handler);
  server.Patch(everything, handler);
  server.Delete(everything, handler);
  server.Options(everything, handler);
  // Statuses httplib sets itself (413 before reading, 400 for a malformed request line...):
  // the same JSON errors. Answers of handle_api already have their body.
  server.set_error_handler([](const httplib::Request&, httplib::Response& res) {
    if (!res.body.empty()) return;
    const std::string message = res.status == 413   ? "the body is too large for this server"
                                : res.status == 404 ? "not found"
                                                    : "the request could not be read as HTTP";
    send(error_response(res.status, message), res);
  });
}

HttpServer::~HttpServer() { stop(); }

bool HttpServer::bind(std::string& error) {
  // A client that goes away mid-answer must not end the server (ffmpeg's pipe too).
  std::signal(SIGPIPE, SIG_IGN);
  const ServeOptions& o = impl_->options;
  if (o.port == 0) {
    impl_->port = impl_->server.bind_to_any_port(o.host);
  } else {
    impl_->port = impl_->server.bind_to_port(o.host, o.port) ? o.port : -1;
  }
  if (impl_->port < 0) {
    error =
        "cannot listen on " + o.host + ":" + std::to_string(o.port) + " (in use, or not an address of this machine)";
    return false;
  }
  raise_listen_backlog(impl_->port);
  return true;
}

int HttpServer::bound_port() const { return impl_->port; }

void HttpServer::listen() {
  impl_->listening = true;
  if (!impl_->stopping) impl_->server.listen_after_bind();
  impl_->listening = false;
}

void HttpServer::stop() {
  // listen() may have been called on another thread and not be running yet: it either sees
  // `stopping` and returns, or runs soon and is stopped here.
  impl_->stopping = true;
  for (int i = 0; i < 500 && impl_->listening && !impl_->server.is_running(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  impl_->server.stop();
}

}  // namespace nbar::web
