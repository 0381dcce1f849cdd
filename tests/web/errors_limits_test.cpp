// The web API's errors (bad JSON, bad YAML with its line and column, unknown endpoints and
// methods, path traversal) and every limit: body size, points, bodies, steps, order, sections,
// frames, pixels, synthesis, the time budget and the cap on concurrent jobs.
#include <chrono>
#include <future>
#include <mutex>
#include <thread>

#include "web/web_support.hpp"

namespace nbar::web_test {
namespace {

void expect_error(const ApiResponse& r, int status, const std::string& kind) {
  EXPECT_EQ(r.status, status) << r.body;
  EXPECT_EQ(r.content_type, "application/json");
  const Json e = error_of(r);
  EXPECT_EQ(e["kind"], kind) << r.body;
  EXPECT_FALSE(e["message"].get<std::string>().empty());
}

void expect_limit(const ApiResponse& r, const std::string& limit) {
  expect_error(r, 413, "limit_exceeded");
  EXPECT_EQ(error_of(r)["limit"], limit) << r.body;
}

TEST(WebErrors, BadJson) {
  const ApiResponse r = call("POST", "/api/solve", "{\"model\": \"x\",\n  \"steps\": }");
  expect_error(r, 400, "bad_json");
  EXPECT_EQ(error_of(r)["line"], 2);
  expect_error(call("POST", "/api/check", ""), 400, "bad_json");
  expect_error(call("POST", "/api/check", "[1, 2]"), 400, "bad_json");
  expect_error(call("POST", "/api/check", "\"model\""), 400, "bad_json");
}

// A number past a double's range was a 500 (nlohmann's out_of_range, not a parse_error).
TEST(WebErrors, ANumberPastADoublesRangeIsBadJson) {
  for (const std::string path : {"/api/solve", "/api/render"}) {
    SCOPED_TRACE(path);
    const ApiResponse r = call("POST", path, "{\"model\": \"x\", \"steps\": 1e400}");
    expect_error(r, 400, "bad_json");
    EXPECT_NE(error_of(r)["message"].get<std::string>().find("1e400"), std::string::npos);
  }
}

// A model sent as a JSON object is written out as indented text to be read: 100 000 levels of
// nesting overflowed the writer's stack (the server died), 20 000 made 800 MB of indentation.
TEST(WebErrors, AModelObjectNestedTooDeepOrTooWideIsRefusedBeforeItIsWrittenOut) {
  const auto nested = [](int depth, const std::string& inner) {
    return "{\"model\": {\"points\": " + std::string(depth, '[') + inner + std::string(depth, ']') + "}}";
  };
  const ApiResponse deep = call("POST", "/api/check", nested(100000, ""));
  expect_error(deep, 400, "bad_input");
  EXPECT_EQ(error_of(deep)["message"], "'model' nests deeper than 64 levels");
  std::string zeros = "0";
  for (int i = 0; i < 200000; ++i) zeros += ",0";
  ServerConfig config = test_config();
  config.limits.max_body_bytes = 1 << 20;
  const ApiResponse wide = call("POST", "/api/check", nested(60, zeros), config);
  expect_error(wide, 413, "limit_exceeded");
  EXPECT_EQ(error_of(wide)["limit"], "model_bytes");
  // Nested as deep as the limit, and small, it is read (and is no model).
  expect_error(call("POST", "/api/check", nested(62, "")), 422, "invalid_model");
}

TEST(WebErrors, EveryComputingEndpointRefusesBadJsonBadYamlAndOversizedBodies) {
  ServerConfig config = test_config();
  config.limits.max_body_bytes = 4096;
  const std::string broken_yaml = "name: broken\npoints:\n  A: [0, 0\n  B: [1, 1]\n";
  for (const std::string path :
       {"/api/check", "/api/solve", "/api/stress", "/api/stress/probe", "/api/synth/five-point", "/api/synth/burmester",
        "/api/synth/function", "/api/render", "/api/report", "/api/explain"}) {
    SCOPED_TRACE(path);
    expect_error(call("POST", path, "{\"model\": \"points: {}\",", config), 400, "bad_json");
    expect_error(call("POST", path, "not json at all", config), 400, "bad_json");
    const ApiResponse big = call("POST", path, std::string(4097, ' '), config);
    expect_error(big, 413, "body_too_large");
    EXPECT_EQ(error_of(big)["max"], 4096);
    // The model (or task) text as broken YAML: 422 at its line and column.
    const bool task = path.starts_with("/api/synth/");
    const ApiResponse yaml = post(path, {{task ? "task" : "model", broken_yaml}}, config);
    expect_error(yaml, 422, "invalid_model");
    EXPECT_EQ(error_of(yaml)["file"], task ? "task" : "model");
    EXPECT_GT(error_of(yaml)["line"].get<int>(), 2);
  }
}

TEST(WebErrors, AModelWrittenAsBrokenJsonIsLocatedToo) {
  // JSON is YAML: the model's own text, not the request, has the error, at line 3.
  const std::string model = "{\n  \"name\": \"x\",\n  \"points\": {\"A\": [0, 0}\n}\n";
  const ApiResponse r = post("/api/check", {{"model", model}});
  expect_error(r, 422, "invalid_model");
  EXPECT_EQ(error_of(r)["line"], 3);
}

TEST(WebErrors, BadOptions) {
  expect_error(post("/api/check", Json::object()), 400, "bad_input");  // no model
  expect_error(post("/api/check", {{"model", 3}}), 400, "bad_input");
  const ApiResponse unknown = post("/api/solve", with_model("examples/five-bar.yaml", {{"stepz", 3}}));
  expect_error(unknown, 400, "bad_input");
  EXPECT_NE(error_of(unknown)["message"].get<std::string>().find("stepz"), std::string::npos);
  expect_error(post("/api/solve", with_model("examples/five-bar.yaml", {{"steps", "3"}})), 400, "bad_input");
  expect_error(post("/api/solve", with_model("examples/five-bar.yaml", {{"steps", 2.5}})), 400, "bad_input");
  expect_error(post("/api/solve", with_model("examples/five-bar.yaml", {{"steps", 0}})), 400, "bad_input");
  expect_error(post("/api/solve", with_model("examples/five-bar.yaml", {{"dynamics", "yes"}})), 400, "bad_input");
  expect_error(post("/api/solve", with_model("examples/five-bar.yaml", {{"format", "xml"}})), 400, "bad_input");
  const ApiResponse columns = post("/api/solve", with_model("examples/five-bar.yaml", {{"columns", "nothing.*"}}));
  expect_error(columns, 400, "bad_input");
  EXPECT_NE(error_of(columns)["message"].get<std::string>().find("the columns are"), std::string::npos);
  expect_error(post("/api/render", with_model("examples/five-bar.yaml", {{"kind", "sculpt"}})), 400, "bad_input");
  expect_error(post("/api/render", with_model("examples/five-bar.yaml", {{"kind", "draw"}, {"frames", 3}})), 400,
               "bad_input");
  expect_error(post("/api/render", with_model("examples/five-bar.yaml", {{"kind", "draw"}, {"format", "gif"}})), 400,
               "bad_input");
  expect_error(post("/api/render", with_model("examples/five-bar.yaml", {{"kind", "draw"}, {"step", 10000}})), 400,
               "bad_input");
  expect_error(post("/api/render", with_model("examples/five-bar.yaml", {{"kind", "draw"}, {"trace", "Q9"}})), 400,
               "bad_input");
  expect_error(post("/api/render", with_model("examples/five-bar.yaml", {{"kind", "plot"}})), 400, "bad_input");
  expect_error(post("/api/render", with_model("examples/five-bar.yaml", {{"kind", "plot"}, {"y", "zz"}})), 400,
               "bad_input");
  expect_error(post("/api/stress", with_model("examples/fourbar-steel-bars.yaml", {{"section_profile", "nobody"}})),
               400, "bad_input");
  expect_error(post("/api/stress", with_model("examples/fourbar-steel-bars.yaml", {{"step", 3}})), 400, "bad_input");
}

// nlohmann's parser kept the last of a key given twice, silently: {"steps": 5, "steps": 500}
// solved 500 steps. The first key given twice is a 400 naming it, wherever it is.
TEST(WebErrors, AKeyGivenTwiceIsBadJsonNamingIt) {
  const std::string model = Json(repo_file("examples/five-bar.yaml")).dump();
  const ApiResponse twice = call("POST", "/api/solve", "{\"model\": " + model + ", \"steps\": 5, \"steps\": 500}");
  expect_error(twice, 400, "bad_json");
  EXPECT_EQ(error_of(twice)["message"], "the body gives 'steps' twice; give each option once");
  EXPECT_EQ(error_of(twice)["key"], "steps");
  // The kind of a render, which is read before the rest.
  const ApiResponse kind =
      call("POST", "/api/render", "{\"kind\": \"draw\", \"model\": " + model + ", \"kind\": \"plot\"}");
  expect_error(kind, 400, "bad_json");
  EXPECT_EQ(error_of(kind)["key"], "kind");
  // Inside a model sent as a JSON object, with where it is.
  const std::string points = R"({"model": {"points": {"A": [0, 0], "B": [1, 0], "A": [2, 2]}}})";
  const ApiResponse nested = call("POST", "/api/check", points);
  expect_error(nested, 400, "bad_json");
  EXPECT_EQ(error_of(nested)["message"], "the body gives the key 'A' twice in 'model.points'");
  const std::string listed = R"({"model": {"drivers": [{"angle": "crank"}, {"angle": "a", "angle": "b"}]}})";
  EXPECT_EQ(error_of(call("POST", "/api/check", listed))["message"],
            "the body gives the key 'angle' twice in 'model.drivers[]'");
  // The same key in different objects is no duplicate.
  const std::string apart =
      R"({"model": {"name": "x", "points": {"name": [0, 0]}, "sweep": {"steps": 3}}, "steps": 3})";
  expect_error(call("POST", "/api/solve", apart), 422, "invalid_model");
}

TEST(WebErrors, YamlErrorsHaveTheirLineAndColumn) {
  const std::string model = "name: broken\npoints:\n  A: [0, 0\n  B: [1, 1]\n";
  const ApiResponse r = post("/api/check", {{"model", model}});
  expect_error(r, 422, "invalid_model");
  const Json e = error_of(r);
  EXPECT_EQ(e["file"], "model");
  EXPECT_GT(e["line"].get<int>(), 2);
  EXPECT_GT(e["column"].get<int>(), 0);
  // The same place the CLI reports for the same text.
  const auto dir = temp_folder("yaml");
  std::ofstream(dir / "model") << model;
  const cli_test::CliRun run = cli_test::run_shell("cd '" + dir.string() + "' && '" + NBAR_CLI_PATH + "' check model");
  EXPECT_EQ(run.code, 1);
  EXPECT_NE(
      run.err.find("model:" + std::to_string(e["line"].get<int>()) + ":" + std::to_string(e["column"].get<int>())),
      std::string::npos)
      << run.err << r.body;
  std::filesystem::remove_all(dir);
}

TEST(WebErrors, ModelErrorsPointAtTheEntity) {
  // An unknown point in a body: the parser's error at its place.
  const std::string unknown = "points: {A: [0, 0], B: [1, 0]}\nground: [A]\nbodies:\n  crank: [A, C]\n";
  const ApiResponse r = post("/api/solve", {{"model", unknown}});
  expect_error(r, 422, "invalid_model");
  EXPECT_EQ(error_of(r)["line"], 4);
  // Drivers that do not match the mobility: found when the model is compiled, at the driver.
  std::string two_drivers = repo_file("examples/fourbar-crank-rocker.yaml");
  const std::size_t sweep = two_drivers.find("\nsweep:");
  ASSERT_NE(sweep, std::string::npos);
  two_drivers.insert(sweep, "\n  - {angle: rocker, from: 90, to: 100}");
  const ApiResponse d = post("/api/solve", {{"model", two_drivers}});
  expect_error(d, 422, "invalid_model");
  const Json e = error_of(d);
  EXPECT_GT(e.value("line", 0), 0) << d.body;
  // The same place the CLI gives.
  const auto dir = temp_folder("drivers");
  std::ofstream(dir / "model") << two_drivers;
  const cli_test::CliRun run = cli_test::run_shell("cd '" + dir.string() + "' && '" + NBAR_CLI_PATH + "' solve model");
  EXPECT_EQ(run.code, 1);
  EXPECT_NE(run.err.find("model:" + std::to_string(e.value("line", 0)) + ":"), std::string::npos) << run.err << d.body;
  std::filesystem::remove_all(dir);
}

TEST(WebErrors, CannotAssembleAndNoShapes) {
  const ApiResponse r = post("/api/solve", with_model("tests/golden/inputs/cannot-assemble.yaml"));
  expect_error(r, 422, "cannot_assemble");
  expect_error(post("/api/stress", with_model("examples/fourbar-crank-rocker.yaml")), 422, "invalid_model");
}

TEST(WebErrors, SynthesisTasks) {
  const ApiResponse wrong = post("/api/synth/burmester", with_task("examples/synthesis/function-log10.yaml"));
  expect_error(wrong, 400, "bad_input");
  EXPECT_NE(error_of(wrong)["message"].get<std::string>().find("/api/synth/function"), std::string::npos);
  const ApiResponse bad = post("/api/synth/function", {{"task", "task: function\nname: x\nfunction: \"log10(x\"\n"}});
  expect_error(bad, 422, "invalid_model");
  EXPECT_EQ(error_of(bad)["file"], "task");
  EXPECT_EQ(error_of(bad)["line"], 3);
  expect_error(post("/api/synth/five-point", with_model("examples/fourbar-crank-rocker.yaml")), 400, "bad_input");
}

TEST(WebErrors, UnknownEndpointsAndMethods) {
  expect_error(call("POST", "/api/simulation", "{}"), 404, "not_found");
  expect_error(call("GET", "/api/synth/six-point"), 404, "not_found");
  expect_error(call("GET", "/no-such-page.html"), 404, "not_found");
  const ApiResponse get_solve = call("GET", "/api/solve");
  expect_error(get_solve, 405, "method_not_allowed");
  EXPECT_EQ(header(get_solve, "Allow"), "POST");
  expect_error(call("DELETE", "/api/check"), 405, "method_not_allowed");
  expect_error(call("POST", "/api/health", "{}"), 405, "method_not_allowed");
  expect_error(call("PUT", "/api/examples/five-bar", "x"), 405, "method_not_allowed");
  expect_error(call("POST", "/", "{}"), 405, "method_not_allowed");
}

TEST(WebErrors, NoPathTraversal) {
  // Paths as the HTTP layer hands them over (decoded), and as they may arrive undecoded.
  for (const std::string name : {"../README.md", "../../../../etc/passwd", "/etc/passwd", "%2e%2e/README.md",
                                 "%2e%2e%2fREADME.md", "..%2f..%2fetc%2fpasswd", "synthesis/../fourbar-crank-rocker",
                                 "fourbar-crank-rocker.yaml", "./fourbar-crank-rocker", "fourbar-crank-rocker/",
                                 "synthesis", "", ".", "..", "..\\..\\etc\\passwd", "~/.ssh/id_rsa"}) {
    SCOPED_TRACE(name);
    expect_error(call("GET", "/api/examples/" + name), 404, "not_found");
  }
  expect_error(call("GET", "/api/examples/" + std::string("fourbar-crank-rocker\0/../x", 26)), 404, "not_found");
  for (const std::string path : {"/../README.md", "/../../etc/passwd", "/%2e%2e/README.md", "/web/ui/index.html",
                                 "//etc/passwd", "/examples/five-bar.yaml"}) {
    SCOPED_TRACE(path);
    expect_error(call("GET", path), 404, "not_found");
  }
}

TEST(WebLimits, BodySize) {
  ServerConfig config = test_config();
  config.limits.max_body_bytes = 1000;
  const ApiResponse r = post("/api/check", with_model("examples/machine-18.yaml"), config);
  expect_error(r, 413, "body_too_large");
  EXPECT_EQ(error_of(r)["max"], 1000);
  // The default: 1 MiB.
  expect_error(call("POST", "/api/check", std::string(2 << 20, ' ')), 413, "body_too_large");
}

TEST(WebLimits, PointsAndBodies) {
  ServerConfig config = test_config();
  config.limits.max_points = 4;
  expect_limit(post("/api/check", with_model("examples/fourbar-crank-rocker.yaml"), config), "points");
  config = test_config();
  config.limits.max_bodies = 2;
  expect_limit(post("/api/solve", with_model("examples/fourbar-crank-rocker.yaml"), config), "bodies");
  EXPECT_EQ(post("/api/check", with_model("examples/machine-18.yaml")).status, 200);
}

TEST(WebLimits, Steps) {
  expect_limit(post("/api/solve", with_model("examples/fourbar-crank-rocker.yaml", {{"steps", 100002}})), "steps");
  // The model's own sweep counts too, from/to and time laws.
  std::string many = repo_file("examples/fourbar-crank-rocker.yaml");
  many.replace(many.find("sweep: {steps: 361}"), 19, "sweep: {steps: 200000}");
  // The model's own sweep is said where its text sets the number of samples, as the model's
  // other errors are, so that the editor underlines it: its `steps`' value (line 22, column 16).
  const auto expect_at = [](const ApiResponse& r, int line, int column) {
    const Json e = error_of(r);
    EXPECT_EQ(e.value("file", ""), "model") << r.body;
    EXPECT_EQ(e.value("line", 0), line) << r.body;
    EXPECT_EQ(e.value("column", 0), column) << r.body;
  };
  const ApiResponse own = post("/api/solve", {{"model", many}});
  expect_limit(own, "steps");
  expect_at(own, 22, 16);
  // Written over two lines, or as JSON.
  std::string block = many;
  block.replace(block.find("sweep: {steps: 200000}"), 22, "sweep:\n  steps: 200000");
  expect_at(post("/api/explain", {{"model", block}}), 23, 10);
  std::string law = repo_file("examples/fourbar-oscillating.yaml");
  const auto at = law.find("\nsweep:");
  ASSERT_NE(at, std::string::npos);
  law = law.substr(0, at) + "\nsweep: {duration: 1e12, step: 1e-6}\n";
  const ApiResponse timed = post("/api/solve", {{"model", law}});
  expect_limit(timed, "steps");
  const int law_line = 1 + static_cast<int>(std::count(law.begin(), law.begin() + static_cast<long>(at) + 1, '\n'));
  expect_at(timed, law_line, 31);  // a sweep in time: its `step`
  expect_limit(post("/api/render", {{"model", law}, {"kind", "draw"}}), "steps");
  // The option `steps` is the request's, not the model's: no place in the model.
  const ApiResponse option = post("/api/solve", with_model("examples/fourbar-crank-rocker.yaml", {{"steps", 100002}}));
  EXPECT_FALSE(error_of(option).contains("line")) << option.body;
  // The table: samples x columns (machine-18 has hundreds of columns).
  const ApiResponse table = post("/api/solve", with_model("examples/machine-18.yaml", {{"steps", 100001}}));
  expect_limit(table, "table_values");
  expect_limit(post("/api/render",
                    with_model("examples/machine-18.yaml", {{"kind", "plot"}, {"y", "crank"}, {"steps", 100001}})),
               "table_values");
  expect_limit(post("/api/report", with_model("examples/machine-18.yaml", {{"steps", 100001}})), "table_values");
  // A scene holds every sample's positions (it answered 76 MB from a light slot).
  expect_limit(post("/api/render",
                    with_model("examples/machine-18.yaml", {{"kind", "draw"}, {"format", "scene"}, {"steps", 100001}})),
               "table_values");
  EXPECT_EQ(
      post("/api/solve", with_model("examples/fourbar-crank-rocker.yaml", {{"steps", 100001}, {"columns", "crank"}}))
          .status,
      200);
  // The order: 0 to 5, as the CLI's.
  expect_error(post("/api/solve", with_model("examples/fourbar-crank-rocker.yaml", {{"order", 6}})), 400, "bad_input");
}

TEST(WebLimits, SectionsFramesAndPixels) {
  const ApiResponse many = post("/api/stress", with_model("examples/fourbar-steel-bars.yaml", {{"sections", 5000}}));
  expect_limit(many, "sections");
  // A limit is a whole number, and JSON says so: 2000, not 2000.0.
  EXPECT_TRUE(error_of(many)["max"].is_number_integer()) << many.body;
  EXPECT_EQ(error_of(many)["max"], 2000);
  const ApiResponse few = post("/api/stress", with_model("examples/fourbar-steel-bars.yaml", {{"sections", 5}}));
  expect_error(few, 400, "bad_input");
  // The request's range, the same in every front-end (nbar/request); over this server's own limit
  // (2000) is a 413, above.
  EXPECT_EQ(error_of(few)["message"], "sections: must be from 10 to 100000, not 5");
  EXPECT_EQ(error_of(few)["option"], "sections");
  expect_limit(
      post("/api/render", with_model("examples/fourbar-crank-rocker.yaml", {{"kind", "animate"}, {"frames", 1000}})),
      "frames");
  expect_limit(post("/api/report", with_model("examples/fourbar-crank-rocker.yaml", {{"frames", 900}})), "frames");
  expect_limit(
      post("/api/render", with_model("examples/fourbar-crank-rocker.yaml", {{"kind", "draw"}, {"width", 5000}})),
      "pixels");
  // Outside the request's range is bad input, with the range every front-end gives; inside it but
  // over this server's limit, a 413 (above).
  const auto message = [](const ApiResponse& r) { return error_of(r)["message"].get<std::string>(); };
  EXPECT_EQ(message(post("/api/render",
                         with_model("examples/fourbar-crank-rocker.yaml", {{"kind", "draw"}, {"width", 20000}}))),
            "width: must be from 100 to 10000, not 20000");
  EXPECT_EQ(message(post("/api/render",
                         with_model("examples/fourbar-crank-rocker.yaml", {{"kind", "animate"}, {"height", 10}}))),
            "height: must be from 64 to 8192, not 10");
  EXPECT_EQ(message(post("/api/render", with_model("examples/fourbar-crank-rocker.yaml",
                                                   {{"kind", "plot"}, {"y", "P.y"}, {"width", 50}}))),
            "width: must be from 200 to 10000, not 50");
  ServerConfig small = test_config();
  small.limits.max_pixels = 1000;
  const ApiResponse narrow =
      post("/api/render", with_model("examples/fourbar-crank-rocker.yaml", {{"kind", "draw"}, {"width", 50}}), small);
  EXPECT_EQ(message(narrow), "width: must be from 100 to 10000, not 50");
  expect_limit(
      post("/api/render", with_model("examples/fourbar-crank-rocker.yaml", {{"kind", "draw"}, {"width", 1200}}), small),
      "pixels");
  expect_limit(post("/api/render", with_model("examples/fourbar-crank-rocker.yaml",
                                              {{"kind", "plot"}, {"y", "P.y"}, {"height", 3000}})),
               "pixels");
  expect_limit(
      post("/api/render", with_model("examples/fourbar-crank-rocker.yaml",
                                     {{"kind", "animate"}, {"frames", 360}, {"width", 2000}, {"height", 2000}})),
      "animation_pixels");
}

TEST(WebLimits, ExplainTakesSmallModels) {
  ServerConfig config = test_config();
  config.limits.max_explain_bodies = 10;
  expect_limit(post("/api/explain", with_model("examples/machine-18.yaml"), config), "explain_bodies");
  config = test_config();
  config.limits.max_explain_points = 10;
  expect_limit(post("/api/explain", with_model("examples/machine-18.yaml"), config), "explain_points");
  EXPECT_EQ(post("/api/explain", with_model("examples/machine-18.yaml", {{"steps", 5}, {"step", 2}})).status, 200);
  expect_limit(post("/api/explain", with_model("examples/fourbar-crank-rocker.yaml", {{"steps", 200000}})), "steps");
}

TEST(WebLimits, Synthesis) {
  expect_limit(
      post("/api/synth/five-point", with_task("examples/synthesis/five-point-crank-rocker.yaml", {{"top", 1000}})),
      "top");
  expect_limit(
      post("/api/synth/five-point", with_task("examples/synthesis/five-point-crank-rocker.yaml", {{"threads", 64}})),
      "threads");
  std::string curves = repo_file("examples/synthesis/burmester-four-positions.yaml");
  const std::string window = "curves: {radius: 400}";
  ASSERT_NE(curves.find(window), std::string::npos);
  curves.replace(curves.find(window), window.size(), "curves: {radius: 1000, step: 0.001}");
  expect_limit(post("/api/synth/burmester", {{"task", curves}}), "curve_samples");
  curves.replace(curves.find("radius: 1000, "), 14, "");
  expect_limit(post("/api/synth/burmester", {{"task", curves}}), "curve_samples");
}

TEST(WebLimits, TimeBudgetCancelsAHugeSweep) {
  ServerConfig config = test_config();
  config.limits.time_budget_seconds = 0.2;
  config.limits.max_table_values = 1e12;
  const auto start = std::chrono::steady_clock::now();
  const ApiResponse r =
      post("/api/solve", with_model("examples/machine-18.yaml", {{"steps", 100001}, {"order", 5}, {"dynamics", true}}),
           config);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  expect_error(r, 504, "time_budget_exceeded");
  EXPECT_LT(seconds, 3.0);
  std::cout << "[ web      ] a 100001-step sweep of machine-18 with a 0.2 s budget answered 504 after " << seconds
            << " s\n";
  // Synthesis too.
  config.limits.time_budget_seconds = 1e-6;
  expect_error(post("/api/synth/five-point", with_task("examples/synthesis/five-point-crank-rocker.yaml"), config), 504,
               "time_budget_exceeded");
}

TEST(WebLimits, TooManyJobsIsA503WithRetryAfter) {
  ServerConfig config = test_config();
  config.jobs = std::make_shared<web::JobSlots>(2);
  config.light_jobs = std::make_shared<web::JobSlots>(1);
  config.queue_wait_seconds = 0;  // no waiting: a full pool answers at once
  const Json task = with_task("examples/synthesis/five-point-crank-rocker.yaml");
  const Json fourbar = with_model("examples/fourbar-crank-rocker.yaml");
  {
    web::JobSlots::Slot a = config.jobs->try_acquire(), b = config.jobs->try_acquire();
    ASSERT_TRUE(a && b);
    const ApiResponse r = post("/api/synth/five-point", task, config);
    expect_error(r, 503, "too_many_jobs");
    EXPECT_EQ(header(r, "Retry-After"), "2");
    EXPECT_EQ(error_of(r)["limit"], "jobs");
    expect_error(post("/api/stress", with_model("examples/fourbar-steel-bars.yaml"), config), 503, "too_many_jobs");
    expect_error(post("/api/report", fourbar, config), 503, "too_many_jobs");
    // Light computations have slots of their own: a class's solves never wait for a synthesis.
    EXPECT_EQ(post("/api/check", fourbar, config).status, 200);
    const ApiResponse solve =
        post("/api/solve", with_model("examples/fourbar-crank-rocker.yaml", {{"steps", 361}}), config);
    EXPECT_EQ(solve.status, 200);
    EXPECT_EQ(Json::parse(solve.body)["rows"].size(), 361u);
    // A sweep whose table is over light_table_values is heavy.
    expect_error(post("/api/solve", with_model("examples/machine-18.yaml", {{"steps", 361}}), config), 503,
                 "too_many_jobs");
    // What computes nothing is still answered.
    EXPECT_EQ(call("GET", "/api/health", "", config).status, 200);
  }
  {
    web::JobSlots::Slot light = config.light_jobs->try_acquire();
    ASSERT_TRUE(light);
    const ApiResponse r = post("/api/check", fourbar, config);
    expect_error(r, 503, "too_many_jobs");
    EXPECT_EQ(error_of(r)["limit"], "light_jobs");
    // Reading the request is work too: a request over a limit waits for its slot like any other
    // (its model must be read to know), and a full pool answers it 503.
    expect_error(post("/api/solve", with_model("examples/fourbar-crank-rocker.yaml", {{"steps", 200000}}), config), 503,
                 "too_many_jobs");
  }
  EXPECT_EQ(config.jobs->in_use(), 0);
  EXPECT_EQ(config.light_jobs->in_use(), 0);
  EXPECT_EQ(post("/api/synth/five-point", task, config).status, 200);
}

TEST(WebLimits, OneMoreSimultaneousHeavyJobThanSlotsGetsOne503WhenNoneMayWait) {
  constexpr int kSlots = 2;
  ServerConfig config = test_config();
  config.jobs = std::make_shared<web::JobSlots>(kSlots);
  config.queue_wait_seconds = 0;
  config.limits.time_budget_seconds = 1.5;  // each heavy job runs into it
  config.limits.max_table_values = 1e12;    // the sweep must run into the time budget
  const Json huge = with_model("examples/machine-18.yaml", {{"steps", 100001}, {"order", 5}, {"dynamics", true}});
  std::vector<std::future<int>> statuses;
  std::promise<void> go;
  std::shared_future<void> started = go.get_future().share();
  for (int i = 0; i < kSlots + 1; ++i)
    statuses.push_back(std::async(std::launch::async, [&, started] {
      started.wait();
      return post("/api/solve", huge, config).status;
    }));
  go.set_value();
  int busy = 0, timed_out = 0;
  for (auto& s : statuses) {
    const int status = s.get();
    busy += status == 503;
    timed_out += status == 504;
  }
  EXPECT_EQ(busy, 1);
  EXPECT_EQ(timed_out, kSlots);
  EXPECT_EQ(config.jobs->in_use(), 0);
}

TEST(WebLimits, AJobWaitsForItsTurnAndItsBudgetStartsThen) {
  // One slot: a job that runs into its 0.5 s budget, and a quick heavy one that waits for it,
  // then gets its whole budget (a budget counted from the request would have run out while it
  // waited, and answered 504).
  ServerConfig config = test_config();
  config.jobs = std::make_shared<web::JobSlots>(1);
  config.queue_wait_seconds = 30;
  config.limits.time_budget_seconds = 0.5;
  config.limits.max_table_values = 1e12;
  const Json huge = with_model("examples/machine-18.yaml", {{"steps", 100001}, {"order", 5}, {"dynamics", true}});
  auto first = std::async(std::launch::async, [&] { return post("/api/solve", huge, config); });
  while (config.jobs->in_use() == 0) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  const Json quick = with_model("examples/fourbar-steel-bars.yaml", {{"steps", 13}, {"sections", 10}});
  auto second = std::async(std::launch::async, [&] { return post("/api/stress", quick, config); });
  const ApiResponse a = first.get(), b = second.get();
  expect_error(a, 504, "time_budget_exceeded");
  EXPECT_EQ(b.status, 200) << b.body;
  EXPECT_EQ(b.body, post("/api/stress", quick).body);
  EXPECT_EQ(config.jobs->in_use(), 0);
  EXPECT_EQ(config.jobs->waiting(), 0);
}

TEST(WebJobSlots, FirstComeFirstServedWithABoundedWait) {
  web::JobSlots slots(1, /*max_waiting=*/2);
  web::JobSlots::Slot held = slots.try_acquire();
  ASSERT_TRUE(held);
  EXPECT_FALSE(slots.try_acquire());
  // A wait that runs out gives nothing and leaves the queue.
  EXPECT_FALSE(slots.acquire(std::chrono::milliseconds(20)));
  EXPECT_EQ(slots.waiting(), 0);
  // Two waiters are served in their order of arrival; a third finds the queue full at once.
  std::vector<int> order;
  std::mutex order_mutex;
  const auto waiter = [&](int id) {
    web::JobSlots::Slot s = slots.acquire(std::chrono::seconds(30));
    const std::lock_guard lock(order_mutex);
    order.push_back(s ? id : -id);
  };
  std::thread one(waiter, 1);
  while (slots.waiting() < 1) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  std::thread two(waiter, 2);
  while (slots.waiting() < 2) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  EXPECT_FALSE(slots.acquire(std::chrono::seconds(30)));  // the queue is full: no wait
  held = web::JobSlots::Slot();                           // gives the slot back
  one.join();
  two.join();
  EXPECT_EQ(order, (std::vector<int>{1, 2}));
  EXPECT_EQ(slots.in_use(), 0);
}

}  // namespace
}  // namespace nbar::web_test
