// nbar synth as users meet it: the bundled task files, the ranked table and JSON, exported
// models that `nbar solve` runs and that pass through the targets, and bad task files.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include "apps/cli_support.hpp"
#include "nbar/analysis/pose.hpp"
#include "nbar/io/model_file.hpp"
#include "nbar/io/synthesis_task.hpp"
#include "nbar/kinematics/mechanism.hpp"
#include "nbar/kinematics/sweep.hpp"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::StartsWith;

using nbar::cli_test::CliRun;
using nbar::cli_test::nbar;
using nbar::io::SynthesisTask;

// A scratch directory, removed at the end of the test.
class TempDir {
 public:
  TempDir() {
    path_ = fs::temp_directory_path() / ("nbar_synth_" + std::to_string(::getpid()) + "_" + std::to_string(count_++));
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  std::string file(const std::string& name, const std::string& text) const {
    std::ofstream(path_ / name) << text;
    return (path_ / name).string();
  }
  std::string path(const std::string& name = "") const { return (path_ / name).string(); }

 private:
  static inline int count_ = 0;
  fs::path path_;
};

const std::string kExamples = std::string(NBAR_EXAMPLES_DIR) + "/synthesis/";

// The coupler point P of an exported model, swept from its start to each input angle.
std::vector<Eigen::Vector2d> coupler_points_at(const std::string& model_file, const std::vector<double>& angles_deg) {
  const nbar::io::LoadedModel loaded = nbar::io::load_model_file(model_file);
  const double unit = loaded.model.units.length_scale;
  std::vector<Eigen::Vector2d> out;
  for (double angle : angles_deg) {
    nbar::Model m = loaded.model;
    m.drivers[0].to = angle * std::numbers::pi / 180;
    // Time runs forward: towards an angle below the start, the crank turns backwards.
    m.drivers[0].speed = std::copysign(m.drivers[0].speed, *m.drivers[0].to - m.drivers[0].from.value_or(0.0));
    m.sweep.steps = 90;
    const nbar::Mechanism mech(m);
    const nbar::SweepResult sweep = nbar::run_sweep(mech, {.steps = std::nullopt, .order = 0});
    EXPECT_TRUE(sweep.complete) << sweep.stop_reason;
    out.push_back(nbar::point_positions(mech, sweep.samples.back().taylor.col(0))[m.find_point("P")] / unit);
  }
  return out;
}

TEST(SynthCli, FivePointFindsTheCrankRockerFirst) {
  const CliRun r = nbar("synth five-point " + kExamples + "five-point-crank-rocker.yaml");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "");  // no progress bar: standard error is not a terminal
  EXPECT_THAT(r.out, StartsWith("five-point task 'Five points of a crank-rocker's coupler curve': parameter homotopy"));
  EXPECT_THAT(r.out, HasSubstr("36 solutions, "));
  EXPECT_THAT(r.out, HasSubstr("rank  Grashof"));
  EXPECT_THAT(r.out,
              HasSubstr("\n   1  crank-rocker           200     80.0007     180.002     150.032     41.41  none"));
}

