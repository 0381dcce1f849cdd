// The transmission angle over a sweep, from the core (transmission_extremes): against the closed
// form of a crank-rocker, where mu is extreme with the crank along the frame line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>

#include "nbar/analysis/analysis.hpp"
#include "nbar/analysis/columns.hpp"
#include "nbar/io/model_file.hpp"

namespace nbar {
namespace {

// cos mu = (b^2 + c^2 - BD^2) / (2 b c), BD the diagonal from the crank pin to the rocker's pivot.
double mu_closed_form(double frame, double crank, double coupler, double rocker, double crank_angle) {
  const double diagonal_squared = crank * crank + frame * frame - 2 * crank * frame * std::cos(crank_angle);
  return std::acos((coupler * coupler + rocker * rocker - diagonal_squared) / (2 * coupler * rocker));
}

// A crank-rocker whose mu runs far past 90 deg: frame 100, crank 20, coupler 50, rocker 80 mm,
// the crank swept once round in `steps` samples.
std::string wide_crank_rocker(int steps) {
  return "units: {length: mm, angle: deg}\n"
         "points: {O2: [0, 0], O4: [100, 0], A: [20, 0], B: [35.625, 47.496]}\n"
         "ground: [O2, O4]\n"
         "bodies: {crank: [O2, A], coupler: [A, B], rocker: [O4, B]}\n"
         "lengths: {crank: 20, coupler: 50, rocker: 80}\n"
         "drivers:\n  - {angle: crank, from: 0, to: 360}\n"
         "sweep: {steps: " +
         std::to_string(steps) + "}\n";
}

TEST(TransmissionExtremes, ACrankRockersExtremesAreWhereTheCrankLiesAlongTheFrame) {
  // examples/fourbar-crank-rocker.yaml: frame 200, crank 80, coupler 180, rocker 150 mm, the
  // crank swept 0 to 360 deg in 361 samples: the crank is along the frame at steps 0 and 180.
  const io::LoadedModel file = io::load_model_file(std::string(NBAR_EXAMPLES_DIR) + "/fourbar-crank-rocker.yaml");
  AnalysisOptions options;
  options.steps = 361;
  options.order = 0;
  const Analysis analysis = analyse(std::make_shared<const Mechanism>(file.model), options);
  const std::vector<TransmissionExtremes> mu = transmission_extremes(analysis);
  ASSERT_EQ(mu.size(), 1u);
  EXPECT_EQ(mu[0].loop, "crank-coupler-rocker");
  // The coupler's length is the drawing's (179.9999998 mm), not given: read it off the points.
  const Model& m = file.model;
  const double coupler = (m.points[m.find_point("B")].position - m.points[m.find_point("A")].position).norm();
  ASSERT_NEAR(coupler, 0.180, 1e-9);
  const double smallest = mu_closed_form(0.200, 0.080, coupler, 0.150, 0.0);              // 41.41 deg
  const double largest = mu_closed_form(0.200, 0.080, coupler, 0.150, std::numbers::pi);  // 115.79 deg
  EXPECT_NEAR(mu[0].min, smallest, 1e-9);
  EXPECT_NEAR(mu[0].max, largest, 1e-9);
  EXPECT_EQ(mu[0].min_step, 0);
  EXPECT_EQ(mu[0].max_step, 180);
  // The design value: 41.41 deg from a dead point at the start beats 180 - 115.79 = 64.21 deg.
  EXPECT_NEAR(mu[0].design, std::min(smallest, std::numbers::pi - largest), 1e-9);
  EXPECT_EQ(mu[0].design_step, 0);
  EXPECT_NEAR(mu[0].min * 180 / std::numbers::pi, 41.4096221536, 1e-8);
}

TEST(TransmissionExtremes, TheDesignValueCountsAnAngleBeyondNinetyDegreesFromTheOtherSide) {
  // A crank-rocker whose mu runs far past 90 deg: frame 100, crank 20, coupler 50, rocker 80;
  // mu from 71.8 deg (crank at 0) to 133.4 deg (crank at 180 deg), which is 46.6 deg from a dead
  // point: nearer than the smallest mu.
  const double frame = 100, crank = 20, coupler = 50, rocker = 80;
  const io::LoadedModel file = io::parse_model(wide_crank_rocker(361), "wide.yaml");
  AnalysisOptions options;
  options.order = 0;
  const Analysis analysis = analyse(std::make_shared<const Mechanism>(file.model), options);
  ASSERT_TRUE(analysis.complete());
  const std::vector<TransmissionExtremes> mu = transmission_extremes(analysis);
  ASSERT_EQ(mu.size(), 1u);
  const double smallest = mu_closed_form(frame, crank, coupler, rocker, 0.0);
  const double largest = mu_closed_form(frame, crank, coupler, rocker, std::numbers::pi);
  ASSERT_GT(std::numbers::pi - largest, 0.0);
  ASSERT_LT(std::numbers::pi - largest, smallest);  // the case this test is for
  EXPECT_NEAR(mu[0].max, largest, 1e-9);
  EXPECT_NEAR(mu[0].design, std::numbers::pi - largest, 1e-9);
  EXPECT_EQ(mu[0].design_step, 180);
}

// The per-sample design value, a column on request: min(mu, 180 deg - mu) against the closed form
// at every sample, its minimum the loop's design value (where the .mu column's minimum is 25 deg
// off it), and nothing else added by asking for it.
TEST(TransmissionExtremes, TheDesignValueColumnIsTheAngleFromTheNearerDeadPoint) {
  const double frame = 100, crank = 20, coupler = 50, rocker = 80;
  const auto mech = std::make_shared<const Mechanism>(io::parse_model(wide_crank_rocker(73), "wide.yaml").model);
  AnalysisOptions options;
  options.order = 0;
  const Analysis analysis = analyse(mech, options);
  ASSERT_TRUE(analysis.complete());
  const std::vector<std::string> asked = {"crank", "*.mu", "*.mu_design"};
  const ResultTable t = select_columns(result_table(analysis, columns_on_request(*mech, asked)), asked);
  ASSERT_EQ(t.columns,
            (std::vector<std::string>{"crank", "crank-coupler-rocker.mu", "crank-coupler-rocker.mu_design"}));
  EXPECT_EQ(t.units[2], "deg");
  double smallest_mu = 180, smallest_design = 180;
  for (const auto& row : t.rows) {
    const double mu =
        mu_closed_form(frame, crank, coupler, rocker, row[0] * std::numbers::pi / 180) * 180 / std::numbers::pi;
    EXPECT_NEAR(row[1], mu, 1e-7) << row[0];
    EXPECT_NEAR(row[2], std::min(mu, 180 - mu), 1e-7) << row[0];
    smallest_mu = std::min(smallest_mu, row[1]);
    smallest_design = std::min(smallest_design, row[2]);
  }
  EXPECT_NEAR(smallest_design, transmission_extremes(analysis)[0].design * 180 / std::numbers::pi, 1e-9);
  EXPECT_NEAR(smallest_design, 46.6, 0.05);
  EXPECT_GT(smallest_mu - smallest_design, 25.0);  // the obvious min() of .mu is not the design value
  // Asked for by name only: the full table has neither it nor cond unless asked.
  const ResultTable plain = result_table(analysis, columns_on_request(*mech, {"*.mu"}));
  EXPECT_EQ(std::count(plain.columns.begin(), plain.columns.end(), "crank-coupler-rocker.mu_design"), 0);
  EXPECT_EQ(std::count(plain.columns.begin(), plain.columns.end(), "cond"), 0);
}

}  // namespace
}  // namespace nbar
