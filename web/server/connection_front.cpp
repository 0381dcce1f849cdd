#include "connection_front.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

namespace nbar::web {

namespace {

using Clock = Connection::Clock;

Clock::duration seconds(double s) {
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
}

// A refused or finished connection is read and dropped for this long after its answer is ended,
// so that the client reads the answer instead of a reset caused by the bytes it still sends.
constexpr double kLingerSeconds = 0.5;

void describe(const sockaddr_storage& end, std::string& address, int& port) {
  char text[INET6_ADDRSTRLEN] = {};
  if (end.ss_family == AF_INET) {
    const auto& v4 = reinterpret_cast<const sockaddr_in&>(end);
    ::inet_ntop(AF_INET, &v4.sin_addr, text, sizeof text);
    port = ntohs(v4.sin_port);
  } else if (end.ss_family == AF_INET6) {
    const auto& v6 = reinterpret_cast<const sockaddr_in6&>(end);
    ::inet_ntop(AF_INET6, &v6.sin6_addr, text, sizeof text);
    port = ntohs(v6.sin6_port);
  }
  address = text;
}

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char ch) { return std::tolower(ch); });
  return text;
}

std::string trimmed(const std::string& text) {
  const std::size_t first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return {};
  return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

int hex_value(char ch) {
  if (ch >= '0' && ch <= '9') return ch - '0';
  if (ch >= 'a' && ch <= 'f') return ch - 'a' + 10;
  if (ch >= 'A' && ch <= 'F') return ch - 'A' + 10;
  return -1;
}

}  // namespace

ConnectionFront::ConnectionFront(int listening_socket, FrontLimits limits, ServeRequest serve, RefusalText refusal)
    : listener_(listening_socket), limits_(limits), serve_(std::move(serve)), refusal_(std::move(refusal)) {
  if (::pipe2(wake_pipe_, O_NONBLOCK | O_CLOEXEC) != 0) wake_pipe_[0] = wake_pipe_[1] = -1;
}

ConnectionFront::~ConnectionFront() {
  stop();
  for (const int fd : wake_pipe_)
    if (fd >= 0) ::close(fd);
}

void ConnectionFront::stop() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  work_ready_.notify_all();
  wake();
}

void ConnectionFront::wake() const {
  const char byte = 1;
  if (wake_pipe_[1] >= 0) [[maybe_unused]]
    const ssize_t ignored = ::write(wake_pipe_[1], &byte, 1);
}

// The loop: connections back from the workers, then one poll over the listening socket, the
// wake-up pipe and every connection the front reads or answers, then the deadlines.
void ConnectionFront::run() {
  for (int i = 0; i < std::max(1, limits_.workers); ++i) workers_.emplace_back([this] { work(); });
  std::vector<pollfd> polled;
  Clock::time_point accept_paused_until{};
  for (;;) {
    {
      const std::lock_guard lock(mutex_);
      if (stopping_) break;
    }
    take_back_served();
    Clock::time_point now = Clock::now();
    polled.clear();
    polled.push_back({wake_pipe_[0], POLLIN, 0});
    polled.push_back({now >= accept_paused_until ? listener_ : -1, POLLIN, 0});
    Clock::time_point next = now + std::chrono::seconds(1);
    for (const auto& [fd, c] : connections_) {
      if (c->state == Connection::State::Serving) continue;
      polled.push_back({fd, static_cast<short>(c->state == Connection::State::Refusing ? POLLOUT : POLLIN), 0});
      next = std::min(next, c->deadline);
    }
    const auto wait = std::chrono::duration_cast<std::chrono::milliseconds>(next - now).count() + 1;
    if (::poll(polled.data(), polled.size(), static_cast<int>(std::clamp<long long>(wait, 0, 1000))) < 0 &&
        errno != EINTR)
      break;
    if (polled[0].revents) {
      char sink[256];
      while (::read(wake_pipe_[0], sink, sizeof sink) > 0) {
      }
    }
    // Connections first: accepting may close one (to make room) and reuse its number.
    for (std::size_t i = 2; i < polled.size(); ++i) {
      if (!polled[i].revents) continue;
      const auto it = connections_.find(polled[i].fd);
      if (it == connections_.end()) continue;
      Connection& c = *it->second;
      if (c.state == Connection::State::Reading)
        read_from(c);
      else if (c.state == Connection::State::Refusing)
        write_refusal(c);
      else if (c.state == Connection::State::Lingering)
        linger(c);
    }
    // Out of descriptors, the listening socket stays readable: it rests a moment.
    if (polled[1].revents && !accept_all()) accept_paused_until = Clock::now() + std::chrono::milliseconds(100);
    expire(Clock::now());
  }
  work_ready_.notify_all();
  for (std::thread& t : workers_) t.join();
  workers_.clear();
  for (auto& [fd, c] : connections_) ::close(fd);
  connections_.clear();
  per_address_.clear();
}

