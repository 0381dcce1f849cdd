// The JSON API: each endpoint reads its body's options (the CLI's long option names), calls the
// library as the CLI does and answers with the library's own writers, so that an answer is
// byte for byte what `nbar ... --format json` prints. Nothing is kept between requests.
#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <thread>
#include <unordered_set>

#include "api_internal.hpp"
#include "nbar/io/json_text.hpp"
#include "nbar/analysis/analysis.hpp"
#include "nbar/analysis/columns.hpp"
#include "nbar/analysis/explain.hpp"
#include "nbar/analysis/pose.hpp"
#include "nbar/io/dxf_writer.hpp"
#include "nbar/analysis/summary.hpp"
#include "nbar/io/model_file.hpp"
#include "nbar/io/explain_writer.hpp"
#include "nbar/io/results_writer.hpp"
#include "nbar/io/summary_writer.hpp"
#include "nbar/io/synthesis_task.hpp"
#include "nbar/io/synthesis_writer.hpp"
#include "nbar/io/yaml_support.hpp"
#include "nbar/kinematics/sweep.hpp"
#include "nbar/render/animation.hpp"
#include "nbar/render/image_canvas.hpp"
#include "nbar/render/pictures.hpp"
#include "nbar/render/plot.hpp"
#include "nbar/render/report.hpp"
#include "nbar/render/scene.hpp"
#include "nbar/synthesis/run.hpp"
#include "nbar/version.hpp"
#include "nbar/web/embedded.hpp"

namespace nbar::web {

namespace {

// ------------------------------------------------------------------------------ request bodies

[[noreturn]] void bad_input(const std::string& message) { throw ApiError(ApiErrorKind::BadInput, message); }

// Line and column (1-based) of a byte offset in a text.
std::pair<int, int> line_column(const std::string& text, std::size_t offset) {
  int line = 1, column = 1;
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return {line, column};
}

// A model or task sent as a JSON object is read as the indented JSON text it makes. Its depth,
// and a bound on that text's size, are checked before it is written: the writer recurses once a
// level (a 200 kB body nested 100 000 deep overflowed the stack), and every level indents every
// line below it (20 000 levels in 40 kB made 800 MB of text).
void check_document_shape(const nlohmann::json& document, const char* key) {
  constexpr int kMaxDepth = 64;
  constexpr std::size_t kPerValue = 40;  // a number's digits, punctuation, a line end
  std::vector<std::pair<const nlohmann::json*, int>> stack{{&document, 1}};
  std::size_t bound = 0;
  while (!stack.empty()) {
    const auto [node, depth] = stack.back();
    stack.pop_back();
    if (depth > kMaxDepth) bad_input(fmt::format("'{}' nests deeper than {} levels", key, kMaxDepth));
    bound += 2 * static_cast<std::size_t>(depth) + kPerValue;
    if (node->is_string()) bound += 6 * node->get_ref<const std::string&>().size();  // \uXXXX at worst
    if (node->is_object()) {
      for (auto it = node->begin(); it != node->end(); ++it) {
        bound += 6 * it.key().size();
        stack.emplace_back(&*it, depth + 1);
      }
    } else if (node->is_array()) {
      for (const nlohmann::json& child : *node) stack.emplace_back(&child, depth + 1);
    }
  }
  check_limit("model_bytes", static_cast<double>(bound), static_cast<double>(io::yaml::kMaxFileBytes),
              fmt::format("the size of '{}' written out as indented JSON (a bound, in bytes)", key));
}

// The request's JSON, with every object's keys told apart: nlohmann keeps the last of a key given
// twice ({"steps": 5, "steps": 500}), silently. The parser's events are followed with a set of
// the keys seen in each open object (only while parsing); the first key given twice is a 400
// naming it and where it is ("model.points"), before anything else is read.
nlohmann::json parse_request(const std::string& text) {
  struct Open {
    std::unordered_set<std::string> keys;
    std::string name;  // this object's own key in its parent, "[]" inside a list
  };
  std::vector<Open> open;
  std::string key;  // the last key read: the name of an object that starts next
  return nlohmann::json::parse(text, [&](int, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    using Event = nlohmann::json::parse_event_t;
    switch (event) {
      case Event::object_start:
      case Event::array_start:
        open.push_back({{}, open.empty() ? std::string() : key});
        key = "[]";  // a list's items have no key of their own
        break;
      case Event::object_end:
      case Event::array_end:
        if (!open.empty()) open.pop_back();
        key = "[]";
        break;
      case Event::key:
        key = parsed.get<std::string>();
        if (!open.empty() && !open.back().keys.insert(key).second) {
          std::string where;
          for (const Open& o : open)
            if (!o.name.empty()) where += (where.empty() || o.name == "[]" ? "" : ".") + o.name;
          throw ApiError(ApiErrorKind::BadJson,
                         where.empty() ? fmt::format("the body gives '{}' twice; give each option once", key)
                                       : fmt::format("the body gives the key '{}' twice in '{}'", key, where),
                         Json{{"key", key}});
        }
        break;
      case Event::value:
        break;
    }
    return true;
  });
}

// The request's JSON object, read option by option; every key must be one the endpoint knows.
class Body {
 public:
  Body(const std::string& text, std::vector<std::string> allowed) {
    try {
      json_ = parse_request(text);
    } catch (const nlohmann::json::parse_error& e) {
      const auto [line, column] = line_column(text, e.byte > 0 ? e.byte - 1 : 0);
      throw ApiError(ApiErrorKind::BadJson, std::string("the body is not valid JSON: ") + e.what(),
                     Json{{"line", line}, {"column", column}});
    } catch (const nlohmann::json::exception& e) {
      // A number beyond a double's range (1e400): the parser gives no place for it.
      throw ApiError(ApiErrorKind::BadJson, std::string("the body is not valid JSON: ") + e.what());
    }
    if (!json_.is_object())
      throw ApiError(ApiErrorKind::BadJson, "the body must be a JSON object, e.g. {\"model\": \"...\"}");
    for (const auto& [key, value] : json_.items()) {
      if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
        std::string list;
        for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
        bad_input("unknown option '" + key + "'; this endpoint takes: " + list);
      }
    }
  }

