// The API's endpoints, each a function of the job and the request's body (web/server/api.cpp
// routes to them). The ones with a request type (nbar/request) read their options through it, as
// the command line and Python do.
#pragma once

#include <string>

#include "job.hpp"
#include "nbar/synthesis/task.hpp"

namespace nbar::web {

// api_analysis.cpp
ApiResponse api_check(Job& job, const std::string& body);
ApiResponse api_outline(Job& job, const std::string& body);
ApiResponse api_solve(Job& job, const std::string& body);
ApiResponse api_stress(Job& job, const std::string& body);
ApiResponse api_stress_probe(Job& job, const std::string& body);
ApiResponse api_report(Job& job, const std::string& body);
ApiResponse api_explain(Job& job, const std::string& body);
// api_simulate.cpp: forward dynamics, and with a `scene` the web app's drawing of its motion
ApiResponse api_simulate(Job& job, const std::string& body);
ApiResponse api_simulate_cancel(Job& job, const std::string& body);
// api_render.cpp: draw, animate, plot or plates, by the body's `kind`
ApiResponse api_render(Job& job, const std::string& body);
// api_synth.cpp
ApiResponse api_synth(Job& job, const std::string& body, synthesis::SynthesisKind kind);
// api_static.cpp: what a GET reads, all of it built into the program
ApiResponse api_examples();
ApiResponse api_example(const std::string& name);
ApiResponse api_health(const ServerConfig& config);
ApiResponse static_file(const std::string& path);

// The request read from the body's options; `format` is JSON unless the body says otherwise (the
// command line's default is for a terminal).
template <class Request>
Request read_request(const RequestBody& body, const std::vector<std::string>& documents, bool json_format = false) {
  request::Options options = body.options(documents);
  if (json_format && !options.has("format")) options.set("format", std::string("json"));
  return Request::read(options);
}

}  // namespace nbar::web
