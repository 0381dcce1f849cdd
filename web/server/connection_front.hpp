// The server's front: one thread that accepts connections and reads each request whole (its
// header and its body) before any worker thread sees it, under a deadline per request and caps on
// connections per client address and in total. A slow or idle client costs a socket and a few
// bytes here, never a thread: cpp-httplib's own loop gives every connection a thread from its
// accept to its close, so 300 slow-loris connections took every thread of the pool.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace nbar::web {

struct FrontLimits {
  std::size_t max_body_bytes = 1 << 20;     // a larger body is answered 413 before it is read
  std::size_t max_header_bytes = 64 << 10;  // request line and headers
  double request_read_seconds = 10;         // the whole request, from its first byte
  double keep_alive_seconds = 5;            // an idle connection between requests
  double write_seconds = 30;                // an answer the client does not read
  int max_connections = 2048;               // in total; the longest-waiting idle one makes room
  int max_connections_per_address = 128;    // from one client address
  int max_requests_per_connection = 100;
  int workers = 64;  // requests served at once
};

// One client connection, owned by the front while it is read and by one worker while a request
// of it is served.
struct Connection {
  using Clock = std::chrono::steady_clock;
  int fd = -1;
  std::string peer_address, local_address;
  int peer_port = 0, local_port = 0;
  std::string input;              // bytes received and not yet served
  std::size_t request_bytes = 0;  // once whole: the first request's header and body in `input`
  int served = 0;                 // requests answered on this connection
  // The front's reading state.
  Clock::time_point deadline;  // of the idle wait, or of the request being read
  Clock::time_point waiting_since;
  bool request_started = false;  // a byte of the next request has come
  std::size_t header_end = 0;    // after the header's blank line; 0 until it has come
  enum class Body { None, Length, Chunked } body = Body::None;
  std::size_t body_length = 0;    // Length: the body's bytes
  std::size_t chunk_scan = 0;     // Chunked: where the next chunk's size line starts
  std::size_t chunked_bytes = 0;  // Chunked: the data so far
  bool trailers = false;          // Chunked: the last chunk has come, its trailer section next
  enum class State { Reading, Serving, Refusing, Lingering } state = State::Reading;
  std::string output;  // a refusal the front writes itself
  std::size_t written = 0;
};

// Serves the first request of a connection (its bytes are `input`'s first `request_bytes`) on a
// worker thread; true when the connection stays open for the next one.
using ServeRequest = std::function<bool(Connection&, bool last)>;
// The HTTP answer (status line, headers and body) the front sends when it refuses a request.
using RefusalText = std::function<std::string(int status, const std::string& message)>;

class ConnectionFront {
 public:
  ConnectionFront(int listening_socket, FrontLimits limits, ServeRequest serve, RefusalText refusal);
  ~ConnectionFront();
  ConnectionFront(const ConnectionFront&) = delete;
  ConnectionFront& operator=(const ConnectionFront&) = delete;
  // Accepts and reads until stop(), on the calling thread; the workers' threads are its own.
  void run();
  void stop();  // from any thread

 private:
  bool accept_all();  // false when out of descriptors
  void admit(std::unique_ptr<Connection> c);
  void read_from(Connection& c);
  void advance(Connection& c);
  bool frame_header(Connection& c);
  bool scan_chunks(Connection& c);
  void refuse(Connection& c, int status, const std::string& message);
  void write_refusal(Connection& c);
  void linger(Connection& c);
  void expire(Connection::Clock::time_point now);
  void close(int fd);
  void dispatch(Connection& c);
  void wait_for_request(Connection& c);
  void take_back_served();
  void work();
  void wake() const;

  int listener_;
  int wake_pipe_[2] = {-1, -1};
  FrontLimits limits_;
  ServeRequest serve_;
  RefusalText refusal_;
  std::map<int, std::unique_ptr<Connection>> connections_;  // by socket, the front's and the served
  std::map<std::string, int> per_address_;
  std::mutex mutex_;
  std::condition_variable work_ready_;
  std::deque<Connection*> ready_;   // whole requests for the workers
  std::deque<Connection*> served_;  // back from the workers: `keep` says whether to go on
  std::map<Connection*, bool> keep_;
  bool stopping_ = false;
  std::vector<std::thread> workers_;
};

}  // namespace nbar::web