  bool has(const char* key) const { return json_.contains(key) && !json_[key].is_null(); }

  // A text (or, for `model` and `task`, a JSON object, read as the same document).
  std::string text(const char* key, bool document = false) const {
    if (!has(key)) bad_input(std::string("missing '") + key + "'");
    const nlohmann::json& v = json_[key];
    if (v.is_string()) return v.get<std::string>();
    if (document && v.is_object()) {
      check_document_shape(v, key);
      return io::json_text(v, 2) + "\n";
    }
    bad_input(std::string("'") + key + "' must be " + (document ? "the text of a YAML or JSON document" : "a string"));
  }
  std::optional<std::string> optional_text(const char* key) const {
    if (!has(key)) return std::nullopt;
    return text(key);
  }
  // An integer in [lo, hi] (the CLI's range); larger values than `limit` are over the server's
  // limit (413), other values outside the range are bad input (400).
  // `shown_hi`, when given, is the top of the range the message names: the server's limit
  // (checked after, with its own answer) when it is lower than what the option could ever be.
  std::optional<long long> integer(const char* key, long long lo, long long hi, long long shown_hi = -1) const {
    if (!has(key)) return std::nullopt;
    const nlohmann::json& v = json_[key];
    const auto out_of_range = [&](const std::string& shown) {
      bad_input(fmt::format("'{}' must be from {} to {}; it is {}", key, lo, shown_hi >= lo ? shown_hi : hi, shown));
    };
    if (v.is_number_unsigned()) {
      const unsigned long long u = v.get<unsigned long long>();
      if (u > static_cast<unsigned long long>(hi) || (lo > 0 && u < static_cast<unsigned long long>(lo)))
        out_of_range(std::to_string(u));
      return static_cast<long long>(u);
    }
    if (v.is_number_integer()) {
      const long long i = v.get<long long>();
      if (i < lo || i > hi) out_of_range(std::to_string(i));
      return i;
    }
    if (v.is_number_float()) {
      const double d = v.get<double>();
      if (!(std::isfinite(d) && std::floor(d) == d)) bad_input(std::string("'") + key + "' must be a whole number");
      if (d < static_cast<double>(lo) || d > static_cast<double>(hi)) out_of_range(fmt::format("{}", d));
      return static_cast<long long>(d);
    }
    bad_input(std::string("'") + key + "' must be a whole number");
  }
  std::optional<double> number(const char* key) const {
    if (!has(key)) return std::nullopt;
    const nlohmann::json& v = json_[key];
    if (!v.is_number() || !std::isfinite(v.get<double>())) bad_input(std::string("'") + key + "' must be a number");
    return v.get<double>();
  }
  bool flag(const char* key) const {
    if (!has(key)) return false;
    if (!json_[key].is_boolean()) bad_input(std::string("'") + key + "' must be true or false");
    return json_[key].get<bool>();
  }
  // A list of names: an array of strings, or one comma-separated string (as on the command line).
  std::vector<std::string> list(const char* key) const {
    std::vector<std::string> out;
    if (!has(key)) return out;
    const nlohmann::json& v = json_[key];
    if (v.is_string()) {
      std::stringstream in(v.get<std::string>());
      for (std::string item; std::getline(in, item, ',');)
        if (!item.empty()) out.push_back(item);
      return out;
    }
    if (v.is_array()) {
      for (const auto& item : v) {
        if (!item.is_string()) bad_input(std::string("'") + key + "' must be a list of names");
        out.push_back(item.get<std::string>());
      }
      return out;
    }
    bad_input(std::string("'") + key + "' must be a list of names or a comma-separated string");
  }
  std::vector<double> numbers(const char* key) const {
    std::vector<double> out;
    if (!has(key)) return out;
    const nlohmann::json& v = json_[key];
    if (!v.is_array()) bad_input(std::string("'") + key + "' must be a list of numbers");
    for (const auto& item : v) {
      if (!item.is_number() || !std::isfinite(item.get<double>()))
        bad_input(std::string("'") + key + "' must be a list of numbers");
      out.push_back(item.get<double>());
    }
    return out;
  }
  std::string choice(const char* key, const std::vector<std::string>& choices, const std::string& otherwise) const {
    if (!has(key)) return otherwise;
    const std::string value = text(key);
    if (std::find(choices.begin(), choices.end(), value) != choices.end()) return value;
    std::string list;
    for (const std::string& c : choices) list += (list.empty() ? "" : ", ") + c;
    bad_input(std::string("'") + key + "' must be one of: " + list + "; it is '" + value + "'");
  }

 private:
  nlohmann::json json_;
};

// ------------------------------------------------------------------------------------ context

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

