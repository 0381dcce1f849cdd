// A guide given by a point and an angle (`along: {point: O2, angle: 30 deg}`): the inclined
// slider-crank of examples/ against its closed form, the same motion as the guide drawn with two
// points, no columns for the point the reader makes, the model written back as it was given, and
// bad input placed at its line and column.
#include "test_constants.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "model_file_support.hpp"
#include "nbar/analysis/analysis.hpp"
#include "nbar/analysis/summary.hpp"
#include "nbar/io/model_export.hpp"
#include "nbar/io/model_file.hpp"
#include "nbar/io/summary_writer.hpp"

namespace nbar {
namespace {

using io::test_support::fails_at;

using nbar::test_constants::kPi;

Analysis analysed(const Model& model, int steps) {
  AnalysisOptions options;
  options.steps = steps;
  return analyse(std::make_shared<const Mechanism>(model), options);
}

std::vector<double> column_of(const ResultTable& t, const std::string& name) {
  const auto at = std::find(t.columns.begin(), t.columns.end(), name);
  EXPECT_NE(at, t.columns.end()) << name;
  std::vector<double> out;
  for (const auto& row : t.rows) out.push_back(row[static_cast<std::size_t>(at - t.columns.begin())]);
  return out;
}

// Crank r = 50, rod l = 180, guide through O2 at alpha = 30 deg: with phi = theta - alpha the
// piston is s = r cos(phi) + sqrt(l^2 - r^2 sin^2(phi)) along the guide, and moves at
// ds/dt = -omega r sin(phi) (1 + r cos(phi) / sqrt(l^2 - r^2 sin^2(phi))).
TEST(GuideByAngle, InclinedSliderCrankFollowsItsClosedForm) {
  const Model model = io::load_model_file(std::string(NBAR_EXAMPLES_DIR) + "/slider-crank-inclined.yaml").model;
  const Analysis a = analysed(model, 25);  // every 15 deg
  ASSERT_TRUE(a.complete());
  const ResultTable t = result_table(a);
  for (const std::string& c : t.columns) EXPECT_EQ(c.find("guide"), std::string::npos) << c;
  const auto crank = column_of(t, "crank"), cx = column_of(t, "C.x"), cy = column_of(t, "C.y"),
             cvx = column_of(t, "C.vx"), cvy = column_of(t, "C.vy");
  const double r = 50, l = 180, alpha = kPi / 6, omega = 600.0 * 2 * kPi / 60.0;
  double worst_position = 0, worst_speed = 0;
  for (std::size_t i = 0; i < crank.size(); ++i) {
    const double phi = crank[i] * kPi / 180.0 - alpha;
    const double root = std::sqrt(l * l - r * r * std::sin(phi) * std::sin(phi));
    const double s = r * std::cos(phi) + root;
    const double speed = -omega * r * std::sin(phi) * (1.0 + r * std::cos(phi) / root);
    worst_position =
        std::max({worst_position, std::abs(cx[i] - s * std::cos(alpha)), std::abs(cy[i] - s * std::sin(alpha))});
    worst_speed =
        std::max({worst_speed, std::abs(cvx[i] - speed * std::cos(alpha)), std::abs(cvy[i] - speed * std::sin(alpha))});
  }
  EXPECT_LT(worst_position, 1e-10);  // mm: the stroke is 100 mm
  EXPECT_LT(worst_speed, 1e-8);      // mm/s: the piston reaches about 5 500 mm/s
}

const char* const kByAngle = R"(units: {length: mm, angle: deg}
points:
  O2: [0, 0]
  A: [50, 0]
  C: [191.873734813, 110.778352444]
ground: [O2]
bodies: {crank: [O2, A], rod: [A, C], piston: [C]}
sliders:
  - {body: piston, point: C, along: {point: O2, angle: ANGLE}}
drivers:
  - {angle: crank, from: 0, to: 360}
)";

std::string by_angle(const std::string& angle) {
  std::string text = kByAngle;
  text.replace(text.find("ANGLE"), 5, angle);
  return text;
}

TEST(GuideByAngle, IsTheGuideDrawnWithTwoPoints) {
  std::string two_points = kByAngle;
  two_points.replace(two_points.find("  O2: [0, 0]"), 12, "  O2: [0, 0]\n  X: [173.205080757, 100]");
  two_points.replace(two_points.find("ground: [O2]"), 12, "ground: [O2, X]");
  two_points.replace(two_points.find("{point: O2, angle: ANGLE}"), 25, "[O2, X]");
  const ResultTable drawn = result_table(analysed(io::parse_model(two_points).model, 13));
  // In degrees by the model's unit, and the same angle written in radians.
  for (const std::string angle : {"30", "30 deg", "0.5235987755982988 rad"}) {
    SCOPED_TRACE(angle);
    const ResultTable given = result_table(analysed(io::parse_model(by_angle(angle)).model, 13));
    for (const std::string c : {"C.x", "C.y", "C.vx", "C.ay", "rod.angle", "rod.alpha"}) {
      const auto a = column_of(given, c), b = column_of(drawn, c);
      for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], b[i], 1e-9 * std::max(1.0, std::abs(b[i]))) << c;
    }
    EXPECT_EQ(given.columns.size() + 2 * 3, drawn.columns.size());  // X.x ... X.ay are the drawn guide's own
  }
}