TEST(SynthCli, FivePointJsonAllAndExportedModels) {
  TempDir dir;
  const std::string task = kExamples + "five-point-crank-rocker.yaml";
  const CliRun r = nbar("synth five-point " + task + " --format json --all --top 0 --threads 2 --seed 7 --export " +
                        dir.path("designs"));
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["task"], "five-point");
  EXPECT_EQ(j["units"]["length"], "mm");
  EXPECT_EQ(j["solutions"], 36);
  ASSERT_EQ(j["designs"].size(), 36u);
  int real = 0;
  for (const auto& d : j["designs"]) real += d["real"].get<bool>();
  EXPECT_EQ((36 - real) % 2, 0);  // complex solutions come in conjugate pairs
  EXPECT_GE(real, 2);

  // The best is the crank-rocker the points were taken from (rounded to 0.001 mm).
  const auto& best = j["designs"][0];
  EXPECT_EQ(best["rank"], 1);
  EXPECT_TRUE(best["defect_free"].get<bool>());
  EXPECT_EQ(best["grashof"], "crank-rocker");
  EXPECT_NEAR(best["lengths"]["frame"].get<double>(), 200, 1e-9);
  EXPECT_NEAR(best["lengths"]["input"].get<double>(), 80, 0.01);
  EXPECT_NEAR(best["lengths"]["coupler"].get<double>(), 180, 0.01);
  EXPECT_NEAR(best["lengths"]["output"].get<double>(), 150, 0.05);
  EXPECT_NEAR(best["min_transmission"].get<double>(), 41.41, 0.01);
  EXPECT_LT(best["max_error"].get<double>(), 1e-9);
  EXPECT_EQ(best["direction"], "counter-clockwise");
  EXPECT_NEAR(best["targets"][0]["input_angle"].get<double>(), -90, 0.01);
  EXPECT_NEAR(best["targets"][4]["input_angle"].get<double>(), 200, 0.01);
  EXPECT_EQ(best["file"], dir.path("designs") + "/design-01.yaml");

  // Every real design was exported; each runs in `nbar solve`.
  for (int rank = 1; rank <= real; ++rank) {
    const std::string file = dir.path("designs") + "/design-" + (rank < 10 ? "0" : "") + std::to_string(rank) + ".yaml";
    ASSERT_TRUE(fs::exists(file)) << file;
    const CliRun solve = nbar("solve " + file + " --steps 37 --format json");
    EXPECT_EQ(solve.code, 0) << file << ": " << solve.err;
  }
  EXPECT_FALSE(fs::exists(dir.path("designs") + "/design-" + std::to_string(real + 1) + ".yaml"));

  // The best design's model, swept to each target's input angle, puts P on the target.
  const nbar::io::SynthesisTask t = nbar::io::load_synthesis_task(task);
  std::vector<double> angles;
  for (const auto& target : best["targets"]) angles.push_back(target["input_angle"].get<double>());
  const auto at = coupler_points_at(dir.path("designs") + "/design-01.yaml", angles);
  for (std::size_t i = 0; i < 5; ++i) EXPECT_LT((at[i] - t.points[i]).norm(), 1e-9) << i;
}

TEST(SynthCli, BurmesterThreeFourAndFivePoses) {
  TempDir dir;
  const CliRun three =
      nbar("synth burmester " + kExamples + "burmester-three-positions.yaml --export " + dir.path("three"));
  ASSERT_EQ(three.code, 0) << three.err;
  EXPECT_THAT(three.out, HasSubstr("three positions, fixed pivots chosen\n1 solution, 1 real, 1 without defects\n"));
  EXPECT_THAT(three.out,
              HasSubstr("   1  crank-rocker           200     79.9997     180.003     150.006     41.41  none"));
  EXPECT_EQ(nbar("solve " + dir.path("three") + "/design-01.yaml").code, 0);

  const CliRun four = nbar("synth burmester " + kExamples +
                           "burmester-four-positions.yaml --top 5 --format json --curves " + dir.path("curves.csv"));
  ASSERT_EQ(four.code, 0) << four.err;
  const auto j = nlohmann::json::parse(four.out);
  EXPECT_EQ(j["designs"].size(), 5u);
  EXPECT_EQ(j["solutions"], 24 * 23);
  double previous = 90;
  for (const auto& d : j["designs"]) {
    EXPECT_TRUE(d["defect_free"].get<bool>());
    EXPECT_LT(d["max_error"].get<double>(), 1e-9);
    EXPECT_LT(d["max_rotation_error"].get<double>(), 1e-9);
    EXPECT_LE(d["min_transmission"].get<double>(), previous);  // ranked by transmission angle
    previous = d["min_transmission"].get<double>();
  }
  std::ifstream csv(dir.path("curves.csv"));
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header, "curve,branch,centre_x,centre_y,circle_x,circle_y");
  for (const std::string ext : {"json", "svg"}) {
    const CliRun c = nbar("synth burmester " + kExamples + "burmester-four-positions.yaml --top 1 --curves " +
                          dir.path("curves." + ext));
    EXPECT_EQ(c.code, 0) << c.err;
    EXPECT_GT(fs::file_size(dir.path("curves." + ext)), 1000u);
  }
  // The picture can be read: labelled axes in the task's unit, a grid, numbered poses.
  std::ifstream svg_file(dir.path("curves.svg"));
  const std::string svg((std::istreambuf_iterator<char>(svg_file)), std::istreambuf_iterator<char>());
  EXPECT_THAT(svg, HasSubstr(">x (mm)<"));
  EXPECT_THAT(svg, HasSubstr(">y (mm)<"));
  EXPECT_THAT(svg, HasSubstr(">200<"));  // a tick label
  EXPECT_THAT(svg, HasSubstr(">-200<"));
  for (const char* pose : {">1<", ">2<", ">3<", ">4<"}) EXPECT_THAT(svg, HasSubstr(pose));
  EXPECT_THAT(svg, HasSubstr("poses 1-4 with their angles"));

  const CliRun five = nbar("synth burmester " + kExamples + "burmester-five-positions.yaml --all");
  ASSERT_EQ(five.code, 0) << five.err;
  EXPECT_THAT(five.out,
              HasSubstr("five positions: 4 real Burmester points, every ordered pair\n12 solutions, 12 real"));
  EXPECT_THAT(five.out,
              HasSubstr("\n   1  crank-rocker       200.002     79.9992     179.998     150.017     41.41  none"));
}