bool ConnectionFront::accept_all() {
  for (;;) {
    sockaddr_storage peer{};
    socklen_t length = sizeof peer;
    const int fd = ::accept4(listener_, reinterpret_cast<sockaddr*>(&peer), &length, SOCK_NONBLOCK | SOCK_CLOEXEC);
    if (fd < 0) {
      if (errno == EINTR || errno == ECONNABORTED) continue;
      return errno != EMFILE && errno != ENFILE;  // EAGAIN: none left
    }
    auto c = std::make_unique<Connection>();
    c->fd = fd;
    describe(peer, c->peer_address, c->peer_port);
    sockaddr_storage local{};
    length = sizeof local;
    if (::getsockname(fd, reinterpret_cast<sockaddr*>(&local), &length) == 0)
      describe(local, c->local_address, c->local_port);
    // Headers and body go out in separate writes: without this, Nagle's algorithm holds the
    // body until the client's delayed acknowledgement, 40 ms on Linux.
    const int yes = 1;
    ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &yes, sizeof yes);
    admit(std::move(c));
  }
}

// The caps: a client address over its own is refused at once (503); at the total, the connection
// that has waited longest without a whole request (an idle or slow one) is closed to make room.
void ConnectionFront::admit(std::unique_ptr<Connection> c) {
  const auto refuse_now = [&](const std::string& message) {
    const std::string text = refusal_(503, message);
    [[maybe_unused]] const ssize_t ignored = ::send(c->fd, text.data(), text.size(), MSG_DONTWAIT | MSG_NOSIGNAL);
    ::close(c->fd);
  };
  const auto from = per_address_.find(c->peer_address);
  if (from != per_address_.end() && from->second >= limits_.max_connections_per_address)
    return refuse_now("too many connections from your address (this server takes " +
                      std::to_string(limits_.max_connections_per_address) + "); close some and try again");
  if (static_cast<int>(connections_.size()) >= limits_.max_connections) {
    Connection* oldest = nullptr;
    for (const auto& [fd, other] : connections_)
      if (other->state != Connection::State::Serving && (!oldest || other->waiting_since < oldest->waiting_since))
        oldest = other.get();
    if (!oldest) return refuse_now("the server has as many connections as it takes; try again in a moment");
    close(oldest->fd);
  }
  ++per_address_[c->peer_address];
  Connection& admitted = *c;
  connections_[c->fd] = std::move(c);
  wait_for_request(admitted);
}

void ConnectionFront::wait_for_request(Connection& c) {
  c.state = Connection::State::Reading;
  c.request_bytes = 0;
  c.header_end = 0;
  c.body = Connection::Body::None;
  c.body_length = c.chunk_scan = c.chunked_bytes = 0;
  c.trailers = false;
  c.waiting_since = Clock::now();
  c.request_started = !c.input.empty();
  const double idle = limits_.keep_alive_seconds > 0 ? limits_.keep_alive_seconds : limits_.request_read_seconds;
  c.deadline = c.waiting_since + seconds(c.request_started ? limits_.request_read_seconds : idle);
  advance(c);
}

