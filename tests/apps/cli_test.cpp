// The nbar command line as users meet it: every bundled example, every documented exit code.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "apps/cli_support.hpp"

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

using nbar::cli_test::CliRun;
using nbar::cli_test::nbar;

// A model file in a temporary directory, removed at the end of the test.
class TempModel {
 public:
  explicit TempModel(const std::string& text, const std::string& name = "model.yaml") {
    dir_ = fs::temp_directory_path() / ("nbar_cli_" + std::to_string(::getpid()) + "_" + std::to_string(count_++));
    fs::create_directories(dir_);
    path_ = dir_ / name;
    std::ofstream(path_) << text;
  }
  ~TempModel() { fs::remove_all(dir_); }
  std::string path() const { return path_.string(); }
  std::string dir() const { return dir_.string(); }

 private:
  static inline int count_ = 0;
  fs::path dir_, path_;
};

std::vector<std::string> examples() {
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(NBAR_EXAMPLES_DIR))
    if (e.path().extension() == ".yaml" || e.path().extension() == ".json") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

int count_lines(const std::string& s) { return static_cast<int>(std::count(s.begin(), s.end(), '\n')); }

const char* const kFourBar = R"(name: four-bar
units: {length: mm, angle: deg}
points:
  O2: [0, 0]
  O4: [200, 0]
  A: [0, 80]
  B: [160, 150]
ground: [O2, O4]
bodies:
  crank: [O2, A]
  coupler: [A, B]
  rocker: [O4, B]
)";

TEST(Cli, EveryExampleChecksAndSolves) {
  const auto files = examples();
  ASSERT_GE(files.size(), 15u);
  for (const std::string& f : files) {
    SCOPED_TRACE(f);
    const CliRun check = nbar("check " + f);
    EXPECT_EQ(check.code, 0) << check.err;
    EXPECT_THAT(check.out, HasSubstr("Degrees of freedom"));
    EXPECT_THAT(check.out, HasSubstr("converged"));
    const CliRun solve = nbar("solve " + f + " --order 3");
    EXPECT_EQ(solve.code, 0) << solve.err;
    EXPECT_GT(count_lines(solve.out), 2);
    EXPECT_THAT(solve.out, Not(HasSubstr("nan")));
    EXPECT_THAT(solve.out, Not(HasSubstr("inf")));
    const CliRun dynamics = nbar("solve " + f + " --dynamics --steps 19");
    EXPECT_EQ(dynamics.code, 0) << dynamics.err;
    EXPECT_THAT(dynamics.out, HasSubstr("energy.kinetic"));
    EXPECT_THAT(dynamics.out, Not(HasSubstr("nan")));
    const CliRun json = nbar("solve " + f + " --format json --steps 5");
    ASSERT_EQ(json.code, 0) << json.err;
    const auto j = nlohmann::json::parse(json.out);
    EXPECT_EQ(j["rows"].size(), 5u);
    EXPECT_EQ(j["columns"].size(), j["rows"][0].size());
    EXPECT_EQ(j["column_units"].size(), j["columns"].size());
    EXPECT_TRUE(j["complete"].get<bool>());
    ASSERT_TRUE(j.contains("stop_reason"));  // always written, as docs/cli.md says
    EXPECT_TRUE(j["stop_reason"].is_null());
  }
}

TEST(Cli, CsvHeaderAndValuesOfTheCrankRocker) {
  const CliRun r = nbar(std::string("solve ") + NBAR_EXAMPLES_DIR + "/fourbar-crank-rocker.yaml --steps 5 --order 3");
  ASSERT_EQ(r.code, 0) << r.err;
  std::istringstream lines(r.out);
  std::string header;
  std::getline(lines, header);
  EXPECT_THAT(header, testing::StartsWith("step,t,crank,"));
  EXPECT_THAT(header, HasSubstr("A.x,A.y,A.vx,A.vy,A.ax,A.ay,A.jx,A.jy"));
  EXPECT_THAT(header, HasSubstr("crank.angle,crank.omega,crank.alpha,crank.jerk"));
  EXPECT_THAT(header, HasSubstr("crank-coupler-rocker.mu"));
  EXPECT_EQ(count_lines(r.out), 6);
}

// Fields of a CSV line (RFC 4180: quoted fields, doubled quotes).
std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
      fields.back() += '"';
      ++i;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  return fields;
}

