// The JSON API's routing: each POST endpoint (endpoints.hpp) reads its body's options, calls the
// library as the CLI does and answers with the library's own writers, so that an answer is byte
// for byte what `nbar ... --format json` prints. Nothing is kept between requests.
#include <fmt/format.h>

#include <atomic>
#include <ctime>
#include <iostream>
#include <map>
#include <new>

#include "endpoints.hpp"
#include "nbar/request/language.hpp"
#include "request/answer_language.hpp"

namespace nbar::web {

namespace {

// ------------------------------------------------------------------------------------ routing

using Endpoint = ApiResponse (*)(Job&, const std::string&);

ApiResponse synth_five_point(Job& job, const std::string& body) {
  return api_synth(job, body, synthesis::SynthesisKind::FivePoint);
}
ApiResponse synth_burmester(Job& job, const std::string& body) {
  return api_synth(job, body, synthesis::SynthesisKind::Burmester);
}
ApiResponse synth_function(Job& job, const std::string& body) {
  return api_synth(job, body, synthesis::SynthesisKind::Function);
}
ApiResponse synth_nine_point(Job& job, const std::string& body) {
  return api_synth(job, body, synthesis::SynthesisKind::NinePoint);
}
ApiResponse synth_path(Job& job, const std::string& body) {
  return api_synth(job, body, synthesis::SynthesisKind::Path);
}

const std::map<std::string, Endpoint, std::less<>>& post_endpoints() {
  static const std::map<std::string, Endpoint, std::less<>> endpoints = {
      {"/api/check", &api_check},
      {"/api/outline", &api_outline},
      {"/api/solve", &api_solve},
      {"/api/stress", &api_stress},
      {"/api/stress/probe", &api_stress_probe},
      {"/api/synth/five-point", &synth_five_point},
      {"/api/synth/burmester", &synth_burmester},
      {"/api/synth/function", &synth_function},
      {"/api/synth/nine-point", &synth_nine_point},
      {"/api/synth/path", &synth_path},
      {"/api/render", &api_render},
      {"/api/report", &api_report},
      {"/api/explain", &api_explain},
      {"/api/simulate", &api_simulate},
      {"/api/simulate/cancel", &api_simulate_cancel},
  };
  return endpoints;
}

ApiResponse method_not_allowed(const std::string& method, const std::string& path, const char* allow) {
  ApiResponse r = error_answer(ApiErrorKind::MethodNotAllowed, method + " " + path + ": use " + allow);
  r.headers.emplace_back("Allow", allow);
  return r;
}

ApiResponse route(const ApiRequest& request, const ServerConfig& config) {
  const std::string& path = request.path;
  const std::string& method = request.method;
  const bool get = method == "GET" || method == "HEAD";
  if (const auto it = post_endpoints().find(path); it != post_endpoints().end()) {
    if (method != "POST") return method_not_allowed(method, path, "POST");
    if (request.body.size() > config.limits.max_body_bytes)
      throw ApiError(ApiErrorKind::BodyTooLarge,
                     fmt::format("the body has {} bytes; this server takes at most {}", request.body.size(),
                                 config.limits.max_body_bytes),
                     Json{{"limit", "body_bytes"}, {"max", config.limits.max_body_bytes}});
    Job job(config);
    try {
      job.start(Weight::Light);
      return it->second(job, request.body);
    } catch (const Error& e) {
      return error_answer(e, job.model(), job.source());
    }
  }
  if (path == "/api/health") return get ? api_health(config) : method_not_allowed(method, path, "GET");
  if (path == "/api/examples") return get ? api_examples() : method_not_allowed(method, path, "GET");
  if (path.starts_with("/api/examples/"))
    return get ? api_example(path.substr(std::string("/api/examples/").size()))
               : method_not_allowed(method, path, "GET");
  if (path == "/api" || path.starts_with("/api/"))
    throw ApiError(ApiErrorKind::NotFound, "no endpoint " + path + "; see docs/web-api.md");
  if (!get) return method_not_allowed(method, path, "GET");
  return static_file(path);
}

ApiResponse answer_or_error(const ApiRequest& request, const ServerConfig& config) {
  try {
    return route(request, config);
  } catch (const ApiError& e) {
    return error_answer(e.kind(), e.what(), e.details());
  } catch (const Error& e) {
    return error_answer(e);
  } catch (const std::bad_alloc&) {
    return error_answer(ApiErrorKind::LimitExceeded, "the request needs more memory than the server has");
  } catch (const std::exception& e) {
    // A last resort: the library throws nbar::Error only, so this is a defect. The request id
    // ties the answer to the server's log.
    static std::atomic<unsigned long> requests{0};
    const std::string id = fmt::format("{:x}-{}", std::time(nullptr), requests.fetch_add(1));
    std::cerr << "nbar serve: internal error in request " << id << " (" << request.method << ' ' << request.path
              << "): " << e.what() << '\n';
    return error_answer(ApiErrorKind::Internal,
                        fmt::format("internal error: {} (request id {}; please report it)", e.what(), id),
                        Json{{"request_id", id}});
  }
}

// The language of the answer's messages: the body's "lang" when it gives one (every endpoint
// takes it beside its options), else the Accept-Language header's. The body is only looked into
// when it names the key, so that a large model is not parsed once more for nothing.
request::Language answer_language(const ApiRequest& request) {
  if (request.body.find("\"lang\"") != std::string::npos) {
    const Json body = Json::parse(request.body, nullptr, false);
    if (body.is_object() && body.contains("lang") && !body["lang"].is_null()) {
      if (!body["lang"].is_string()) throw request::OptionError("lang", "give the language as a text: en or es");
      return request::read_language(body["lang"].get<std::string>());
    }
  }
  return request::accept_language(request.accept_language);
}

}  // namespace

ApiResponse handle_api(const ApiRequest& request, const ServerConfig& config) {
  request::Language language = request::Language::English;
  try {
    language = answer_language(request);
  } catch (const Error& e) {
    return error_answer(e);
  }
  ApiResponse r = answer_or_error(request, config);
  if (language != request::Language::English && r.content_type.starts_with("application/json"))
    r.body = request::translate_json_answer(r.body, language, request::json_answer_indent(r.body));
  if (r.status == http_status(ApiErrorKind::TooManyJobs))
    r.headers.emplace_back("Retry-After", std::to_string(config.retry_after_seconds));
  return r;
}

ApiResponse body_too_large_response(const std::string& message, std::size_t max_body_bytes) {
  return error_answer(ApiErrorKind::BodyTooLarge, message, Json{{"limit", "body_bytes"}, {"max", max_body_bytes}});
}

ApiResponse held_answers_response(const std::string& message, std::size_t max_bytes, int retry_after_seconds) {
  ApiResponse r = error_answer(ApiErrorKind::TooManyJobs, message, Json{{"limit", "held_answers"}, {"max", max_bytes}});
  r.headers.emplace_back("Retry-After", std::to_string(retry_after_seconds));
  return r;
}

ApiResponse error_response(int status, const std::string& message) {
  // The front's refusals too: a client over its connections is told as a full server is (503
  // too_many_jobs), a transfer coding it does not take as not implemented; only a defect is internal.
  const ApiErrorKind kind = status == 413   ? ApiErrorKind::BodyTooLarge
                            : status == 404 ? ApiErrorKind::NotFound
                            : status == 405 ? ApiErrorKind::MethodNotAllowed
                            : status < 500  ? ApiErrorKind::BadInput
                            : status == 501 ? ApiErrorKind::NotImplemented
                            : status == 503 ? ApiErrorKind::TooManyJobs
                                            : ApiErrorKind::Internal;
  ApiResponse r = error_answer(kind, message);
  r.status = status;
  return r;
}

}  // namespace nbar::web