TEST(SynthCli, FunctionGeneratorRunsOverTheRangeOfX) {
  TempDir dir;
  const CliRun r = nbar("synth function " + kExamples + "function-log10.yaml --export " + dir.path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("Freudenstein, 3 Chebyshev precision points\n1 solution, 1 real, 1 without defects\n"));
  EXPECT_THAT(r.out, HasSubstr("note: structural error: the output is off by up to 0.472 deg"));
  EXPECT_THAT(r.out, HasSubstr("   1  triple-rocker          100     33.8673     85.6935      29.565     54.58  none"));
  // The task's own angles (the example's convention: from the frame line O2 -> O4, counter-
  // clockwise): the exported model sweeps the input from 90 to 150 deg, and its output.angle
  // column reads the output against 60 to 120 deg. Freudenstein gives this design a negative
  // input and output length (K1, K2 < 0), so both links point opposite to their angles, which
  // put them 180 deg off before.
  const CliRun solve = nbar("solve " + dir.path("design-01.yaml") + " --format json --steps 3");
  ASSERT_EQ(solve.code, 0) << solve.err;
  const auto j = nlohmann::json::parse(solve.out);
  EXPECT_NEAR(j["rows"][0][2].get<double>(), 90, 1e-9);
  EXPECT_NEAR(j["rows"][2][2].get<double>(), 150, 1e-9);

  // Driven through the task's input range, the exported model meets f at the precision points:
  // phi = 90 + 60 (x - 1) deg, and the output angle psi = 60 + 60 log10(x) / log10(2) deg.
  const nbar::Mechanism mech(nbar::io::load_model_file(dir.path("design-01.yaml")).model);
  const int output = mech.model().find_body("output");
  ASSERT_GE(output, 0);
  const auto& pts = mech.model().bodies[output].points;
  const double deg = std::numbers::pi / 180;
  const auto output_angle = [&](double phi_deg) {
    const Eigen::VectorXd q = nbar::pose_at(mech, phi_deg).positions();
    const Eigen::Vector2d v = mech.point_position(pts[1], q) - mech.point_position(pts[0], q);
    return std::atan2(v.y(), v.x()) / deg;
  };
  for (int j = 1; j <= 3; ++j) {
    const double x = 1.5 - 0.5 * std::cos((2 * j - 1) * std::numbers::pi / 6);  // Chebyshev on [1, 2]
    const double phi = 90 + 60 * (x - 1), psi = 60 + 60 * std::log10(x) / std::log10(2.0);
    EXPECT_NEAR(output_angle(phi), psi, 1e-9) << "at precision point x = " << x;
  }
  // And between them within the structural error the table reports (0.472 deg).
  EXPECT_NEAR(output_angle(90), 60, 0.48);
  EXPECT_NEAR(output_angle(150), 120, 0.48);

  // The report says the same: the targets' input angles are the task's.
  const CliRun json = nbar("synth function " + kExamples + "function-log10.yaml --format json");
  ASSERT_EQ(json.code, 0) << json.err;
  const auto targets = nlohmann::json::parse(json.out)["designs"][0]["targets"];
  ASSERT_EQ(targets.size(), 3u);
  EXPECT_NEAR(targets[0]["input_angle"].get<double>(), 90 + 60 * (1.5 - 0.5 * std::cos(std::numbers::pi / 6) - 1),
              1e-9);
  EXPECT_NEAR(targets[1]["input_angle"].get<double>(), 120, 1e-9);
}