// A point named "a,b" (a valid name) made a header of more fields than the rows had.
TEST(Cli, CsvHeaderQuotesNamesWithCommasAndQuotes) {
  const std::string text = R"(units: {length: mm, angle: deg}
points: {O2: [0, 0], O4: [200, 0], "a,b": [0, 80], 'q"t': [160, 150]}
ground: [O2, O4]
bodies: {crank: [O2, "a,b"], coupler: ["a,b", 'q"t'], rocker: [O4, 'q"t']}
drivers: [{angle: crank, from: 90, to: 120}]
sweep: {steps: 3}
)";
  const TempModel model(text);
  const CliRun r = nbar("solve " + model.path());
  ASSERT_EQ(r.code, 0) << r.err << text;
  std::istringstream lines(r.out);
  std::string header, row;
  std::getline(lines, header);
  std::getline(lines, row);
  const auto names = csv_fields(header);
  EXPECT_EQ(names.size(), csv_fields(row).size()) << header;
  EXPECT_NE(std::find(names.begin(), names.end(), "a,b.x"), names.end()) << header;
  EXPECT_NE(std::find(names.begin(), names.end(), "q\"t.y"), names.end()) << header;
  EXPECT_THAT(header, HasSubstr("\"a,b.x\",\"a,b.y\""));
}

TEST(Cli, OutputFileAndColumnSelection) {
  TempModel dir("");
  const std::string out = dir.dir() + "/out.csv";
  const CliRun r = nbar(std::string("solve ") + NBAR_EXAMPLES_DIR +
                        "/fourbar-crank-rocker.yaml --steps 3 --columns 'crank,rocker.*' -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream f(out);
  std::string header;
  std::getline(f, header);
  EXPECT_EQ(header, "crank,rocker.angle,rocker.omega,rocker.alpha");
  const CliRun bad = nbar(std::string("solve ") + NBAR_EXAMPLES_DIR + "/fourbar-crank-rocker.yaml --columns nosuch");
  EXPECT_EQ(bad.code, 2);
  EXPECT_THAT(bad.err, HasSubstr("no column matches 'nosuch'"));
  // A force column without --dynamics: the hint, not a list of the kinematic columns.
  for (const char* format : {"csv", "table"}) {
    const CliRun force = nbar(std::string("solve ") + NBAR_EXAMPLES_DIR +
                              "/fourbar-steel-bars.yaml --steps 3 --format " + format + " --columns crank.torque");
    EXPECT_EQ(force.code, 2);
    EXPECT_THAT(force.err, HasSubstr("no column matches 'crank.torque': the force and torque columns come from the "
                                     "inverse dynamics, add --dynamics"));
  }
}

TEST(Cli, TableFormatHasUnits) {
  const CliRun r = nbar(std::string("solve ") + NBAR_EXAMPLES_DIR +
                        "/fourbar-crank-rocker.yaml --steps 3 --format table --columns crank,rocker.omega");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("[deg/s]"));
  EXPECT_EQ(count_lines(r.out), 5);
}

TEST(Cli, HelpAndBadUsage) {
  EXPECT_EQ(nbar("--help").code, 0);
  EXPECT_THAT(nbar("--help").out, HasSubstr("Exit codes"));
  EXPECT_EQ(nbar("solve --help").code, 0);
  EXPECT_EQ(nbar("").code, 2);
  EXPECT_EQ(nbar("frobnicate").code, 2);
  EXPECT_THAT(nbar("frobnicate").err,
              HasSubstr("error: 'frobnicate' is not an nbar command (the commands are: check, solve, "));
  EXPECT_THAT(nbar("sovle x.yaml").err, testing::EndsWith("explain, export, import, serve); did you mean 'solve'?\n"));
  const std::string model = std::string(NBAR_EXAMPLES_DIR) + "/fourbar-crank-rocker.yaml";
  EXPECT_EQ(nbar("solve " + model + " --order 6").code, 2);
  EXPECT_EQ(nbar("solve " + model + " --order -1").code, 2);
  EXPECT_EQ(nbar("solve " + model + " --steps 0").code, 2);
  EXPECT_EQ(nbar("solve " + model + " --format xml").code, 2);
  EXPECT_EQ(nbar("solve " + model + " --bogus").code, 2);
  EXPECT_EQ(nbar("solve").code, 2);
  EXPECT_EQ(nbar("solve " + model + " -o /nonexistent-dir/x.csv").code, 2);
}

