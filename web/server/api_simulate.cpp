// Forward dynamics: /api/simulate lets the model move under its loads as `nbar simulate` does,
// its options read by the same request (request::SimulateRequest), and answers what `nbar
// simulate --format json` prints (or csv, or the table). With a `scene` ({"width", "height",
// "labels", "trace", "title"}: a drawing's options), the web app's drawing of the simulated motion
// comes with it: {"simulation": <that JSON>, "scene": <the scene, one step per row>}.
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
#include "nbar/analysis/columns.hpp"
#include "nbar/io/results_writer.hpp"
#include "nbar/render/scene.hpp"
#include "nbar/request/requests.hpp"

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
  const bool plain = !name.empty() && name.size() <= 64 &&
                     std::all_of(name.begin(), name.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_'; });
  if (!plain) bad_input("'run' must be a name of 1 to 64 letters, digits, '-' or '_'");
  return name;
}

}  // namespace

ApiResponse api_simulate_cancel(Job&, const std::string& text) {
  const RequestBody body(text, {"run"});
  const bool found = named_runs().cancel(run_name(body));
  return answer(found ? "{\"cancelled\":true}\n" : "{\"cancelled\":false}\n");
}

ApiResponse api_simulate(Job& job, const std::string& text) {
  const RequestBody body(text, request::SimulateRequest::rules(), {"model", "scene", "run"});
  const auto simulate = read_request<request::SimulateRequest>(body, {"model", "scene", "run"}, true);
  const std::optional<std::string> name = body.has("run") ? std::optional(run_name(body)) : std::nullopt;
  load_model(job, body.text("model", true));
  const SimulationOptions options = simulate.simulation_options(*job.mechanism);
  check_simulation_size(job, options);
  std::optional<render::DrawOptions> scene;
  if (body.has("scene")) scene = scene_options(job, parse_request(text).at("scene"));
  // How long an integration takes is known only once it has run (the tolerance, the stiffness of
  // the springs): a heavy computation, whatever its rows.
  job.start(Weight::Heavy);
  // Named only now, as the integration starts: a cancel that came while the model was read would
  // stop the job at one of those steps' checkpoints, which answer as the time budget does (504),
  // where a cancelled run answers with its rows; that cancel finds no run and says so.
  std::optional<NamedRuns::Entry> named;
  if (name) {
    if (!named_runs().add(*name, job.control.token)) bad_input("a run named '" + *name + "' is running already");
    named.emplace(named_runs(), *name);
  }
  const Simulation simulation = nbar::simulate(*job.mechanism, options, job.control);
  // The core keeps a cancelled run's rows, and so does the answer to a page that cancelled it; the
  // server's deadline is its own limit, said as one.
  if (simulation.cancelled && job.control.token.deadline_passed()) job.control.throw_stopped("simulate");
  const ResultTable table = simulate.table(*job.mechanism, simulation);
  const std::string answer_text =
      write([&](std::ostream& out) { simulate.write(out, *job.mechanism, simulation, table, io::kTextTableWidth); });
  if (!scene) return answer(answer_text, text_type(simulate.format));
  if (!simulation.cancelled) job.checkpoint("render");  // a run cancelled is drawn as far as it went
  const std::string drawing =
      render::drawing_scene_json(*job.mechanism, request::simulated_motion(simulation), *scene, 0);
  // The two documents as their writers wrote them, so that each is byte for byte its own answer.
  return answer("{\"simulation\":" + answer_text + ",\"scene\":" + drawing + "}\n");
}

}  // namespace nbar::web