  explicit Job(const ServerConfig& c) : config(c), limits(c.limits) {
    control.on_progress = c.on_progress;
    start_clock();
  }
  const Model* model() const { return file ? &file->model : nullptr; }
  const io::SourceMap* source() const { return file ? &file->source : nullptr; }
  // Waits for a job slot of its weight (the first call only; the request is read and checked
  // against the limits before, so that nothing over a limit ever waits). The time budget runs
  // from the moment the slot is held: waiting is bounded on its own.
  void start(Weight weight) {
    if (slot) return;
    JobSlots& slots = weight == Weight::Heavy ? *config.jobs : *config.light_jobs;
    slot = slots.acquire(std::chrono::duration<double>(config.queue_wait_seconds));
    if (!slot)
      throw ApiError(ApiErrorKind::TooManyJobs,
                     fmt::format("the server is busy ({} {} computations running, {} waiting); try again in a moment",
                                 slots.total(), weight == Weight::Heavy ? "heavy" : "light", slots.waiting()),
                     Json{{"limit", weight == Weight::Heavy ? "jobs" : "light_jobs"}, {"max", slots.total()}});
    start_clock();
  }
  // Between stages that do not check the deadline themselves.
  void checkpoint(const char* stage) const { control.checkpoint(stage, 0, 0); }

 private:
  void start_clock() { control.token.set_time_budget(std::chrono::duration<double>(limits.time_budget_seconds)); }
};

constexpr const char* kModelFile = "model";  // the model's name in messages

// Parses, checks the size limits and compiles the model; errors are located in its text.
void load_model(Job& job, const std::string& text) {
  job.file = io::parse_model(text, kModelFile);
  job.text = text;
  const Model& m = job.file->model;
  check_limit("points", static_cast<double>(m.points.size()), job.limits.max_points, "the number of points");
  check_limit("bodies", static_cast<double>(m.bodies.size()), job.limits.max_bodies, "the number of bodies");
  try {
    job.mechanism = std::make_shared<const Mechanism>(m);
  } catch (const ModelError& e) {
    throw Error(ErrorKind::InvalidModel, e.message(), e.where(), kModelFile, job.file->source.find(e.where()));
  }
}

// Where the model's text sets its sweep's number of samples: the value of `sweep: {steps}`, or
// for a sweep in time its `step` (else `duration`); the `sweep:` key when none is written there.
// The source map marks the sweep at its key only, so the text is read again (an error's path:
// the text was parsed once already, and is within the body's limit).
SourceMark sweep_size_mark(const Job& job) {
  const io::SourceMap& source = job.file->source;
  const SourceMark fallback = source.sweep.line > 0 ? source.sweep : source.model;
  try {
    const YAML::Node sweep = YAML::Load(job.text)["sweep"];
    if (!sweep.IsMap()) return fallback;
    const bool in_time = job.mechanism->model().has_time_law();
    for (const char* key : {"steps", "step", "duration"}) {
      if (!in_time && std::string_view(key) != "steps") continue;
      const YAML::Node value = sweep[key];
      if (value && !value.IsNull()) return io::yaml::mark(value);
    }
  } catch (const YAML::Exception&) {
    // The model parser read this text; a second reading that fails keeps the sweep's key.
  }
  return fallback;
}

// The steps option (a positive number, as the CLI's) and the sweep's size against the limit. A
// sweep over it by the model's own `sweep:` is said at that place in the model's text, as the
// model's other errors are, so that an editor underlines it.
std::optional<int> sweep_steps(const Job& job, const Body& body) {
  std::optional<int> steps;
  if (auto s = body.integer("steps", 1, std::numeric_limits<int>::max())) steps = static_cast<int>(*s);
  try {
    check_limit("steps", sweep_sample_count(job.mechanism->model(), steps), job.limits.max_steps,
                "the number of samples of the sweep");
  } catch (const ApiError& e) {
    if (steps) throw;
    Json details = e.details();
    const SourceMark at = sweep_size_mark(job);
    details["file"] = kModelFile;
    if (at.line > 0) {
      details["line"] = at.line;
      details["column"] = at.column;
    }
    throw ApiError(e.kind(), e.what(), details);
  }
  return steps;
}

// The table a solve or plot builds, samples x columns, against the limit (its memory and the
// answer's size grow with it).
double table_values(const Job& job, const AnalysisOptions& options) {
  const double samples = sweep_sample_count(job.mechanism->model(), options.steps);
  const int order = options.dynamics ? std::max(2, options.order) : options.order;
  return samples * static_cast<double>(column_catalogue(*job.mechanism, order, options.dynamics).size());
}

void check_table_size(const Job& job, const AnalysisOptions& options) {
  const double values = table_values(job, options);
  const double samples = sweep_sample_count(job.mechanism->model(), options.steps);
  check_limit("table_values", values, job.limits.max_table_values,
              fmt::format("the table (samples x columns, {} columns)", values / samples));
}

// Stresses and large tables are heavy; a sweep that asks neither is light.
Analysis run_analysis(Job& job, AnalysisOptions options) {
  job.start(options.stress || table_values(job, options) > job.config.light_table_values ? Weight::Heavy : Weight::Light);
  options.control = job.control;
  return analyse(job.mechanism, options);
}

ApiResponse answer(std::string body, std::string content_type = "application/json") {
  ApiResponse r;
  r.body = std::move(body);
  r.content_type = std::move(content_type);
  return r;
}

