// A simulation drawn from the command line: `nbar animate --simulate` (every frame the pose of the
// simulation's row at that frame's time) and `nbar report --simulate` (its Simulation section),
// checked against `nbar simulate --format json`'s rows; and what they refuse.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "apps/cli_support.hpp"

namespace nbar::cli_test {
namespace {

using ::testing::HasSubstr;
using Json = nlohmann::json;

const std::string kReleased = std::string(NBAR_EXAMPLES_DIR) + "/crank-rocker-released.yaml";
const std::string kRun = " --to 2 --dt 0.1";  // 21 rows

Json simulated_rows() {
  const CliRun run = nbar("simulate " + kReleased + kRun + " --format json");
  EXPECT_EQ(run.code, 0) << run.err;
  return Json::parse(run.out);
}

double cell(const Json& table, std::size_t row, const std::string& column) {
  const auto& columns = table["columns"];
  const auto at = std::find(columns.begin(), columns.end(), column);
  EXPECT_NE(at, columns.end()) << column;
  return table["rows"][row][static_cast<std::size_t>(at - columns.begin())].get<double>();
}

// The numbers of a JavaScript array of arrays `const NAME = [\n[...],\n...];` in the HTML player.
std::vector<std::vector<double>> js_rows(const std::string& html, const std::string& name) {
  const std::size_t start = html.find("const " + name + " = [\n");
  EXPECT_NE(start, std::string::npos) << name;
  const std::size_t end = html.find("];\n", start);
  std::vector<std::vector<double>> rows;
  const std::string block = html.substr(start, end - start);
  const std::regex row(R"(\n\[([^\]]*)\])");
  for (auto it = std::sregex_iterator(block.begin(), block.end(), row); it != std::sregex_iterator(); ++it) {
    std::vector<double> values;
    std::stringstream numbers((*it)[1].str());
    for (std::string v; std::getline(numbers, v, ',');) values.push_back(std::stod(v));
    rows.push_back(values);
  }
  return rows;
}

// Each frame of the HTML animation is the row at its time: the read-out says the row's time and
// crank angle, and every moving point's label is moved from the first frame by the row's
// displacement of that point, on the drawing's one scale (pixels per mm, y down).
TEST(SimulateCli, AnimationFramesAreTheSimulationsRowsAtTheirTimes) {
  const Json table = simulated_rows();
  ASSERT_EQ(table["rows"].size(), 21u);
  ScratchDir f("nbar_simulate_cli");
  const std::string out = f.file("released.html");
  const CliRun run = nbar("animate " + kReleased + " --simulate" + kRun + " --frames 21 -o " + out);
  ASSERT_EQ(run.code, 0) << run.err;
  const std::string html = read_file(out);
  const std::regex readout(R"re("t = ([-0-9.e]+) s, crank = ([-0-9.e]+) deg")re");
  std::vector<std::pair<double, double>> readouts;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), readout); it != std::sregex_iterator(); ++it)
    readouts.emplace_back(std::stod((*it)[1].str()), std::stod((*it)[2].str()));
  ASSERT_EQ(readouts.size(), 21u);
  for (std::size_t k = 0; k < readouts.size(); ++k) {
    EXPECT_NEAR(readouts[k].first, cell(table, k, "t"), 1e-9) << "frame " << k;
    EXPECT_NEAR(readouts[k].second, cell(table, k, "crank"), 1e-3 * std::max(1.0, std::abs(cell(table, k, "crank"))))
        << "frame " << k;
  }
  // The labels of the moving points A, B, P (the model's order), moved by the rows' displacements.
  const std::vector<std::vector<double>> shifts = js_rows(html, "shifts");
  ASSERT_EQ(shifts.size(), 21u);
  const std::vector<std::string> points = {"A", "B", "P"};
  // The drawing's one scale (px per mm), fitted by least squares to every shift: then each shift
  // must be that scale times its row's displacement, to the 0.01 px the player's numbers keep.
  const auto moved = [&](std::size_t k, const std::string& point, const char* axis) {
    return cell(table, k, point + axis) - cell(table, 0, point + axis);
  };
  double along = 0, squared = 0;
  for (std::size_t k = 0; k < shifts.size(); ++k)
    for (std::size_t p = 0; p < points.size(); ++p) {
      along += shifts[k][2 * p] * moved(k, points[p], ".x") - shifts[k][2 * p + 1] * moved(k, points[p], ".y");
      squared += std::pow(moved(k, points[p], ".x"), 2) + std::pow(moved(k, points[p], ".y"), 2);
    }
  ASSERT_GT(squared, 100.0) << "the mechanism moves";
  const double scale = along / squared;
  ASSERT_GT(scale, 0.5);
  for (std::size_t k = 0; k < shifts.size(); ++k)
    for (std::size_t p = 0; p < points.size(); ++p) {
      const double dx = cell(table, k, points[p] + ".x") - cell(table, 0, points[p] + ".x");
      const double dy = cell(table, k, points[p] + ".y") - cell(table, 0, points[p] + ".y");
      EXPECT_NEAR(shifts[k][2 * p], scale * dx, 0.02) << points[p] << " at frame " << k;
      EXPECT_NEAR(shifts[k][2 * p + 1], -scale * dy, 0.02) << points[p] << " at frame " << k;
    }
  // The crank's body turns by the row's crank angle (clockwise on screen, so the angle's negative).
  const std::vector<std::vector<double>> motion = js_rows(html, "motion");
  ASSERT_EQ(motion.size(), 21u);
  EXPECT_NEAR(motion[20][0], -(cell(table, 20, "crank") - cell(table, 0, "crank")), 0.01);
}