TEST(Cli, MissingFileIsAnInvalidModel) {
  const CliRun r = nbar("check /nonexistent/model.yaml");
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("/nonexistent/model.yaml"));
}

TEST(Cli, SyntaxErrorGivesFileLineColumn) {
  TempModel m("name: x\npoints:\n  A: [0, 0\n  B: [1, 1]\n");
  const CliRun r = nbar("check " + m.path());
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr(m.path() + ":"));
  EXPECT_THAT(r.err, testing::ContainsRegex(":[0-9]+:[0-9]+: "));
}

TEST(Cli, DriversNotMatchingTheDegreesOfFreedomAreAnInvalidModel) {
  TempModel m(std::string(kFourBar) +
              "drivers:\n  - {angle: crank, from: 90, to: 100}\n  - {angle: rocker, from: 60, to: 70}\n");
  const CliRun r = nbar("check " + m.path());
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("1 degree of freedom"));
  EXPECT_THAT(r.err, HasSubstr("2 drivers"));
  EXPECT_THAT(r.err, HasSubstr(m.path() + ":"));
}

TEST(Cli, CheckWarnsOfASweepThatWillStopOrTurnTooOften) {
  const std::string body =
      "points: {O2: [0, 0], O4: [200, 0], A: [80, 0], B: [181.25, 148.823511]}\n"
      "ground: [O2, O4]\nbodies: {crank: [O2, A], coupler: [A, B], rocker: [O4, B]}\n";
  TempModel limited("units: {length: mm, angle: deg}\n" + body +
                    "lengths: {crank: 130, rocker: 150}\ndrivers: [{angle: crank, from: 0, to: 360}]\n");
  const CliRun r = nbar("check " + limited.path());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("Warnings: 1\n  warning: the sweep asks crank to turn 360 deg, from 0 deg to 360 deg, "
                               "but loop crank-coupler-rocker lets it turn only between -179.99"));
  EXPECT_EQ(nbar("solve " + limited.path()).code, 4);

  TempModel rad("units: {length: mm, angle: rad}\n" + body + "drivers: [{angle: crank, from: 0, to: 360}]\n");
  const CliRun turns = nbar("check " + rad.path());
  EXPECT_EQ(turns.code, 0) << turns.err;
  EXPECT_THAT(turns.out, HasSubstr("warning: the sweep turns crank 57.3 times, from 0 rad to 360 rad (the model's "
                                   "angle unit is rad: for 360 degrees, write `units: {angle: deg}`)"));

  const CliRun dynamics =
      nbar("solve " + std::string(NBAR_EXAMPLES_DIR) + "/fourbar-crank-rocker.yaml --dynamics --steps 3");
  EXPECT_EQ(dynamics.code, 0);
  EXPECT_THAT(dynamics.err, HasSubstr("warning: the model has no masses or loads"));
}

TEST(Cli, CheckPrintsNoCentreOfMassForABodyWithoutMass) {
  // The four-bar with a given mass on the crank only, and gravity.
  TempModel m(
      "name: four-bar\nunits: {length: mm, angle: deg}\n"
      "points: {O2: [0, 0], O4: [200, 0], A: [0, 80], B: [160, 150]}\nground: [O2, O4]\ngravity: [0, -9.81]\n"
      "bodies:\n  crank: {points: [O2, A], mass: 0.5, cg: [0, 40], inertia: 0.001}\n"
      "  coupler: [A, B]\n  rocker: [O4, B]\n"
      "drivers:\n  - {angle: crank, from: 90, to: 100}\n");
  const CliRun r = nbar("check " + m.path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("  crank        mass 0.5  cg (0, 40)  inertia 0.001  [given]\n"));
  EXPECT_THAT(r.out, HasSubstr("  coupler      mass 0  [none]\n"));
  EXPECT_THAT(r.out, Not(HasSubstr("cg (0, 0)")));
}