ApiResponse answer_bytes(const std::vector<std::uint8_t>& bytes, std::string content_type) {
  return answer(std::string(bytes.begin(), bytes.end()), std::move(content_type));
}

// HTML from the API runs in a sandbox of its own: its scripts cannot act for the page's origin.
ApiResponse answer_html(std::string html) {
  ApiResponse r = answer(std::move(html), "text/html; charset=utf-8");
  r.headers.emplace_back("Content-Security-Policy", "sandbox allow-scripts");
  return r;
}

// ---------------------------------------------------------------------------------- endpoints

ApiResponse api_check(Job& job, const std::string& request) {
  const Body body(request, {"model"});
  load_model(job, body.text("model", true));
  job.start(Weight::Light);
  const ModelSummary summary = summarize(*job.mechanism);
  return answer(io::summary_json(*job.mechanism, summary, job.file->source));
}

std::string write(const std::function<void(std::ostream&)>& writer) {
  std::ostringstream out;
  writer(out);
  return out.str();
}

const char* text_type(const std::string& format) {
  return format == "json" ? "application/json" : format == "csv" ? "text/csv; charset=utf-8" : "text/plain; charset=utf-8";
}

ApiResponse api_solve(Job& job, const std::string& request) {
  const Body body(request, {"model", "steps", "order", "columns", "dynamics", "format"});
  const std::string format = body.choice("format", {"json", "csv", "table"}, "json");
  load_model(job, body.text("model", true));
  AnalysisOptions options;
  options.steps = sweep_steps(job, body);
  options.order = static_cast<int>(body.integer("order", 0, 5).value_or(2));
  options.dynamics = body.flag("dynamics");
  const std::vector<std::string> columns = body.list("columns");
  check_table_size(job, options);
  const Analysis analysis = run_analysis(job, options);
  ResultTable table = result_table(analysis);
  if (!columns.empty()) {
    try {
      table = select_columns(table, columns);
    } catch (const std::invalid_argument& e) {
      std::string names;
      for (const std::string& n : column_names(column_catalogue(*job.mechanism, 2, false)))
        names += (names.empty() ? "" : ", ") + n;
      bad_input(std::string("columns: ") + e.what() + "; the columns are: " + names);
    }
  }
  return answer(write([&](std::ostream& out) {
                  io::write_table(out, format, analysis, table, analysis.dynamics ? &*analysis.dynamics : nullptr,
                                  io::kTextTableWidth);
                }),
                text_type(format));
}

ApiResponse api_stress(Job& job, const std::string& request) {
  const Body body(request, {"model", "steps", "sections", "format", "section_profile", "step", "method", "mesh_size"});
  const std::string format = body.choice("format", {"json", "csv", "table"}, "json");
  load_model(job, body.text("model", true));
  AnalysisOptions options;
  options.steps = sweep_steps(job, body);
  options.stress = true;
  if (body.choice("method", {"beam", "fe"}, "beam") == "fe") {
    options.stress_method = StressMethod::fe;
    options.fe.max_nodes = job.limits.max_fe_nodes;
    if (const std::optional<double> size = body.number("mesh_size")) {
      if (!(*size > 0.0)) bad_input("'mesh_size' must be a positive length (in the model's unit)");
      options.fe.mesh_size = *size * job.mechanism->model().units.length_scale;
    }
  } else if (body.has("mesh_size")) {
    bad_input("'mesh_size' is the finite elements': give \"method\": \"fe\" too");
  }
  const long long sections = body.integer("sections", kMinSectionsPerLink, kMaxSectionsPerLink, job.limits.max_sections).value_or(200);
  check_limit("sections", static_cast<double>(sections), job.limits.max_sections, "the number of sections per link");
  options.sections = static_cast<int>(sections);
  const std::optional<std::string> profile = body.optional_text("section_profile");
  const std::optional<long long> step = body.integer("step", 0, std::numeric_limits<int>::max());
  if (step && !profile) bad_input("'step' is the step of 'section_profile': give both");
  int profile_body = -1;
  if (profile) {
    profile_body = job.mechanism->model().find_body(*profile);
    if (profile_body < 0) bad_input("section_profile: '" + *profile + "' is not a body of the model");
  }
  const Analysis analysis = run_analysis(job, options);
  if (!profile) return answer(write([&](std::ostream& out) { io::write_stress_report(out, format, analysis); }), text_type(format));
  if (!analysis.stress->links) bad_input("section_profile cuts sections, which the beam method has: leave out \"method\": \"fe\"");
  if (!analysis.stress->links->analysed(profile_body)) bad_input("section_profile: '" + *profile + "' has no shape to cut");
  const ResultTable t = section_profile_table(analysis, profile_body, static_cast<int>(step.value_or(0)));
  return answer(write([&](std::ostream& out) { io::write_table(out, format, analysis, t); }), text_type(format));
}

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

ApiResponse api_synth(Job& job, const std::string& request, synthesis::SynthesisKind kind) {
  const Body body(request, {"task", "all", "top", "seed", "threads", "models"});
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
  if (body.has("seed")) run.seed = static_cast<std::uint64_t>(*body.integer("seed", 0, std::numeric_limits<long long>::max()));
  job.start(Weight::Heavy);
  run.control = job.control;
  const synthesis::SynthesisOutcome outcome = synthesis::run_synthesis(task, run);
  io::SynthesisListing listing;
  listing.all = body.flag("all");
  // top 0 lists every design (the CLI's meaning), here at most the limit.
  listing.shown = synthesis::shown_rows(outcome, listing.all, top == 0 ? job.limits.max_synthesis_top : static_cast<int>(top));
  if (!body.flag("models")) return answer(io::synthesis_json(task, outcome, listing));
  return answer(with_design_models(io::synthesis_json(task, outcome, listing), task, outcome, listing));
}

