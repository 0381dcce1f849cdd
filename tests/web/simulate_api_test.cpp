// /api/simulate: the forward dynamics of `nbar simulate` through the web API, its answer byte for
// byte the CLI's, its drawing (the `scene`) posed at every row of the simulation, the run in other
// formats in the same answer (`downloads`), its limits, errors and cancellation.
#include <chrono>
#include <thread>

#include "web/web_support.hpp"

namespace nbar::web_test {
namespace {

const char* const kReleased = "examples/crank-rocker-released.yaml";

std::size_t column_of(const Json& table, const std::string& name) {
  const auto& columns = table["columns"];
  const auto at = std::find(columns.begin(), columns.end(), name);
  EXPECT_NE(at, columns.end()) << name;
  return static_cast<std::size_t>(at - columns.begin());
}

TEST(WebSimulate, IsByteForByteNbarSimulateFormatJson) {
  const ApiResponse r = post("/api/simulate", with_model(kReleased, {{"to", 3}, {"dt", 0.01}, {"rtol", 1e-10}}));
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(r.content_type, "application/json");
  const cli_test::CliRun run =
      cli(std::string("simulate ") + kReleased + " --to 3 --dt 0.01 --rtol 1e-10 --format json");
  ASSERT_EQ(run.code, 0) << run.err;
  EXPECT_EQ(r.body, run.out);
  // The numbers: the crank at t = 3 s (docs/dynamics.md: 6.9145 deg), the drift and the balance.
  const Json j = Json::parse(r.body);
  ASSERT_EQ(j["rows"].size(), 301u);
  EXPECT_NEAR(j["rows"][300][column_of(j, "t")].get<double>(), 3.0, 1e-12);
  EXPECT_NEAR(j["rows"][300][column_of(j, "crank")].get<double>(), 6.9145, 5e-5);
  EXPECT_TRUE(j["complete"].get<bool>());
  EXPECT_LT(j["constraint_drift"]["position"].get<double>(), 1e-9);
  EXPECT_GT(j["integrator"]["accepted_steps"].get<long>(), 10);
  EXPECT_LT(std::abs(j["largest_energy_error"].get<double>()), 1e-6);
}

TEST(WebSimulate, CsvTableColumnsAndStopConditionAsTheCommandLine) {
  const std::string flags = " --to 1 --dt 0.05 --columns 't,crank,energy.*'";
  const Json options = {{"to", 1}, {"dt", 0.05}, {"columns", "t,crank,energy.*"}};
  Json csv = options;
  csv["format"] = "csv";
  const ApiResponse c = post("/api/simulate", with_model(kReleased, csv));
  ASSERT_EQ(c.status, 200) << c.body;
  EXPECT_EQ(c.content_type, "text/csv; charset=utf-8");
  EXPECT_EQ(c.body, cli(std::string("simulate ") + kReleased + flags).out);
  Json table = options;
  table["format"] = "table";
  table["stop_when"] = "crank > 15";
  const ApiResponse t = post("/api/simulate", with_model(kReleased, table));
  ASSERT_EQ(t.status, 200) << t.body;
  const cli_test::CliRun run =
      cli(std::string("simulate ") + kReleased + flags + " --format table --stop-when 'crank > 15'");
  EXPECT_EQ(t.body, run.out);
  // The event is said after the table, as the CLI says it.
  EXPECT_NE(t.body.find("Event: "), std::string::npos) << t.body;
}

// POST /api/explain with `simulate` and `at`: the equations of motion, byte for byte `nbar
// explain --simulate`'s, in JSON and text; a bad time is refused by name.
TEST(WebSimulate, ExplainAtATimeIsTheCommandLines) {
  const ApiResponse j = post("/api/explain", with_model(kReleased, {{"simulate", true}, {"at", 0.5}}));
  ASSERT_EQ(j.status, 200) << j.body;
  EXPECT_EQ(j.content_type, "application/json");
  const cli_test::CliRun json = cli(std::string("explain ") + kReleased + " --simulate --at 0.5 --format json");
  ASSERT_EQ(json.code, 0) << json.err;
  EXPECT_EQ(j.body, json.out);
  EXPECT_EQ(Json::parse(j.body)["coordinates"].size(), 6u);
  const ApiResponse t =
      post("/api/explain", with_model(kReleased, {{"simulate", true}, {"at", 0.5}, {"format", "text"}}));
  ASSERT_EQ(t.status, 200) << t.body;
  EXPECT_EQ(t.body, cli(std::string("explain ") + kReleased + " --simulate --at 0.5").out);
  const ApiResponse bad = post("/api/explain", with_model(kReleased, {{"simulate", true}, {"at", -1}}));
  EXPECT_EQ(bad.status, 400) << bad.body;
  EXPECT_EQ(error_of(bad)["option"], "at");
}

// The scene's step k is the simulation's row k: each point label moves from the start by the
// row's displacement of that point, in the scene's pixels (to_model's scale, y down).
TEST(WebSimulate, TheSceneIsPosedAtEveryRowOfTheSimulation) {
  const Json body = with_model(kReleased, {{"to", 2}, {"dt", 0.1}, {"scene", {{"width", 600}, {"height", 400}}}});
  const ApiResponse r = post("/api/simulate", body);
  ASSERT_EQ(r.status, 200) << r.body.substr(0, 400);
  const Json j = Json::parse(r.body);
  const Json& table = j["simulation"];
  const Json& scene = j["scene"];
  // The simulation is the answer without a scene, byte for byte.
  Json plain = body;
  plain.erase("scene");
  EXPECT_EQ(Json::parse(post("/api/simulate", plain).body), table);
  ASSERT_EQ(scene["steps"].size(), table["rows"].size());
  EXPECT_EQ(scene["width"], 600);
  const double k = scene["to_model"][0].get<double>();
  // The labels are the points' in the model's order: O2, O4, A, B, P, S.
  const std::vector<std::string> points = {"O2", "O4", "A", "B", "P", "S"};
  const auto& rows = table["rows"];
  for (std::size_t row : {std::size_t{7}, rows.size() - 1}) {
    for (std::size_t p = 0; p < points.size(); ++p) {
      const double dx = rows[row][column_of(table, points[p] + ".x")].get<double>() -
                        rows[0][column_of(table, points[p] + ".x")].get<double>();
      const double dy = rows[row][column_of(table, points[p] + ".y")].get<double>() -
                        rows[0][column_of(table, points[p] + ".y")].get<double>();
      const Json& shift = scene["steps"][row]["labels"][p];
      // The scene's shifts are written to 0.01 px.
      EXPECT_NEAR(k * shift[0].get<double>(), dx, 6e-3 * k) << points[p] << " at row " << row;
      EXPECT_NEAR(-k * shift[1].get<double>(), dy, 6e-3 * k) << points[p] << " at row " << row;
    }
  }
  // The crank moves in 2 s: the scene is not a still picture.
  EXPECT_GT(std::abs(scene["steps"][rows.size() - 1]["labels"][2][1].get<double>()), 5.0);
}

// `downloads`: the run also written as `nbar simulate --format F` writes it, byte for byte, in
// the same answer (the web app's CSV and JSON downloads, with no second run); with `json` among
// them the simulation is not sent twice.
TEST(WebSimulate, DownloadsAreTheRunInEachFormatInTheSameAnswer) {
  const ApiResponse r = post("/api/simulate", with_model(kReleased, {{"to", 3},
                                                                     {"dt", 0.01},
                                                                     {"rtol", 1e-10},
                                                                     {"scene", {{"width", 600}, {"height", 400}}},
                                                                     {"downloads", {"csv", "json"}}}));
  ASSERT_EQ(r.status, 200) << r.body.substr(0, 400);
  EXPECT_EQ(r.content_type, "application/json");
  const Json j = Json::parse(r.body);
  EXPECT_FALSE(j.contains("simulation"));
  const std::string flags = std::string("simulate ") + kReleased + " --to 3 --dt 0.01 --rtol 1e-10";
  EXPECT_EQ(j["downloads"]["csv"], cli(flags).out);
  EXPECT_EQ(j["downloads"]["json"], cli(flags + " --format json").out);
  const Json table = Json::parse(j["downloads"]["json"].get<std::string>());
  ASSERT_EQ(table["rows"].size(), 301u);
  EXPECT_EQ(j["scene"]["steps"].size(), 301u);
  // The CSV's last row is the JSON's, to the CSV's 12 significant digits: t = 3 s, the crank at
  // 6.9145 deg (docs/dynamics.md).
  const std::string& csv = j["downloads"]["csv"].get_ref<const std::string&>();
  const std::string last = csv.substr(csv.rfind('\n', csv.size() - 2) + 1);
  EXPECT_EQ(last.substr(0, last.find(',')), "300");
  EXPECT_NEAR(table["rows"][300][column_of(table, "crank")].get<double>(), 6.9145, 5e-5);
  // A comma-separated list, a table among them and no json: the simulation stays in the answer,
  // and each download is the command line's for the same options (columns and stop condition).
  const Json options = {{"to", 1}, {"dt", 0.05}, {"columns", "t,crank,energy.*"}, {"stop_when", "crank > 15"}};
  Json asked = options;
  asked["downloads"] = "table,csv";
  const Json both = Json::parse(post("/api/simulate", with_model(kReleased, asked)).body);
  const std::string same =
      std::string("simulate ") + kReleased + " --to 1 --dt 0.05 --columns 't,crank,energy.*' --stop-when 'crank > 15'";
  EXPECT_EQ(both["downloads"]["table"], cli(same + " --format table").out);
  EXPECT_EQ(both["downloads"]["csv"], cli(same).out);
  EXPECT_EQ(both["simulation"], Json::parse(post("/api/simulate", with_model(kReleased, options)).body));
  EXPECT_EQ(both["downloads"].size(), 2u);
}

// A run stopped part way (the engine's Cancel: its progress callback answers false) carries its
// rows so far in every download, with `cancelled` and the stop reason its JSON answer has.
TEST(WebSimulate, ACancelledRunsDownloadsHoldItsRowsSoFar) {
  ServerConfig config = test_config();
  config.on_progress = [](const Progress& p) { return !(std::string(p.stage) == "simulate" && p.done > 50); };
  const Json options = {{"to", 1}, {"dt", 0.01}};
  Json asked = options;
  asked["downloads"] = {"json", "csv"};
  asked["scene"] = {{"width", 400}, {"height", 300}};
  const ApiResponse r = post("/api/simulate", with_model(kReleased, asked), config);
  ASSERT_EQ(r.status, 200) << r.body.substr(0, 400);
  const Json j = Json::parse(r.body);
  // Byte for byte the answers of the same run stopped the same way, in JSON and in CSV.
  EXPECT_EQ(j["downloads"]["json"], post("/api/simulate", with_model(kReleased, options), config).body);
  Json csv = options;
  csv["format"] = "csv";
  EXPECT_EQ(j["downloads"]["csv"], post("/api/simulate", with_model(kReleased, csv), config).body);
  const Json table = Json::parse(j["downloads"]["json"].get<std::string>());
  EXPECT_TRUE(table["cancelled"].get<bool>());
  EXPECT_FALSE(table["complete"].get<bool>());
  EXPECT_EQ(table["stop_reason"], "cancelled at t = 0.5 s");
  ASSERT_EQ(table["rows"].size(), 51u);
  const std::string& text = j["downloads"]["csv"].get_ref<const std::string&>();
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 52);  // the header and the 51 rows
  EXPECT_EQ(j["scene"]["steps"].size(), 51u);
}

TEST(WebSimulate, DownloadsAndFormatRefusedByName) {
  for (const Json& downloads : {Json{"csv", "pdf"}, Json(3), Json("csv,svg")}) {
    const ApiResponse r = post("/api/simulate", with_model(kReleased, {{"to", 1}, {"downloads", downloads}}));
    EXPECT_EQ(r.status, 400) << r.body;
    EXPECT_EQ(error_of(r)["option"], "downloads") << r.body;
  }
  // A CSV cannot stand inside the JSON of a scene's answer: asked as a download instead.
  for (const Json& extra : {Json{{"scene", {{"width", 400}, {"height", 300}}}}, Json{{"downloads", "table"}}}) {
    Json asked = {{"to", 1}, {"format", "csv"}};
    asked.update(extra);
    const ApiResponse r = post("/api/simulate", with_model(kReleased, asked));
    EXPECT_EQ(r.status, 400) << r.body;
    EXPECT_EQ(error_of(r)["option"], "format") << r.body;
  }
}

TEST(WebSimulate, OptionErrorsLimitsAndModelErrorsAreTheApisErrors) {
  // An option out of its rule's range, named as JSON spells it.
  const ApiResponse rtol = post("/api/simulate", with_model(kReleased, {{"to", 1}, {"rtol", 1}}));
  EXPECT_EQ(rtol.status, 400);
  EXPECT_EQ(error_of(rtol)["option"], "rtol");
  const ApiResponse no_to = post("/api/simulate", with_model(kReleased));
  EXPECT_EQ(no_to.status, 400);
  EXPECT_EQ(error_of(no_to)["option"], "to");
  const ApiResponse unknown = post("/api/simulate", with_model(kReleased, {{"to", 1}, {"steps", 3}}));
  EXPECT_EQ(unknown.status, 400);
  const ApiResponse scene = post("/api/simulate", with_model(kReleased, {{"to", 1}, {"scene", {{"stress", true}}}}));
  EXPECT_EQ(scene.status, 400) << scene.body;
  // More rows than the server keeps: 413 before the run.
  ServerConfig small = test_config();
  small.limits.max_steps = 1000;
  const ApiResponse rows = post("/api/simulate", with_model(kReleased, {{"to", 10}, {"dt", 0.001}}), small);
  EXPECT_EQ(rows.status, 413);
  EXPECT_EQ(error_of(rows)["limit"], "steps");
  // A model error at its line and column, as every endpoint places it.
  std::string broken = repo_file(kReleased);
  broken.replace(broken.find("[O2, A]"), 7, "[O2, nowhere]");
  const ApiResponse model = post("/api/simulate", Json{{"model", broken}, {"to", 1}});
  EXPECT_EQ(model.status, 422) << model.body;
  EXPECT_GT(error_of(model)["line"].get<int>(), 0);
  // A free motion without mass cannot be simulated: said at the free driver's line and column, with
  // the CLI's words.
  std::string massless = repo_file("examples/fourbar-crank-rocker.yaml");
  massless.replace(massless.find("speed: 120 rpm}"), 15, "speed: 120 rpm, free: true}");
  const ApiResponse free = post("/api/simulate", Json{{"model", massless}, {"to", 1}});
  EXPECT_EQ(free.status, 422) << free.body;
  const Json error = error_of(free);
  EXPECT_EQ(error["line"], 21);
  EXPECT_EQ(error["column"], 5);
  EXPECT_NE(error["message"].get<std::string>().find("a free motion has no inertia"), std::string::npos) << free.body;
}

// The run checks the deadline between its output rows: a stop there answers 504, as a passed
// deadline does, and the slot is given back.
TEST(WebSimulate, ARunStopsWhenToldToAndReportsItsProgress) {
  ServerConfig config = test_config();
  long last_done = 0, total = 0;
  config.on_progress = [&](const Progress& p) {
    if (std::string(p.stage) == "simulate") last_done = p.done, total = p.total;
    return true;
  };
  const Json body = with_model(kReleased, {{"to", 1}, {"dt", 0.01}});
  ASSERT_EQ(post("/api/simulate", body, config).status, 200);
  EXPECT_EQ(total, 100);
  EXPECT_EQ(last_done, 100);
  // A progress callback that answers false (the in-browser engine's Cancel) stops the run, which
  // answers with its rows so far, as Ctrl-C leaves `nbar simulate`'s.
  config.on_progress = [](const Progress& p) { return !(std::string(p.stage) == "simulate" && p.done > 50); };
  const ApiResponse stopped = post("/api/simulate", body, config);
  ASSERT_EQ(stopped.status, 200) << stopped.body;
  const Json j = Json::parse(stopped.body);
  EXPECT_FALSE(j["complete"].get<bool>());
  EXPECT_TRUE(j["cancelled"].get<bool>());
  ASSERT_EQ(j["rows"].size(), 51u);  // the rows up to the 51st output time's checkpoint: t = 0 to 0.5 s
  EXPECT_NEAR(j["time_reached"].get<double>(), 0.5, 1e-12);
  EXPECT_EQ(j["stop_reason"], "cancelled at t = 0.5 s");
  EXPECT_EQ(config.jobs->in_use() + config.light_jobs->in_use(), 0);
  // The server's time budget stays a limit: 504, no rows.
  config.on_progress = nullptr;
  config.limits.time_budget_seconds = 1e-9;
  const ApiResponse late = post("/api/simulate", body, config);
  EXPECT_EQ(late.status, 504) << late.body;
  EXPECT_EQ(error_of(late)["kind"], "time_budget_exceeded");
}

// A run named by `run` is stopped by /api/simulate/cancel from another request and answers with
// its rows so far, a row every dt up to where it stopped; the name is taken while it runs, and a
// cancel of a name not running says so.
TEST(WebSimulate, ANamedRunCancelledKeepsItsRowsSoFar) {
  const ServerConfig config = test_config();
  // With a scene, as the web app asks: the rows so far are drawn too.
  const Json body = with_model(kReleased, {{"to", 1000},
                                           {"dt", 0.05},
                                           {"rtol", 1e-13},
                                           {"run", "long-run_1"},
                                           {"scene", {{"width", 400}, {"height", 300}}}});
  ApiResponse answer;
  std::thread running([&] { answer = post("/api/simulate", body, config); });
  Json said;
  for (int attempt = 0; attempt < 2000; ++attempt) {
    said = Json::parse(post("/api/simulate/cancel", {{"run", "long-run_1"}}, config).body);
    if (said["cancelled"].get<bool>()) break;
    if (attempt == 10) {  // most likely running by now: its name is taken (a short run of it otherwise)
      const ApiResponse twice =
          post("/api/simulate", with_model(kReleased, {{"to", 0.1}, {"run", "long-run_1"}}), config);
      if (twice.status != 200) {
        EXPECT_EQ(error_of(twice)["message"], "a run named 'long-run_1' is running already");
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  running.join();
  EXPECT_TRUE(said["cancelled"].get<bool>());
  ASSERT_EQ(answer.status, 200) << answer.body;
  const Json both = Json::parse(answer.body);
  const Json& j = both["simulation"];
  EXPECT_EQ(both["scene"]["steps"].size(), j["rows"].size());
  EXPECT_FALSE(j["complete"].get<bool>());
  EXPECT_TRUE(j["cancelled"].get<bool>());
  const double reached = j["time_reached"].get<double>();
  EXPECT_LT(reached, 1000.0);
  EXPECT_EQ(j["rows"].size(), static_cast<std::size_t>(std::llround(reached / 0.05)) + 1);
  EXPECT_NEAR(j["rows"].back()[column_of(j, "t")].get<double>(), reached, 1e-12);
  EXPECT_EQ(j["stop_reason"].get<std::string>().rfind("cancelled at t = ", 0), 0u) << j["stop_reason"];
  // Ended: the name is free, and a cancel of it finds nothing.
  EXPECT_EQ(post("/api/simulate/cancel", {{"run", "long-run_1"}}, config).body, "{\"cancelled\":false}\n");
  const ApiResponse bad = post("/api/simulate/cancel", {{"run", "no spaces"}}, config);
  EXPECT_EQ(bad.status, 400) << bad.body;
}

}  // namespace
}  // namespace nbar::web_test