TEST(Cli, DegreesOfFreedomNotMatchingPointAtTheLikelyCulprit) {
  const std::string head =
      "name: s\npoints: {O2: [0, 0], X: [400, 0], A: [50, 20], C: [230, 0]}\n"
      "ground: [O2, X]\nbodies:\n  crank: [O2, A]\n  rod: [A, C]\n";
  const std::string driver = "drivers:\n  - {angle: crank, from: 0, to: 360}\n";
  TempModel wrong(head + "sliders:\n  - {body: rod, point: C, along: [O2, X]}\n" + driver);
  const CliRun w = nbar("check " + wrong.path());
  EXPECT_EQ(w.code, 1);
  EXPECT_THAT(w.err, HasSubstr(wrong.path() + ":8:5: the mechanism has 0 degrees of freedom"));
  EXPECT_THAT(w.err, HasSubstr("is the slider on the right body?"));
  TempModel forgotten(std::string(head).replace(head.find("C: [230, 0]"), 11, "C: [230, 0], D: [260, 0]") +
                      "  piston: [C, D]\n" + driver);
  const CliRun f = nbar("check " + forgotten.path());
  EXPECT_EQ(f.code, 1);
  EXPECT_THAT(f.err, HasSubstr(forgotten.path() + ":7:3: the mechanism has 3 degrees of freedom"));
  EXPECT_THAT(f.err, HasSubstr("body 'piston' can still move with the drivers held"));
}

TEST(Cli, BarsTooShortToCloseCannotAssemble) {
  TempModel m(std::string(kFourBar) + "lengths: {coupler: 20}\ndrivers:\n  - {angle: crank, from: 90, to: 100}\n");
  const CliRun check = nbar("check " + m.path());
  EXPECT_EQ(check.code, 3);
  EXPECT_THAT(check.err, HasSubstr("cannot be met"));
  const CliRun solve = nbar("solve " + m.path());
  EXPECT_EQ(solve.code, 3);
  EXPECT_EQ(solve.out, "");
  // explain says it at the same line and column as solve (it gave the file name only).
  const std::string at = solve.err.substr(0, solve.err.find(": cannot"));
  EXPECT_THAT(at, testing::MatchesRegex("error: .*model.yaml:[0-9]+:[0-9]+"));
  const CliRun explain = nbar("explain " + m.path());
  EXPECT_EQ(explain.code, 3);
  EXPECT_EQ(explain.err.substr(0, at.size()), at);
}

