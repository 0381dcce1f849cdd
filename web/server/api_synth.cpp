// The synthesis endpoints: /api/synth/five-point, burmester, function, nine-point and path.
#include "endpoints.hpp"
#include "io/json_text.hpp"
#include "nbar/io/synthesis_task.hpp"
#include "nbar/io/synthesis_writer.hpp"
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

ApiResponse api_synth(Job& job, const std::string& request, synthesis::SynthesisKind kind) {
  const RequestBody body(request, {"task", "all", "top", "seed", "threads", "models"});
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
  const long long top = body.integer("top", 0, std::numeric_limits<int>::max()).value_or(20);
  check_limit("top", static_cast<double>(top), job.limits.max_synthesis_top, "top");
  const unsigned max_threads = std::max(1u, job.limits.max_synthesis_threads);
  synthesis::SynthesisRunOptions run;
  run.threads = static_cast<unsigned>(body.integer("threads", 1, 1024).value_or(max_threads));
  check_limit("threads", run.threads, max_threads, "threads");
  if (body.has("seed"))
    run.seed = static_cast<std::uint64_t>(*body.integer("seed", 0, std::numeric_limits<long long>::max()));
  job.start(Weight::Heavy);
  run.control = job.control;
  const synthesis::SynthesisOutcome outcome = synthesis::run_synthesis(task, run);
  io::SynthesisListing listing;
  listing.all = body.flag("all");
  // top 0 lists every design (the CLI's meaning), here at most the limit.
  listing.shown =
      synthesis::shown_rows(outcome, listing.all, top == 0 ? job.limits.max_synthesis_top : static_cast<int>(top));
  if (!body.flag("models")) return answer(io::synthesis_json(task, outcome, listing));
  return answer(with_design_models(io::synthesis_json(task, outcome, listing), task, outcome, listing));
}

}  // namespace nbar::web
