// The web API in WebAssembly: JavaScript hands a request (method, path, body) to the same
// handle_api that `nbar serve` answers with, and gets its status, content type and bytes back.
// nbar.mjs beside this file wraps it as the module's `request(path, body)`.
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <cstdint>
#include <string>

#include "nbar/version.hpp"
#include "nbar/web/api.hpp"

namespace {

using emscripten::val;

// The server's limits and time budget, on one thread: the browser engine has no shared memory
// (a static host gives no cross-origin isolation), so synthesis tracks its paths on one.
nbar::web::ServerConfig& engine_config() {
  static nbar::web::ServerConfig config = [] {
    nbar::web::ServerConfig defaults;
    defaults.limits.max_synthesis_threads = 1;
    return defaults;
  }();
  return config;
}

// As `nbar serve --time-budget S`: a program (not a page) may give its long jobs, a nine-point
// synthesis on one thread, longer than the server's 30 s. nbar.mjs checks the value.
void set_time_budget(double seconds) { engine_config().limits.time_budget_seconds = seconds; }

// {status, contentType, headers: [[name, value]...], body: Uint8Array}; the body is copied out of
// the module's memory, which the next request may reuse.
val answer_of(const nbar::web::ApiRequest& api_request, const nbar::web::ServerConfig& config) {
  const nbar::web::ApiResponse response = nbar::web::handle_api(api_request, config);
  val answer = val::object();
  answer.set("status", response.status);
  answer.set("contentType", response.content_type);
  val headers = val::array();
  for (const auto& [name, value] : response.headers) {
    val header = val::array();
    header.call<void>("push", name, value);
    headers.call<void>("push", header);
  }
  answer.set("headers", headers);
  const auto* bytes = reinterpret_cast<const std::uint8_t*>(response.body.data());
  answer.set("body", val::global("Uint8Array").new_(emscripten::typed_memory_view(response.body.size(), bytes)));
  return answer;
}

val request(const std::string& method, const std::string& path, const std::string& body) {
  return answer_of({method, path, body}, engine_config());
}

// The same request, calling on_progress(stage, done, total) at every checkpoint of its
// computation (sweep samples, FE links, synthesis paths...), for a page's progress bar. An answer
// of false from on_progress stops the computation as a cancel does (a simulation then answers
// with its rows so far); anything else lets it go on. A page may also cancel by ending the worker
// the engine runs in.
val request_with_progress(const std::string& method, const std::string& path, const std::string& body,
                          val on_progress) {
  nbar::web::ServerConfig config = engine_config();
  config.on_progress = [&on_progress](const nbar::Progress& progress) {
    const val go_on = on_progress(std::string(progress.stage), static_cast<double>(progress.done),
                                  static_cast<double>(progress.total));
    return !go_on.strictlyEquals(val(false));
  };
  return answer_of({method, path, body}, config);
}

std::string version() { return nbar::kVersion; }

}  // namespace

EMSCRIPTEN_BINDINGS(nbar_engine) {
  emscripten::function("request", &request);
  emscripten::function("requestWithProgress", &request_with_progress);
  emscripten::function("version", &version);
  emscripten::function("setTimeBudget", &set_time_budget);
}