render::DrawOptions draw_options(const Job& job, const Body& body, int min_size, int width, int height) {
  render::DrawOptions draw;
  // The range named in a message is this server's (max_pixels), the limit checked below.
  draw.width = static_cast<int>(body.integer("width", min_size, 10000, job.limits.max_pixels).value_or(width));
  draw.height = static_cast<int>(body.integer("height", min_size, 10000, job.limits.max_pixels).value_or(height));
  check_limit("pixels", draw.width, job.limits.max_pixels, "width");
  check_limit("pixels", draw.height, job.limits.max_pixels, "height");
  draw.labels = body.flag("labels");
  if (auto title = body.optional_text("title")) draw.title = *title;
  try {
    draw.traces = render::trace_points(job.mechanism->model(), body.list("trace"));
  } catch (const Error& e) {
    bad_input("trace: " + e.message());
  }
  return draw;
}

const std::vector<std::string> kDrawKeys{"model", "kind", "format", "step", "at", "steps", "labels", "trace",
                                         "width", "height", "title"};
const std::vector<std::string> kAnimateKeys{"model", "kind", "format", "steps", "labels", "trace",
                                            "width", "height", "frames", "fps"};
const std::vector<std::string> kPlotKeys{"model", "kind", "format", "y", "x", "steps", "order", "dynamics",
                                         "y_range", "width", "height", "title"};
const std::vector<std::string> kPlatesKeys{"model", "kind", "format", "at"};

// The links' plates for cutting, as `nbar export --dxf/--svg [--at]` writes them.
ApiResponse render_plates(Job& job, const std::string& request) {
  const Body body(request, kPlatesKeys);
  const std::string format = body.choice("format", {"svg", "dxf"}, "svg");
  load_model(job, body.text("model", true));
  const Mechanism& mech = *job.mechanism;
  job.start(Weight::Light);
  std::vector<Eigen::Vector2d> points;
  for (const Point& p : mech.model().points) points.push_back(p.position);
  if (const std::optional<double> at = body.number("at"))
    points = point_positions(mech, pose_at(mech, *at, 0, job.control).taylor.col(0));
  if (format == "dxf") return answer(io::cutting_dxf(mech, points), "image/vnd.dxf");
  return answer(io::cutting_svg(mech, points), "image/svg+xml");
}

ApiResponse render_draw(Job& job, const std::string& request) {
  const Body body(request, kDrawKeys);
  const std::string format = body.choice("format", {"svg", "png", "scene"}, "svg");
  if (body.has("step") && body.has("at")) bad_input("give 'step' or 'at', not both");
  if (format == "scene" && body.has("at")) bad_input("a scene is drawn at a solved step: give 'step', not 'at'");
  load_model(job, body.text("model", true));
  const render::DrawOptions draw = draw_options(job, body, 100, 900, 640);
  AnalysisOptions options;
  options.steps = sweep_steps(job, body);
  options.order = 0;
  const std::optional<long long> step = body.integer("step", 0, std::numeric_limits<int>::max());
  const std::optional<double> at = body.number("at");
  // A scene carries every sample's positions: a table as large as a solve's of positions.
  if (format == "scene") check_table_size(job, options);
  const Analysis analysis = run_analysis(job, options);
  const Mechanism& mech = *job.mechanism;
  std::vector<Eigen::Vector2d> points;
  if (at) {
    points = render::sample_points(mech, pose_at(mech, *at, 0, job.control));
  } else {
    const long long k = step.value_or(render::default_drawn_step(mech, analysis.sweep));
    if (k >= static_cast<long long>(analysis.sweep.samples.size()))
      bad_input(fmt::format("step {} is not a solved step (0 to {})", k, analysis.sweep.samples.size() - 1));
    points = render::sample_points(mech, analysis.sweep.samples[static_cast<std::size_t>(k)]);
  }
  job.checkpoint("render");
  if (format == "scene")
    return answer(render::drawing_scene_json(mech, analysis.sweep, draw,
                                             static_cast<int>(step.value_or(render::default_drawn_step(mech, analysis.sweep)))));
  if (format == "svg") return answer(render::drawing_svg(mech, analysis.sweep, points, draw), "image/svg+xml");
  return answer_bytes(render::drawing_png(mech, analysis.sweep, points, draw), "image/png");
}

