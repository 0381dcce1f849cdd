// The server over a real socket: started on 127.0.0.1 with a free port in a thread, and asked
// with httplib's client. Its answers are handle_api's.
#include <arpa/inet.h>
#include <fmt/format.h>
#include <httplib.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <thread>

#include "nbar/web/server.hpp"
#include "web/web_support.hpp"

namespace nbar::web_test {
namespace {

class WebServer : public ::testing::Test {
 protected:
  void SetUp() override {
    web::ServeOptions options;
    options.host = "127.0.0.1";
    options.port = 0;
    options.max_jobs = 2;
    server_ = std::make_unique<web::HttpServer>(options);
    std::string error;
    ASSERT_TRUE(server_->bind(error)) << error;
    thread_ = std::thread([this] { server_->listen(); });
    client_ = std::make_unique<httplib::Client>("127.0.0.1", server_->bound_port());
    client_->set_read_timeout(60, 0);
  }
  void TearDown() override {
    server_->stop();
    if (thread_.joinable()) thread_.join();
  }
  std::unique_ptr<web::HttpServer> server_;
  std::thread thread_;
  std::unique_ptr<httplib::Client> client_;
};

TEST_F(WebServer, HealthAndIndex) {
  const auto health = client_->Get("/api/health");
  ASSERT_TRUE(health);
  EXPECT_EQ(health->status, 200);
  EXPECT_EQ(Json::parse(health->body)["status"], "ok");
  EXPECT_EQ(health->get_header_value("Content-Type"), "application/json");
  EXPECT_EQ(health->get_header_value("X-Content-Type-Options"), "nosniff");
  const auto index = client_->Get("/");
  ASSERT_TRUE(index);
  EXPECT_EQ(index->status, 200);
  EXPECT_NE(index->body.find("<title>nbar</title>"), std::string::npos);
}

TEST_F(WebServer, SolveOverHttpIsTheApiAnswer) {
  const Json body = with_model("examples/fourbar-crank-rocker.yaml", {{"steps", 9}, {"order", 3}});
  const auto r = client_->Post("/api/solve", body.dump(), "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_EQ(r->body, post("/api/solve", body).body);
  EXPECT_EQ(r->body, cli("solve examples/fourbar-crank-rocker.yaml --steps 9 --order 3 --format json").out);
  // Pictures keep their bytes.
  const auto png = client_->Post("/api/render", with_model("examples/five-bar.yaml", {{"format", "png"}}).dump(),
                                 "application/json");
  ASSERT_TRUE(png);
  EXPECT_EQ(png->status, 200);
  EXPECT_EQ(png->get_header_value("Content-Type"), "image/png");
  EXPECT_EQ(png->body.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
}

TEST_F(WebServer, ErrorsOverHttp) {
  const auto yaml = client_->Post("/api/check", Json{{"model", "points:\n  A: [0, 0\n"}}.dump(), "application/json");
  ASSERT_TRUE(yaml);
  EXPECT_EQ(yaml->status, 422);
  EXPECT_GT(Json::parse(yaml->body)["error"]["line"].get<int>(), 0);
  const auto bad = client_->Post("/api/check", "{nope", "application/json");
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->status, 400);
  EXPECT_EQ(Json::parse(bad->body)["error"]["kind"], "bad_json");
  const auto missing = client_->Get("/api/nothing");
  ASSERT_TRUE(missing);
  EXPECT_EQ(missing->status, 404);
  EXPECT_EQ(Json::parse(missing->body)["error"]["kind"], "not_found");
  const auto put = client_->Put("/api/solve", "{}", "application/json");
  ASSERT_TRUE(put);
  EXPECT_EQ(put->status, 405);
  EXPECT_EQ(put->get_header_value("Allow"), "POST");
}

TEST_F(WebServer, OversizedBodies) {
  // Over the limit: the API's 413. Far over it: refused by its Content-Length, still as JSON.
  for (std::size_t size : {std::size_t(1) << 20 | 1, std::size_t(5) << 20}) {
    const auto r = client_->Post("/api/check", std::string(size, ' '), "application/json");
    ASSERT_TRUE(r) << size;
    EXPECT_EQ(r->status, 413) << size;
    EXPECT_EQ(Json::parse(r->body)["error"]["kind"], "body_too_large") << size;
  }
}

TEST_F(WebServer, PathTraversalOverHttp) {
  for (const std::string path :
       {"/api/examples/..%2f..%2fREADME.md", "/api/examples/%2e%2e%2f%2e%2e%2fetc%2fpasswd",
        "/api/examples/../../etc/passwd", "/../../etc/passwd", "/%2e%2e/%2e%2e/etc/passwd",
        "/api/examples/%2Fetc%2Fpasswd", "/api/examples//etc/passwd", "/index.html/../../etc/passwd",
        "/..%5c..%5cetc%5cpasswd", "/%2e%2e%2fREADME.md", "/app.js%00.html",
        "/api/examples/five-bar%00../../etc/passwd", "/api/examples/%2e%2e%2f%2e%2e%2fexamples%2ffive-bar.yaml"}) {
    SCOPED_TRACE(path);
    const auto r = client_->Get(path);
    ASSERT_TRUE(r);
    EXPECT_TRUE(r->status == 404 || r->status == 400) << r->status;
    EXPECT_EQ(r->body.find("root:"), std::string::npos);
    EXPECT_EQ(r->body.find("# nbar"), std::string::npos);
    EXPECT_NO_THROW(Json::parse(r->body)["error"]);
  }
  const auto ok = client_->Get("/api/examples/five-bar");
  ASSERT_TRUE(ok);
  EXPECT_EQ(ok->body, repo_file("examples/five-bar.yaml"));
}

// Raw bytes to the server, and what it answers (everything until it closes, or 5 s; `closed`
// says which).
std::string raw_exchange(int port, const std::string& bytes, bool* closed = nullptr) {
  const int sock = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(sock, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) {
    ::close(sock);
    return {};
  }
  timeval timeout{5, 0};
  ::setsockopt(sock, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  for (std::size_t sent = 0; sent < bytes.size();) {
    const ssize_t n = ::send(sock, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) break;  // the server may refuse before reading it all
    sent += static_cast<std::size_t>(n);
  }
  std::string answer;
  char buffer[4096];
  ssize_t n = 0;
  while ((n = ::recv(sock, buffer, sizeof buffer, 0)) > 0) answer.append(buffer, static_cast<std::size_t>(n));
  if (closed) *closed = n == 0;
  ::close(sock);
  return answer;
}

TEST_F(WebServer, MalformedRequestsAndChunkedBodiesAreAnsweredAsJsonAndTheServerStaysUp) {
  const int port = server_->bound_port();
  bool closed = false;
  const std::string garbage = raw_exchange(port, "HELLO there\r\n\r\n", &closed);
  EXPECT_EQ(garbage.rfind("HTTP/1.1 400", 0), 0u) << garbage.substr(0, 200);
  EXPECT_TRUE(closed) << "what is not HTTP is not a connection to go on with";
  EXPECT_NE(garbage.find("\"bad_input\""), std::string::npos) << garbage;
  // A body over the limit without a Content-Length, in chunks: refused as it grows.
  std::string chunked =
      "POST /api/check HTTP/1.1\r\nHost: x\r\nTransfer-Encoding: chunked\r\n"
      "Content-Type: application/json\r\nConnection: close\r\n\r\n";
  const std::string chunk(64 * 1024, ' ');
  for (int i = 0; i < 48; ++i) chunked += "10000\r\n" + chunk + "\r\n";  // 3 MiB
  chunked += "0\r\n\r\n";
  const std::string big = raw_exchange(port, chunked);
  EXPECT_EQ(big.rfind("HTTP/1.1 413", 0), 0u) << big.substr(0, 200);
  EXPECT_NE(big.find("\"body_too_large\""), std::string::npos) << big.substr(0, 400);
  // A small chunked body is a request like any other.
  const std::string body = Json{{"model", repo_file("examples/five-bar.yaml")}}.dump();
  std::string small =
      "POST /api/check HTTP/1.1\r\nHost: x\r\nTransfer-Encoding: chunked\r\n"
      "Content-Type: application/json\r\nConnection: close\r\n\r\n";
  small += fmt::format("{:x}\r\n", body.size()) + body + "\r\n0\r\n\r\n";
  const std::string ok = raw_exchange(port, small);
  EXPECT_EQ(ok.rfind("HTTP/1.1 200", 0), 0u) << ok.substr(0, 300);
  const auto health = client_->Get("/api/health");
  ASSERT_TRUE(health);
  EXPECT_EQ(health->status, 200);
}

// RFC 9112: a body framed two ways (two Content-Lengths that disagree, or a Content-Length with
// chunked) is how a request is smuggled past a proxy that frames it the other way. Refused with
// 400 and the connection closed, before the body is read; agreeing duplicates are one length.
TEST_F(WebServer, RequestsFramedTwoWaysAreRefused) {
  const int port = server_->bound_port();
  const std::string body = Json{{"model", repo_file("examples/five-bar.yaml")}}.dump();
  const std::string head = "POST /api/check HTTP/1.1\r\nHost: x\r\nContent-Type: application/json\r\n";
  const std::string length = "Content-Length: " + std::to_string(body.size()) + "\r\n";
  bool closed = false;
  const std::string two_lengths = raw_exchange(port, head + length + "Content-Length: 5\r\n\r\n" + body, &closed);
  EXPECT_TRUE(closed);
  EXPECT_EQ(two_lengths.rfind("HTTP/1.1 400", 0), 0u) << two_lengths.substr(0, 200);
  EXPECT_NE(two_lengths.find("Content-Length headers disagree"), std::string::npos) << two_lengths;
  EXPECT_NE(two_lengths.find("Connection: close"), std::string::npos) << two_lengths.substr(0, 400);
  const std::string chunked = fmt::format("{:x}\r\n", body.size()) + body + "\r\n0\r\n\r\n";
  const std::string both = raw_exchange(port, head + length + "Transfer-Encoding: chunked\r\n\r\n" + chunked);
  EXPECT_EQ(both.rfind("HTTP/1.1 400", 0), 0u) << both.substr(0, 200);
  EXPECT_NE(both.find("both Transfer-Encoding and Content-Length"), std::string::npos) << both;
  // The refused request's body is never read as a request of its own (smuggled past a proxy
  // that took the first length): one answer, and the connection closes.
  const std::string smuggled = raw_exchange(
      port, head + "Content-Length: 0\r\nContent-Length: 38\r\n\r\nGET /api/health HTTP/1.1\r\nHost: x\r\n\r\n",
      &closed);
  EXPECT_TRUE(closed) << "the connection stayed open after the refusal";
  EXPECT_EQ(smuggled.rfind("HTTP/1.1 400", 0), 0u) << smuggled.substr(0, 200);
  EXPECT_EQ(smuggled.find("HTTP/1.1", 1), std::string::npos) << smuggled;
  const std::string same = raw_exchange(port, head + length + length + "Connection: close\r\n\r\n" + body);
  EXPECT_EQ(same.rfind("HTTP/1.1 200", 0), 0u) << same.substr(0, 300);
}

// httplib inflated a compressed body whole before the size limit: 1 MB of gzipped zeros took
// 1.7 GB. A body with a Content-Encoding is refused before it is read.
TEST_F(WebServer, CompressedBodiesAreRefusedBeforeTheyAreRead) {
  const int port = server_->bound_port();
  std::string request =
      "POST /api/check HTTP/1.1\r\nHost: x\r\nContent-Encoding: gzip\r\n"
      "Content-Type: application/json\r\nContent-Length: 1000000\r\n\r\n";
  request += std::string(1000000, '\x1f');  // not even gzip: it is never inflated
  const std::string answer = raw_exchange(port, request);
  EXPECT_EQ(answer.rfind("HTTP/1.1 415", 0), 0u) << answer.substr(0, 200);
  EXPECT_NE(answer.find("without Content-Encoding (here 'gzip')"), std::string::npos) << answer.substr(0, 400);
  EXPECT_NE(answer.find("\"bad_input\""), std::string::npos);
  const auto identity = client_->Post("/api/check", httplib::Headers{{"Content-Encoding", "identity"}},
                                      Json{{"model", repo_file("examples/five-bar.yaml")}}.dump(), "application/json");
  ASSERT_TRUE(identity);
  EXPECT_EQ(identity->status, 200);
  const auto health = client_->Get("/api/health");
  ASSERT_TRUE(health);
  EXPECT_EQ(health->status, 200);
}

// A browser accepts br, which httplib wrote at brotli's best quality (about 1 MB/s: minutes for a
// long sweep's answer); the server answers it in gzip, and br alone in identity.
TEST_F(WebServer, BrowsersGetGzipNotBrotli) {
  const int port = server_->bound_port();
  const std::string body = Json{{"model", repo_file("examples/fourbar-crank-rocker.yaml")}, {"steps", 721}}.dump();
  const auto request = [&](const std::string& accept) {
    return "POST /api/solve HTTP/1.1\r\nHost: x\r\nAccept-Encoding: " + accept +
           "\r\nContent-Type: application/json\r\nConnection: close\r\nContent-Length: " + std::to_string(body.size()) +
           "\r\n\r\n" + body;
  };
  const std::string browser = raw_exchange(port, request("gzip, deflate, br"));
  ASSERT_EQ(browser.rfind("HTTP/1.1 200", 0), 0u) << browser.substr(0, 300);
  const std::string head = browser.substr(0, browser.find("\r\n\r\n"));
  EXPECT_NE(head.find("Content-Encoding: gzip"), std::string::npos) << head;
  const std::string only_br = raw_exchange(port, request("br"));
  const std::string only_head = only_br.substr(0, only_br.find("\r\n\r\n"));
  EXPECT_EQ(only_head.find("Content-Encoding"), std::string::npos) << only_head;
  EXPECT_NE(only_br.find("\"complete\": true"), std::string::npos);
}

TEST_F(WebServer, BindsOnlyWhereAsked) {
  // A second server on the same port cannot bind it.
  web::ServeOptions options;
  options.port = server_->bound_port();
  web::HttpServer second(options);
  std::string error;
  EXPECT_FALSE(second.bind(error));
  EXPECT_NE(error.find("127.0.0.1"), std::string::npos);
}

}  // namespace
}  // namespace nbar::web_test
