// The columns a table has only when asked for: every massive body's centre of mass (B.cg.x ...)
// and the constraint Jacobian's condition number (cond). The centre of mass against the body's
// pose in closed form and its derivatives against central differences of the positions; cond
// against a four-bar's closed-form toggle; and the ordinary columns bit for bit the same whether
// or not the extra ones are asked for.
#include "test_constants.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "nbar/analysis/analysis.hpp"
#include "nbar/analysis/columns.hpp"
#include "nbar/analysis/table_stream.hpp"
#include "nbar/io/model_file.hpp"

namespace nbar {
namespace {

using nbar::test_constants::kPi;

// A crank-rocker (crank 80, coupler 180, rocker 150, frame 200 mm) at 60 rpm: the crank a steel
// bar (its centre of mass the middle of O2-A by symmetry), the coupler with a given mass whose
// centre P lies off the line A-B, the rocker massless.
const char* const kFourBar = R"(
name: cg four-bar
units: {length: mm, angle: deg}
points:
  O2: [0, 0]
  O4: [200, 0]
  A:  [80, 0]
  B:  [181.25, 148.823511]
ground: [O2, O4]
bodies:
  crank:
    points: [O2, A]
    bar: {width: 20, margin: 12, hole: 5}
    thickness: 8
    material: steel
  coupler:
    points: [A, B]
    mass: 2
    cg: [150, 100]
  rocker: [O4, B]
drivers:
  - {angle: crank, from: 0, to: 360, speed: 60 rpm}
sweep: {steps: 721}
)";

std::shared_ptr<const Mechanism> mechanism_of(const std::string& text) {
  return std::make_shared<const Mechanism>(io::parse_model(text).model);
}

std::size_t column(const ResultTable& table, const std::string& name) {
  const auto at = std::find(table.columns.begin(), table.columns.end(), name);
  EXPECT_NE(at, table.columns.end()) << name;
  return static_cast<std::size_t>(at - table.columns.begin());
}

std::vector<double> values(const ResultTable& table, const std::string& name) {
  const std::size_t c = column(table, name);
  std::vector<double> out;
  for (const auto& row : table.rows) out.push_back(row[c]);
  return out;
}

double largest(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

TEST(ColumnsOnRequest, CentresOfMassAreOnlyOfBodiesWithMass) {
  const auto mech = mechanism_of(kFourBar);
  const ColumnsOnRequest every = every_column_on_request(*mech);
  ASSERT_EQ(every.points.size(), 2u);
  EXPECT_EQ(every.points[0].name, "crank.cg");
  EXPECT_EQ(every.points[1].name, "coupler.cg");
  EXPECT_TRUE(every.condition);
  // Ordinary patterns ask for nothing more; patterns that name them ask for what they name.
  EXPECT_TRUE(columns_on_request(*mech, {"crank", "coupler.*", "*.x", "*"}).empty());
  const ColumnsOnRequest cg = columns_on_request(*mech, {"coupler.cg.*"});
  ASSERT_EQ(cg.points.size(), 1u);
  EXPECT_EQ(cg.points[0].name, "coupler.cg");
  EXPECT_FALSE(cg.condition);
  EXPECT_TRUE(columns_on_request(*mech, {"cond"}).condition);
  EXPECT_EQ(columns_on_request(*mech, {"*.cg.ay"}).points.size(), 2u);
}

TEST(ColumnsOnRequest, CentreOfMassIsWhereTheBodyCarriesIt) {
  const auto mech = mechanism_of(kFourBar);
  AnalysisOptions options;
  options.order = 2;
  const Analysis analysis = analyse(mech, options);
  const ResultTable t = result_table(analysis, every_column_on_request(*mech));
  const auto ax = values(t, "A.x"), ay = values(t, "A.y"), bx = values(t, "B.x"), by = values(t, "B.y");
  const auto crank_x = values(t, "crank.cg.x"), crank_y = values(t, "crank.cg.y");
  const auto coupler_x = values(t, "coupler.cg.x"), coupler_y = values(t, "coupler.cg.y");
  // The coupler's given centre (150, 100) in its drawn frame (A, direction A->B), turned with it.
  const double drawn_angle = std::atan2(148.823511, 181.25 - 80.0);
  const double dx = 150.0 - 80.0, dy = 100.0;
  double worst = 0.0;
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    // The bar is symmetric about its middle, holes and margins alike: its centroid is there.
    worst = std::max({worst, std::abs(crank_x[r] - 0.5 * ax[r]), std::abs(crank_y[r] - 0.5 * ay[r])});
    const double turn = std::atan2(by[r] - ay[r], bx[r] - ax[r]) - drawn_angle;
    const double ex = ax[r] + std::cos(turn) * dx - std::sin(turn) * dy;
    const double ey = ay[r] + std::sin(turn) * dx + std::cos(turn) * dy;
    worst = std::max({worst, std::abs(coupler_x[r] - ex), std::abs(coupler_y[r] - ey)});
  }
  EXPECT_LT(worst, 1e-10);  // mm, on a linkage of 200 mm
  EXPECT_EQ(t.units[column(t, "coupler.cg.x")], "mm");
  EXPECT_EQ(t.units[column(t, "coupler.cg.vx")], "mm/s");
  EXPECT_EQ(t.units[column(t, "coupler.cg.ay")], "mm/s^2");
}

// Central differences over the sweep's time step h: the first derivative's error is at most
// h^2/6 max|x'''| and the second's h^2/12 max|x''''|, bounds read from the table's own jerk and
// fourth-derivative columns, so the tolerance follows the step.
TEST(ColumnsOnRequest, CentreOfMassDerivativesAreThoseOfItsPath) {
  const auto mech = mechanism_of(kFourBar);
  AnalysisOptions options;
  options.order = 4;
  const Analysis analysis = analyse(mech, options);
  const ResultTable t = result_table(analysis, every_column_on_request(*mech));
  const auto time = values(t, "t");
  const double h = time[1] - time[0];
  ASSERT_NEAR(h, 1.0 / 720.0, 1e-15);  // one turn a second, 720 intervals
  for (const std::string body : {"crank.cg", "coupler.cg"})
    for (const std::string axis : {"x", "y"}) {
      SCOPED_TRACE(body + " " + axis);
      const auto x = values(t, body + "." + axis), v = values(t, body + ".v" + axis), a = values(t, body + ".a" + axis);
      const double velocity_bound = h * h / 6.0 * largest(values(t, body + ".j" + axis));
      const double acceleration_bound = h * h / 12.0 * largest(values(t, body + ".d4" + axis));
      double worst_v = 0.0, worst_a = 0.0;
      for (std::size_t r = 1; r + 1 < x.size(); ++r) {
        worst_v = std::max(worst_v, std::abs((x[r + 1] - x[r - 1]) / (2 * h) - v[r]));
        worst_a = std::max(worst_a, std::abs((x[r + 1] - 2 * x[r] + x[r - 1]) / (h * h) - a[r]));
      }
      // Rounding of x (1e-13 mm) over h and h^2 adds 1e-10 mm/s and 1e-7 mm/s^2 at most.
      EXPECT_LE(worst_v, 1.05 * velocity_bound + 1e-9);
      EXPECT_LE(worst_a, 1.05 * acceleration_bound + 1e-6);
      // The bounds are tight enough to mean something: a fraction of the sizes themselves.
      EXPECT_LT(velocity_bound, 1e-4 * largest(v));
      EXPECT_LT(acceleration_bound, 1e-4 * largest(a));
    }
}

// What the request every front-end uses (SolveRequest::table) does with --columns.
ResultTable asked_for(const Analysis& analysis, const std::vector<std::string>& patterns) {
  return select_columns(result_table(analysis, columns_on_request(*analysis.mechanism, patterns)), patterns);
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

// Asking for the extra columns changes no other number, not even the noise made 0: a far centre
// of mass would otherwise raise the threshold of every length column.
TEST(ColumnsOnRequest, OrdinaryColumnsAreBitForBitTheSame) {
  std::string far = kFourBar;
  far.replace(far.find("cg: [150, 100]"), 14, "cg: [9e6, 4e6]");
  for (const std::string& text : {std::string(kFourBar), far}) {
    const auto mech = mechanism_of(text);
    for (const bool dynamics : {false, true}) {
      SCOPED_TRACE(dynamics ? "with dynamics" : "kinematics");
      AnalysisOptions options;
      options.steps = 181;
      options.dynamics = dynamics;
      const ResultTable plain = result_table(analyse(mech, options));
      // The condition estimates read the sweep's factors and change nothing either.
      AnalysisOptions with_condition = options;
      with_condition.condition = true;
      const Analysis analysis = analyse(mech, with_condition);
      const ResultTable extra = result_table(analysis, every_column_on_request(*mech));
      ASSERT_GT(extra.columns.size(), plain.columns.size());
      for (const std::string& name : plain.columns) EXPECT_TRUE(same_bits(values(plain, name), values(extra, name)));

      // The same as the front-ends select them, and through the streamed CSV's rows.
      const ResultTable asked = asked_for(analysis, {"crank", "A.*", "coupler.*", "coupler.cg.*", "cond"});
      const ResultTable ordinary = asked_for(analysis, {"crank", "A.*", "coupler.*"});
      EXPECT_EQ(asked.columns.size(), ordinary.columns.size() + 7);
      EXPECT_EQ(asked.columns.back(), "cond");
      for (const std::string& name : ordinary.columns)
        EXPECT_TRUE(same_bits(values(ordinary, name), values(asked, name))) << name;
      TableStream stream(mech, options);
      stream.select({"crank", "A.*", "coupler.*", "coupler.cg.*", "cond"});
      std::vector<std::vector<double>> rows;
      stream.rows([&](const double* row) { rows.emplace_back(row, row + stream.columns().size()); });
      ASSERT_EQ(stream.columns(), asked.columns);
      ASSERT_EQ(rows.size(), asked.rows.size());
      for (std::size_t r = 0; r < rows.size(); ++r) EXPECT_TRUE(same_bits(rows[r], asked.rows[r])) << r;
    }
  }
}

// The double-rocker of examples/fourbar-double-rocker.yaml driven as a rocker towards its toggle,
// where coupler and output fold in line: |A - O4| = coupler + output, so
// cos(theta) = (a^2 + g^2 - (b + c)^2) / (2 a g).
TEST(ColumnsOnRequest, ConditionGrowsTowardsTheToggle) {
  const double ax = 20.837781, ay = -118.17693, bx = 51.787322, by = -23.086837, g = 200.0;
  const double a = std::hypot(ax, ay), b = std::hypot(bx - ax, by - ay), c = std::hypot(bx - g, by);
  const double toggle = std::acos((a * a + g * g - (b + c) * (b + c)) / (2 * a * g)) * 180.0 / kPi;
  ASSERT_NEAR(toggle, 99.7151, 1e-4);  // as the example says
  // From -80 deg to 0.05 deg short of the toggle, a sample every 0.05 deg near it.
  const double end = toggle - 0.05;
  std::string text = R"(
units: {length: mm, angle: deg}
points: {O2: [0, 0], O4: [200, 0], A: [20.837781, -118.17693], B: [51.787322, -23.086837]}
ground: [O2, O4]
bodies: {input: [O2, A], coupler: [A, B], output: [O4, B]}
drivers:
  - {angle: input, from: -80, to: END, speed: 30 deg/s}
sweep: {steps: STEPS}
)";
  const int steps = static_cast<int>(std::lround((end + 80.0) / 0.05)) + 1;
  text.replace(text.find("END"), 3, std::to_string(end));
  text.replace(text.find("STEPS"), 5, std::to_string(steps));
  const auto mech = mechanism_of(text);
  AnalysisOptions options;
  options.condition = true;
  const Analysis analysis = analyse(mech, options);
  ASSERT_TRUE(analysis.complete()) << analysis.sweep.stop_reason;
  const ResultTable t = asked_for(analysis, {"input", "cond"});
  double within_tenth = HUGE_VAL, away_largest = 0.0, previous = 0.0;
  for (const auto& row : t.rows) {
    const double input = row[0], cond = row[1];
    ASSERT_TRUE(std::isfinite(cond)) << input;
    EXPECT_GE(cond, 1.0);
    if (toggle - input < 0.1) within_tenth = std::min(within_tenth, cond);
    if (toggle - input > 30.0) away_largest = std::max(away_largest, cond);
    // Over the last degree it only grows.
    if (toggle - input < 1.0) {
      EXPECT_GT(cond, previous) << input;
    }
    previous = cond;
  }
  // Away from the toggle the Jacobian is well conditioned; 0.05 deg from it, five times worse.
  EXPECT_LT(away_largest, 12.0);
  EXPECT_GT(within_tenth, 5.0 * away_largest);
  // Towards a fold it grows as 1/sqrt(distance): 9 times nearer (0.45 to 0.05 deg), 3 times as
  // large, which holds only if the toggle is where the closed form puts it.
  const double at_0_45 = t.rows[static_cast<std::size_t>(steps - 1 - 8)][1];
  const double at_0_05 = t.rows.back()[1];
  EXPECT_NEAR(at_0_05 / at_0_45, 3.0, 0.15);
}

}  // namespace
}  // namespace nbar
