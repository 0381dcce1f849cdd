// Forward dynamics: /api/simulate lets the model move under its loads as `nbar simulate` does,
// its options read by the same request (request::SimulateRequest), and answers what `nbar
// simulate --format json` prints (or csv, or the table). With a `scene` ({"width", "height",
// "labels", "trace", "title"}: a drawing's options), the web app's drawing of the simulated motion
// comes with it: {"simulation": <that JSON>, "scene": <the scene, one step per row>}.
//
// With `downloads` (a list of formats: csv, json, table) the answer also carries the run written
// in each, as `nbar simulate --format F` writes it: {"downloads": {"csv": "<text>", ...}}. The web
// app's CSV and JSON downloads are these texts, so that a download holds the rows on screen (a
// cancelled run's rows so far) and never runs the simulation again. Why in the answer and not
// elsewhere: the server keeps nothing between requests (several instances may share a class
// behind a proxy, docs/deploy.md), so it cannot hand a run out later by its name; and the page
// cannot send the rows back to be written (a 10 s run at 1 ms is 9.8 MB of JSON, over the 1 MiB
// body limit). The CSV costs about 0.6 of the JSON's bytes; the JSON is not sent twice: with
// `json` among the downloads, `simulation` is left out and the client parses downloads.json.
//
// A run named by the body's `run` (a string the page chooses) can be stopped from outside by
// POST /api/simulate/cancel {"run": that string}: it then ends as Ctrl-C ends `nbar simulate`,
// answered 200 with the rows so far (`complete` false, `cancelled` true, `stop_reason` "cancelled
// at t = ... s"). The server's own time budget stays a limit, answered 504.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <mutex>
#include <optional>
#include <string>

#include "endpoints.hpp"
#include "io/json_text.hpp"
#include "nbar/analysis/columns.hpp"
#include "nbar/io/results_writer.hpp"
#include "nbar/render/scene.hpp"
#include "nbar/request/requests.hpp"
#include "request/answer_language.hpp"

namespace nbar::web {

namespace {

// The rows a run writes (one per output time and the start), before it runs: the options as the
// run takes them, the model's `simulation:` section filling in what the request leaves out.
double simulated_rows(const SimulationOptions& options) {
  const double step = options.output_step > 0 ? options.output_step : options.end_time / 100;
  return std::floor(options.end_time / step + 1e-9) + 1;
}

// Every row is kept until the run ends and goes into the answer: the rows against the sweep's
// sample limit, the rows times the columns against the table's (the kinematic columns of order 2
// and the six energies).
void check_simulation_size(const Job& job, const SimulationOptions& options) {
  const double rows = simulated_rows(options);
  check_limit("steps", rows, job.limits.max_steps, "the number of rows of the simulation (to / dt + 1)");
  const double columns = static_cast<double>(column_catalogue(*job.mechanism, 2, false).size()) + 6;
  check_limit("table_values", rows * columns, job.limits.max_table_values,
              fmt::format("the table (rows x columns, {} columns)", columns));
}

// The drawing options of the `scene` object, read by the drawing's own rules (the picture's only:
// size, labels, traced points, title).
render::DrawOptions scene_options(const Job& job, const nlohmann::json& scene) {
  if (!scene.is_object())
    bad_input("'scene' must be an object of a drawing's options: {\"width\", \"height\", \"labels\"}");
  std::vector<request::OptionRule> rules;
  for (const request::OptionRule& rule : request::DrawRequest::rules())
    if (rule.key == "width" || rule.key == "height" || rule.key == "labels" || rule.key == "trace" ||
        rule.key == "title")
      rules.push_back(rule);
  const RequestBody body(scene.dump(), rules, {});
  const auto draw = read_request<request::DrawRequest>(body, {});
  check_limit("pixels", draw.picture.width, job.limits.max_pixels, "width");
  check_limit("pixels", draw.picture.height, job.limits.max_pixels, "height");
  return draw.picture.draw_options(job.mechanism->model());
}

// The runs that a page may cancel, by their name, while they run.
class NamedRuns {
 public:
  // Takes a name added (add) out when it ends. A name already running is refused (two pages that
  // chose the same name would stop each other's runs).
  class Entry {
   public:
    Entry(NamedRuns& runs, std::string name) : runs_(&runs), name_(std::move(name)) {}
    Entry(const Entry&) = delete;
    Entry& operator=(const Entry&) = delete;
    ~Entry() {
      if (!runs_) return;
      const std::lock_guard lock(runs_->mutex_);
      runs_->tokens_.erase(name_);
    }