TEST(GuideByAngle, IsWrittenBackAsGiven) {
  const Model model = io::parse_model(by_angle("30")).model;
  const std::string text = io::model_yaml(model);
  EXPECT_NE(text.find("along: {point: O2, angle: 30}"), std::string::npos) << text;
  EXPECT_EQ(text.find("guide"), std::string::npos) << text;
  const Model back = io::parse_model(text).model;
  ASSERT_EQ(back.points.size(), model.points.size());
  for (std::size_t i = 0; i < model.points.size(); ++i) {
    EXPECT_EQ(back.points[i].guide_direction, model.points[i].guide_direction);
    EXPECT_NEAR((back.points[i].position - model.points[i].position).norm(), 0.0, 1e-15);
  }
}

// A guide by an angle on a moving body (`body: arm`, as Q is also a ground point): a slot along a
// line through the arm's pivot Q, turning with the arm, is the slot drawn with two points of the
// arm, Q and E, on that line.
TEST(GuideByAngle, TurnsWithTheBodyThatCarriesIt) {
  const std::string base = R"(units: {length: mm, angle: deg}
points: {O2: [0, 0], Q: [0, -100], A: [30, 0], E: [60, 100]}
ground: [O2, Q]
bodies: {crank: [O2, A], arm: [Q, E]}
slots:
  - {point: A, along: GUIDE}
drivers:
  - {angle: crank, from: 0, to: 360}
)";
  std::string by_angle = base, two_points = base;
  // The angle of Q->A (and Q->E) in the drawing: atan2(100, 30).
  by_angle.replace(by_angle.find("GUIDE"), 5, "{point: Q, angle: 1.2793395323170296 rad, body: arm}");
  two_points.replace(two_points.find("GUIDE"), 5, "[Q, E]");
  const ResultTable a = result_table(analysed(io::parse_model(by_angle).model, 13));
  const ResultTable b = result_table(analysed(io::parse_model(two_points).model, 13));
  for (const std::string c : {"arm.angle", "arm.omega", "arm.alpha", "E.x", "E.ay"}) {
    const auto x = column_of(a, c), y = column_of(b, c);
    for (std::size_t i = 0; i < x.size(); ++i) EXPECT_NEAR(x[i], y[i], 1e-9 * std::max(1.0, std::abs(y[i]))) << c;
  }
  // The arm swings: the guide turned with it.
  const auto swing = column_of(a, "arm.angle");
  EXPECT_GT(*std::max_element(swing.begin(), swing.end()) - *std::min_element(swing.begin(), swing.end()), 30.0);
  // Written back with its body.
  EXPECT_NE(io::model_yaml(io::parse_model(by_angle).model).find(", body: arm}"), std::string::npos);
}

