// The web API's tests: requests to handle_api without a socket, and the CLI's answers to the
// same requests, to compare with.
#pragma once

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "apps/cli_support.hpp"
#include "nbar/web/api.hpp"

namespace nbar::web_test {

using Json = nlohmann::json;
using web::ApiRequest;
using web::ApiResponse;
using web::ServerConfig;

inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A file of the repository, by its path from the root.
inline std::string repo_file(const std::string& path) {
  return read_file(std::filesystem::path(NBAR_SOURCE_DIR) / path);
}

// The tests compare answers; a budget of their own keeps a slow machine or the sanitizer build
// (a path synthesis there takes 30 s, the server's default budget) from turning them into tests
// of the budget. The budget's own tests set theirs.
inline ServerConfig test_config() {
  ServerConfig config;
  config.jobs = std::make_shared<web::JobSlots>(4);
  config.limits.time_budget_seconds = 300;
  return config;
}

inline ApiResponse call(const std::string& method, const std::string& path, const std::string& body = "",
                        const ServerConfig& config = test_config()) {
  return web::handle_api(ApiRequest{method, path, body}, config);
}

inline ApiResponse post(const std::string& path, const Json& body, const ServerConfig& config = test_config()) {
  return call("POST", path, body.dump(), config);
}

// {"model": <the text of the repository's file>, ...options}
inline Json with_model(const std::string& file, Json options = Json::object()) {
  options["model"] = repo_file(file);
  return options;
}

inline Json with_task(const std::string& file, Json options = Json::object()) {
  options["task"] = repo_file(file);
  return options;
}

// The error object of an error answer.
inline Json error_of(const ApiResponse& r) {
  const Json j = Json::parse(r.body);
  return j.at("error");
}

inline std::string header(const ApiResponse& r, const std::string& name) {
  for (const auto& [n, v] : r.headers)
    if (n == name) return v;
  return {};
}

// The same JSON up to rounding: equal structure, strings and booleans; numbers within
// `absolute` + `relative` x their size. For results that may differ in their last bits between
// runs (synthesis paths tracked on several threads in unoptimised builds).
inline ::testing::AssertionResult json_near(const Json& a, const Json& b, double relative = 1e-9,
                                            double absolute = 1e-5, const std::string& at = "$") {
  if (a.is_number() && b.is_number()) {
    const double x = a.get<double>(), y = b.get<double>();
    if (std::abs(x - y) <= absolute + relative * std::max(std::abs(x), std::abs(y)))
      return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << at << ": " << x << " != " << y;
  }
  if (a.type() != b.type()) return ::testing::AssertionFailure() << at << ": " << a.dump() << " != " << b.dump();
  if (a.is_object()) {
    if (a.size() != b.size()) return ::testing::AssertionFailure() << at << ": different keys";
    for (const auto& [key, value] : a.items()) {
      if (!b.contains(key)) return ::testing::AssertionFailure() << at << ": no " << key;
      if (auto r = json_near(value, b[key], relative, absolute, at + "." + key); !r) return r;
    }
    return ::testing::AssertionSuccess();
  }
  if (a.is_array()) {
    if (a.size() != b.size())
      return ::testing::AssertionFailure() << at << ": " << a.size() << " != " << b.size() << " items";
    for (std::size_t i = 0; i < a.size(); ++i)
      if (auto r = json_near(a[i], b[i], relative, absolute, at + "[" + std::to_string(i) + "]"); !r) return r;
    return ::testing::AssertionSuccess();
  }
  if (a == b) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << at << ": " << a.dump() << " != " << b.dump();
}

// Runs nbar ARGS from the repository's root.
inline cli_test::CliRun cli(const std::string& args) {
  return cli_test::run_shell("cd '" + std::string(NBAR_SOURCE_DIR) + "' && '" + NBAR_CLI_PATH + "' " + args);
}

// A fresh empty folder for files the CLI writes.
inline std::filesystem::path temp_folder(const std::string& name) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("nbar_web_test_" + std::to_string(::getpid()) + "_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace nbar::web_test