   private:
    NamedRuns* runs_ = nullptr;
    std::string name_;
  };

  // False where the name is running already. An Entry made after a true takes it out again.
  bool add(const std::string& name, const CancelToken& token) {
    const std::lock_guard lock(mutex_);
    return tokens_.emplace(name, token).second;
  }
  bool cancel(const std::string& name) {
    const std::lock_guard lock(mutex_);
    const auto found = tokens_.find(name);
    if (found == tokens_.end()) return false;
    found->second.cancel();
    return true;
  }

 private:
  std::mutex mutex_;
  std::map<std::string, CancelToken> tokens_;
};

NamedRuns& named_runs() {
  static NamedRuns runs;
  return runs;
}

// A run's name: a short string of letters, digits, '-' and '_', so that it is never a secret or
// a document.
std::string run_name(const RequestBody& body) {
  const std::string name = body.text("run");
  const bool plain = !name.empty() && name.size() <= 64 && std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_';
  });
  if (!plain) bad_input("'run' must be a name of 1 to 64 letters, digits, '-' or '_'");
  return name;
}

// The web API's own option of a simulation: the formats to carry the run in besides the answer.
const request::OptionRule& downloads_rule() {
  static const request::OptionRule rule = [] {
    request::OptionRule r;
    r.key = "downloads";
    r.kind = request::OptionKind::Names;
    r.help = "the run also written in these formats (csv, json, table), as texts in the answer's `downloads`";
    return r;
  }();
  return rule;
}

std::vector<request::OptionRule> simulate_rules() {
  std::vector<request::OptionRule> rules = request::SimulateRequest::rules();
  rules.push_back(downloads_rule());
  return rules;
}

// The formats asked for in `downloads`, each once, each one of `format`'s choices.
std::vector<std::string> download_formats(const RequestBody& body) {
  const std::vector<std::string>& formats = request::rule_of(request::SimulateRequest::rules(), "format").choices;
  std::vector<std::string> asked;
  for (const std::string& name : request::read_names(body.options({"model", "scene", "run"}), downloads_rule())) {
    if (std::find(formats.begin(), formats.end(), name) == formats.end())
      throw request::OptionError("downloads", "must list formats among csv, json and table, not '" + name + "'");
    if (std::find(asked.begin(), asked.end(), name) == asked.end()) asked.push_back(name);
  }
  return asked;
}

// What one request of a simulation asks besides the run's options.
struct SimulateExtras {
  std::optional<std::string> run;
  std::optional<render::DrawOptions> scene;
  std::vector<std::string> downloads;
  // The answer is then an object of its parts, in which the simulation is JSON.
  bool composite() const { return scene || !downloads.empty(); }
};

SimulateExtras simulate_extras(const Job& job, const RequestBody& body, const std::string& text,
                               const request::SimulateRequest& simulate) {
  SimulateExtras extras;
  if (body.has("run")) extras.run = run_name(body);
  if (body.has("scene")) extras.scene = scene_options(job, parse_request(text).at("scene"));
  extras.downloads = download_formats(body);
  // A csv or a table cannot stand inside a JSON object as a document (it went in as raw bytes):
  // those are asked as downloads, which carry them as texts.
  if (extras.composite() && simulate.format != "json")
    throw request::OptionError("format",
                               "must be json with {scene} or {downloads}: ask for csv or table in {downloads}");
  return extras;
}