TEST(Cli, APoseTheSweepDoesNotReachIsSaidWhereTheStoppedSweepIs) {
  // The double-rocker's input toggles near 99.7 deg: driven to 120, its sweep stops there.
  std::ifstream in(std::string(NBAR_EXAMPLES_DIR) + "/fourbar-double-rocker.yaml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_NE(text.find("to: 80,"), std::string::npos);
  text.replace(text.find("to: 80,"), 7, "to: 120,");
  TempModel m(text);
  const CliRun solve = nbar("solve " + m.path());
  EXPECT_EQ(solve.code, 4);
  const std::string at = solve.err.substr(0, solve.err.find(": sweep stopped"));
  EXPECT_THAT(at, testing::MatchesRegex("error: .*model.yaml:[0-9]+:[0-9]+"));
  // draw and explain named the file only.
  for (const std::string& command :
       {"draw " + m.path() + " --at 110 -o " + m.dir() + "/a.svg", "explain " + m.path() + " --step 150"}) {
    SCOPED_TRACE(command);
    const CliRun run = nbar(command);
    EXPECT_EQ(run.code, 4);
    EXPECT_EQ(run.err.substr(0, at.size() + 2), at + ": ");
  }
}

// check --at-limits reverse describes the sweep solve --at-limits reverse runs: the double-rocker
// driven to 120 deg would stop at its toggle (99.7151 deg, |O4 A| = coupler + output); rocking, it
// turns back there and at -99.7151 deg, and check warns of no stop. draw --at on a rocking path
// draws where the motion first has the value, and says the range it rocks over for one it never has.
TEST(Cli, CheckAndDrawOnARockingPath) {
  std::ifstream in(std::string(NBAR_EXAMPLES_DIR) + "/fourbar-double-rocker.yaml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_NE(text.find("to: 80,"), std::string::npos);
  text.replace(text.find("to: 80,"), 7, "to: 120,");
  TempModel m(text);
  const CliRun stopping = nbar("check " + m.path());
  EXPECT_EQ(stopping.code, 0) << stopping.err;
  EXPECT_THAT(stopping.out, HasSubstr("the sweep will stop at 99.7151 deg"));
  const CliRun rocking = nbar("check " + m.path() + " --at-limits reverse --cycles 2");
  EXPECT_EQ(rocking.code, 0) << rocking.err;
  EXPECT_THAT(rocking.out, HasSubstr("Rocking: driver 'input' turns back at 99.7151 deg (coupler and output in line "
                                     "at B (four-bar loop input-coupler-output)), then -99.7151 deg"));
  EXPECT_THAT(rocking.out, Not(HasSubstr("will stop")));
  EXPECT_EQ(nbar("check " + m.path() + " --at-limits bounce").code, 2);

  const std::string example = std::string(NBAR_EXAMPLES_DIR) + "/fourbar-double-rocker-rocking.yaml";
  const CliRun drawn = nbar("draw " + example + " --at -90 -o " + m.dir() + "/at.svg");
  EXPECT_EQ(drawn.code, 0) << drawn.err;
  const CliRun never = nbar("draw " + example + " --at 120 -o " + m.dir() + "/never.svg");
  EXPECT_EQ(never.code, 4);
  EXPECT_THAT(never.err, HasSubstr("driver 'input' rocks between -99.7151 deg and 99.7151 deg (`at_limits: reverse`): "
                                   "it never reaches 120 deg"));
  EXPECT_EQ(nbar("draw " + example + " --step 150 -o " + m.dir() + "/step.svg").code, 0);
}

TEST(Cli, DriverOutsideItsRangeStopsTheSweepEarlyAndKeepsTheRows) {
  // Crank 80, coupler ~174, rocker 150, frame 200: s + l = 280 < 324: a crank-rocker, but
  // driving the rocker through a full turn is impossible.
  TempModel m(std::string(kFourBar) + "drivers:\n  - {angle: rocker, to: 400}\nsweep: {steps: 361}\n");
  const CliRun r = nbar("solve " + m.path());
  EXPECT_EQ(r.code, 4);
  EXPECT_THAT(r.err, HasSubstr("sweep stopped"));
  EXPECT_THAT(r.err, HasSubstr("toggle"));
  EXPECT_GT(count_lines(r.out), 3);
  EXPECT_LT(count_lines(r.out), 362);
  const CliRun json = nbar("solve " + m.path() + " --format json");
  EXPECT_EQ(json.code, 4);
  const auto j = nlohmann::json::parse(json.out);
  EXPECT_FALSE(j["complete"].get<bool>());
  EXPECT_THAT(j["stop_reason"].get<std::string>(), HasSubstr("toggle"));
}

TEST(Cli, DynamicsColumnsAndJson) {
  const std::string model = std::string(NBAR_EXAMPLES_DIR) + "/fourbar-steel-bars.yaml";
  const CliRun r = nbar("solve " + model + " --dynamics --steps 7");
  ASSERT_EQ(r.code, 0) << r.err;
  std::istringstream lines(r.out);
  std::string header;
  std::getline(lines, header);
  for (const char* column :
       {"O2.ground>crank.Fx", "A.crank>coupler.Fy", "A.crank>coupler.along", "B.coupler>rocker.across",
        "O4.ground>rocker.Fx", "crank.torque", "energy.kinetic", "energy.potential"})
    EXPECT_THAT(header, HasSubstr(column));
  const CliRun json = nbar("solve " + model + " --dynamics --steps 7 --format json");
  ASSERT_EQ(json.code, 0) << json.err;
  const auto j = nlohmann::json::parse(json.out);
  EXPECT_TRUE(j["dynamics"]["unique"].get<bool>());
  EXPECT_LT(j["dynamics"]["max_residual"].get<double>(), 1e-9);
}

TEST(Cli, DynamicsOfARedundantMechanismSaysTheForcesAreNotUnique) {
  const CliRun r =
      nbar(std::string("solve ") + NBAR_EXAMPLES_DIR + "/parallelogram-redundant.yaml --dynamics --steps 5");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("not unique"));
}

TEST(Cli, StressReportAndProfile) {
  const std::string model = std::string(NBAR_EXAMPLES_DIR) + "/fourbar-steel-bars.yaml";
  const CliRun table = nbar("stress " + model + " --steps 37");
  ASSERT_EQ(table.code, 0) << table.err;
  EXPECT_THAT(table.out, HasSubstr("von_mises"));
  EXPECT_THAT(table.out, HasSubstr("safety_factor"));
  const CliRun json = nbar("stress " + model + " --steps 37 --format json");
  ASSERT_EQ(json.code, 0) << json.err;
  const auto j = nlohmann::json::parse(json.out);
  ASSERT_EQ(j["links"].size(), 3u);
  for (const auto& link : j["links"]) {
    EXPECT_GT(link["von_mises"].get<double>(), 0.0);
    EXPECT_GT(link["safety_factor"].get<double>(), 1.0);
  }
  const CliRun profile = nbar("stress " + model + " --steps 37 --section-profile coupler --step 3 --format csv");
  ASSERT_EQ(profile.code, 0) << profile.err;
  EXPECT_THAT(profile.out, testing::StartsWith("x,area,N,V,M,sigma_right,sigma_left,tau,von_mises\n"));
  EXPECT_GE(count_lines(profile.out), 101);
}

TEST(Cli, SectionProfileSaysWhichBodyAndStep) {
  const std::string model = std::string(NBAR_EXAMPLES_DIR) + "/fourbar-steel-bars.yaml";
  const CliRun profile = nbar("stress " + model + " --steps 37 --section-profile coupler --step 3");
  ASSERT_EQ(profile.code, 0) << profile.err;
  EXPECT_THAT(profile.out, testing::StartsWith("Sections of coupler at step 3 (crank = 30 deg, t = "));
}

TEST(Cli, WritingIntoAMissingFolderSaysTheFolderIsMissing) {
  TempModel dir("");
  const std::string missing = dir.dir() + "/no-such-folder";
  const CliRun solve =
      nbar(std::string("solve ") + NBAR_EXAMPLES_DIR + "/fourbar-crank-rocker.yaml -o " + missing + "/a.csv");
  EXPECT_EQ(solve.code, 2);
  EXPECT_THAT(solve.err, HasSubstr("cannot write " + missing + "/a.csv: the folder '" + missing + "' does not exist"));
  const CliRun draw =
      nbar(std::string("draw ") + NBAR_EXAMPLES_DIR + "/fourbar-crank-rocker.yaml -o " + missing + "/a.png");
  EXPECT_NE(draw.code, 0);
  EXPECT_THAT(draw.err, HasSubstr("the folder '" + missing + "' does not exist"));
}

TEST(Cli, AFullDiskIsAnErrorNotALostOutput) {
  // /dev/full takes the open and every write, and fails the flush: the outputs said exit 0.
  if (!std::filesystem::exists("/dev/full")) GTEST_SKIP() << "no /dev/full here";
  const std::string examples = NBAR_EXAMPLES_DIR;
  for (const std::string& command :
       {"solve " + examples + "/fourbar-crank-rocker.yaml -o /dev/full",
        "solve " + examples + "/fourbar-crank-rocker.yaml --format json > /dev/full",
        "stress " + examples + "/fourbar-steel-bars.yaml --steps 3 -o /dev/full",
        "explain " + examples + "/fourbar-crank-rocker.yaml > /dev/full",
        "synth five-point " + examples + "/synthesis/five-point-crank-rocker.yaml -o /dev/full",
        "check " + examples + "/fourbar-crank-rocker.yaml > /dev/full",
        "check " + examples + "/fourbar-crank-rocker.yaml --format json > /dev/full",
        "import " + examples + "/sketches/fourbar-sketch.dxf > /dev/full", std::string("--help > /dev/full"),
        std::string("solve --help > /dev/full"), std::string("--version > /dev/full")}) {
    SCOPED_TRACE(command);
    const CliRun run = nbar(command);
    EXPECT_EQ(run.code, 2);
    EXPECT_THAT(run.err, HasSubstr("No space left on device"));
  }
}

TEST(Cli, AnOutputThatCannotBeWrittenIsRefusedBeforeAnythingIsComputed) {
  // The input does not exist either: the output's folder is said first, before the input is
  // read (animate used to compute the whole animation, then refuse the file).
  TempModel dir("");
  const std::string missing = dir.dir() + "/no-such-folder";
  const std::string input = dir.dir() + "/no-such-model.yaml";
  for (const std::string& command :
       {"animate " + input + " -o " + missing + "/a.gif", "draw " + input + " -o " + missing + "/a.svg",
        "report " + input + " -o " + missing + "/a.html", "plot " + input + " --y crank -o " + missing + "/a.svg",
        "solve " + input + " -o " + missing + "/a.csv", "stress " + input + " -o " + missing + "/a.csv",
        "explain " + input + " -o " + missing + "/a.txt", "import " + dir.dir() + "/no.dxf -o " + missing + "/a.yaml",
        "synth five-point " + input + " -o " + missing + "/a.txt"}) {
    SCOPED_TRACE(command);
    const CliRun run = nbar(command);
    EXPECT_EQ(run.code, 2);
    EXPECT_THAT(run.err, HasSubstr("cannot write " + missing + "/a."));
    EXPECT_THAT(run.err, HasSubstr("the folder '" + missing + "' does not exist"));
    EXPECT_THAT(run.err, testing::Not(HasSubstr("no-such-model")));
  }
  const CliRun into_a_file =
      nbar("draw " + input + " -o " + std::string(NBAR_EXAMPLES_DIR) + "/fourbar-crank-rocker.yaml/a.svg");
  EXPECT_EQ(into_a_file.code, 2);
  EXPECT_THAT(into_a_file.err, HasSubstr("fourbar-crank-rocker.yaml' is a file, not a folder"));
}

TEST(Cli, WideTablesAreWrappedIntoColumnGroups) {
  ::setenv("COLUMNS", "80", 1);
  const CliRun r =
      nbar(std::string("solve ") + NBAR_EXAMPLES_DIR + "/fourbar-crank-rocker.yaml --steps 3 --format table");
  ::unsetenv("COLUMNS");
  ASSERT_EQ(r.code, 0) << r.err;
  std::istringstream lines(r.out);
  std::string line;
  int groups = 0;
  while (std::getline(lines, line)) {
    EXPECT_LE(line.size(), 80u) << line;
    std::istringstream words(line);
    std::string first;
    words >> first;
    if (first == "step") ++groups;  // every group is led by the step column
  }
  EXPECT_GT(groups, 2);
}

TEST(Cli, ColumnsSuggestTheNameWithItsCase) {
  const CliRun r = nbar(std::string("solve ") + NBAR_EXAMPLES_DIR + "/compressor-myszka.yaml --columns C.X");
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.err, HasSubstr("no column matches 'C.X' (did you mean 'C.x'?); the columns are: step"));
}