void ConnectionFront::read_from(Connection& c) {
  char buffer[64 * 1024];
  const ssize_t n = ::recv(c.fd, buffer, sizeof buffer, MSG_DONTWAIT);
  if (n == 0 || (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)) return close(c.fd);
  if (n < 0) return;
  if (!c.request_started) {
    c.request_started = true;
    c.deadline = Clock::now() + seconds(limits_.request_read_seconds);
  }
  c.input.append(buffer, static_cast<std::size_t>(n));
  advance(c);
  // A chunked body's framing around little chunks is bounded too (at most four bytes of it for
  // each byte of data).
  if (c.state == Connection::State::Reading && c.input.size() > limits_.max_header_bytes + 5 * limits_.max_body_bytes)
    refuse(c, 413, "the request is over " + std::to_string(limits_.max_body_bytes) + " bytes with its framing");
}

// Whether the first request in `input` is whole: then it goes to a worker.
void ConnectionFront::advance(Connection& c) {
  if (c.state != Connection::State::Reading) return;
  if (c.header_end == 0) {
    // Blank lines before a request are allowed (RFC 9112, 2.2).
    const std::size_t start = c.input.find_first_not_of("\r\n");
    c.input.erase(0, start == std::string::npos ? c.input.size() : start);
    if (!frame_header(c)) return;
  }
  switch (c.body) {
    case Connection::Body::None: c.request_bytes = c.header_end; break;
    case Connection::Body::Length:
      if (c.input.size() < c.header_end + c.body_length) return;
      c.request_bytes = c.header_end + c.body_length;
      break;
    case Connection::Body::Chunked:
      if (!scan_chunks(c)) return;
      break;
  }
  dispatch(c);
}

// Reads the header's framing once it is whole: the body's length, chunked, or none. Whatever
// this server cannot frame safely is refused here, before a worker sees it; a body framed two
// ways goes to the worker without its body, to be refused there (and the connection closed).
bool ConnectionFront::frame_header(Connection& c) {
  const std::size_t blank = c.input.find("\r\n\r\n");
  if (blank == std::string::npos || blank + 4 > limits_.max_header_bytes) {
    if (c.input.size() > limits_.max_header_bytes || blank != std::string::npos)
      refuse(c, 431, "the request's header is over " + std::to_string(limits_.max_header_bytes) + " bytes");
    return false;
  }
  c.header_end = blank + 4;
  // httplib skips a line that ends in a bare LF: a header hidden that way would frame the body
  // differently there than here.
  for (std::size_t i = 0; i < blank + 2; ++i) {
    const bool bare_lf = c.input[i] == '\n' && (i == 0 || c.input[i - 1] != '\r');
    const bool bare_cr = c.input[i] == '\r' && c.input[i + 1] != '\n';
    if (bare_lf || bare_cr || c.input[i] == '\0') {
      refuse(c, 400, "the request's header has a line that does not end with CR LF, or a NUL byte");
      return false;
    }
  }
  std::vector<std::string> lengths, encodings;
  std::size_t expect_at = std::string::npos, expect_end = 0;
  for (std::size_t at = c.input.find("\r\n") + 2; at < blank + 2;) {
    const std::size_t end = c.input.find("\r\n", at);
    const std::string line = c.input.substr(at, end - at);
    const std::size_t colon = line.find(':');
    if (colon == std::string::npos || colon == 0 || line[0] == ' ' || line[0] == '\t') {
      refuse(c, 400, "a header line is not 'name: value': '" + line.substr(0, 60) + "'");
      return false;
    }
    const std::string name = lower(line.substr(0, colon));
    const std::string value = trimmed(line.substr(colon + 1));
    if (name == "content-length") lengths.push_back(value);
    if (name == "transfer-encoding") encodings.push_back(lower(value));
    if (name == "expect" && lower(value) == "100-continue") expect_at = at, expect_end = end + 2;
    at = end + 2;
  }
  const bool disagree = std::any_of(lengths.begin(), lengths.end(), [&](const auto& l) { return l != lengths[0]; });
  if ((!lengths.empty() && !encodings.empty()) || encodings.size() > 1 || disagree) return true;
  if (!encodings.empty()) {
    if (encodings[0] != "chunked") {
      refuse(c, 501, "this server reads bodies sent whole or chunked, not '" + encodings[0].substr(0, 40) + "'");
      return false;
    }
    c.body = Connection::Body::Chunked;
    c.chunk_scan = c.header_end;
  } else if (!lengths.empty()) {
    const std::string& length = lengths[0];
    if (length.empty() || length.size() > 18 || length.find_first_not_of("0123456789") != std::string::npos) {
      refuse(c, 400, "the Content-Length '" + length.substr(0, 40) + "' is not a number of bytes");
      return false;
    }
    c.body_length = std::stoull(length);
    if (c.body_length > limits_.max_body_bytes) {
      refuse(c, 413,
             "the body has " + length + " bytes; this server takes at most " + std::to_string(limits_.max_body_bytes));
      return false;
    }
    c.body = c.body_length > 0 ? Connection::Body::Length : Connection::Body::None;
  }
  // The front reads the body itself: the client is told to send it now (the worker must not
  // say so again after the body has come).
  if (expect_at != std::string::npos && c.body != Connection::Body::None) {
    c.input.erase(expect_at, expect_end - expect_at);
    c.header_end -= expect_end - expect_at;
    if (c.chunk_scan) c.chunk_scan = c.header_end;
    const char* go_on = "HTTP/1.1 100 Continue\r\n\r\n";
    [[maybe_unused]] const ssize_t ignored = ::send(c.fd, go_on, std::strlen(go_on), MSG_DONTWAIT | MSG_NOSIGNAL);
  }
  return true;
}

