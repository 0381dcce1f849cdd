// HTTP with cpp-httplib: every request goes to handle_api, whose answer is sent as it is. The
// connections are the front's (connection_front.hpp): it reads each request whole under its
// deadlines and caps, then a worker hands the request's bytes to httplib's request processing.
// The only decisions taken here are those taken before the body is read (a request framed two
// ways, a compressed body); they are answered with the API's JSON errors too.
#include "nbar/web/server.hpp"

#include <fmt/format.h>
#include <httplib.h>
#include <netdb.h>
#include <poll.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <unistd.h>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "connection_front.hpp"

namespace nbar::web {

namespace {

// httplib's processing of one request (parse, route, write the answer), called on a stream that
// holds the request whole; httplib's own socket loop is not used.
class RequestProcessor : public httplib::Server {
 public:
  bool process(httplib::Stream& stream, bool last, bool& client_closes) {
    return process_request(stream, last, client_closes, nullptr);
  }
};

// Set by the logger, which httplib calls once an answer is written: the answer said
// "Connection: close" (a request refused before its body was read).
thread_local bool answer_closes = false;

// One request's bytes, as the front read them, and the connection's socket to write the answer
// to within the write deadline.
class RequestStream final : public httplib::Stream {
 public:
  RequestStream(const Connection& c, double write_seconds)
      : c_(c),
        request_(c.input.data(), c.request_bytes),
        write_until_(std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                            std::chrono::duration<double>(write_seconds))) {}
  bool is_readable() const override { return at_ < request_.size(); }
  bool is_writable() const override { return wait_writable(); }
  ssize_t read(char* ptr, size_t size) override {
    const std::size_t n = std::min(size, request_.size() - at_);
    std::memcpy(ptr, request_.data() + at_, n);
    at_ += n;
    return static_cast<ssize_t>(n);
  }
  ssize_t write(const char* ptr, size_t size) override {
    for (;;) {
      const ssize_t n = ::send(c_.fd, ptr, size, MSG_DONTWAIT | MSG_NOSIGNAL);
      if (n >= 0) return n;
      if (errno == EINTR) continue;
      if ((errno != EAGAIN && errno != EWOULDBLOCK) || !wait_writable()) return -1;
    }
  }
  void get_remote_ip_and_port(std::string& ip, int& port) const override {
    ip = c_.peer_address;
    port = c_.peer_port;
  }
  void get_local_ip_and_port(std::string& ip, int& port) const override {
    ip = c_.local_address;
    port = c_.local_port;
  }
  // httplib asks only to refuse a socket select() cannot watch (>= FD_SETSIZE); this one is
  // never given to select(), so none is refused: the front serves more connections than that.
  socket_t socket() const override { return c_.fd < FD_SETSIZE ? c_.fd : INVALID_SOCKET; }