TEST(Cli, StressBadUsage) {
  const std::string model = std::string(NBAR_EXAMPLES_DIR) + "/fourbar-steel-bars.yaml";
  EXPECT_EQ(nbar("stress " + model + " --section-profile nosuch").code, 2);
  EXPECT_EQ(nbar("stress " + model + " --steps 5 --section-profile crank --step 9").code, 2);
  EXPECT_EQ(nbar("stress " + model + " --step 2").code, 2);  // --step needs --section-profile
  const CliRun no_shapes = nbar(std::string("stress ") + NBAR_EXAMPLES_DIR + "/fourbar-crank-rocker.yaml");
  EXPECT_EQ(no_shapes.code, 1);
  EXPECT_THAT(no_shapes.err, HasSubstr("no link has a shape"));
}

TEST(Cli, PlotOfASweepInTimeIsAgainstTimeByDefault) {
  TempModel dir("");
  const std::string svg = dir.dir() + "/omega.svg";
  const CliRun r =
      nbar("plot " + std::string(NBAR_EXAMPLES_DIR) + "/fourbar-oscillating.yaml --y output.omega -o " + svg);
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream in(svg);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_THAT(text, HasSubstr(">t [s]<"));
  EXPECT_THAT(text, Not(HasSubstr(">input [deg]<")));
  // Swept by a driver's from/to, the plot stays against that driver.
  const CliRun driver = nbar("plot " + std::string(NBAR_EXAMPLES_DIR) +
                             "/fourbar-crank-rocker.yaml --y rocker.angle --steps 13 -o " + svg);
  ASSERT_EQ(driver.code, 0) << driver.err;
  std::ifstream again(svg);
  EXPECT_THAT(std::string((std::istreambuf_iterator<char>(again)), std::istreambuf_iterator<char>()),
              HasSubstr(">crank [deg]<"));
}