// The run as `nbar simulate --format F` writes it (a csv or a table: the json is the answer's own).
std::string written_as(const Job& job, request::SimulateRequest simulate, const std::string& format,
                       const Simulation& simulation, const ResultTable& table) {
  simulate.format = format;
  return write([&](std::ostream& o) { simulate.write(o, *job.mechanism, simulation, table, io::kTextTableWidth); });
}

// {"simulation"?, "scene"?, "downloads"?}: each document as its writer wrote it, so that each is
// byte for byte its own answer; the simulation left out when its JSON comes as a download.
std::string composite_answer(const Job& job, const request::SimulateRequest& simulate, const SimulateExtras& extras,
                             const Simulation& simulation, const ResultTable& table,
                             const std::string& simulation_json) {
  std::string out = "{";
  const auto member = [&](const char* key, const std::string& value) {
    out += (out.size() > 1 ? ",\"" : "\"") + std::string(key) + "\":" + value;
  };
  const bool json_download =
      std::find(extras.downloads.begin(), extras.downloads.end(), "json") != extras.downloads.end();
  if (!json_download) member("simulation", simulation_json);
  if (extras.scene) {
    if (!simulation.cancelled) job.checkpoint("render");  // a run cancelled is drawn as far as it went
    member("scene",
           render::drawing_scene_json(*job.mechanism, request::simulated_motion(simulation), *extras.scene, 0));
  }
  if (!extras.downloads.empty()) {
    // The JSON text's messages in the job's language, as the JSON answer of its own has them
    // (handle_api translates an answer's fields, and does not look inside a text).
    Json texts = Json::object();
    for (const std::string& format : extras.downloads)
      texts[format] = format == "json" ? request::translate_json_answer(simulation_json, job.language)
                                       : written_as(job, simulate, format, simulation, table);
    member("downloads", io::json_text(texts, -1));
  }
  return out + "}\n";
}

}  // namespace

ApiResponse api_simulate_cancel(Job&, const std::string& text) {
  const RequestBody body(text, {"run"});
  const bool found = named_runs().cancel(run_name(body));
  return answer(found ? "{\"cancelled\":true}\n" : "{\"cancelled\":false}\n");
}

ApiResponse api_simulate(Job& job, const std::string& text) {
  const RequestBody body(text, simulate_rules(), {"model", "scene", "run"});
  const auto simulate = read_request<request::SimulateRequest>(body, {"model", "scene", "run", "downloads"}, true);
  load_model(job, body.text("model", true));
  const SimulationOptions options = simulate.simulation_options(*job.mechanism);
  check_simulation_size(job, options);
  const SimulateExtras extras = simulate_extras(job, body, text, simulate);
  // How long an integration takes is known only once it has run (the tolerance, the stiffness of
  // the springs): a heavy computation, whatever its rows.
  job.start(Weight::Heavy);
  // Named only now, as the integration starts: a cancel that came while the model was read would
  // stop the job at one of those steps' checkpoints, which answer as the time budget does (504),
  // where a cancelled run answers with its rows; that cancel finds no run and says so.
  std::optional<NamedRuns::Entry> named;
  if (extras.run) {
    if (!named_runs().add(*extras.run, job.control.token))
      bad_input("a run named '" + *extras.run + "' is running already");
    named.emplace(named_runs(), *extras.run);
  }
  const Simulation simulation = nbar::simulate(*job.mechanism, options, job.control);
  // The core keeps a cancelled run's rows, and so does the answer to a page that cancelled it; the
  // server's deadline is its own limit, said as one.
  if (simulation.cancelled && job.control.token.deadline_passed()) job.control.throw_stopped("simulate");
  const ResultTable table = simulate.table(*job.mechanism, simulation);
  const std::string answer_text =
      write([&](std::ostream& out) { simulate.write(out, *job.mechanism, simulation, table, io::kTextTableWidth); });
  if (!extras.composite()) return answer(answer_text, text_type(simulate.format));
  return answer(composite_answer(job, simulate, extras, simulation, table, answer_text));
}

}  // namespace nbar::web