 private:
  bool wait_writable() const {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(write_until_ - std::chrono::steady_clock::now());
    pollfd p{c_.fd, POLLOUT, 0};
    return left.count() > 0 && ::poll(&p, 1, static_cast<int>(left.count())) > 0 && !(p.revents & (POLLERR | POLLHUP));
  }
  const Connection& c_;
  std::string_view request_;
  std::size_t at_ = 0;
  std::chrono::steady_clock::time_point write_until_;
};

const char* reason_phrase(int status) {
  switch (status) {
    case 400: return "Bad Request";
    case 408: return "Request Timeout";
    case 413: return "Payload Too Large";
    case 431: return "Request Header Fields Too Large";
    case 501: return "Not Implemented";
    case 503: return "Service Unavailable";
    default: return "Error";
  }
}

// A refusal of the front: the API's JSON error, and the connection closes after it.
std::string refusal_text(int status, const std::string& message, std::size_t max_body_bytes) {
  // A body over the limit is told as handle_api tells it, with the limit's name and value.
  const ApiResponse answer =
      status == 413 ? body_too_large_response(message, max_body_bytes) : error_response(status, message);
  return "HTTP/1.1 " + std::to_string(status) + " " + reason_phrase(status) +
         "\r\nContent-Type: " + answer.content_type + "\r\nContent-Length: " + std::to_string(answer.body.size()) +
         "\r\nX-Content-Type-Options: nosniff\r\nCache-Control: no-store\r\nConnection: close\r\n\r\n" + answer.body;
}

// Room for the connections the front takes: the soft limit on descriptors (often 1 024) raised to
// the hard one.
int descriptors_available() {
  rlimit limit{};
  if (::getrlimit(RLIMIT_NOFILE, &limit) != 0) return 1024;
  if (limit.rlim_cur < limit.rlim_max) {
    limit.rlim_cur = limit.rlim_max;
    ::setrlimit(RLIMIT_NOFILE, &limit);
    ::getrlimit(RLIMIT_NOFILE, &limit);
  }
  return limit.rlim_cur > 1 << 20 ? 1 << 20 : static_cast<int>(limit.rlim_cur);
}

// A listening socket on host:port (port 0: any free one), or -1. SO_REUSEADDR but not
// SO_REUSEPORT: a second server on a port in use fails to bind instead of sharing it silently.
int listen_on(const std::string& host, int port, int& bound_port) {
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  hints.ai_flags = AI_PASSIVE | AI_NUMERICSERV;
  addrinfo* found = nullptr;
  if (::getaddrinfo(host.c_str(), std::to_string(port).c_str(), &hints, &found) != 0) return -1;
  int fd = -1;
  for (const addrinfo* a = found; a && fd < 0; a = a->ai_next) {
    fd = ::socket(a->ai_family, a->ai_socktype | SOCK_NONBLOCK | SOCK_CLOEXEC, a->ai_protocol);
    if (fd < 0) continue;
    const int yes = 1;
    ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
    if (::bind(fd, a->ai_addr, a->ai_addrlen) != 0 || ::listen(fd, SOMAXCONN) != 0) {
      ::close(fd);
      fd = -1;
    }
  }
  ::freeaddrinfo(found);
  if (fd < 0) return -1;
  sockaddr_storage address{};
  socklen_t length = sizeof address;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length);
  bound_port = address.ss_family == AF_INET6 ? ntohs(reinterpret_cast<sockaddr_in6*>(&address)->sin6_port)
                                             : ntohs(reinterpret_cast<sockaddr_in*>(&address)->sin_port);
  return fd;
}

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

void send(ApiResponse answer, httplib::Response& res) {
  res.status = answer.status;
  for (const auto& [name, value] : answer.headers) res.set_header(name, value);
  res.set_header("X-Content-Type-Options", "nosniff");
  res.set_header("Cache-Control", "no-store");
  // Moved, not copied as set_content would: a 78 MB sweep would be in memory twice.
  res.body = std::move(answer.body);
  res.set_header("Content-Type", answer.content_type);
}

// The bytes of answers being written, by client address. A worker holds its answer until the
// client has read it or the write deadline has passed: 30 clients that asked for 100 001-step
// sweeps and read nothing held 78 MB each (4.5 GB). An answer that would take the bytes held past
// the total, or its client's address past its share, is refused 503 instead of held, unless
// nothing else is held (so that any one answer can be had) or it is small (what the socket's
// buffer takes at once costs no wait).
class HeldAnswers {
 public:
  static constexpr std::size_t kAlwaysTaken = 64 << 10;
  HeldAnswers(std::size_t total, std::size_t per_address) : max_total_(total), max_per_address_(per_address) {}
  bool take(const std::string& address, std::size_t bytes) {
    const std::lock_guard lock(mutex_);
    std::size_t& mine = by_address_[address];
    const bool over_total = total_ > 0 && total_ + bytes > max_total_;
    const bool over_share = mine > 0 && mine + bytes > max_per_address_;
    if (bytes > kAlwaysTaken && (over_total || over_share)) {
      if (mine == 0) by_address_.erase(address);
      return false;
    }
    mine += bytes;
    total_ += bytes;
    return true;
  }
  void give_back(const std::string& address, std::size_t bytes) {
    const std::lock_guard lock(mutex_);
    const auto it = by_address_.find(address);
    if (it == by_address_.end()) return;
    it->second -= std::min(it->second, bytes);
    total_ -= std::min(total_, bytes);
    if (it->second == 0) by_address_.erase(it);
  }
  std::size_t max_total() const { return max_total_; }
  std::size_t max_per_address() const { return max_per_address_; }

 private:
  std::mutex mutex_;
  std::map<std::string, std::size_t> by_address_;
  std::size_t total_ = 0;
  const std::size_t max_total_, max_per_address_;
};

// What this worker's answer holds (set by the handler, given back once it is written).
thread_local std::size_t answer_held_bytes = 0;
thread_local std::string answer_held_by;