ApiResponse render_animate(Job& job, const std::string& request) {
  const Body body(request, kAnimateKeys);
  const std::string format = body.choice("format", {"gif", "svg", "html", "mp4"}, "html");
  if (format == "mp4" && !render::Animation::program_available("ffmpeg"))
    throw ApiError(ApiErrorKind::NotImplemented,
                   "MP4 needs the ffmpeg program on the server (apt-get install ffmpeg); GIF, SVG and HTML work without it");
  load_model(job, body.text("model", true));
  const render::DrawOptions draw = draw_options(job, body, 64, 900, 640);
  const double fps = body.number("fps").value_or(24.0);
  if (!(fps >= 0.1 && fps <= 120)) bad_input("'fps' must be from 0.1 to 120");
  const std::optional<long long> frames = body.integer("frames", 1, 100000);
  if (frames) check_limit("frames", static_cast<double>(*frames), job.limits.max_frames, "the number of frames");
  AnalysisOptions options;
  options.steps = sweep_steps(job, body);
  options.order = 0;
  job.start(Weight::Heavy);  // the frames
  const Analysis analysis = run_analysis(job, options);
  if (analysis.sweep.samples.empty()) bad_input("the sweep has no sample to show");
  render::Animation animation(analysis.mechanism, analysis.sweep, draw, static_cast<int>(frames.value_or(0)), fps);
  animation.set_control(job.control);  // every format checks the deadline between frames
  check_limit("animation_pixels", static_cast<double>(animation.frame_count()) * draw.width * draw.height,
              job.limits.max_animation_pixels, "frames x width x height");
  job.checkpoint("render");
  if (format == "gif") return answer_bytes(animation.gif_bytes(), "image/gif");
  if (format == "svg") return answer(animation.svg_animation(), "image/svg+xml");
  if (format == "html") return answer_html(animation.html_animation());
  return answer_bytes(animation.mp4_bytes(), "video/mp4");
}

ApiResponse render_plot(Job& job, const std::string& request) {
  const Body body(request, kPlotKeys);
  const std::string format = body.choice("format", {"svg", "png"}, "svg");
  load_model(job, body.text("model", true));
  const Model& m = job.mechanism->model();
  const std::vector<std::string> y = body.list("y");
  if (y.empty()) bad_input("missing 'y': the columns to plot");
  const std::string x = body.optional_text("x").value_or(m.drivers.empty() ? std::string("t") : m.drivers[0].name);
  const std::vector<double> y_range = body.numbers("y_range");
  if (!y_range.empty() && !(y_range.size() == 2 && y_range[0] < y_range[1] && std::abs(y_range[0]) <= 1e300 &&
                            std::abs(y_range[1]) <= 1e300))
    bad_input("'y_range' must be [LO, HI], finite numbers with LO < HI");
  std::optional<int> order;
  if (auto o = body.integer("order", 0, 5)) order = static_cast<int>(*o);
  const int width = static_cast<int>(body.integer("width", 200, 10000, job.limits.max_pixels).value_or(900));
  const int height = static_cast<int>(body.integer("height", 150, 10000, job.limits.max_pixels).value_or(520));
  check_limit("pixels", width, job.limits.max_pixels, "width");
  check_limit("pixels", height, job.limits.max_pixels, "height");

  // Which stages and order the columns need, from the library's column catalogue.
  std::vector<std::string> patterns = y;
  patterns.push_back(x);
  const ColumnNeeds needs = column_needs(*job.mechanism, patterns, order, body.flag("dynamics"));
  if (needs.unmatched >= 0)
    bad_input(std::string(needs.unmatched < static_cast<int>(y.size()) ? "y" : "x") + ": " + needs.message);
  AnalysisOptions options;
  options.steps = sweep_steps(job, body);
  options.order = needs.order;
  options.dynamics = needs.dynamics;
  check_table_size(job, options);
  const Analysis analysis = run_analysis(job, options);
  const ResultTable table = result_table(analysis);
  const ResultTable x_column = select_columns(table, {x});
  if (x_column.columns.size() != 1)
    bad_input(fmt::format("x: '{}' matches {} columns; name one", x, x_column.columns.size()));
  const ResultTable y_columns = select_columns(table, y);

  render::PlotSpec spec;
  spec.title = body.optional_text("title").value_or(!m.name.empty() ? m.name : std::string(kModelFile));
  if (!y_range.empty()) {
    spec.y_lo = y_range[0];
    spec.y_hi = y_range[1];
  }
  spec.width = width;
  spec.height = height;
  render::set_plot_data(spec, x_column, y_columns);
  job.checkpoint("render");
  if (format == "svg") {
    render::SvgCanvas canvas(spec.width, spec.height);
    render::draw_plot(canvas, spec);
    return answer(canvas.document(), "image/svg+xml");
  }
  render::ImageCanvas canvas(spec.width, spec.height);
  render::draw_plot(canvas, spec);
  return answer_bytes(canvas.png_bytes(), "image/png");
}

ApiResponse api_render(Job& job, const std::string& request) {
  // The kind decides which options are known; read it first, leniently.
  std::string kind = "draw";
  try {
    const nlohmann::json j = parse_request(request);
    if (j.is_object() && j.contains("kind")) {
      if (!j["kind"].is_string()) bad_input("'kind' must be draw, animate, plot or plates");
      kind = j["kind"].get<std::string>();
    }
  } catch (const nlohmann::json::exception&) {
    // Body reports it, with its place when there is one.
  }
  if (kind == "draw") return render_draw(job, request);
  if (kind == "animate") return render_animate(job, request);
  if (kind == "plot") return render_plot(job, request);
  if (kind == "plates") return render_plates(job, request);
  bad_input("'kind' must be draw, animate, plot or plates; it is '" + kind + "'");
}

