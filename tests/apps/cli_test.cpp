// The nbar command line as users meet it: every bundled example, every documented exit code.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "apps/cli_support.hpp"

#include <array>
#include <cstdio>
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

TEST(Cli, OutputFileAndColumnSelection) {
  TempModel dir("");
  const std::string out = dir.dir() + "/out.csv";
  const CliRun r = nbar(std::string("solve ") + NBAR_EXAMPLES_DIR + "/fourbar-crank-rocker.yaml --steps 3 --columns 'crank,rocker.*' -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream f(out);
  std::string header;
  std::getline(f, header);
  EXPECT_EQ(header, "crank,rocker.angle,rocker.omega,rocker.alpha");
  const CliRun bad = nbar(std::string("solve ") + NBAR_EXAMPLES_DIR + "/fourbar-crank-rocker.yaml --columns nosuch");
  EXPECT_EQ(bad.code, 2);
  EXPECT_THAT(bad.err, HasSubstr("no column matches 'nosuch'"));
}

TEST(Cli, TableFormatHasUnits) {
  const CliRun r = nbar(std::string("solve ") + NBAR_EXAMPLES_DIR + "/fourbar-crank-rocker.yaml --steps 3 --format table --columns crank,rocker.omega");
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
  TempModel m(std::string(kFourBar) + "drivers:\n  - {angle: crank, from: 90, to: 100}\n  - {angle: rocker, from: 60, to: 70}\n");
  const CliRun r = nbar("check " + m.path());
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("1 degree of freedom"));
  EXPECT_THAT(r.err, HasSubstr("2 drivers"));
  EXPECT_THAT(r.err, HasSubstr(m.path() + ":"));
}

TEST(Cli, BarsTooShortToCloseCannotAssemble) {
  TempModel m(std::string(kFourBar) + "lengths: {coupler: 20}\ndrivers:\n  - {angle: crank, from: 90, to: 100}\n");
  const CliRun check = nbar("check " + m.path());
  EXPECT_EQ(check.code, 3);
  EXPECT_THAT(check.err, HasSubstr("cannot be met"));
  const CliRun solve = nbar("solve " + m.path());
  EXPECT_EQ(solve.code, 3);
  EXPECT_EQ(solve.out, "");
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
}

TEST(Cli, DynamicsColumnsAndJson) {
  const std::string model = std::string(NBAR_EXAMPLES_DIR) + "/fourbar-steel-bars.yaml";
  const CliRun r = nbar("solve " + model + " --dynamics --steps 7");
  ASSERT_EQ(r.code, 0) << r.err;
  std::istringstream lines(r.out);
  std::string header;
  std::getline(lines, header);
  for (const char* column : {"O2.ground>crank.Fx", "A.crank>coupler.Fy", "A.crank>coupler.along", "B.coupler>rocker.across",
                             "O4.ground>rocker.Fx", "crank.torque", "energy.kinetic", "energy.potential"})
    EXPECT_THAT(header, HasSubstr(column));
  const CliRun json = nbar("solve " + model + " --dynamics --steps 7 --format json");
  ASSERT_EQ(json.code, 0) << json.err;
  const auto j = nlohmann::json::parse(json.out);
  EXPECT_TRUE(j["dynamics"]["unique"].get<bool>());
  EXPECT_LT(j["dynamics"]["max_residual"].get<double>(), 1e-9);
}

TEST(Cli, DynamicsOfARedundantMechanismSaysTheForcesAreNotUnique) {
  const CliRun r = nbar(std::string("solve ") + NBAR_EXAMPLES_DIR + "/parallelogram-redundant.yaml --dynamics --steps 5");
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

TEST(Cli, StressBadUsage) {
  const std::string model = std::string(NBAR_EXAMPLES_DIR) + "/fourbar-steel-bars.yaml";
  EXPECT_EQ(nbar("stress " + model + " --section-profile nosuch").code, 2);
  EXPECT_EQ(nbar("stress " + model + " --steps 5 --section-profile crank --step 9").code, 2);
  EXPECT_EQ(nbar("stress " + model + " --step 2").code, 2);  // --step needs --section-profile
  const CliRun no_shapes = nbar(std::string("stress ") + NBAR_EXAMPLES_DIR + "/fourbar-crank-rocker.yaml");
  EXPECT_EQ(no_shapes.code, 1);
  EXPECT_THAT(no_shapes.err, HasSubstr("no link has a shape"));
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
  const CliRun drawn = nbar("explain " + model + " --step 30 -o " + (dir / "e.md").string() + " --format markdown --draw " +
                            (dir / "c.svg").string());
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
