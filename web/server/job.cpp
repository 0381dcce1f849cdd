#include "job.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <limits>
#include <sstream>

#include "io/yaml_support.hpp"
#include "nbar/analysis/columns.hpp"
#include "nbar/kinematics/sweep.hpp"

namespace nbar::web {

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
  // Reading and checking the model do not look at the deadline as they go; their time counts.
  job.checkpoint("model");
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

// The sweep's size against the limit. A sweep over it by the model's own `sweep:` is said at that
// place in the model's text, as the model's other errors are, so that an editor underlines it.
void check_sweep_size(const Job& job, std::optional<int> steps) {
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
  job.start(options.stress || table_values(job, options) > job.config.light_table_values ? Weight::Heavy
                                                                                         : Weight::Light);
  options.control = job.control;
  return analyse(job.mechanism, options);
}

ApiResponse answer(std::string body, std::string content_type) {
  ApiResponse r;
  r.body = std::move(body);
  r.content_type = std::move(content_type);
  return r;
}

ApiResponse answer_bytes(const std::vector<std::uint8_t>& bytes, std::string content_type) {
  return answer(std::string(bytes.begin(), bytes.end()), std::move(content_type));
}

ApiResponse answer_html(std::string html) {
  ApiResponse r = answer(std::move(html), "text/html; charset=utf-8");
  r.headers.emplace_back("Content-Security-Policy", "sandbox allow-scripts");
  return r;
}

std::string write(const std::function<void(std::ostream&)>& writer) {
  std::ostringstream out;
  writer(out);
  return out.str();
}

const char* text_type(const std::string& format) {
  return format == "json"  ? "application/json"
         : format == "csv" ? "text/csv; charset=utf-8"
                           : "text/plain; charset=utf-8";
}

}  // namespace nbar::web