TEST(SimulateCli, ReportHasTheSimulationSectionAndPlotsAgainstTime) {
  ScratchDir f("nbar_simulate_cli");
  const std::string out = f.file("released.html");
  const CliRun run = nbar("report " + kReleased + " --simulate" + kRun + " --frames 12 -o " + out);
  ASSERT_EQ(run.code, 0) << run.err;
  const std::string html = read_file(out);
  EXPECT_THAT(html, HasSubstr("<section id=\"simulation\"><h2>Simulation</h2>"));
  EXPECT_THAT(html, HasSubstr("<tr><th>Simulation</th><td>21 rows in time"));
  EXPECT_THAT(html, HasSubstr("<tr><th>Free drivers</th><td>crank</td></tr>"));
  EXPECT_THAT(html, HasSubstr("<tr><th>Simulated</th><td>2 s, 21 rows</td></tr>"));
  EXPECT_THAT(html, HasSubstr("Constraint drift"));
  EXPECT_THAT(html, HasSubstr(">Energies<"));
  // The sweep's force section is not there: a simulation's forces are not the sweep's.
  EXPECT_THAT(html, ::testing::Not(HasSubstr("<section id=\"forces\">")));
}

TEST(SimulateCli, RunOptionsNeedSimulateAndTheSweepsStressesAreRefused) {
  ScratchDir f("nbar_simulate_cli");
  const CliRun to = nbar("animate " + kReleased + " --to 2 -o " + f.file("a.html"));
  EXPECT_EQ(to.code, 2);
  EXPECT_THAT(to.err, HasSubstr("--to: is an option of a simulation: give --simulate too"));
  const CliRun no_to = nbar("report " + kReleased + " --simulate -o " + f.file("r.html"));
  EXPECT_EQ(no_to.code, 2);
  EXPECT_THAT(no_to.err, HasSubstr("--to"));
  const CliRun stress = nbar("animate " + kReleased + " --simulate --to 1 --stress -o " + f.file("a.gif"));
  EXPECT_EQ(stress.code, 2);
  EXPECT_THAT(stress.err, HasSubstr("--stress"));
  // A free motion without mass cannot be simulated: the same error as `nbar simulate`'s.
  std::string massless = read_file(std::string(NBAR_EXAMPLES_DIR) + "/fourbar-crank-rocker.yaml");
  massless.replace(massless.find("speed: 120 rpm}"), 15, "speed: 120 rpm, free: true}");
  const std::string driven = f.file("massless.yaml");
  std::ofstream(driven) << massless;
  const CliRun simulate = nbar("simulate " + driven + " --to 1");
  const CliRun animate = nbar("animate " + driven + " --simulate --to 1 -o " + f.file("d.html"));
  EXPECT_EQ(simulate.code, 1);
  EXPECT_THAT(simulate.err, HasSubstr("massless.yaml:21:5: a free motion has no inertia"));
  EXPECT_EQ(animate.code, simulate.code);
  EXPECT_EQ(animate.err, simulate.err);
}

// A column asked for that the table does not have is said before the run: a run of 1e6 s of the
// released crank-rocker (minutes) is refused at once, with no row written.
TEST(SimulateCli, AnUnknownColumnIsRefusedBeforeTheRun) {
  const CliRun run = nbar("simulate " + kReleased + " --to 1000000 --dt 1000 --columns t,nosuch");
  EXPECT_EQ(run.code, 2);
  EXPECT_THAT(run.err, HasSubstr("--columns: no column matches 'nosuch'"));
  EXPECT_EQ(run.out, "");
}

}  // namespace
}  // namespace nbar::cli_test
