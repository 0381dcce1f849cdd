#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "nbar/model/bar_width.hpp"
#include "nbar/model/model.hpp"

namespace nbar {
namespace {

using ::testing::HasSubstr;
using Kind = EntityRef::Kind;

int add_point(Model& m, const std::string& name, double x, double y, bool ground = false) {
  m.points.push_back(Point{name, Eigen::Vector2d(x, y), ground});
  return static_cast<int>(m.points.size()) - 1;
}

int add_body(Model& m, const std::string& name, std::vector<int> points) {
  Body body;
  body.name = name;
  body.points = std::move(points);
  m.bodies.push_back(std::move(body));
  return static_cast<int>(m.bodies.size()) - 1;
}

Driver angle_driver(const std::string& name, int body) {
  Driver d;
  d.name = name;
  d.kind = DriverKind::Angle;
  d.body = body;
  return d;
}

// The crank-rocker of the format documentation, in metres.
Model four_bar() {
  Model m;
  const int o2 = add_point(m, "O2", 0, 0, true);
  const int o4 = add_point(m, "O4", 0.2, 0, true);
  const int a = add_point(m, "A", 0.04, 0.07);
  const int b = add_point(m, "B", 0.21, 0.14);
  const int p = add_point(m, "P", 0.14, 0.19);
  const int crank = add_body(m, "crank", {o2, a});
  add_body(m, "coupler", {a, b, p});
  add_body(m, "rocker", {o4, b});
  m.drivers.push_back(angle_driver("crank", crank));
  return m;
}

// Crank O-A, rod A-C, piston [C] sliding along the ground line O-X.
Model slider_crank() {
  Model m;
  const int o = add_point(m, "O", 0, 0, true);
  const int x = add_point(m, "X", 1, 0, true);
  const int a = add_point(m, "A", 0.1, 0.1);
  const int c = add_point(m, "C", 0.5, 0);
  const int crank = add_body(m, "crank", {o, a});
  add_body(m, "rod", {a, c});
  const int piston = add_body(m, "piston", {c});
  m.sliders.push_back(Slider{piston, c, {o, x}});
  m.drivers.push_back(angle_driver("crank", crank));
  return m;
}

// Crank O-A whose pin A runs in a slot along the lever Q-E, pivoted at ground point Q.
Model slotted_lever() {
  Model m;
  const int o = add_point(m, "O", 0, 0, true);
  const int a = add_point(m, "A", 0.1, 0);
  const int q = add_point(m, "Q", 0, -0.3, true);
  const int e = add_point(m, "E", 0.2, 0.3);  // A drawn on the slot's line Q-E
  const int crank = add_body(m, "crank", {o, a});
  add_body(m, "lever", {q, e});
  m.slots.push_back(Slot{a, {q, e}});
  m.drivers.push_back(angle_driver("crank", crank));
  return m;
}

void expect_error(const Model& m, Kind kind, int index, const std::string& phrase) {
  try {
    validate(m);
    ADD_FAILURE() << "expected a ModelError containing: " << phrase;
  } catch (const ModelError& e) {
    EXPECT_EQ(e.where().kind, kind) << e.what();
    EXPECT_EQ(e.where().index, index) << e.what();
    EXPECT_THAT(e.what(), HasSubstr(phrase));
  }
}

TEST(Validate, AcceptsValidModels) {
  EXPECT_NO_THROW(validate(four_bar()));
  EXPECT_NO_THROW(validate(slider_crank()));
  EXPECT_NO_THROW(validate(slotted_lever()));
}

TEST(Validate, AcceptsSliderGuidedByAnotherBody) {
  Model m = slider_crank();
  // The guide becomes the crank itself: O and a new point G on it, in line with C.
  const int g = add_point(m, "G", 0.2, 0.0);
  m.bodies[0].points.push_back(g);
  m.sliders[0].along = {0, g};
  EXPECT_NO_THROW(validate(m));
}

TEST(Validate, FindsByName) {
  const Model m = four_bar();
  EXPECT_EQ(m.find_point("O2"), 0);
  EXPECT_EQ(m.find_point("P"), 4);
  EXPECT_EQ(m.find_point("Z"), -1);
  EXPECT_EQ(m.find_body("coupler"), 1);
  EXPECT_EQ(m.find_body("frame"), -1);
}

TEST(Validate, HasTimeLaw) {
  Model m = four_bar();
  EXPECT_FALSE(m.has_time_law());
  m.drivers[0].law = Law::parse("30*t");
  EXPECT_TRUE(m.has_time_law());
}

// The web app's first width of a new bar: a tenth of the drawn length from the body's first point
// to its second, in the model's unit, to two significant digits (the rule it had in JavaScript,
// `+(len / 10).toPrecision(2) || 1`).
TEST(Validate, ANewBarIsATenthOfItsBodysDrawnLengthWide) {
  Model m;
  m.units = *Units::make("mm", "deg");
  const int o = add_point(m, "O", 0, 0, true);
  const int a = add_point(m, "A", 0, 0.080);               // 80 mm from O
  const int b = add_point(m, "B", 0.179999999795, 0.080);  // 179.999999795 mm from A
  const int d = add_point(m, "D", 1.234, 0.080);           // 1234 mm from A
  const int e = add_point(m, "E", 0.0123456, 0);           // 12.3456 mm from O
  const int f = add_point(m, "F", 1.25, 0);                // 1250 mm from O
  EXPECT_EQ(default_bar_width(m, add_body(m, "crank", {o, a})), 8.0);
  EXPECT_EQ(default_bar_width(m, add_body(m, "coupler", {a, b, o})), 18.0);
  EXPECT_EQ(default_bar_width(m, add_body(m, "long", {a, d})), 120.0);
  EXPECT_EQ(default_bar_width(m, add_body(m, "tiny", {o, e})), 1.2);
  EXPECT_EQ(default_bar_width(m, add_body(m, "same", {a, a})), 1.0);  // no length
  EXPECT_EQ(default_bar_width(m, add_body(m, "one", {a})), 1.0);
  const int tie = add_body(m, "tie", {o, f});
  m.units = Units{};                                           // metres
  EXPECT_EQ(default_bar_width(m, m.find_body("long")), 0.12);  // 1.234 m / 10
  EXPECT_EQ(default_bar_width(m, tie), 0.13);                  // 0.125 exactly: a tie, rounded up
}

TEST(Validate, Points) {
  expect_error(Model{}, Kind::Model, -1, "the model has no points");

  Model m = four_bar();
  m.points[2].name = "";
  expect_error(m, Kind::Point, 2, "point #3 has no name");

  m = four_bar();
  m.points[3].name = m.points[2].name;
  expect_error(m, Kind::Point, 3, "two points are named 'A'");

  m = four_bar();
  m.points[4].position.y() = std::numeric_limits<double>::quiet_NaN();
  expect_error(m, Kind::Point, 4, "point 'P' has a coordinate that is not a finite number");

  m = four_bar();
  m.points[1].position.x() = std::numeric_limits<double>::infinity();
  expect_error(m, Kind::Point, 1, "not a finite number");
}

TEST(Validate, PointNotAttached) {
  Model m = four_bar();
  add_point(m, "Q", 1, 1);
  expect_error(m, Kind::Point, 5, "point 'Q' is not attached to any body or to ground");

  // A lone ground point is fine: it is attached to the frame.
  m.points[5].ground = true;
  EXPECT_NO_THROW(validate(m));
}

TEST(Validate, BodyNames) {
  Model m = four_bar();
  m.bodies[1].name = "";
  expect_error(m, Kind::Body, 1, "body #2 has no name");

  m = four_bar();
  m.bodies[2].name = "crank";
  expect_error(m, Kind::Body, 2, "two bodies are named 'crank'");

  // Points and bodies live in separate namespaces.
  m = four_bar();
  m.bodies[2].name = "A";
  EXPECT_NO_THROW(validate(m));
}

TEST(Validate, BodyPoints) {
  Model m = four_bar();
  m.bodies[1].points.clear();
  expect_error(m, Kind::Body, 1, "body 'coupler' has no points");

  m = four_bar();
  m.bodies[1].points.push_back(9);
  expect_error(m, Kind::Body, 1, "body 'coupler' refers to point #9, which does not exist");

  m = four_bar();
  m.bodies[1].points.push_back(-1);
  expect_error(m, Kind::Body, 1, "does not exist");

  m = four_bar();
  m.bodies[1].points.push_back(2);
  expect_error(m, Kind::Body, 1, "body 'coupler' lists point 'A' twice");
}

TEST(Validate, ZeroLengthBar) {
  Model m = four_bar();
  m.points[2].position = m.points[0].position;
  expect_error(m, Kind::Body, 0, "body 'crank' has zero length: points O2 and A coincide");

  // Only the first two points define the angle; a third point may sit anywhere.
  m = four_bar();
  m.points[4].position = m.points[2].position;
  EXPECT_NO_THROW(validate(m));
}

TEST(Validate, BodyOfGroundPointsOnly) {
  Model m = four_bar();
  add_body(m, "frame", {0, 1});
  expect_error(m, Kind::Body, 3, "cannot move: list its points under ground instead");

  m = four_bar();
  add_body(m, "post", {0});
  expect_error(m, Kind::Body, 3, "cannot move");
}

TEST(Validate, BodyLength) {
  Model m = four_bar();
  m.bodies[0].length = 0.08;
  EXPECT_NO_THROW(validate(m));

  m.bodies[0].length = 0.0;
  expect_error(m, Kind::Body, 0, "the length of body 'crank' must be a positive number");
  m.bodies[0].length = -1.0;
  expect_error(m, Kind::Body, 0, "must be a positive number");
  m.bodies[0].length = std::numeric_limits<double>::quiet_NaN();
  expect_error(m, Kind::Body, 0, "must be a positive number");

  m = four_bar();
  m.bodies[1].length = 0.1;
  expect_error(m, Kind::Body, 1, "body 'coupler' has 3 points: an exact length applies only to a body with two points");
}

// The drawn pose starts the assembly: a sliding point drawn off its guide would be moved onto it
// silently (by 226 mm in a reviewer's slider-crank). Rounding of the drawing passes.
TEST(Validate, SlidingPointDrawnOffItsGuide) {
  Model m = slider_crank();  // guide O-X along y = 0, drawing 1.118 m across
  m.points[3].position.y() = 0.002;
  expect_error(m, Kind::Slider, 0, "point 'C' is drawn 0.002 m off the line through 'O' and 'X'");
  m.points[3].position.y() = 1e-4;  // 0.01% of the drawing: rounding, left to the assembly
  EXPECT_NO_THROW(validate(m));

  Model slot = slotted_lever();
  slot.points[1].position = {0.1, 0.1};  // 0.1 m above the slot's line, whose slope is 3: 0.1 / sqrt(10) across it
  expect_error(slot, Kind::Slot, 0, "point 'A' is drawn 0.0316228 m off the line through 'Q' and 'E'");
}

// A driver's name is a column of the results: these gave two columns of one name, or one
// indistinguishable from a point's, a body's or time.
TEST(Validate, DriverNamesCannotBeOtherColumns) {
  for (const char* taken : {"rocker.angle", "A.x", "t", "step", "crank."}) {
    Model m = four_bar();
    m.drivers[0].name = taken;
    expect_error(m, Kind::Driver, 0, "a driver's name is its column in the results");
  }
  Model m = four_bar();
  m.drivers[0].name = "theta_2";
  EXPECT_NO_THROW(validate(m));
}

// From 360 to 0 at +120 rpm gave t from 0 down to -0.5 s and omega +720 deg/s.
TEST(Validate, ASpeedAgainstTheTravelIsAnError) {
  Model m = four_bar();
  m.drivers[0].from = 2 * std::acos(-1.0);
  m.drivers[0].to = 0.0;
  m.drivers[0].speed = 4 * std::acos(-1.0);
  expect_error(m, Kind::Driver, 0, "goes from 360 deg to 0 deg against the sign of its speed");
  m.drivers[0].speed = -m.drivers[0].speed;
  EXPECT_NO_THROW(validate(m));
}

TEST(Validate, SinglePointBodyNeedsSlider) {
  Model m = slider_crank();
  m.sliders.clear();
  expect_error(m, Kind::Body, 2, "body 'piston' has a single point, so its orientation is undefined");
}

TEST(Validate, SliderReferences) {
  Model m = slider_crank();
  m.sliders[0].body = 7;
  expect_error(m, Kind::Slider, 0, "slider #1 refers to body #7, which does not exist");

  m = slider_crank();
  m.sliders[0].point = 12;
  expect_error(m, Kind::Slider, 0, "the slider of body 'piston' refers to point #12");

  m = slider_crank();
  m.sliders[0].point = 2;
  expect_error(m, Kind::Slider, 0, "moves point 'A', which is not one of the points of body 'piston'");

  m = slider_crank();
  m.sliders[0].along = {0, 9};
  expect_error(m, Kind::Slider, 0, "the guide of the slider of body 'piston' refers to point #9");
}

TEST(Validate, SliderGuide) {
  Model m = slider_crank();
  m.sliders[0].along = {0, 0};
  expect_error(m, Kind::Slider, 0, "the guide of the slider of body 'piston' uses point 'O' twice");

  m = slider_crank();
  m.points[1].position = m.points[0].position;
  expect_error(m, Kind::Slider, 0, "the guide points O and X of the slider of body 'piston' coincide");

  // X is ground, A is on the crank and the rod, which do not hold X: no common owner.
  m = slider_crank();
  m.sliders[0].along = {1, 2};
  expect_error(m, Kind::Slider, 0, "the guide points of a slider must belong to one other body or to ground");

  // The guide on the slider's own body guides nothing.
  m = slider_crank();
  const int d = add_point(m, "D", 0.6, 0.1);
  m.bodies[2].points.push_back(d);
  m.sliders[0].along = {3, d};
  m.sliders[0].point = 3;
  expect_error(m, Kind::Slider, 0, "cannot also be a guide point");

  m = slider_crank();
  const int e = add_point(m, "E", 0.6, 0.1);
  const int f = add_point(m, "F", 0.7, 0.1);
  m.bodies[2].points = {3, e, f};
  m.sliders[0].along = {e, f};
  expect_error(m, Kind::Slider, 0, "must belong to one other body or to ground");
}

TEST(Validate, OneSliderPerBody) {
  Model m = slider_crank();
  m.sliders.push_back(m.sliders[0]);
  expect_error(m, Kind::Slider, 1, "body 'piston' has two sliders");
}

TEST(Validate, Slots) {
  Model m = slotted_lever();
  m.slots[0].point = 8;
  expect_error(m, Kind::Slot, 0, "slot #1 refers to point #8, which does not exist");

  m = slotted_lever();
  m.slots[0].along = {2, 2};
  expect_error(m, Kind::Slot, 0, "the guide of the slot of point 'A' uses point 'Q' twice");

  m = slotted_lever();
  m.points[3].position = m.points[2].position;
  expect_error(m, Kind::Body, 1, "zero length");  // the lever itself fails first

  m = slotted_lever();
  m.slots[0].along = {0, 3};  // O is ground, E is on the lever
  expect_error(m, Kind::Slot, 0, "the guide points of a slot must belong to one body or to ground");

  m = slotted_lever();
  m.slots[0].point = 2;
  expect_error(m, Kind::Slot, 0, "cannot be one of its own guide points");

  // A on the crank, guide O-A on the crank too: A cannot slide relative to itself.
  m = slotted_lever();
  const int g = add_point(m, "G", 0.2, 0.05);
  m.bodies[0].points.push_back(g);
  m.slots[0] = Slot{g, {0, 1}};
  expect_error(m, Kind::Slot, 0, "belongs to body 'crank', which also carries the guide");

  m = slotted_lever();
  const int h = add_point(m, "H", 0.5, 0.5, true);
  const int k = add_point(m, "K", 0.6, 0.5, true);
  m.slots[0] = Slot{0, {h, k}};
  expect_error(m, Kind::Slot, 0, "point 'O' is on ground, like its guide");
}

TEST(Validate, AngleDrivers) {
  Model m = four_bar();
  m.drivers[0].body = 5;
  expect_error(m, Kind::Driver, 0, "driver 'crank' refers to body #5, which does not exist");

  m = slider_crank();
  m.drivers[0].body = 2;
  expect_error(m, Kind::Driver, 0, "body 'piston' needs two points to have an angle");

  m = four_bar();
  m.drivers[0].relative_to = 0;
  expect_error(m, Kind::Driver, 0, "driver 'crank' cannot be relative to its own body");

  m = four_bar();
  m.drivers[0].relative_to = 3;
  expect_error(m, Kind::Driver, 0, "is relative to body #3, which does not exist");

  m = slider_crank();
  m.drivers[0].relative_to = 2;
  expect_error(m, Kind::Driver, 0, "body 'piston' needs two points to have an angle");

  m = four_bar();
  m.drivers[0].relative_to = 2;
  EXPECT_NO_THROW(validate(m));
}

TEST(Validate, DistanceAndSlideDrivers) {
  Model m = four_bar();
  m.drivers[0].kind = DriverKind::Distance;
  m.drivers[0].points = {2, 2};
  expect_error(m, Kind::Driver, 0, "measures the distance from point 'A' to itself");

  m.drivers[0].points = {2, 5};
  expect_error(m, Kind::Driver, 0, "refers to point #5, which does not exist");

  m.drivers[0].points = {0, 3};
  EXPECT_NO_THROW(validate(m));

  m.drivers[0].points = {0, 1};
  expect_error(m, Kind::Driver, 0, "drives the distance between two ground points, which cannot change");

  m.drivers[0].points = {4, 3};
  expect_error(m, Kind::Driver, 0, "drives the distance between two points of body 'coupler', which cannot change");

  m = slider_crank();
  m.drivers[0].kind = DriverKind::Slide;
  m.drivers[0].slider = 1;
  expect_error(m, Kind::Driver, 0, "refers to slider #1, which does not exist");
  m.drivers[0].slider = 0;
  EXPECT_NO_THROW(validate(m));
}

TEST(Validate, DriverNames) {
  Model m = four_bar();
  m.drivers.push_back(m.drivers[0]);
  expect_error(m, Kind::Driver, 1, "two drivers are named 'crank': give one a `name:`");

  m = four_bar();
  m.drivers[0].name = "";
  expect_error(m, Kind::Driver, 0, "driver #1 has no name");
}

TEST(Validate, DriverValues) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  Model m = four_bar();
  m.drivers[0].from = nan;
  expect_error(m, Kind::Driver, 0, "driver 'crank': `from` is not a finite number");