// 30 points measured (0.3 mm of noise) on a crank-rocker's coupler curve: the best fit is within
// the noise, and its exported model, driven to each target's input angle, puts the coupler point
// where the check says.
TEST(SynthCli, PathFitsThirtyMeasuredPoints) {
  TempDir dir;
  const std::string file = kExamples + "path/crank-rocker-measured.yaml";
  const CliRun r = nbar("synth path " + file + " --format json --top 3 --export " + dir.path("designs"));
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["task"], "path");
  ASSERT_EQ(j["designs"].size(), 3u);
  const nlohmann::json& best = j["designs"][0];
  EXPECT_TRUE(best["defect_free"].get<bool>());
  EXPECT_TRUE(best["input_turns_fully"].get<bool>());  // the task asks for a crank
  EXPECT_GE(best["min_transmission_full"].get<double>(), 30);
  // The true linkage misses the targets by the noise (0.42 mm RMS): the fit does no worse.
  EXPECT_LT(best["rms_error"].get<double>(), 0.42);
  EXPECT_LT(best["max_error"].get<double>(), 1.0);
  double previous = 0;
  for (const auto& d : j["designs"]) {
    EXPECT_GE(d["rms_error"].get<double>(), previous);  // ranked by RMS deviation
    previous = d["rms_error"].get<double>();
  }
  const SynthesisTask t = nbar::io::load_synthesis_task(file);
  std::vector<double> angles;
  for (const auto& target : best["targets"]) angles.push_back(target["input_angle"].get<double>());
  const auto at = coupler_points_at(dir.path("designs") + "/design-01.yaml", angles);
  double worst = 0;
  for (std::size_t i = 0; i < at.size(); ++i) worst = std::max(worst, (at[i] - t.points[i]).norm());
  EXPECT_NEAR(worst, best["max_error"].get<double>(), 1e-6);
  EXPECT_EQ(nbar("solve " + dir.path("designs") + "/design-03.yaml").code, 0);
}

TEST(SynthCli, BadPathTasksSayWhereTheProblemIs) {
  TempDir dir;
  std::string points = "points:\n";
  for (int k = 0; k < 11; ++k)
    points += "  - [" + std::to_string(std::cos(k * 0.5)) + ", " + std::to_string(std::sin(k * 0.5)) + "]\n";
  const CliRun repeated = nbar("synth path " + dir.file("r.yaml", "task: path\n" + points + "  - [1, 0]\n"));
  EXPECT_EQ(repeated.code, 1);
  EXPECT_EQ(repeated.err, "error: " + dir.path("r.yaml") +
                              ":14:5: points 1 and 12 coincide: the coupler point meets each target once (a closed "
                              "curve is given once round: leave out the last point)\n");
  dir.file("c.csv", "x,y\n0,0\n1,1\n2,oops\n");
  const CliRun csv = nbar("synth path " + dir.file("c.yaml", "task: path\ncurve: c.csv\n"));
  EXPECT_EQ(csv.code, 1);
  EXPECT_EQ(csv.err, "error: " + dir.path("c.csv") + ":4:3: 'oops' is not a finite number (y)\n");
  // --curve-csv reads the user's file, from the current directory, and its mistakes are located.
  const CliRun option = nbar("synth path --curve-csv " + dir.path("c.csv"));
  EXPECT_EQ(option.code, 2);  // task options: bad usage
  EXPECT_EQ(option.err, "error: " + dir.path("c.csv") + ":4:3: 'oops' is not a finite number (y)\n");
  EXPECT_EQ(nbar("synth path --curve-csv " + kExamples + "path/d-shape.csv --top 1").code, 0);
  const CliRun few = nbar("synth path --points '[[0, 0], [1, 1], [2, 0]]'");
  EXPECT_EQ(few.code, 2);
  EXPECT_EQ(few.err,
            "error: --points: a path task needs at least 10 target points, not 3 (with 5 points and both pivots, use "
            "`task: five-point`)\n");
}