// glibc keeps what a burst of requests freed in its arenas (one per thread, up to eight per
// core) and gave little of it back: after four 100 001-step sweeps the server stayed at 940 MB.
// Two things return it. Its thresholds are fixed, not raised by every large block freed (which
// let each arena keep up to 64 MB at its top, where malloc_trim does not reach in a thread's
// arena): blocks of 1 MB or more (an answer, a sweep's columns) are mapped on their own and
// unmapped when freed, and an arena's top is trimmed past 8 MB. And malloc_trim returns the free
// pages in the middle of every arena once the last request in flight ends, or after a large
// answer is computed (while clients hold answers, the server is never idle).
void set_allocator_thresholds() {
#if defined(__GLIBC__) && !defined(__EMSCRIPTEN__)
  ::mallopt(M_MMAP_THRESHOLD, 1 << 20);
  ::mallopt(M_TRIM_THRESHOLD, 8 << 20);
#endif
}
std::atomic<int> requests_in_flight{0};
void return_free_memory() {
#if defined(__GLIBC__) && !defined(__EMSCRIPTEN__)
  ::malloc_trim(0);
#endif
}
constexpr std::size_t kLargeAnswer = 1 << 20;

}  // namespace

struct HttpServer::Impl {
  ServeOptions options;
  ServerConfig config;
  RequestProcessor server;
  int listener = -1;
  int port = -1;
  std::unique_ptr<ConnectionFront> front;
  HeldAnswers held;
  std::atomic<bool> stopping{false};
  explicit Impl(const ServeOptions& o) : held(o.max_held_answer_bytes, o.max_held_answer_bytes_per_address) {}
  ~Impl() {
    front.reset();
    if (listener >= 0) ::close(listener);
  }
};