TEST(Cli, DrawAtAValuePastATogglePositionSaysWhereItStops) {
  // The double-rocker's 161-step sweep runs from -80 to 80 deg; 120 deg lies past its toggle.
  // The message speaks of driver values, not of steps (it once gave step numbers of an
  // internal refinement, "between steps 404 and 405").
  TempModel dir("");
  const CliRun r = nbar("draw " + std::string(NBAR_EXAMPLES_DIR) + "/fourbar-double-rocker.yaml --at 120 -o " +
                        dir.dir() + "/x.svg");
  EXPECT_EQ(r.code, 4);
  EXPECT_THAT(r.err, HasSubstr("cannot reach input = 120 deg: it stops at input = 99.7"));
  EXPECT_THAT(r.err, Not(HasSubstr("step")));
}

TEST(Cli, DrawWritesSvgAndPngAndChecksItsArguments) {
  TempModel dir("");
  const std::string model = std::string(NBAR_EXAMPLES_DIR) + "/fourbar-crank-rocker.yaml";
  const CliRun svg = nbar("draw " + model + " -o " + dir.dir() + "/a.svg --labels --trace P --at 90");
  ASSERT_EQ(svg.code, 0) << svg.err;
  std::ifstream f(dir.dir() + "/a.svg");
  std::stringstream text;
  text << f.rdbuf();
  EXPECT_THAT(text.str(), HasSubstr("<svg"));
  EXPECT_THAT(text.str(), HasSubstr("id=\"traces\""));
  const CliRun png = nbar("draw " + model + " -o " + dir.dir() + "/a.png --step 10");
  ASSERT_EQ(png.code, 0) << png.err;
  std::ifstream p(dir.dir() + "/a.png", std::ios::binary);
  char magic[8] = {};
  p.read(magic, 8);
  EXPECT_EQ(std::string(magic + 1, 3), "PNG");
  EXPECT_EQ(nbar("draw " + model + " -o " + dir.dir() + "/a.pdf").code, 2);
  EXPECT_EQ(nbar("draw " + model + " -o " + dir.dir() + "/b.svg --trace Nope").code, 2);
  EXPECT_EQ(nbar("draw " + model + " -o " + dir.dir() + "/b.svg --step 999").code, 2);
  EXPECT_EQ(nbar("draw " + model + " -o " + dir.dir() + "/b.svg --step 1 --at 5").code, 2);
}