ApiResponse api_report(Job& job, const std::string& request) {
  const Body body(request, {"model", "steps", "frames"});
  load_model(job, body.text("model", true));
  const long long frames = body.integer("frames", render::kMinReportFrames, render::kMaxReportFrames).value_or(72);
  check_limit("frames", static_cast<double>(frames), job.limits.max_frames, "the number of frames");
  const ModelSummary summary = summarize(*job.mechanism);
  AnalysisOptions options = render::report_analysis_options(summary);
  options.steps = sweep_steps(job, body);
  check_table_size(job, options);
  job.start(Weight::Heavy);
  const Analysis analysis = run_analysis(job, options);
  job.checkpoint("report");
  render::ReportOptions report;
  report.source = kModelFile;
  report.frames = static_cast<int>(frames);
  report.control = job.control;
  return answer_html(render::html_report(analysis, summary, report));
}

ApiResponse api_explain(Job& job, const std::string& request) {
  const Body body(request, {"model", "step", "steps", "format"});
  const std::string format = body.choice("format", {"json", "text", "markdown", "latex"}, "json");
  load_model(job, body.text("model", true));
  // The explanation writes Phi_q whole and every pair of links' instant centre: small models.
  const Model& m = job.mechanism->model();
  check_limit("explain_points", static_cast<double>(m.points.size()), job.limits.max_explain_points,
              "the number of points of a model to explain");
  check_limit("explain_bodies", static_cast<double>(m.bodies.size()), job.limits.max_explain_bodies,
              "the number of bodies of a model to explain");
  ExplainOptions options;
  options.steps = sweep_steps(job, body);
  options.step = static_cast<int>(body.integer("step", 0, std::numeric_limits<int>::max()).value_or(0));
  options.control = job.control;
  job.start(Weight::Light);
  const Explanation ex = explain(job.mechanism, options);
  job.checkpoint("explain");
  if (format == "json") return answer(io::json_text(io::explanation_json(ex), 2) + '\n');
  const ExplainFormat f = format == "markdown" ? ExplainFormat::Markdown
                          : format == "latex"  ? ExplainFormat::Latex
                                               : ExplainFormat::Text;
  return answer(render_explanation(ex, f), format == "markdown" ? "text/markdown; charset=utf-8"
                                           : format == "latex"  ? "application/x-latex; charset=utf-8"
                                                                : "text/plain; charset=utf-8");
}

// ----------------------------------------------------------------------- examples and statics

struct Example {
  std::string name, kind, task, file, title, description;
  std::string_view text;
};

// The comment lines at the top of a file, joined.
std::string leading_comment(std::string_view text) {
  std::string out;
  std::size_t at = 0;
  while (at < text.size() && text[at] == '#') {
    std::size_t end = text.find('\n', at);
    if (end == std::string_view::npos) end = text.size();
    std::string line(text.substr(at + 1, end - at - 1));
    if (!line.empty() && line[0] == ' ') line.erase(0, 1);
    if (line.rfind("  nbar ", 0) != 0) out += (out.empty() ? "" : " ") + line;
    at = end + 1;
  }
  return out;
}

const std::vector<Example>& examples() {
  static const std::vector<Example> list = [] {
    std::vector<Example> out;
    for (const EmbeddedFile& f : example_files()) {
      Example e;
      std::string path(f.path);
      e.file = "examples/" + path;
      const std::size_t slash = path.rfind('/');
      e.name = path.substr(slash == std::string::npos ? 0 : slash + 1);
      if (e.name.size() > 5 && e.name.ends_with(".yaml")) e.name.resize(e.name.size() - 5);
      e.text = f.data;
      // A template (examples/templates/) is a small model to start a new one from; its name
      // is prefixed so that it never clashes with an example's.
      const bool is_template = path.starts_with("templates/");
      if (is_template) e.name = "template-" + e.name;
      try {
        const YAML::Node node = YAML::Load(std::string(f.data));
        if (is_template) {
          e.kind = "template";
        } else if (node["task"]) {
          e.kind = "task";
          e.task = node["task"].as<std::string>();
        } else {
          e.kind = "model";
        }
        if (node["name"]) e.title = node["name"].as<std::string>();
        if (node["description"]) e.description = node["description"].as<std::string>();
      } catch (const YAML::Exception&) {
        e.kind = is_template ? "template" : "model";
      }
      if (e.description.empty()) e.description = leading_comment(f.data);
      out.push_back(std::move(e));
    }
    // Models first, then tasks, then templates, each by name.
    std::stable_sort(out.begin(), out.end(), [](const Example& a, const Example& b) {
      return std::tie(a.kind, a.name) < std::tie(b.kind, b.name);
    });
    return out;
  }();
  return list;
}

ApiResponse api_examples() {
  Json list = Json::array();
  for (const Example& e : examples()) {
    Json item = {{"name", e.name}, {"kind", e.kind}};
    if (!e.task.empty()) item["task"] = e.task;
    item["title"] = e.title;
    item["description"] = e.description;
    item["file"] = e.file;
    list.push_back(item);
  }
  return answer(io::json_text(Json{{"examples", list}}, 2) + '\n');
}

// Only a name from the embedded list: nothing a request says ever reaches the file system.
ApiResponse api_example(const std::string& name) {
  for (const Example& e : examples())
    if (e.name == name) return answer(std::string(e.text), "application/yaml; charset=utf-8");
  throw ApiError(ApiErrorKind::NotFound, "no example named '" + name + "'; GET /api/examples lists them");
}