  m = four_bar();
  m.drivers[0].to = inf;
  expect_error(m, Kind::Driver, 0, "`to` is not a finite number");

  m = four_bar();
  m.drivers[0].speed = nan;
  expect_error(m, Kind::Driver, 0, "the speed is not a finite number");

  m = four_bar();
  m.drivers[0].accel = -inf;
  expect_error(m, Kind::Driver, 0, "the acceleration is not a finite number");

  m = four_bar();
  m.drivers[0].speed = 0.0;
  expect_error(m, Kind::Driver, 0, "driver 'crank': the speed must not be zero");

  m = four_bar();
  m.drivers[0].speed = -2.0;
  m.drivers[0].accel = 3.0;
  EXPECT_NO_THROW(validate(m));
}

TEST(Validate, LawDrivers) {
  Model m = four_bar();
  m.drivers[0].law = Law::parse("sin(t)");
  EXPECT_NO_THROW(validate(m));

  m.drivers[0].from = 0.0;
  expect_error(m, Kind::Driver, 0, "driver 'crank' follows a law, so it takes no `from` or `to`");

  m.drivers[0].from.reset();
  m.drivers[0].to = 1.0;
  expect_error(m, Kind::Driver, 0, "takes no `from` or `to`");

  // Beside a law, other drivers run at their speed from `from`: a `to` would be ignored.
  m = four_bar();
  m.drivers[0].law = Law::parse("sin(t)");
  Driver other = angle_driver("rocker", 2);
  other.from = 0.5;
  EXPECT_NO_THROW({
    m.drivers.push_back(other);
    validate(m);
  });
  m.drivers[1].to = 1.0;
  expect_error(m, Kind::Driver, 1, "driver 'rocker': `to` has no meaning when another driver follows a time law");
}

TEST(Validate, Sweep) {
  Model m = four_bar();
  m.sweep.steps = 0;
  expect_error(m, Kind::Sweep, -1, "the sweep needs at least 1 step (got 0)");

  m = four_bar();
  m.sweep.steps = 1;  // one pose
  EXPECT_NO_THROW(validate(m));

  m = four_bar();
  m.sweep.duration = 0.0;
  expect_error(m, Kind::Sweep, -1, "the sweep duration must be positive");

  m = four_bar();
  m.sweep.duration = std::numeric_limits<double>::infinity();
  expect_error(m, Kind::Sweep, -1, "the sweep duration must be positive");

  m = four_bar();
  m.sweep.time_step = 0.0;
  expect_error(m, Kind::Sweep, -1, "the sweep time step must be positive");

  m = four_bar();
  m.sweep.duration = 0.1;
  m.sweep.time_step = 0.2;
  expect_error(m, Kind::Sweep, -1, "the sweep time step is longer than its duration");

  m.sweep.time_step = 0.1;
  EXPECT_NO_THROW(validate(m));
}

// ---- kinetics: shapes, materials, mass properties, loads, springs ----

// The four-bar with a steel bar on its coupler and given mass properties on its crank.
Model four_bar_with_mass() {
  Model m = four_bar();
  Body& coupler = m.bodies[1];
  coupler.shape = make_bar(m.points[2].position, m.points[3].position, 0.02, 0.01, 0.004, 0.004);
  coupler.thickness = 0.005;
  coupler.material = Material{"steel", 7850, 250e6, 200e9, 0.3};
  m.bodies[0].inertia = GivenInertia{0.3, Eigen::Vector2d(0.02, 0.035), 1e-4};
  m.gravity = Eigen::Vector2d(0, -9.81);
  m.point_loads.push_back(PointLoad{4, 1, Law::parse("0"), Law::parse("-100")});
  m.point_loads.push_back(PointLoad{3, -1, Law::parse("10*t"), Law::parse("0")});
  m.torques.push_back(BodyTorque{2, Law::parse("-5"), std::nullopt});
  m.springs.push_back(Spring{"return", {4, 1}, 2000, 0.1, 5, 0.0});
  return m;
}

TEST(Validate, AcceptsKinetics) {
  EXPECT_NO_THROW(validate(four_bar_with_mass()));
  // Given mass properties make the material optional, and a shape then serves only stresses.
  Model m = four_bar_with_mass();
  m.bodies[1].material.reset();
  m.bodies[1].inertia = GivenInertia{};
  EXPECT_NO_THROW(validate(m));
  // A material without a yield strength (brittle) is fine.
  m = four_bar_with_mass();
  m.bodies[1].material->yield_strength.reset();
  EXPECT_NO_THROW(validate(m));
}

TEST(Validate, Shapes) {
  Model m = four_bar_with_mass();
  m.bodies[1].shape->circle_holes.push_back(Circle{m.points[2].position, 0.002});  // over the bar's hole
  expect_error(m, Kind::Body, 1, "the shape of body 'coupler' is not valid: circle hole 0");

  m = four_bar_with_mass();
  m.bodies[1].shape->outline.resize(2);
  expect_error(m, Kind::Body, 1, "the shape of body 'coupler' is not valid: the outline has 2 vertices");

  m = four_bar_with_mass();
  m.bodies[1].thickness = 0.0;
  expect_error(m, Kind::Body, 1, "body 'coupler' has a shape, so its thickness must be a positive number");
  m.bodies[1].thickness = std::numeric_limits<double>::quiet_NaN();
  expect_error(m, Kind::Body, 1, "its thickness must be a positive number");

  m = four_bar_with_mass();
  m.bodies[1].material.reset();
  expect_error(m, Kind::Body, 1, "body 'coupler' has a shape but no material and no given mass");

  m = four_bar_with_mass();
  m.bodies[2].material = Material{"steel", 7850, 250e6, 200e9, 0.3};
  expect_error(m, Kind::Body, 2, "body 'rocker' has a material but no shape to weigh and no given mass");
}

TEST(Validate, Materials) {
  Model m = four_bar_with_mass();
  m.bodies[1].material->density = 0.0;
  expect_error(m, Kind::Body, 1, "material 'steel' needs a positive density");
  m.bodies[1].material->density = std::numeric_limits<double>::infinity();
  expect_error(m, Kind::Body, 1, "material 'steel' needs a positive density");

  m = four_bar_with_mass();
  m.bodies[1].material->name = "";
  m.bodies[1].material->density = -1.0;
  expect_error(m, Kind::Body, 1, "the material of body 'coupler' needs a positive density");

  m = four_bar_with_mass();
  m.bodies[1].material->yield_strength = 0.0;
  expect_error(m, Kind::Body, 1, "the yield strength of material 'steel' must be a positive number");

  m = four_bar_with_mass();
  m.bodies[1].material->youngs_modulus = -200e9;
  expect_error(m, Kind::Body, 1, "Young's modulus of material 'steel' must be a positive number");
  m = four_bar_with_mass();
  m.bodies[1].material->poisson_ratio = 0.5;
  expect_error(m, Kind::Body, 1, "Poisson's ratio of material 'steel' must be at least 0 and less than 0.5");
  m.bodies[1].material->poisson_ratio = std::numeric_limits<double>::quiet_NaN();
  expect_error(m, Kind::Body, 1, "Poisson's ratio of material 'steel' must be at least 0 and less than 0.5");
}

TEST(Validate, GivenMassProperties) {
  Model m = four_bar_with_mass();
  m.bodies[0].inertia->mass = -1.0;
  expect_error(m, Kind::Body, 0, "the mass of body 'crank' must not be negative");
  m.bodies[0].inertia->mass = std::numeric_limits<double>::quiet_NaN();
  expect_error(m, Kind::Body, 0, "the mass of body 'crank' must not be negative");

  m = four_bar_with_mass();
  m.bodies[0].inertia->inertia = -1e-3;
  expect_error(m, Kind::Body, 0, "the moment of inertia of body 'crank' must not be negative");

  m = four_bar_with_mass();
  m.bodies[0].inertia->cg.x() = std::numeric_limits<double>::infinity();
  expect_error(m, Kind::Body, 0, "the centre of mass of body 'crank' is not a finite point");

  m = four_bar_with_mass();
  m.bodies[0].inertia->mass = 0.0;  // massless is allowed
  EXPECT_NO_THROW(validate(m));

  m.gravity.y() = std::numeric_limits<double>::quiet_NaN();
  expect_error(m, Kind::Model, -1, "gravity is not a finite vector");
}

TEST(Validate, PointLoadsAndTorques) {
  Model m = four_bar_with_mass();
  m.point_loads[1].point = 9;
  expect_error(m, Kind::PointLoad, 1, "force #2 acts on point #9, which does not exist");

  m = four_bar_with_mass();
  m.point_loads[0].body = 7;
  expect_error(m, Kind::PointLoad, 0, "force #1 acts on body #7, which does not exist");

  m = four_bar_with_mass();
  m.point_loads[0].body = 0;  // P is not a point of the crank
  expect_error(m, Kind::PointLoad, 0, "force #1 acts on point 'P' of body 'crank', which does not have that point");

  m = four_bar_with_mass();
  m.point_loads[1].fy = Law();
  expect_error(m, Kind::PointLoad, 1, "force #2 has no value for fx or fy");

  m = four_bar_with_mass();
  m.torques[0].body = -1;
  expect_error(m, Kind::Torque, 0, "torque #1 acts on body #-1, which does not exist");

  m = four_bar_with_mass();
  m.torques.push_back(BodyTorque{1, Law(), std::nullopt});
  expect_error(m, Kind::Torque, 1, "torque #2 on body 'coupler' has no value");
}

TEST(Validate, Springs) {
  Model m = four_bar_with_mass();
  m.springs.push_back(m.springs[0]);
  expect_error(m, Kind::Spring, 1, "two springs are named 'return'");

  m = four_bar_with_mass();
  m.springs[0].name = "";
  expect_error(m, Kind::Spring, 0, "spring #1 has no name");

  m = four_bar_with_mass();
  m.springs[0].points = {4, 5};
  expect_error(m, Kind::Spring, 0, "spring 'return' refers to point #5, which does not exist");

  m = four_bar_with_mass();
  m.springs[0].points = {2, 2};
  expect_error(m, Kind::Spring, 0, "spring 'return' joins point 'A' to itself");

  m = four_bar_with_mass();
  m.springs[0].stiffness = -1;
  expect_error(m, Kind::Spring, 0, "the stiffness of spring 'return' must not be negative");

  m = four_bar_with_mass();
  m.springs[0].damping = std::numeric_limits<double>::infinity();
  expect_error(m, Kind::Spring, 0, "the damping of spring 'return' must not be negative");

  m = four_bar_with_mass();
  m.springs[0].free_length = -0.1;
  expect_error(m, Kind::Spring, 0, "the free length of spring 'return' must not be negative");

  m = four_bar_with_mass();
  m.springs[0].stiffness = 0;
  m.springs[0].damping = 0;
  m.springs[0].free_length = 0;
  EXPECT_NO_THROW(validate(m));
}

}  // namespace
}  // namespace nbar