TEST(Cli, ReportWritesOneHtmlFile) {
  TempModel dir("");
  const std::string model = std::string(NBAR_EXAMPLES_DIR) + "/fourbar-steel-bars.yaml";
  const CliRun r = nbar("report " + model + " -o " + dir.dir() + "/r.html --steps 37 --frames 12");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::file_size(dir.dir() + "/r.html") > 10000);
  EXPECT_EQ(nbar("report " + model + " -o " + dir.dir() + "/r.txt").code, 2);
}

}  // namespace

namespace {

TEST(Cli, ExplainWritesEveryFormatAndDrawsTheCentres) {
  const std::string model = std::string(NBAR_EXAMPLES_DIR) + "/fourbar-crank-rocker.yaml";
  const CliRun text = nbar("explain " + model + " --step 30");
  ASSERT_EQ(text.code, 0) << text.err;
  EXPECT_THAT(text.out, HasSubstr("x_A*sin(th_crank) - y_A*cos(th_crank) = 0"));
  EXPECT_THAT(text.out, HasSubstr("G = 3 (n - 1) - 2 PI - PII = 3 (4 - 1) - 2*4 - 0 = 1"));
  EXPECT_THAT(text.out, HasSubstr("I(crank,rocker)"));
  const CliRun md = nbar("explain " + model + " --step 30 --format markdown");
  ASSERT_EQ(md.code, 0) << md.err;
  EXPECT_THAT(md.out, HasSubstr("$$"));
  const CliRun json = nbar("explain " + model + " --step 30 --format json");
  ASSERT_EQ(json.code, 0) << json.err;
  const nlohmann::json j = nlohmann::json::parse(json.out);
  EXPECT_EQ(j["count"]["links"], 4);
  EXPECT_EQ(j["centres"].size(), 6u);
  EXPECT_THAT(json.out, Not(HasSubstr("null")));

  const fs::path dir = fs::temp_directory_path() / ("nbar_explain_cli_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const CliRun drawn = nbar("explain " + model + " --step 30 -o " + (dir / "e.md").string() +
                            " --format markdown --draw " + (dir / "c.svg").string());
  ASSERT_EQ(drawn.code, 0) << drawn.err;
  EXPECT_TRUE(drawn.out.empty());
  std::ifstream svg(dir / "c.svg");
  std::stringstream ss;
  ss << svg.rdbuf();
  EXPECT_THAT(ss.str(), HasSubstr("marked-points"));
  for (const char* label : {"I12", "I13", "I14", "I23", "I24", "I34"}) EXPECT_THAT(ss.str(), HasSubstr(label));
  EXPECT_TRUE(fs::exists(dir / "e.md"));
  fs::remove_all(dir);

  EXPECT_EQ(nbar("explain " + model + " --step 400").code, 2);
  EXPECT_EQ(nbar("explain " + model + " --format docx").code, 2);
  EXPECT_EQ(nbar("explain " + model + " --draw x.gif").code, 2);
  EXPECT_EQ(nbar("explain no-such-file.yaml").code, 1);
}

}  // namespace
