// The server over a real socket: started on 127.0.0.1 with a free port in a thread, and asked
// with httplib's client. Its answers are handle_api's.
#include <httplib.h>

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
  for (const std::string path : {"/api/examples/..%2f..%2fREADME.md", "/api/examples/%2e%2e%2f%2e%2e%2fetc%2fpasswd",
                                 "/api/examples/../../etc/passwd", "/../../etc/passwd", "/%2e%2e/%2e%2e/etc/passwd",
                                 "/api/examples/%2Fetc%2Fpasswd", "/api/examples//etc/passwd"}) {
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
