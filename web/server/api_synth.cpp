// The synthesis endpoints: /api/synth/five-point, burmester, function, nine-point and path.
#include "endpoints.hpp"
#include "io/json_text.hpp"
#include "nbar/io/synthesis_task.hpp"
#include "nbar/io/synthesis_writer.hpp"
#include "nbar/request/synthesis_request.hpp"
#include "nbar/synthesis/run.hpp"

namespace nbar::web {

namespace {

// "models": true adds each listed design's model file (what `nbar synth --export` writes for
// it), so a client opens a design without writing a model of its own.
std::string with_design_models(const std::string& json, const synthesis::SynthesisTask& task,
                               const synthesis::SynthesisOutcome& outcome, const io::SynthesisListing& listing) {
  Json j = Json::parse(json);
  Json& designs = j["designs"];
  for (std::size_t k = 0; k < designs.size() && k < listing.shown.size(); ++k) {
    if (!designs[k].value("real", false) || !designs[k].value("valid", false)) continue;
    designs[k]["model"] = io::design_model_yaml(task, outcome, listing.shown[k], static_cast<int>(k) + 1);
  }
  return j.dump(2) + '\n';
}

}  // namespace

ApiResponse api_synth(Job& job, const std::string& text, synthesis::SynthesisKind kind) {
  // "models" is this endpoint's own: the designs' model files in the answer.
  const RequestBody body(text, request::SynthesisRequest::rules(kind), {"task", "models"});
  const bool with_models = body.flag("models");
  request::Options options = body.options({"task", "models"});
  if (!options.has("format")) options.set("format", std::string("json"));
  const auto synth = request::SynthesisRequest::read(kind, options);
  const synthesis::SynthesisTask task =
      io::parse_synthesis_task(body.text("task", true), "task", io::CurveFiles::refused);  // opens no file
  if (task.kind != kind)
    bad_input("this is a " + io::to_string(task.kind) + " task: send it to /api/synth/" + io::to_string(task.kind));
  if (task.kind == synthesis::SynthesisKind::Burmester && task.poses.size() == 4 && task.curves.step > 0) {
    if (task.curves.radius <= 0)
      throw ApiError(ApiErrorKind::LimitExceeded, "curves: this server needs `radius` when `step` is given",
                     Json{{"limit", "curve_samples"}, {"max", json_number(job.limits.max_curve_samples)}});
    check_limit("curve_samples", task.curves.radius / task.curves.step, job.limits.max_curve_samples,
                "curves: radius / step");
  }
  check_limit("top", static_cast<double>(synth.top), job.limits.max_synthesis_top, "top");
  // Every hardware thread (threads 0) is, here, as many as this server gives one request.
  const unsigned max_threads = std::max(1u, job.limits.max_synthesis_threads);
  synthesis::SynthesisRunOptions run = synth.run_options();
  if (run.threads == 0) run.threads = max_threads;
  check_limit("threads", run.threads, max_threads, "threads");
  job.start(Weight::Heavy);
  run.control = job.control;
  const synthesis::SynthesisOutcome outcome = synthesis::run_synthesis(task, run);
  // top 0 lists every design (the CLI's meaning), here at most the limit.
  request::SynthesisRequest listed = synth;
  if (listed.top == 0) listed.top = job.limits.max_synthesis_top;
  const io::SynthesisListing listing = listed.listing(outcome);
  const std::string answer_text = synth.answer(task, outcome, listing);
  if (synth.format != "json") return answer(answer_text, "text/plain; charset=utf-8");
  if (!with_models) return answer(answer_text);
  return answer(with_design_models(answer_text, task, outcome, listing));
}

}  // namespace nbar::web