// Follows a chunked body's framing as it comes: true once the last chunk and its trailer section
// have come. The data is counted as it is announced, so a chunk that would pass the limit is
// refused before it is read.
bool ConnectionFront::scan_chunks(Connection& c) {
  for (;;) {
    const std::size_t line_end = c.input.find("\r\n", c.chunk_scan);
    if (line_end == std::string::npos) {
      if (c.input.size() - c.chunk_scan > 4096) refuse(c, 400, "a chunk's size line or a trailer is too long");
      return false;
    }
    if (c.trailers) {  // bounded as the whole request is (read_from)
      if (line_end == c.chunk_scan) {
        c.request_bytes = line_end + 2;
        return true;
      }
      c.chunk_scan = line_end + 2;
      continue;
    }
    std::size_t size = 0, digits = 0, at = c.chunk_scan;
    for (; at < line_end && hex_value(c.input[at]) >= 0; ++at, ++digits)
      if (digits < 16) size = size * 16 + static_cast<std::size_t>(hex_value(c.input[at]));
    if (digits == 0 || (at < line_end && c.input[at] != ';' && c.input[at] != ' ' && c.input[at] != '\t')) {
      refuse(c, 400, "a chunk's size is not a hexadecimal number");
      return false;
    }
    if (digits >= 16 || c.chunked_bytes + size > limits_.max_body_bytes) {
      refuse(c, 413,
             "the chunked body passes " + std::to_string(limits_.max_body_bytes) + " bytes, this server's limit");
      return false;
    }
    if (size == 0) {
      c.trailers = true;
      c.chunk_scan = line_end + 2;
      continue;
    }
    const std::size_t data_end = line_end + 2 + size;
    if (c.input.size() < data_end + 2) return false;
    if (c.input.compare(data_end, 2, "\r\n") != 0) {
      refuse(c, 400, "a chunk does not end where its size says");
      return false;
    }
    c.chunked_bytes += size;
    c.chunk_scan = data_end + 2;
  }
}