namespace {

// What every request meets before and after its handler: the limits checked before a body is
// read, and httplib's own failures answered as the API's JSON errors.
void guard_requests(httplib::Server& server, const ServeOptions& options) {
  // The front refuses a body over the limit before reading it; httplib's own check stays as a
  // second line.
  server.set_payload_max_length(options.limits.max_body_bytes);
  // httplib inflates a gzip or deflate body whole before its size is checked (1 MB of gzipped
  // zeros became 1 GB in memory), and the API's bodies are small JSON: it takes them as sent. The
  // check runs before the body is read; the connection closes, its unread body with it.
  server.set_pre_routing_handler([](const httplib::Request& req, httplib::Response& res) {
    // Every answer is sent whole: httplib would cut any answer to a Range header's bytes, an
    // error's JSON too (a 400 of 11 bytes of JSON, found by the random requests' test). The
    // request is httplib's own non-const object, handed to handlers as const.
    const_cast<httplib::Request&>(req).ranges.clear();
    without_brotli(req);  // for the refusals below too
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
  // Refused before their bodies were read (above), or not read as HTTP (the error handler,
  // below): the front closes the connection once answered, with whatever the client sent after.
  server.set_logger([](const httplib::Request& req, const httplib::Response& res) {
    answer_closes = answer_closes || res.get_header_value("Connection") == "close" || req.method.empty();
  });
  // The handlers answer every error themselves; what is left is httplib's own reading (memory
  // for a body, say): never a 500 with the exception's text in a header, as httplib would.
  server.set_exception_handler([](const httplib::Request& req, httplib::Response& res, std::exception_ptr error) {
    without_brotli(req);
    bool out_of_memory = false;
    try {
      std::rethrow_exception(error);
    } catch (const std::bad_alloc&) {
      out_of_memory = true;
    } catch (...) {
    }
    send(out_of_memory ? error_response(413, "the request needs more memory than the server has")
                       : error_response(400, "the request could not be read as HTTP"),
         res);
    res.set_header("Connection", "close");
  });
  // Statuses httplib sets itself (413 before reading, 400 for a malformed request line...):
  // the same JSON errors. Answers of handle_api already have their body.
  server.set_error_handler([](const httplib::Request& req, httplib::Response& res) {
    without_brotli(req);  // a header line too long for httplib is answered before routing
    if (!res.body.empty()) return;
    answer_closes = true;  // what httplib could not read is not a request to go on from
    const std::string message = res.status == 413   ? "the body is too large for this server"
                                : res.status == 404 ? "not found"
                                                    : "the request could not be read as HTTP";
    send(error_response(res.status, message), res);
  });
}

// Every method and path goes to the API (handle_api answers the static files too); an answer
// waits in memory until its client reads it, within the held-answer budget.
void route_requests(httplib::Server& server, const ServerConfig* config, HeldAnswers* held) {
  const auto handler = [config, held](const httplib::Request& req, httplib::Response& res) {
    without_brotli(req);
    ApiResponse answer =
        handle_api(ApiRequest{req.method, req.path, req.body, req.get_header_value("Accept-Language")}, *config);
    if (answer.body.size() > kLargeAnswer) return_free_memory();  // what computing it took
    if (!held->take(req.remote_addr, answer.body.size())) {
      answer = held_answers_response(
          fmt::format("the answer has {:.1f} MB and the server already holds answers not yet read by their clients "
                      "(at most {} MiB in all, {} MiB for one client address); read them, or try again in a moment",
                      answer.body.size() / 1e6, held->max_total() >> 20, held->max_per_address() >> 20),
          held->max_total(), config->retry_after_seconds);
    } else {
      answer_held_bytes = answer.body.size();
      answer_held_by = req.remote_addr;
    }
    send(std::move(answer), res);
  };
  const char* everything = R"(/.*)";
  server.Get(everything, handler);
  server.Post(everything, handler);
  server.Put(everything, handler);
  server.Patch(everything, handler);
  server.Delete(everything, handler);
  server.Options(everything, handler);
}

}  // namespace

HttpServer::HttpServer(const ServeOptions& options) : impl_(std::make_unique<Impl>(options)) {
  set_allocator_thresholds();
  impl_->options = options;
  impl_->config.limits = options.limits;
  impl_->config.jobs = std::make_shared<JobSlots>(std::max(1, options.max_jobs));
  const int cores = static_cast<int>(std::thread::hardware_concurrency());
  impl_->config.light_jobs =
      std::make_shared<JobSlots>(options.light_jobs > 0 ? options.light_jobs : std::max(2, cores));
  impl_->config.queue_wait_seconds = options.queue_wait_seconds;
  guard_requests(impl_->server, options);
  route_requests(impl_->server, &impl_->config, &impl_->held);
}

HttpServer::~HttpServer() { stop(); }

bool HttpServer::bind(std::string& error) {
  // A client that goes away mid-answer must not end the server (ffmpeg's pipe too).
  std::signal(SIGPIPE, SIG_IGN);
  const ServeOptions& o = impl_->options;
  impl_->listener = listen_on(o.host, o.port, impl_->port);
  if (impl_->listener < 0) {
    impl_->port = -1;
    error =
        "cannot listen on " + o.host + ":" + std::to_string(o.port) + " (in use, or not an address of this machine)";
    return false;
  }
  FrontLimits limits;
  limits.max_body_bytes = o.limits.max_body_bytes;
  limits.request_read_seconds = o.request_read_seconds;
  limits.keep_alive_seconds = o.keep_alive_seconds;
  limits.max_requests_per_connection = o.keep_alive_seconds > 0 ? 100 : 1;
  // Each connection is a descriptor; some are kept for the rest of the program (ffmpeg's pipes).
  limits.max_connections = std::max(16, std::min(o.max_connections, descriptors_available() - 64));
  limits.max_connections_per_address = std::max(1, o.max_connections_per_address);
  limits.workers = std::max(2, o.threads);
  RequestProcessor* server = &impl_->server;
  const double write_seconds = limits.write_seconds;
  impl_->front = std::make_unique<ConnectionFront>(
      impl_->listener, limits,
      [server, write_seconds, held = &impl_->held](Connection& c, bool last) {
        // Once process() has written the answer (or given up at the write deadline) and freed
        // it, even by an exception.
        struct AnswerDone {
          HeldAnswers* held;
          AnswerDone(HeldAnswers* h) : held(h) {
            ++requests_in_flight;
            answer_held_bytes = 0;
          }
          ~AnswerDone() {
            if (answer_held_bytes > 0) held->give_back(answer_held_by, answer_held_bytes);
            answer_held_bytes = 0;
            if (--requests_in_flight == 0) return_free_memory();
          }
        } done(held);
        RequestStream stream(c, write_seconds);
        bool client_closes = false;
        answer_closes = false;
        const bool written = server->process(stream, last, client_closes);
        return written && !client_closes && !last && !answer_closes;
      },
      [max_body = limits.max_body_bytes](int status, const std::string& message) {
        return refusal_text(status, message, max_body);
      });
  if (impl_->stopping) impl_->front->stop();
  return true;
}

int HttpServer::bound_port() const { return impl_->port; }

void HttpServer::listen() {
  if (impl_->front) impl_->front->run();
}

void HttpServer::stop() {
  // listen() may run on another thread, before or after this: the front's stop holds either way.
  impl_->stopping = true;
  if (impl_->front) impl_->front->stop();
}

}  // namespace nbar::web
