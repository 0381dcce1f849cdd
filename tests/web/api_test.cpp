// Every endpoint of the web API with real models and tasks, against the CLI's own output for
// the same request: the answers must be the same JSON (byte for byte where the CLI writes it
// as it is) and the same pictures.
#include "web/web_support.hpp"

#include "nbar/render/animation.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <regex>

namespace nbar::web_test {
namespace {

// A primitive's vertices (px), sorted: a body's outline is the same whichever vertex it starts at.
using Vertices = std::vector<std::pair<double, double>>;
Vertices sorted(Vertices v) {
  std::sort(v.begin(), v.end(),
            [](const auto& a, const auto& b) { return a.first + 1e-3 * a.second < b.first + 1e-3 * b.second; });
  return v;
}

// The vertices of every `points="..."` (or every circle's centre) of an SVG, in order.
std::vector<Vertices> svg_primitives(const std::string& svg, const std::regex& pattern) {
  std::vector<Vertices> out;
  for (std::sregex_iterator it(svg.begin(), svg.end(), pattern), end; it != end; ++it) {
    const std::string text = (*it)[1].str();
    const std::regex number(R"(-?[0-9.]+)");
    std::vector<double> numbers;
    for (std::sregex_iterator n(text.begin(), text.end(), number); n != end; ++n)
      numbers.push_back(std::stod(n->str()));
    Vertices v;
    for (std::size_t i = 0; i + 1 < numbers.size(); i += 2) v.emplace_back(numbers[i], numbers[i + 1]);
    out.push_back(sorted(v));
  }
  return out;
}

// The same from a scene's items, each body group moved by its motion in `motions`.
void scene_primitives(const Json& items, const Json& scene, const Json& motions, int body,
                      std::vector<Vertices>& points, std::vector<Vertices>& circles) {
  auto place = [&](double x, double y) {
    if (body < 0) return std::pair{x, y};
    const Json& m = motions[body];
    const double a = m[0].get<double>() * M_PI / 180, dx = m[1], dy = m[2];
    const double px = scene["bodies"][body]["pivot"][0], py = scene["bodies"][body]["pivot"][1];
    return std::pair{std::cos(a) * (x - px) - std::sin(a) * (y - py) + px + dx,
                     std::sin(a) * (x - px) + std::cos(a) * (y - py) + py + dy};
  };
  for (const Json& it : items) {
    const std::string type = it["type"];
    if (type == "group") {
      if (it["id"] == "labels") continue;  // placed anew by nbar draw at other poses
      int inner = body;
      for (std::size_t k = 0; k < scene["bodies"].size(); ++k)
        if (scene["bodies"][k]["group"] == it["id"]) inner = static_cast<int>(k);
      scene_primitives(it["items"], scene, motions, inner, points, circles);
    } else if (type == "polygon" || type == "polyline") {
      Vertices v;
      for (std::size_t i = 0; i + 1 < it["points"].size(); i += 2)
        v.push_back(place(it["points"][i], it["points"][i + 1]));
      points.push_back(sorted(v));
    } else if (type == "circle") {
      circles.push_back({place(it["cx"], it["cy"])});
    }
  }
}

TEST(WebApi, CheckIsTheJsonOfNbarCheck) {
  for (const std::string file : {"examples/fourbar-crank-rocker.yaml", "examples/fourbar-steel-bars.yaml",
                                 "examples/parallelogram-redundant.yaml", "examples/machine-18.yaml"}) {
    SCOPED_TRACE(file);
    const ApiResponse r = post("/api/check", with_model(file));
    ASSERT_EQ(r.status, 200) << r.body;
    EXPECT_EQ(r.content_type, "application/json");
    const cli_test::CliRun run = cli("check " + file + " --format json");
    ASSERT_EQ(run.code, 0) << run.err;
    Json expected = Json::parse(run.out);
    expected["source"] = "model";  // the CLI names the file, the server the request's model
    EXPECT_EQ(Json::parse(r.body), expected);
    EXPECT_EQ(Json::parse(r.body)["dof"]["mobility"], 1);
  }
}

TEST(WebApi, CheckReportsAnAssemblyFailureInTheSummary) {
  const ApiResponse r = post("/api/check", with_model("tests/golden/inputs/cannot-assemble.yaml"));
  ASSERT_EQ(r.status, 200) << r.body;
  const Json j = Json::parse(r.body);
  EXPECT_TRUE(j["assembly"].is_null());
  EXPECT_EQ(j["assembly_error"]["kind"], "cannot_assemble");
  EXPECT_GT(j["assembly_error"]["line"].get<int>(), 0);
}

TEST(WebApi, CheckTakesAModelWrittenAsJson) {
  // JSON is YAML: the model can come as JSON text, or as a JSON object inside the body.
  const Json model = {{"name", "json four-bar"},
                      {"points", {{"O2", {0, 0}}, {"O4", {4, 0}}, {"A", {1, 0}}, {"B", {4.5, 3}}}},
                      {"ground", {"O2", "O4"}},
                      {"bodies", {{"crank", {"O2", "A"}}, {"coupler", {"A", "B"}}, {"rocker", {"O4", "B"}}}},
                      {"drivers", {{{"angle", "crank"}, {"from", 0}, {"to", 360}}}}};
  const ApiResponse as_text = post("/api/check", {{"model", model.dump()}});
  const ApiResponse as_object = post("/api/check", {{"model", model}});
  ASSERT_EQ(as_text.status, 200) << as_text.body;
  EXPECT_EQ(as_text.body, as_object.body);
  EXPECT_EQ(Json::parse(as_text.body)["model"], "json four-bar");
}

TEST(WebApi, SolveIsByteForByteNbarSolveFormatJson) {
  const ApiResponse r =
      post("/api/solve", with_model("examples/fourbar-crank-rocker.yaml", {{"steps", 7}, {"order", 3}}));
  ASSERT_EQ(r.status, 200) << r.body;
  const cli_test::CliRun run = cli("solve examples/fourbar-crank-rocker.yaml --steps 7 --order 3 --format json");
  ASSERT_EQ(run.code, 0);
  EXPECT_EQ(r.body, run.out);
  // The numbers themselves: the rocker's angle at the start of the crank-rocker.
  const Json j = Json::parse(r.body);
  const auto& columns = j["columns"];
  const auto at = std::find(columns.begin(), columns.end(), "rocker.angle") - columns.begin();
  EXPECT_NEAR(j["rows"][0][at].get<double>(), 97.18075589957508, 1e-9);
}

TEST(WebApi, SolveWithDynamicsColumnsAndOrderFive) {
  const ApiResponse r = post(
      "/api/solve", with_model("examples/fourbar-steel-bars.yaml",
                               {{"steps", 13}, {"dynamics", true}, {"columns", {"crank", "crank.torque", "*.Fx"}}}));
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(r.body,
            cli("solve examples/fourbar-steel-bars.yaml --steps 13 --dynamics --columns 'crank,crank.torque,*.Fx' "
                "--format json")
                .out);
  const ApiResponse o5 = post("/api/solve", with_model("examples/compressor-myszka.yaml",
                                                       {{"steps", 5}, {"order", 5}, {"columns", "crank,C.*"}}));
  ASSERT_EQ(o5.status, 200) << o5.body;
  EXPECT_EQ(o5.body,
            cli("solve examples/compressor-myszka.yaml --steps 5 --order 5 --columns 'crank,C.*' --format json").out);
}

TEST(WebApi, SolveAsCsvAndTable) {
  const ApiResponse csv = post("/api/solve", with_model("examples/five-bar.yaml", {{"steps", 5}, {"format", "csv"}}));
  ASSERT_EQ(csv.status, 200);
  EXPECT_EQ(csv.content_type, "text/csv; charset=utf-8");
  EXPECT_EQ(csv.body, cli("solve examples/five-bar.yaml --steps 5").out);
  const ApiResponse table =
      post("/api/solve", with_model("examples/five-bar.yaml", {{"steps", 5}, {"format", "table"}}));
  EXPECT_EQ(table.body, cli("solve examples/five-bar.yaml --steps 5 --format table").out);
}

TEST(WebApi, ASweepStoppedAtAToggleIsNotAnError) {
  const ApiResponse r =
      post("/api/solve", with_model("tests/golden/inputs/toggle-stop.yaml", {{"columns", {"input", "output.angle"}}}));
  ASSERT_EQ(r.status, 200) << r.body;
  const Json j = Json::parse(r.body);
  EXPECT_FALSE(j["complete"].get<bool>());
  EXPECT_FALSE(j["stop_reason"].get<std::string>().empty());
  const cli_test::CliRun run =
      cli("solve tests/golden/inputs/toggle-stop.yaml --columns input,output.angle --format json");
  EXPECT_EQ(run.code, 4);
  EXPECT_EQ(r.body, run.out);
}

TEST(WebApi, StressIsNbarStressFormatJson) {
  const ApiResponse r =
      post("/api/stress", with_model("examples/fourbar-steel-bars.yaml", {{"steps", 13}, {"sections", 40}}));
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(r.body, cli("stress examples/fourbar-steel-bars.yaml --steps 13 --sections 40 --format json").out);
  const ApiResponse profile =
      post("/api/stress", with_model("examples/crank-rocker-gravity-spring.yaml",
                                     {{"steps", 13}, {"section_profile", "coupler"}, {"step", 9}, {"sections", 40}}));
  ASSERT_EQ(profile.status, 200) << profile.body;
  EXPECT_EQ(profile.body, cli("stress examples/crank-rocker-gravity-spring.yaml --steps 13 --section-profile coupler "
                              "--step 9 --sections 40 --format json")
                              .out);
}

TEST(WebApi, FiniteElementStressIsNbarStressMethodFe) {
  const ApiResponse r = post("/api/stress", with_model("examples/fourbar-steel-bars.yaml",
                                                       {{"steps", 5}, {"method", "fe"}, {"mesh_size", 4}}));
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(r.body,
            cli("stress examples/fourbar-steel-bars.yaml --steps 5 --method fe --mesh-size 4 --format json").out);
  EXPECT_NE(r.body.find("\"method\": \"fe\""), std::string::npos);
  EXPECT_EQ(post("/api/stress", with_model("examples/fourbar-steel-bars.yaml", {{"method", "fem"}})).status, 400);
  EXPECT_EQ(post("/api/stress", with_model("examples/fourbar-steel-bars.yaml", {{"mesh_size", 4}})).status, 400);
}

TEST(WebApi, FiniteElementFieldQueriesAnswerAsTheCommandLine) {
  const std::string plates = "examples/fourbar-ansys-plates.yaml";
  const std::vector<std::pair<Json, std::string>> cases = {
      {{{"around_hole", "crank:A"}}, "--around-hole crank:A"},
      {{{"section_profile", "crank"}, {"at", {"0.5", "0.1", "0.3", "0.2"}}},
       "--section-profile crank --at 0.5,0.1,0.3,0.2"},
      {{{"section_profile", "coupler"}, {"along", "A,B"}, {"samples", 21}, {"coordinates", "model"}},
       "--section-profile coupler --along A,B --samples 21 --coordinates model"},
      {{{"section_profile", "rocker"}, {"samples", 11}}, "--section-profile rocker --samples 11"},
  };
  for (const auto& [options, flags] : cases) {
    Json body = options;
    body["steps"] = 1;
    body["method"] = "fe";
    body["format"] = "json";
    const ApiResponse r = post("/api/stress", with_model(plates, body));
    ASSERT_EQ(r.status, 200) << flags << ": " << r.body;
    EXPECT_EQ(r.body, cli("stress " + plates + " --steps 1 --method fe --format json " + flags).out) << flags;
  }
  const ApiResponse off = post(
      "/api/stress", with_model(plates, {{"steps", 1}, {"method", "fe"}, {"section_profile", "crank"}, {"at", "O2"}}));
  EXPECT_EQ(off.status, 400);
  EXPECT_NE(off.body.find("is not on the plate of 'crank'"), std::string::npos) << off.body;
  const ApiResponse files =
      post("/api/stress", with_model(plates, {{"steps", 1}, {"method", "fe"}, {"export_mesh", "/tmp"}}));
  EXPECT_EQ(files.status, 400);
  EXPECT_NE(files.body.find("\"option\": \"export_mesh\""), std::string::npos) << files.body;
}

// A table of the command line's JSON (`--format json`): the value of `column` in its one row.
double cli_table_value(const std::string& json, const std::string& column) {
  const Json t = Json::parse(json);
  const auto& columns = t.at("columns");
  for (std::size_t c = 0; c < columns.size(); ++c)
    if (columns[c] == column) return t.at("rows").at(0).at(c).get<double>();
  ADD_FAILURE() << "no column " << column << " in " << json;
  return std::nan("");
}

std::string number_17(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

TEST(WebApi, StressProbeIsTheCommandLinesPointQueryOnTheLinkDrawnThere) {
  const std::string plates = "examples/fourbar-ansys-plates.yaml";
  const int step = 2;  // of 3: the crank turned from 60 to 0 deg, every link moved from where it is drawn
  const ApiResponse solve = post("/api/solve", with_model(plates, {{"steps", 3}}));
  ASSERT_EQ(solve.status, 200) << solve.body;
  const Json s = Json::parse(solve.body);
  auto posed = [&](const std::string& point) {
    const auto& columns = s.at("columns");
    const auto at = [&](const std::string& c) {
      const auto i = std::find(columns.begin(), columns.end(), c) - columns.begin();
      return s.at("rows").at(step).at(i).get<double>();
    };
    return Eigen::Vector2d(at(point + ".x"), at(point + ".y"));
  };
  // Model coordinates where the model draws its points (the file's).
  const std::map<std::string, Eigen::Vector2d> drawn = {
      {"O4", {2, 0}}, {"A", {0.5, 0.8660254038}}, {"B", {1.8623724357, 1.4936742197}}};
  struct Case {
    std::string link, from, to;
    double along, left;  // of the link's axis from `from` to `to` (length units), to its left
  };
  for (const Case& c : {Case{"coupler", "A", "B", 0.5, 0.0}, Case{"rocker", "O4", "B", 0.3, 0.1},
                        Case{"coupler", "A", "B", 0.02, -0.2}}) {
    SCOPED_TRACE(c.link + " at " + std::to_string(c.along));
    auto place = [&](const Eigen::Vector2d& p0, const Eigen::Vector2d& p1) {
      const Eigen::Vector2d u = (p1 - p0).normalized();
      return Eigen::Vector2d(p0 + c.along * (p1 - p0) + c.left * Eigen::Vector2d(-u.y(), u.x()));
    };
    const Eigen::Vector2d seen = place(posed(c.from), posed(c.to));
    const ApiResponse r =
        post("/api/stress/probe", with_model(plates, {{"steps", 3}, {"step", step}, {"x", seen.x()}, {"y", seen.y()}}));
    ASSERT_EQ(r.status, 200) << r.body;
    const Json probe = Json::parse(r.body);
    ASSERT_EQ(probe.at("link"), c.link) << r.body;
    // The same place on the link as the file draws it: the rigid motion undone.
    const Eigen::Vector2d model_point = place(drawn.at(c.from), drawn.at(c.to));
    EXPECT_NEAR(probe.at("model_x").get<double>(), model_point.x(), 1e-8);
    EXPECT_NEAR(probe.at("model_y").get<double>(), model_point.y(), 1e-8);
    const std::string at =
        number_17(probe.at("model_x").get<double>()) + "," + number_17(probe.at("model_y").get<double>());
    const cli_test::CliRun run = cli("stress " + plates + " --steps 3 --method fe --format json --section-profile " +
                                     c.link + " --step " + std::to_string(step) + " --coordinates model --at=" + at);
    ASSERT_EQ(run.code, 0) << run.out;
    const double expected = cli_table_value(run.out, "von_mises");
    EXPECT_GT(expected, 0.0);
    EXPECT_NEAR(probe.at("von_mises").get<double>(), expected, 1e-9 * expected);
    EXPECT_NEAR(probe.at("sigma_xx").get<double>(), cli_table_value(run.out, "sigma_xx"), 1e-9 * expected);
    EXPECT_EQ(probe.at("units").at("stress"), "MPa");
    EXPECT_EQ(probe.at("units").at("length"), "m");
  }
  // Off every plate: far away, and in the crank's pin hole at O2 (which never moves).
  for (const auto& [x, y] : std::vector<std::pair<double, double>>{{40, -40}, {0, 0}}) {
    const ApiResponse off =
        post("/api/stress/probe", with_model(plates, {{"steps", 3}, {"step", step}, {"x", x}, {"y", y}}));
    ASSERT_EQ(off.status, 200) << off.body;
    const Json j = Json::parse(off.body);
    EXPECT_TRUE(j.at("link").is_null()) << off.body;
    EXPECT_FALSE(j.contains("von_mises")) << off.body;
  }
  // Errors at their option, as the other requests give them.
  const ApiResponse past =
      post("/api/stress/probe", with_model(plates, {{"steps", 3}, {"step", 7}, {"x", 1}, {"y", 1}}));
  EXPECT_EQ(past.status, 400);
  EXPECT_EQ(error_of(past)["option"], "step") << past.body;
  const ApiResponse no_y = post("/api/stress/probe", with_model(plates, {{"steps", 3}, {"x", 1}}));
  EXPECT_EQ(no_y.status, 400);
  EXPECT_EQ(error_of(no_y)["option"], "y") << no_y.body;
  const ApiResponse unplated =
      post("/api/stress/probe", with_model("examples/fourbar-crank-rocker.yaml", {{"x", 1}, {"y", 1}}));
  EXPECT_EQ(unplated.status, 422) << unplated.body;
  EXPECT_EQ(error_of(unplated)["kind"], "invalid_model");
}

TEST(WebApi, SynthesisIsNbarSynthFormatJson) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"five-point", "examples/synthesis/five-point-crank-rocker.yaml"},
      {"burmester", "examples/synthesis/burmester-five-positions.yaml"},
      {"burmester", "examples/synthesis/burmester-three-positions.yaml"},
      {"function", "examples/synthesis/function-log10.yaml"},
  };
  for (const auto& [kind, file] : cases) {
    SCOPED_TRACE(file);
    const ApiResponse r = post("/api/synth/" + kind, with_task(file, {{"all", true}, {"top", 5}}));
    ASSERT_EQ(r.status, 200) << r.body;
    // The same designs; the last bits of the homotopy's numbers may differ between runs in
    // unoptimised builds (paths on several threads), so numbers are compared to 1e-9.
    EXPECT_TRUE(json_near(Json::parse(r.body),
                          Json::parse(cli("synth " + kind + " " + file + " --all --top 5 --format json").out)));
  }
  // Nine-point tasks have their endpoint; a task sent to another method's is refused, naming the right one.
  const Json wrong =
      error_of(post("/api/synth/nine-point", with_task("examples/synthesis/five-point-crank-rocker.yaml")));
  EXPECT_EQ(wrong["kind"], "bad_input");
  EXPECT_NE(wrong["message"].get<std::string>().find("/api/synth/five-point"), std::string::npos);
  EXPECT_NE(
      error_of(post("/api/synth/five-point", with_task("examples/synthesis/nine-point-crank-rocker.yaml")))["message"]
          .get<std::string>()
          .find("/api/synth/nine-point"),
      std::string::npos);
  const ApiResponse five = post("/api/synth/five-point", with_task("examples/synthesis/five-point-crank-rocker.yaml"));
  ASSERT_EQ(five.status, 200);
  EXPECT_NE(five.body.find("crank-rocker"), std::string::npos);
  // Another seed, one thread: still the CLI's answer for that seed.
  const ApiResponse seeded = post("/api/synth/five-point", with_task("examples/synthesis/five-point-crank-rocker.yaml",
                                                                     {{"seed", 7}, {"threads", 1}, {"top", 0}}));
  ASSERT_EQ(seeded.status, 200) << seeded.body;
  EXPECT_TRUE(
      json_near(Json::parse(seeded.body),
                Json::parse(cli("synth five-point examples/synthesis/five-point-crank-rocker.yaml --seed 7 --top 0 "
                                "--format json")
                                .out)));
  // The task as a JSON object.
  const Json task = {{"task", "function"}, {"name", "square"},         {"function", "x^2"},
                     {"x", {0, 1}},        {"input_range", {90, 150}}, {"output_range", {60, 120}}};
  const ApiResponse object = post("/api/synth/function", {{"task", task}});
  ASSERT_EQ(object.status, 200) << object.body;
  EXPECT_EQ(Json::parse(object.body)["name"], "square");
}