TEST(SynthCli, BadTaskFilesSayWhereTheProblemIs) {
  TempDir dir;
  const std::string pivots = "pivots: {a: [0, 0], b: [1, 0]}\n";
  const std::string points = "points:\n  - [0, 1]\n  - [0.5, 1.2]\n  - [1, 1.1]\n  - [1.2, 0.6]\n  - [0.3, 0.4]\n";

  const CliRun missing = nbar("synth five-point " + dir.file("missing.yaml", "task: five-point\n" + points));
  EXPECT_EQ(missing.code, 1);
  EXPECT_EQ(missing.err, "error: " + dir.path("missing.yaml") + ":1:1: a five-point task needs `pivots`\n");

  const CliRun four =
      nbar("synth five-point " +
           dir.file("four.yaml", "task: five-point\n" + pivots +
                                     "points:\n  - [0, 1]\n  - [0.5, 1.2]\n  - [1, 1.1]\n  - [1.2, 0.6]\n"));
  EXPECT_EQ(four.code, 1);
  EXPECT_EQ(four.err, "error: " + dir.path("four.yaml") +
                          ":4:3: a five-point task needs exactly 5 points for the coupler point, not 4\n");

  const CliRun same =
      nbar("synth five-point " + dir.file("same.yaml", "task: five-point\npivots: {a: [1, 0], b: [1, 0]}\n" + points));
  EXPECT_EQ(same.code, 1);
  EXPECT_EQ(same.err, "error: " + dir.path("same.yaml") +
                          ":2:24: the fixed pivots a and b coincide: a four-bar needs two distinct fixed pivots\n");

  const CliRun burmester =
      nbar("synth burmester " + dir.file("b.yaml", "task: burmester\nposes:\n  - {point: [0, 0], angle: 0}\n"));
  EXPECT_EQ(burmester.code, 1);
  EXPECT_THAT(burmester.err, HasSubstr("b.yaml:3:3: a burmester task needs 3, 4 or 5 poses, not 1"));

  const CliRun law = nbar("synth function " + dir.file("f.yaml",
                                                       "task: function\nfunction: sqrt(x) + (\nx: [1, 2]\n"
                                                       "input_range: [0, 60]\noutput_range: [0, 60]\n"));
  EXPECT_EQ(law.code, 1);
  EXPECT_THAT(law.err, HasSubstr("f.yaml:2:22: in the function 'sqrt(x) + ('"));

  const CliRun unreadable = nbar("synth five-point " + dir.path("nonexistent.yaml"));
  EXPECT_EQ(unreadable.code, 1);
  EXPECT_THAT(unreadable.err, HasSubstr("nonexistent.yaml: cannot read"));
}

TEST(SynthCli, TaskOptionsInsteadOfAFile) {
  const CliRun file = nbar("synth function " + kExamples + "function-log10.yaml --format json");
  const CliRun options = nbar(
      "synth function --name 'Logarithm generator' --units '{length: mm}' --function 'log10(x)' "
      "--x 1,2 --input-range 90,150 --output-range 60,120 --points 3 --spacing chebyshev "
      "--frame 100 --format json");
  ASSERT_EQ(options.code, 0) << options.err;
  EXPECT_EQ(options.out, file.out);

  const CliRun bad = nbar("synth five-point --pivots '{a: [0, 0], b: [1, 0]}' --points '[[0, 1], [1, 1]]'");
  EXPECT_EQ(bad.code, 2);
  EXPECT_EQ(bad.err, "error: --points: a five-point task needs exactly 5 points for the coupler point, not 2\n");
  const CliRun law = nbar("synth function --function 'log10(x' --x 1,2 --input-range 0,60 --output-range 0,60");
  EXPECT_EQ(law.code, 2);
  EXPECT_THAT(law.err, StartsWith("error: --function: in the function 'log10(x': "));
  const CliRun missing = nbar("synth five-point --pivots '{a: [0, 0], b: [1, 0]}'");
  EXPECT_EQ(missing.code, 2);
  EXPECT_EQ(missing.err, "error: task options: a five-point task needs `points`\n");
  const CliRun both =
      nbar("synth five-point " + kExamples + "five-point-crank-rocker.yaml --pivots '{a: [0, 0], b: [1, 0]}'");
  EXPECT_EQ(both.code, 2);
  EXPECT_THAT(both.err, HasSubstr("give a task file or task options"));
}