void ConnectionFront::refuse(Connection& c, int status, const std::string& message) {
  c.output = refusal_(status, message);
  c.written = 0;
  c.state = Connection::State::Refusing;
  c.deadline = Clock::now() + seconds(2);
  write_refusal(c);
}

void ConnectionFront::write_refusal(Connection& c) {
  while (c.written < c.output.size()) {
    const ssize_t n =
        ::send(c.fd, c.output.data() + c.written, c.output.size() - c.written, MSG_DONTWAIT | MSG_NOSIGNAL);
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) return;
    if (n <= 0) return close(c.fd);
    c.written += static_cast<std::size_t>(n);
  }
  ::shutdown(c.fd, SHUT_WR);
  c.state = Connection::State::Lingering;
  c.input.clear();
  c.deadline = Clock::now() + seconds(kLingerSeconds);
}

void ConnectionFront::linger(Connection& c) {
  char sink[64 * 1024];
  const ssize_t n = ::recv(c.fd, sink, sizeof sink, MSG_DONTWAIT);
  if (n == 0 || (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)) close(c.fd);
}

void ConnectionFront::expire(Clock::time_point now) {
  std::vector<int> due;
  for (const auto& [fd, c] : connections_)
    if (c->state != Connection::State::Serving && c->deadline <= now) due.push_back(fd);
  for (const int fd : due) {
    Connection& c = *connections_.at(fd);
    if (c.state == Connection::State::Reading && c.request_started) {
      char limit[32];
      std::snprintf(limit, sizeof limit, "%g", limits_.request_read_seconds);
      refuse(c, 408, std::string("the request did not arrive whole within ") + limit + " s");
    } else {
      close(fd);
    }
  }
}

void ConnectionFront::close(int fd) {
  const auto it = connections_.find(fd);
  if (it == connections_.end()) return;
  const auto from = per_address_.find(it->second->peer_address);
  if (from != per_address_.end() && --from->second <= 0) per_address_.erase(from);
  ::close(fd);
  connections_.erase(it);
}

void ConnectionFront::dispatch(Connection& c) {
  c.state = Connection::State::Serving;
  {
    const std::lock_guard lock(mutex_);
    ready_.push_back(&c);
  }
  work_ready_.notify_one();
}

// A served connection goes on with its next request (it may have come already, pipelined), or
// is ended: its answer is complete, then what the client still sends is read and dropped for a
// moment (a body the worker did not read, after a refusal), then it is closed.
void ConnectionFront::take_back_served() {
  std::deque<Connection*> served;
  std::map<Connection*, bool> keep;
  {
    const std::lock_guard lock(mutex_);
    served.swap(served_);
    keep.swap(keep_);
  }
  for (Connection* c : served) {
    c->input.erase(0, c->request_bytes);
    if (keep[c]) {
      wait_for_request(*c);
      continue;
    }
    ::shutdown(c->fd, SHUT_WR);
    c->state = Connection::State::Lingering;
    c->input.clear();
    c->deadline = Clock::now() + seconds(kLingerSeconds);
  }
}

void ConnectionFront::work() {
  for (;;) {
    Connection* c = nullptr;
    {
      std::unique_lock lock(mutex_);
      work_ready_.wait(lock, [&] { return stopping_ || !ready_.empty(); });
      if (stopping_) return;
      c = ready_.front();
      ready_.pop_front();
    }
    const bool last = c->served + 1 >= std::max(1, limits_.max_requests_per_connection);
    bool keep = false;
    try {
      keep = serve_(*c, last);
    } catch (...) {
      keep = false;  // the answer could not be written (the worker's errors are answers)
    }
    ++c->served;
    {
      const std::lock_guard lock(mutex_);
      served_.push_back(c);
      keep_[c] = keep;
    }
    wake();
  }
}

}  // namespace nbar::web