TEST(WebApi, PathSynthesisIsNbarSynthPathAndOpensNoFile) {
  const std::string file = "examples/synthesis/path/crank-rocker-measured.yaml";
  const ApiResponse r = post("/api/synth/path", with_task(file, {{"top", 3}, {"threads", 1}}));
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_TRUE(json_near(Json::parse(r.body),
                        Json::parse(cli("synth path " + file + " --top 3 --threads 1 --format json").out)));
  // A client's `curve:` names a file on the server: refused at its line and column, unread
  // (the file exists and its second line would be quoted back if it were read).
  const auto dir = temp_folder("path-curve");
  const std::string secret = (dir / "secret.csv").string();
  std::ofstream(secret) << "x,y\n1,do-not-show-this\n";
  const ApiResponse curve = post("/api/synth/path", {{"task", "task: path\ncurve: " + secret + "\n"}});
  EXPECT_EQ(curve.status, 422) << curve.body;
  const Json error = error_of(curve);
  EXPECT_EQ(error["line"], 2);
  EXPECT_EQ(error["column"], 8);
  EXPECT_EQ(error["message"],
            "`curve` reads a CSV file, which only a task read from a file may do: give the targets "
            "here as `points: [[x, y], ...]`");
  EXPECT_EQ(curve.body.find("do-not-show-this"), std::string::npos);
  // The same from another method's endpoint, which parses the task before checking its kind.
  EXPECT_EQ(post("/api/synth/five-point", {{"task", "task: path\ncurve: " + secret + "\n"}}).body.find("do-not-show"),
            std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST(WebApi, SynthesisModelsAreTheFilesOfSynthExport) {
  // "models": true gives each real design the model file `nbar synth --export` writes for it;
  // complex designs have none.
  const auto dir = temp_folder("synth-export");
  const std::string file = "examples/synthesis/five-point-crank-rocker.yaml";
  const ApiResponse r =
      post("/api/synth/five-point", with_task(file, {{"models", true}, {"all", true}, {"top", 0}, {"threads", 1}}));
  ASSERT_EQ(r.status, 200) << r.body;
  const cli_test::CliRun run = cli("synth five-point " + file + " --all --top 0 --threads 1 --export " + dir.string());
  ASSERT_EQ(run.code, 0) << run.err;
  const Json designs = Json::parse(r.body)["designs"];
  ASSERT_EQ(designs.size(), 36u);  // every solution of the 36 paths
  const auto file_of = [&](int rank) {
    return dir / ((rank < 10 ? "design-0" : "design-") + std::to_string(rank) + ".yaml");
  };
  int with_model = 0;
  int without = 0;
  for (const Json& d : designs) {
    const int rank = d["rank"].get<int>();
    SCOPED_TRACE(rank);
    if (!d["real"].get<bool>() || !d.value("valid", false)) {
      EXPECT_FALSE(d.contains("model"));
      EXPECT_FALSE(std::filesystem::exists(file_of(rank)));
      ++without;
      continue;
    }
    ++with_model;
    ASSERT_TRUE(d.contains("model"));
    const std::string got = d["model"].get<std::string>();
    const std::string expected = read_file(file_of(rank));
    // The CLI's first comment names the task file, the server's the request's task.
    const auto after_first_line = [](const std::string& s) { return s.substr(s.find('\n')); };
    EXPECT_EQ(after_first_line(got), after_first_line(expected));
    EXPECT_EQ(got.rfind("# Design " + std::to_string(rank) + " of nbar synth five-point task\n", 0), 0u);
    // A model the server analyses: one degree of freedom, the design's coupler point at P.
    const ApiResponse check = post("/api/check", {{"model", got}});
    ASSERT_EQ(check.status, 200) << check.body;
    EXPECT_EQ(Json::parse(check.body)["dof"]["mobility"], 1);
    const ApiResponse solve = post("/api/solve", {{"model", got}, {"steps", 2}, {"columns", "P.x,P.y"}});
    ASSERT_EQ(solve.status, 200) << solve.body;
    const Json row = Json::parse(solve.body)["rows"][0];
    EXPECT_NEAR(row[0].get<double>(), d["pivots"]["coupler_point"][0].get<double>(), 1e-6);
    EXPECT_NEAR(row[1].get<double>(), d["pivots"]["coupler_point"][1].get<double>(), 1e-6);
  }
  EXPECT_GE(with_model, 2);
  EXPECT_GE(without, 1);
  // Without the option, no model (the CLI's JSON as it is).
  const ApiResponse plain = post("/api/synth/five-point", with_task(file, {{"top", 3}}));
  EXPECT_FALSE(Json::parse(plain.body)["designs"][0].contains("model"));
  EXPECT_EQ(error_of(post("/api/synth/five-point", with_task(file, {{"models", 1}})))["kind"], "bad_input");
}

TEST(WebApi, RenderDrawIsNbarDraw) {
  const auto dir = temp_folder("draw");
  for (const std::string format : {"svg", "png"}) {
    const ApiResponse r = post("/api/render", with_model("examples/fourbar-crank-rocker.yaml", {{"kind", "draw"},
                                                                                                {"format", format},
                                                                                                {"labels", true},
                                                                                                {"trace", "P"},
                                                                                                {"step", 30},
                                                                                                {"width", 400},
                                                                                                {"height", 300}}));
    ASSERT_EQ(r.status, 200) << r.body;
    EXPECT_EQ(r.content_type, format == "svg" ? "image/svg+xml" : "image/png");
    const std::string out = (dir / ("draw." + format)).string();
    ASSERT_EQ(
        cli("draw examples/fourbar-crank-rocker.yaml --labels --trace P --step 30 --width 400 --height 300 -o " + out)
            .code,
        0);
    EXPECT_EQ(r.body, read_file(out)) << format;
  }
  const ApiResponse at =
      post("/api/render", with_model("examples/fourbar-crank-rocker.yaml", {{"kind", "draw"}, {"at", 90}}));
  ASSERT_EQ(at.status, 200);
  const std::string out = (dir / "at.svg").string();
  ASSERT_EQ(cli("draw examples/fourbar-crank-rocker.yaml --at 90 -o " + out).code, 0);
  EXPECT_EQ(at.body, read_file(out));
  std::filesystem::remove_all(dir);
}

// The scene is what nbar draw draws: at its pose the same primitives, and posed at another sample
// by its motions, the primitives nbar draw --step draws there (labels aside), within 0.05 px.
TEST(WebApi, RenderSceneIsNbarDrawAtEverySample) {
  const auto dir = temp_folder("scene");
  for (const std::string example : {"fourbar-crank-rocker", "slider-crank-offset", "dump-truck-tipper"}) {
    const std::string file = "examples/" + example + ".yaml";
    const ApiResponse r = post(
        "/api/render",
        with_model(file, {{"kind", "draw"}, {"format", "scene"}, {"labels", true}, {"width", 400}, {"height", 300}}));
    ASSERT_EQ(r.status, 200) << r.body;
    EXPECT_EQ(r.content_type, "application/json");
    const Json scene = Json::parse(r.body);
    const Json solve = Json::parse(post("/api/solve", with_model(file)).body);
    ASSERT_EQ(scene["steps"].size(), solve["rows"].size()) << example;
    const int reference = scene["reference_step"];
    const std::regex points(R"re(points="([^"]*)")re"), circles(R"re(<circle cx="([^"]*" cy="[^"]*)")re");
    for (const int step : {reference, reference + 40}) {
      const std::string out = (dir / (example + ".svg")).string();
      ASSERT_EQ(
          cli("draw " + file + " --labels --width 400 --height 300 --step " + std::to_string(step) + " -o " + out).code,
          0);
      std::string svg = read_file(out);
      svg = std::regex_replace(svg, std::regex(R"(<g id="labels"[\s\S]*?</g>)"), "");
      std::vector<Vertices> scene_lines, scene_circles;
      scene_primitives(scene["items"], scene, scene["steps"][step]["bodies"], -1, scene_lines, scene_circles);
      for (const auto& [mine, theirs, what] : {std::tuple{scene_lines, svg_primitives(svg, points), "polygon or line"},
                                               std::tuple{scene_circles, svg_primitives(svg, circles), "circle"}}) {
        ASSERT_EQ(mine.size(), theirs.size()) << example << " step " << step << ": " << what << "s";
        for (std::size_t i = 0; i < mine.size(); ++i) {
          ASSERT_EQ(mine[i].size(), theirs[i].size()) << example << " step " << step << " " << what << " " << i;
          for (std::size_t j = 0; j < mine[i].size(); ++j)
            ASSERT_LT(std::hypot(mine[i][j].first - theirs[i][j].first, mine[i][j].second - theirs[i][j].second), 0.05)
                << example << " step " << step << " " << what << " " << i << " vertex " << j;
        }
      }
    }
    // to_model takes a pixel to the model's (x, -y): the first ground pivot's apex is its point.
    const Json& column = solve["columns"];
    const Json& ground = scene["items"][0];
    ASSERT_EQ(ground["id"], "ground");
    for (const Json& it : ground["items"]) {
      if (it["type"] != "polygon" || it["points"].size() != 6) continue;
      const double k = scene["to_model"][0], tx = scene["to_model"][1], ty = scene["to_model"][2];
      const double x = k * it["points"][0].get<double>() + tx, y = k * it["points"][1].get<double>() + ty;
      bool found = false;
      for (std::size_t c = 0; c + 1 < column.size(); ++c) {
        const std::string name = column[c];
        if (name.size() < 2 || name.substr(name.size() - 2) != ".x" ||
            column[c + 1] != name.substr(0, name.size() - 2) + ".y")
          continue;
        const double px = solve["rows"][reference][c], py = solve["rows"][reference][c + 1];
        found = found || std::hypot(px - x, -py - y) < 0.02 * k * 100;
      }
      EXPECT_TRUE(found) << example << ": no point at the pivot (" << x << ", " << -y << ")";
      break;
    }
  }
  EXPECT_EQ(error_of(post("/api/render", with_model("examples/fourbar-crank-rocker.yaml",
                                                    {{"kind", "draw"}, {"format", "scene"}, {"at", 30}})))["kind"],
            "bad_input");
  std::filesystem::remove_all(dir);
}

// ffprobe's count of the video frames of an MP4 file and their size, as "frames WxH".
std::string probe_mp4(const std::string& path) {
  const std::string command =
      "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
      "stream=nb_read_frames,width,height,codec_name -of csv=p=0 '" +
      path + "'";
  std::FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return "";
  std::string out;
  char buf[256];
  while (std::fgets(buf, sizeof buf, pipe)) out += buf;
  pclose(pipe);
  return out;
}

TEST(WebApi, RenderAnimateIsNbarAnimate) {
  const auto dir = temp_folder("animate");
  for (const std::string format : {"gif", "svg", "html"}) {
    const ApiResponse r = post(
        "/api/render",
        with_model(
            "examples/fourbar-crank-rocker.yaml",
            {{"kind", "animate"}, {"format", format}, {"frames", 12}, {"fps", 10}, {"width", 300}, {"height", 200}}));
    ASSERT_EQ(r.status, 200) << r.body;
    const std::string out = (dir / ("anim." + format)).string();
    ASSERT_EQ(
        cli("animate examples/fourbar-crank-rocker.yaml --frames 12 --fps 10 --width 300 --height 200 -o " + out).code,
        0);
    EXPECT_EQ(r.body, read_file(out)) << format;
    if (format == "html") {
      EXPECT_EQ(header(r, "Content-Security-Policy"), "sandbox allow-scripts");
    }
  }
  const ApiResponse mp4 = post("/api/render", with_model("examples/fourbar-crank-rocker.yaml",
                                                         {{"kind", "animate"}, {"format", "mp4"}, {"frames", 4}}));
  if (render::Animation::program_available("ffmpeg")) {
    EXPECT_EQ(mp4.status, 200);
    EXPECT_EQ(mp4.content_type, "video/mp4");
    // A real H.264 video of the frames asked for, at the default size; `nbar animate` writes one.
    if (render::Animation::program_available("ffprobe")) {
      const std::string file = (dir / "anim.mp4").string();
      std::ofstream(file, std::ios::binary) << mp4.body;
      EXPECT_EQ(probe_mp4(file), "h264,900,640,4\n");
      const std::string cli_file = (dir / "cli.mp4").string();
      ASSERT_EQ(
          cli("animate examples/fourbar-crank-rocker.yaml --frames 6 --width 320 --height 240 -o " + cli_file).code, 0);
      EXPECT_EQ(probe_mp4(cli_file), "h264,320,240,6\n");
    }
  } else {
    EXPECT_EQ(mp4.status, 501);
    EXPECT_EQ(error_of(mp4)["kind"], "not_implemented");
    EXPECT_NE(error_of(mp4)["message"].get<std::string>().find("ffmpeg"), std::string::npos);
  }
  std::filesystem::remove_all(dir);
}

TEST(WebApi, RenderPlatesIsNbarExport) {
  const auto dir = temp_folder("plates");
  const std::string model = "examples/fourbar-rounded-crank.yaml";
  for (const std::string format : {"svg", "dxf"}) {
    const std::string out = (dir / ("plates." + format)).string();
    ASSERT_EQ(cli("export " + model + " --" + format + " " + out).code, 0);
    const ApiResponse r = post("/api/render", with_model(model, {{"kind", "plates"}, {"format", format}}));
    ASSERT_EQ(r.status, 200) << r.body;
    EXPECT_EQ(r.content_type, format == "svg" ? "image/svg+xml" : "image/vnd.dxf");
    EXPECT_EQ(r.body, read_file(out)) << format;
    // Posed where the crank is at 90 degrees, as `--at 90`: another drawing.
    const std::string posed = (dir / ("posed." + format)).string();
    ASSERT_EQ(cli("export " + model + " --" + format + " " + posed + " --at 90").code, 0);
    const ApiResponse at = post("/api/render", with_model(model, {{"kind", "plates"}, {"format", format}, {"at", 90}}));
    ASSERT_EQ(at.status, 200) << at.body;
    EXPECT_EQ(at.body, read_file(posed)) << format;
    EXPECT_NE(at.body, r.body);
  }
  EXPECT_EQ(error_of(post("/api/render", with_model(model, {{"kind", "plates"}, {"format", "png"}})))["kind"],
            "bad_input");
  std::filesystem::remove_all(dir);
}

TEST(WebApi, RenderPlotIsNbarPlot) {
  const auto dir = temp_folder("plot");
  for (const std::string format : {"svg", "png"}) {
    const ApiResponse r =
        post("/api/render", with_model("examples/fourbar-crank-rocker.yaml", {{"kind", "plot"},
                                                                              {"format", format},
                                                                              {"x", "P.x"},
                                                                              {"y", "P.y"},
                                                                              {"steps", 37},
                                                                              {"title", "coupler curve"}}));
    ASSERT_EQ(r.status, 200) << r.body;
    const std::string out = (dir / ("plot." + format)).string();
    ASSERT_EQ(
        cli("plot examples/fourbar-crank-rocker.yaml --x P.x --y P.y --steps 37 --title 'coupler curve' -o " + out)
            .code,
        0);
    EXPECT_EQ(r.body, read_file(out)) << format;
  }
  // Force columns switch the dynamics on, as in the CLI.
  const ApiResponse torque =
      post("/api/render",
           with_model("examples/fourbar-steel-bars.yaml", {{"kind", "plot"}, {"y", {"crank.torque"}}, {"steps", 19}}));
  ASSERT_EQ(torque.status, 200) << torque.body;
  const std::string out = (dir / "torque.svg").string();
  ASSERT_EQ(cli("plot examples/fourbar-steel-bars.yaml --y crank.torque --steps 19 -o " + out).code, 0);
  EXPECT_EQ(torque.body, read_file(out));
  std::filesystem::remove_all(dir);
}

TEST(WebApi, ReportIsNbarReport) {
  const ApiResponse r =
      post("/api/report", with_model("examples/fourbar-steel-bars.yaml", {{"steps", 13}, {"frames", 6}}));
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(r.content_type, "text/html; charset=utf-8");
  const auto dir = temp_folder("report");
  // The CLI shows the file's path where the server shows "model": the same report otherwise.
  const std::filesystem::path model = dir / "model";
  std::filesystem::copy_file(std::filesystem::path(NBAR_SOURCE_DIR) / "examples/fourbar-steel-bars.yaml", model);
  const std::string out = (dir / "report.html").string();
  ASSERT_EQ(cli_test::run_shell("cd '" + dir.string() + "' && '" + NBAR_CLI_PATH +
                                "' report model --steps 13 --frames 6 -o " + out)
                .code,
            0);
  EXPECT_EQ(r.body, read_file(out));
  std::filesystem::remove_all(dir);
}

TEST(WebApi, ExplainIsNbarExplain) {
  const ApiResponse r = post("/api/explain", with_model("examples/scissor-lift.yaml", {{"steps", 13}, {"step", 3}}));
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(r.content_type, "application/json");
  EXPECT_EQ(r.body, cli("explain examples/scissor-lift.yaml --steps 13 --step 3 --format json").out);
  for (const std::string format : {"text", "markdown", "latex"}) {
    const ApiResponse doc =
        post("/api/explain", with_model("examples/fourbar-crank-rocker.yaml", {{"step", 30}, {"format", format}}));
    ASSERT_EQ(doc.status, 200) << doc.body;
    EXPECT_EQ(doc.body, cli("explain examples/fourbar-crank-rocker.yaml --step 30 --format " + format).out) << format;
  }
  // A step the sweep does not have: bad input, as the CLI's exit code 2.
  const ApiResponse bad = post("/api/explain", with_model("examples/fourbar-crank-rocker.yaml", {{"step", 361}}));
  EXPECT_EQ(bad.status, 400) << bad.body;
  EXPECT_EQ(cli("explain examples/fourbar-crank-rocker.yaml --step 361").code, 2);
}

TEST(WebApi, ExamplesAreListedAndServedFromTheBinary) {
  const ApiResponse list = call("GET", "/api/examples");
  ASSERT_EQ(list.status, 200);
  const Json j = Json::parse(list.body)["examples"];
  int models = 0, tasks = 0, templates = 0;
  for (const Json& e : j) {
    (e["kind"] == "task" ? tasks : e["kind"] == "template" ? templates : models) += 1;
    EXPECT_FALSE(e["title"].get<std::string>().empty()) << e;
    EXPECT_FALSE(e["description"].get<std::string>().empty()) << e;
    const ApiResponse text = call("GET", "/api/examples/" + e["name"].get<std::string>());
    ASSERT_EQ(text.status, 200);
    EXPECT_EQ(text.content_type, "application/yaml; charset=utf-8");
    EXPECT_EQ(text.body, repo_file(e["file"].get<std::string>()));
  }
  EXPECT_EQ(models, 31);  // every model file of examples/, slider-crank-inclined.yaml (a guide by an angle) the newest
  EXPECT_EQ(tasks, 7);    // path/crank-rocker-measured.yaml the newest
  EXPECT_EQ(templates, 6);
  // Each runs as it is; a template too, and its name never clashes with the example's.
  const ApiResponse five_bar = call("GET", "/api/examples/template-five-bar");
  ASSERT_EQ(five_bar.status, 200);
  EXPECT_EQ(five_bar.body, repo_file("examples/templates/five-bar.yaml"));
  EXPECT_NE(call("GET", "/api/examples/five-bar").body, five_bar.body);
  EXPECT_EQ(Json::parse(post("/api/check", Json{{"model", five_bar.body}}).body)["dof"]["mobility"], 2);
  const Json crank_rocker = {{"model", call("GET", "/api/examples/fourbar-crank-rocker").body}};
  EXPECT_EQ(post("/api/check", crank_rocker).status, 200);
  const Json log10 = {{"task", call("GET", "/api/examples/function-log10").body}};
  EXPECT_EQ(post("/api/synth/function", log10).status, 200);
}

// An example's comment that says a point is drawn above or below the ground line (y = 0) says
// where the server draws it at the sweep's start (fourbar-double-rocker.yaml said "B above the
// ground line" of a B at y = -23).
TEST(WebApi, ExampleCommentsPutPointsOnTheSideOfTheGroundLineTheyAreDrawn) {
  const Json list = Json::parse(call("GET", "/api/examples").body)["examples"];
  const std::regex claim(R"(#[^\n]*\b([A-Za-z]\w*) (above|below) the ground line)");
  int claims = 0;
  for (const Json& e : list) {
    if (e["kind"] != "model") continue;
    const std::string text = call("GET", "/api/examples/" + e["name"].get<std::string>()).body;
    for (auto m = std::sregex_iterator(text.begin(), text.end(), claim); m != std::sregex_iterator(); ++m) {
      const std::string point = (*m)[1], side = (*m)[2];
      SCOPED_TRACE(e["name"].get<std::string>() + ": " + point + " " + side);
      const ApiResponse r = post("/api/solve", Json{{"model", text}, {"steps", 1}, {"columns", point + ".y"}});
      ASSERT_EQ(r.status, 200) << r.body;
      const Json solve = Json::parse(r.body);
      const Json& columns = solve["columns"];
      const auto at = std::find(columns.begin(), columns.end(), point + ".y");
      ASSERT_NE(at, columns.end()) << r.body;
      const double y = solve["rows"][0][static_cast<std::size_t>(at - columns.begin())].get<double>();
      EXPECT_EQ(y > 0 ? "above" : "below", side) << point << ".y = " << y;
      ++claims;
    }
  }
  EXPECT_GE(claims, 1);
}

TEST(WebApi, HealthAndStaticPages) {
  const ApiResponse health = call("GET", "/api/health");
  ASSERT_EQ(health.status, 200);
  const Json h = Json::parse(health.body);
  EXPECT_EQ(h["status"], "ok");
  EXPECT_EQ(h["limits"]["max_steps"], 100001);
  // Whole limits held as doubles are written as integers (5000000, not 5000000.0).
  EXPECT_TRUE(h["limits"]["max_table_values"].is_number_integer()) << health.body;
  EXPECT_TRUE(h["limits"]["max_curve_samples"].is_number_integer()) << health.body;
  const ApiResponse index = call("GET", "/");
  ASSERT_EQ(index.status, 200);
  EXPECT_EQ(index.content_type, "text/html; charset=utf-8");
  EXPECT_NE(index.body.find("<title>nbar</title>"), std::string::npos);  // the web app, or its placeholder
  EXPECT_EQ(call("GET", "/index.html").body, index.body);
}

}  // namespace
}  // namespace nbar::web_test
