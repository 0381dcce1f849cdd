// One request's computation on the server: its limits, its job slot, its deadline, the model it
// loaded, and the helpers every endpoint answers with.
#pragma once

#include <fmt/format.h>

#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "api_internal.hpp"
#include "nbar/analysis/analysis.hpp"
#include "nbar/io/model_file.hpp"
#include "nbar/request/language.hpp"
#include "request_body.hpp"

namespace nbar::web {

// How much a computation asks of the machine, for the choice of its job slots.
enum class Weight { Light, Heavy };

// One request's computation: its limits, its job slot, its deadline, and what the error answer
// may point at.
struct Job {
  const ServerConfig& config;
  const Limits& limits;
  RunControl control;
  std::optional<io::LoadedModel> file;
  std::string text;  // the model's text, as parsed
  std::shared_ptr<const Mechanism> mechanism;
  JobSlots::Slot slot;
  // The language of the answer's messages (the body's `lang` or Accept-Language): handle_api says
  // a JSON answer's messages in it; an endpoint that carries a JSON document inside its answer as
  // a text says that text's (request/answer_language.hpp).
  request::Language language = request::Language::English;

  explicit Job(const ServerConfig& c) : config(c), limits(c.limits) { control.on_progress = c.on_progress; }
  const Model* model() const { return file ? &file->model : nullptr; }
  const io::SourceMap* source() const { return file ? &file->source : nullptr; }
  // Waits for a job slot of its weight. Every request takes a light slot before it reads its
  // body, so that parsing and checking the model (a plate of 20 000 holes, a drawing of
  // thousands of entities) run inside a slot and under the deadline; a computation found heavy
  // then trades its light slot for a heavy one. The time budget runs from the first slot and
  // counts all the work; a wait for the heavy slot is not counted (it is bounded on its own).
  void start(Weight weight) {
    if (slot && (weight == Weight::Light || weight_ == Weight::Heavy)) return;
    const auto spent = slot ? std::chrono::steady_clock::now() - started_ : std::chrono::steady_clock::duration{};
    slot = JobSlots::Slot();  // a light slot is given back before the heavy one is waited for
    JobSlots& slots = weight == Weight::Heavy ? *config.jobs : *config.light_jobs;
    slot = slots.acquire(std::chrono::duration<double>(config.queue_wait_seconds));
    if (!slot)
      throw ApiError(ApiErrorKind::TooManyJobs,
                     fmt::format("the server is busy ({} {} computations running, {} waiting); try again in a moment",
                                 slots.total(), weight == Weight::Heavy ? "heavy" : "light", slots.waiting()),
                     Json{{"limit", weight == Weight::Heavy ? "jobs" : "light_jobs"}, {"max", slots.total()}});
    weight_ = weight;
    started_ = std::chrono::steady_clock::now() - spent;
    control.token.set_time_budget(std::chrono::duration<double>(limits.time_budget_seconds) - spent);
  }
  // Between stages that do not check the deadline themselves.
  void checkpoint(const char* stage) const { control.checkpoint(stage, 0, 0); }

 private:
  Weight weight_ = Weight::Light;
  std::chrono::steady_clock::time_point started_;
};

constexpr const char* kModelFile = "model";  // the model's name in messages

// Parses, checks the size limits and compiles the model; errors are located in its text.
void load_model(Job& job, const std::string& text);
// The sweep's number of samples against the server's limit (413), placed at the model's
// `sweep:` when the model's own sweep is over it.
void check_sweep_size(const Job& job, std::optional<int> steps);
// The table a solve or plot builds, samples x columns, against the limit.
double table_values(const Job& job, const AnalysisOptions& options);
void check_table_size(const Job& job, const AnalysisOptions& options);
// Runs the analysis in a job slot (heavy for stresses and large tables), under the deadline.
Analysis run_analysis(Job& job, AnalysisOptions options);

ApiResponse answer(std::string body, std::string content_type = "application/json");
ApiResponse answer_bytes(const std::vector<std::uint8_t>& bytes, std::string content_type);
// HTML from the API runs in a sandbox of its own: its scripts cannot act for the page's origin.
ApiResponse answer_html(std::string html);
// What a writer writes, as text.
std::string write(const std::function<void(std::ostream&)>& writer);
// The content type of a table's format: json, csv or text.
const char* text_type(const std::string& format);

}  // namespace nbar::web