ApiResponse api_health(const ServerConfig& config) {
  const Limits& l = config.limits;
  Json limits = {{"max_body_bytes", l.max_body_bytes},
                 {"max_points", l.max_points},
                 {"max_bodies", l.max_bodies},
                 {"max_steps", l.max_steps},
                 {"max_order", 5},
                 {"max_table_values", json_number(l.max_table_values)},
                 {"max_sections", l.max_sections},
                 {"max_fe_nodes", l.max_fe_nodes},
                 {"max_explain_points", l.max_explain_points},
                 {"max_explain_bodies", l.max_explain_bodies},
                 {"max_frames", l.max_frames},
                 {"max_pixels", l.max_pixels},
                 {"max_animation_pixels", json_number(l.max_animation_pixels)},
                 {"max_synthesis_top", l.max_synthesis_top},
                 {"max_synthesis_threads", l.max_synthesis_threads},
                 {"max_curve_samples", json_number(l.max_curve_samples)},
                 {"time_budget_seconds", json_number(l.time_budget_seconds)},
                 {"max_jobs", config.jobs->total()},
                 {"max_light_jobs", config.light_jobs->total()},
                 {"light_table_values", config.light_table_values},
                 {"queue_wait_seconds", json_number(config.queue_wait_seconds)}};
  Json j = {{"status", "ok"},
            {"version", kVersion},
            {"jobs", {{"running", config.jobs->in_use()}, {"waiting", config.jobs->waiting()}, {"max", config.jobs->total()}}},
            {"light_jobs",
             {{"running", config.light_jobs->in_use()}, {"waiting", config.light_jobs->waiting()}, {"max", config.light_jobs->total()}}},
            {"mp4", render::Animation::program_available("ffmpeg")},
            {"limits", limits}};
  return answer(io::json_text(j, 2) + '\n');
}

std::string content_type_of(std::string_view path) {
  const std::size_t dot = path.rfind('.');
  const std::string_view ext = dot == std::string_view::npos ? std::string_view() : path.substr(dot + 1);
  static const std::map<std::string_view, const char*> types = {
      {"html", "text/html; charset=utf-8"}, {"css", "text/css; charset=utf-8"},
      {"js", "text/javascript; charset=utf-8"}, {"json", "application/json"},
      {"svg", "image/svg+xml"}, {"png", "image/png"}, {"ico", "image/x-icon"},
      {"woff2", "font/woff2"}, {"txt", "text/plain; charset=utf-8"}, {"yaml", "application/yaml; charset=utf-8"}};
  const auto it = types.find(ext);
  return it == types.end() ? "application/octet-stream" : it->second;
}

ApiResponse static_file(const std::string& path) {
  const std::string wanted = path == "/" ? "index.html" : path.substr(1);
  for (const EmbeddedFile& f : static_files())
    if (f.path == wanted) return answer(std::string(f.data), content_type_of(f.path));
  throw ApiError(ApiErrorKind::NotFound, "no page at " + path);
}

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
      {"/api/solve", &api_solve},
      {"/api/stress", &api_stress},
      {"/api/synth/five-point", &synth_five_point},
      {"/api/synth/burmester", &synth_burmester},
      {"/api/synth/function", &synth_function},
      {"/api/synth/nine-point", &synth_nine_point},
      {"/api/synth/path", &synth_path},
      {"/api/render", &api_render},
      {"/api/report", &api_report},
      {"/api/explain", &api_explain},
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
      return it->second(job, request.body);
    } catch (const Error& e) {
      return error_answer(e, job.model(), job.source());
    }
  }
  if (path == "/api/health") return get ? api_health(config) : method_not_allowed(method, path, "GET");
  if (path == "/api/examples") return get ? api_examples() : method_not_allowed(method, path, "GET");
  if (path.starts_with("/api/examples/"))
    return get ? api_example(path.substr(std::string("/api/examples/").size())) : method_not_allowed(method, path, "GET");
  if (path == "/api" || path.starts_with("/api/"))
    throw ApiError(ApiErrorKind::NotFound, "no endpoint " + path + "; see docs/web-api.md");
  if (!get) return method_not_allowed(method, path, "GET");
  return static_file(path);
}

}  // namespace

namespace {

ApiResponse answer_or_error(const ApiRequest& request, const ServerConfig& config) {
  try {
    return route(request, config);
  } catch (const ApiError& e) {
    return error_answer(e.kind(), e.what(), e.details());
  } catch (const Error& e) {
    return error_answer(e);
  } catch (const std::invalid_argument& e) {
    return error_answer(ApiErrorKind::BadInput, e.what());
  } catch (const std::bad_alloc&) {
    return error_answer(ApiErrorKind::LimitExceeded, "the request needs more memory than the server has");
  } catch (const std::exception& e) {
    return error_answer(ApiErrorKind::Internal, e.what());
  }
}

}  // namespace

ApiResponse handle_api(const ApiRequest& request, const ServerConfig& config) {
  ApiResponse r = answer_or_error(request, config);
  if (r.status == http_status(ApiErrorKind::TooManyJobs))
    r.headers.emplace_back("Retry-After", std::to_string(config.retry_after_seconds));
  return r;
}

ApiResponse error_response(int status, const std::string& message) {
  const ApiErrorKind kind = status == 413   ? ApiErrorKind::BodyTooLarge
                            : status == 404 ? ApiErrorKind::NotFound
                            : status == 405 ? ApiErrorKind::MethodNotAllowed
                            : status < 500  ? ApiErrorKind::BadInput
                                            : ApiErrorKind::Internal;
  ApiResponse r = error_answer(kind, message);
  r.status = status;
  return r;
}

}  // namespace nbar::web