// A task option is read as YAML like a task file, and its errors are located like a file's:
// at the character of the option's text (a file's line:column), not only at the option.
TEST(SynthCli, MalformedYamlInAnOptionSaysWhere) {
  const CliRun unclosed = nbar("synth path --points '[[0, 1], [1, 2], [2, 3'");
  EXPECT_EQ(unclosed.code, 2);
  EXPECT_EQ(unclosed.err,
            "error: --points at character 18: invalid YAML: this '[' is never closed by a ']' (end of sequence flow "
            "not found)\n");
  const CliRun word = nbar(
      "synth five-point --pivots '{a: [0, 0], b: [1, 0]}' --points '[[0, 1], [1, abc], [2, 1.5], [3, 1], [4, 0.5]]'");
  EXPECT_EQ(word.code, 2);
  EXPECT_EQ(word.err, "error: --points at character 14: point 2 must be a number, not 'abc'\n");
  // 1,2 is read as [1, 2]: the character is still the option's own.
  const CliRun range =
      nbar("synth function --function 'log10(x)' --x 1,abc --input-range 90,150 --output-range 60,120");
  EXPECT_EQ(range.code, 2);
  EXPECT_THAT(range.err, StartsWith("error: --x at character 3: "));
}

// Issue 16, item 15: an option's value becomes one line of the task; a line break in it must
// not add a key of its own (here a second `points`, which would have replaced the first).
TEST(SynthCli, AnOptionWithALineBreakAddsNoKey) {
  const CliRun injected = nbar(
      "synth five-point --pivots \"$(printf '{a: [0, 0], b: [1, 0]}\\npoints: [[0, 0]]')\" "
      "--points '[[0, 1], [1, 1], [2, 1.5], [3, 1], [4, 0.5]]'");
  EXPECT_EQ(injected.code, 2);
  EXPECT_EQ(injected.err,
            "error: --pivots: the value holds a line break or another control character (at character 23); give it "
            "on one line\n");
}

TEST(SynthCli, BadUsage) {
  TempDir dir;
  const std::string task = kExamples + "five-point-crank-rocker.yaml";
  const CliRun wrong_kind = nbar("synth burmester " + task);
  EXPECT_EQ(wrong_kind.code, 2);
  EXPECT_THAT(wrong_kind.err, HasSubstr("this is a five-point task: run `nbar synth five-point"));
  EXPECT_EQ(nbar("synth six-point " + task).code, 2);
  EXPECT_EQ(nbar("synth five-point " + task + " --format xml").code, 2);
  EXPECT_EQ(nbar("synth five-point").code, 2);
  const CliRun curves = nbar("synth five-point " + task + " --curves " + dir.path("c.svg"));
  EXPECT_EQ(curves.code, 2);
  EXPECT_THAT(curves.err, HasSubstr("--curves applies to burmester tasks with 4 poses"));
  const CliRun export_to_file = nbar("synth five-point " + task + " --export " + dir.file("not-a-dir", "x"));
  EXPECT_EQ(export_to_file.code, 2);
  EXPECT_THAT(export_to_file.err, HasSubstr("--export"));
}

}  // namespace

namespace {

TEST(SynthCli, ATimeoutStopsANinePointTaskOnAConic) {
  // Nine points on an ellipse: the solver takes minutes (every design degenerates), and the
  // command had no bound but Ctrl-C. --timeout gives up with exit 5.
  TempDir dir;
  const std::string task =
      dir.file("ellipse.yaml",
               "task: nine-point\npoints:\n  - [2, 0]\n  - [1.5321, 0.6428]\n  - [0.3473, 0.9848]\n"
               "  - [-1, 0.866]\n  - [-1.8794, 0.342]\n  - [-1.8794, -0.342]\n  - [-1, -0.866]\n"
               "  - [0.3473, -0.9848]\n  - [1.5321, -0.6428]\n");
  const auto start = std::chrono::steady_clock::now();
  const CliRun run = nbar("synth nine-point " + task + " --timeout 0.5");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(30));
  EXPECT_EQ(run.code, 5);
  EXPECT_THAT(run.err, HasSubstr("the time budget ran out"));
  EXPECT_NE(nbar("synth nine-point " + task + " --timeout 0").code, 0);
}

}  // namespace