// `nbar check` lists the points the user wrote: the one the reader adds to give the guide its
// direction is not among them, and the guide is told as it was given, through a point at an angle.
TEST(GuideByAngle, CheckListsOnlyTheUsersPointsAndTheGuideAsGiven) {
  const io::LoadedModel file = io::load_model_file(std::string(NBAR_EXAMPLES_DIR) + "/slider-crank-inclined.yaml");
  const Mechanism mech(file.model);
  ASSERT_EQ(file.model.points.size(), 4u);  // O2, A, C and the guide's direction point
  const ModelSummary summary = summarize(mech);
  EXPECT_EQ(summary.ground_points, std::vector<std::string>{"O2"});
  EXPECT_EQ(summary.moving_points, (std::vector<std::string>{"A", "C"}));
  std::ostringstream text;
  io::write_summary_text(text, mech, summary, "inclined.yaml");
  EXPECT_NE(text.str().find("Points: 3 (1 fixed: O2; 2 moving: A, C)\n"), std::string::npos) << text.str();
  EXPECT_NE(text.str().find("  slider piston at C along the line through O2 at 30 deg\n"), std::string::npos)
      << text.str();
  EXPECT_EQ(text.str().find(".guide"), std::string::npos) << text.str();
  const std::string json = io::summary_json(mech, summary, file.source);
  EXPECT_NE(json.find("\"points\": {\n    \"count\": 3,\n    \"ground\": [\n      \"O2\"\n    ],"), std::string::npos)
      << json;
  EXPECT_EQ(json.find(".guide"), std::string::npos);
}

// A guide carried by a moving body: the body's points are the user's, and the angle is the drawing's
// (atan2(100, 30) = 73.3008 deg).
TEST(GuideByAngle, CheckTellsAMovingGuideByItsPointAndAngle) {
  const std::string text = R"(units: {length: mm, angle: deg}
points: {O2: [0, 0], Q: [0, -100], A: [30, 0], E: [60, 100]}
ground: [O2, Q]
bodies: {crank: [O2, A], arm: [Q, E]}
slots:
  - {point: A, along: {point: Q, angle: 1.2793395323170296 rad, body: arm}}
drivers:
  - {angle: crank, from: 0, to: 360}
)";
  const Mechanism mech(io::parse_model(text).model);
  const ModelSummary summary = summarize(mech);
  ASSERT_EQ(summary.bodies.size(), 2u);
  EXPECT_EQ(summary.bodies[1].points, (std::vector<std::string>{"Q", "E"}));
  EXPECT_EQ(summary.moving_points, (std::vector<std::string>{"A", "E"}));
  EXPECT_NE(std::find(summary.joints.begin(), summary.joints.end(), "slot A in the line through Q at 73.3008 deg"),
            summary.joints.end());
}

TEST(GuideByAngle, BadInputIsPlaced) {
  auto with = [](const std::string& along) {
    std::string text = kByAngle;
    text.replace(text.find("{point: O2, angle: ANGLE}"), 25, along);
    return text;
  };
  // Line 9 is the slider's: `  - {body: piston, point: C, along: ` is 36 characters.
  EXPECT_TRUE(fails_at(with("{point: O3, angle: 30}"), "9:45", "unknown point 'O3'; did you mean 'O2'?"));
  EXPECT_TRUE(fails_at(with("{point: O2}"), "9:37", "needs `angle`"));
  EXPECT_TRUE(fails_at(with("{angle: 30}"), "9:37", "needs `point`"));
  EXPECT_TRUE(fails_at(with("{point: O2, angle: 30 grad}"), "9:56",
                       "unknown unit in the guide's angle '30 grad' (use deg, rad)"));
  EXPECT_TRUE(fails_at(with("{point: O2, angle: 30, angel: 2}"), "9:60", "unknown key 'angel'"));
  EXPECT_TRUE(fails_at(with("{point: O2, angle: [30]}"), "9:56",
                       "the guide's angle must be a number or a quantity like '30 deg', not a list"));
  EXPECT_TRUE(fails_at(with("{point: O2, angle: 30, body: rod}"), "9:66", "does not hold point 'O2'"));
  EXPECT_TRUE(fails_at(with("{point: A, angle: 30}"), "9:45", "belongs to bodies 'crank' and 'rod'"));
  // The piston's pin drawn off the inclined guide.
  EXPECT_TRUE(fails_at(with("{point: O2, angle: 40}"), "9:5", "off the line"));
}

}  // namespace
}  // namespace nbar
