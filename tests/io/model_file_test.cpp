// The project headers come first: <signal.h>, which gtest pulls in, defines a macro
// named value_si that would break units.hpp's Quantity::value_si.
#include "nbar/io/model_file.hpp"
#include "io/model_file_support.hpp"
#include "nbar/io/file_text.hpp"
#include "test_constants.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

namespace nbar::io {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

using nbar::test_constants::kDeg;
using nbar::test_constants::kPi;

// The example of docs/model-format.md.
const std::string kExample = R"(name: Crank-rocker four-bar
units: {length: mm, angle: deg}
points:
  O2: [0, 0]
  O4: [200, 0]
  A:  [40, 70]
  B:  [210, 140]
  P:  [140, 190]
ground: [O2, O4]
bodies:
  crank:   [O2, A]
  coupler: [A, B, P]
  rocker:  [O4, B]
lengths: {crank: 80}
drivers:
  - {angle: crank, from: 0, to: 360, speed: 1750 rpm}
sweep: {steps: 361}
)";

const std::string kExampleJson = R"({
  "name": "Crank-rocker four-bar",
  "units": {"length": "mm", "angle": "deg"},
  "points": {"O2": [0, 0], "O4": [200, 0], "A": [40, 70], "B": [210, 140], "P": [140, 190]},
  "ground": ["O2", "O4"],
  "bodies": {"crank": ["O2", "A"], "coupler": ["A", "B", "P"], "rocker": ["O4", "B"]},
  "lengths": {"crank": 80},
  "drivers": [{"angle": "crank", "from": 0, "to": 360, "speed": "1750 rpm"}],
  "sweep": {"steps": 361}
})";

// Lines 1-10; the tests append their own lines from line 11 on.
const std::string kFourBar =
    "points:\n"            // 1
    "  O: [0, 0]\n"        // 2
    "  A: [10, 0]\n"       // 3
    "  B: [30, 20]\n"      // 4
    "  Q: [40, 0]\n"       // 5
    "ground: [O, Q]\n"     // 6
    "bodies:\n"            // 7
    "  crank: [O, A]\n"    // 8
    "  coupler: [A, B]\n"  // 9
    "  rocker: [Q, B]\n";  // 10

const std::string kSliderCrank =
    "points:\n"          // 1
    "  O: [0, 0]\n"      // 2
    "  X: [100, 0]\n"    // 3
    "  A: [30, 40]\n"    // 4
    "  C: [150, 0]\n"    // 5
    "ground: [O, X]\n"   // 6
    "bodies:\n"          // 7
    "  crank: [O, A]\n"  // 8
    "  rod: [A, C]\n"    // 9
    "  piston: [C]\n";   // 10

const std::string kSlottedLever =
    "points:\n"          // 1
    "  O: [0, 0]\n"      // 2
    "  A: [10, 0]\n"     // 3
    "  Q: [0, -30]\n"    // 4
    "  E: [20, 30]\n"    // 5  (A on the line Q-E)
    "ground: [O, Q]\n"   // 6
    "bodies:\n"          // 7
    "  crank: [O, A]\n"  // 8
    "  lever: [Q, E]\n"  // 9
    "slots:\n";          // 10

using test_support::fails_at;

// ---- valid files ----

TEST(ModelFile, ParsesTheDocumentedExample) {
  const LoadedModel loaded = parse_model(kExample, "example.yaml");
  const Model& m = loaded.model;
  EXPECT_EQ(m.name, "Crank-rocker four-bar");
  EXPECT_EQ(m.units.length, "mm");
  EXPECT_EQ(m.units.angle, "deg");
  EXPECT_DOUBLE_EQ(m.units.length_scale, 0.001);

  ASSERT_EQ(m.points.size(), 5u);
  EXPECT_EQ(m.points[0].name, "O2");
  EXPECT_EQ(m.points[4].name, "P");
  EXPECT_DOUBLE_EQ(m.points[1].position.x(), 0.2);
  EXPECT_DOUBLE_EQ(m.points[1].position.y(), 0.0);
  EXPECT_DOUBLE_EQ(m.points[2].position.x(), 0.04);
  EXPECT_DOUBLE_EQ(m.points[2].position.y(), 0.07);
  EXPECT_DOUBLE_EQ(m.points[3].position.x(), 0.21);
  EXPECT_DOUBLE_EQ(m.points[4].position.y(), 0.19);
  EXPECT_TRUE(m.points[0].ground);
  EXPECT_TRUE(m.points[1].ground);
  EXPECT_FALSE(m.points[2].ground);

  ASSERT_EQ(m.bodies.size(), 3u);
  EXPECT_EQ(m.bodies[0].name, "crank");
  EXPECT_EQ(m.bodies[0].points, (std::vector<int>{0, 2}));
  EXPECT_EQ(m.bodies[1].points, (std::vector<int>{2, 3, 4}));
  EXPECT_EQ(m.bodies[2].points, (std::vector<int>{1, 3}));
  ASSERT_TRUE(m.bodies[0].length.has_value());
  EXPECT_DOUBLE_EQ(*m.bodies[0].length, 0.08);
  EXPECT_FALSE(m.bodies[1].length.has_value());

  ASSERT_EQ(m.drivers.size(), 1u);
  const Driver& d = m.drivers[0];
  EXPECT_EQ(d.name, "crank");
  EXPECT_EQ(d.kind, DriverKind::Angle);
  EXPECT_EQ(d.body, 0);
  EXPECT_EQ(d.relative_to, -1);
  ASSERT_TRUE(d.from && d.to);
  EXPECT_DOUBLE_EQ(*d.from, 0.0);
  EXPECT_DOUBLE_EQ(*d.to, 2 * kPi);
  EXPECT_NEAR(d.speed, 183.2595714594046, 1e-12);
  EXPECT_EQ(d.accel, 0.0);
  EXPECT_FALSE(d.law.has_value());

  EXPECT_EQ(m.sweep.steps, 361);
  EXPECT_FALSE(m.sweep.time_step.has_value());
  EXPECT_FALSE(m.has_time_law());
}

TEST(ModelFile, FillsTheSourceMap) {
  const SourceMap s = parse_model(kExample, "example.yaml").source;
  EXPECT_EQ(s.file, "example.yaml");
  EXPECT_EQ(s.model.line, 1);
  EXPECT_EQ(s.model.column, 1);
  ASSERT_EQ(s.points.size(), 5u);
  EXPECT_EQ(s.points[0].line, 4);
  EXPECT_EQ(s.points[0].column, 3);
  EXPECT_EQ(s.points[4].line, 8);
  ASSERT_EQ(s.bodies.size(), 3u);
  EXPECT_EQ(s.bodies[1].line, 12);
  EXPECT_EQ(s.bodies[1].column, 3);
  ASSERT_EQ(s.drivers.size(), 1u);
  EXPECT_EQ(s.drivers[0].line, 16);
  EXPECT_EQ(s.drivers[0].column, 5);
  EXPECT_EQ(s.sweep.line, 17);
  EXPECT_EQ(s.sweep.column, 1);
}

TEST(ModelFile, JsonReadsLikeYaml) {
  const Model y = parse_model(kExample).model;
  const LoadedModel loaded = parse_model(kExampleJson, "example.json");
  const Model& j = loaded.model;
  EXPECT_EQ(j.name, y.name);
  EXPECT_EQ(j.units.length, y.units.length);
  ASSERT_EQ(j.points.size(), y.points.size());
  for (std::size_t i = 0; i < y.points.size(); ++i) {
    EXPECT_EQ(j.points[i].name, y.points[i].name);
    EXPECT_EQ(j.points[i].position, y.points[i].position);
    EXPECT_EQ(j.points[i].ground, y.points[i].ground);
  }
  ASSERT_EQ(j.bodies.size(), y.bodies.size());
  for (std::size_t i = 0; i < y.bodies.size(); ++i) {
    EXPECT_EQ(j.bodies[i].name, y.bodies[i].name);
    EXPECT_EQ(j.bodies[i].points, y.bodies[i].points);
    EXPECT_EQ(j.bodies[i].length, y.bodies[i].length);
  }
  ASSERT_EQ(j.drivers.size(), 1u);
  EXPECT_EQ(j.drivers[0].name, y.drivers[0].name);
  EXPECT_EQ(j.drivers[0].from, y.drivers[0].from);
  EXPECT_EQ(j.drivers[0].to, y.drivers[0].to);
  EXPECT_EQ(j.drivers[0].speed, y.drivers[0].speed);
  EXPECT_EQ(j.sweep.steps, y.sweep.steps);
  EXPECT_EQ(loaded.source.points[2].line, 4);
  EXPECT_EQ(loaded.source.drivers[0].line, 8);
  EXPECT_EQ(loaded.source.drivers[0].column, 15);
}

TEST(ModelFile, DefaultsToMetresAndDegrees) {
  const Model m = parse_model(kFourBar + "drivers:\n  - {angle: crank, to: 90}\n").model;
  EXPECT_EQ(m.units.length, "m");
  EXPECT_EQ(m.units.angle, "deg");
  EXPECT_DOUBLE_EQ(m.points[3].position.x(), 40.0);
  const Driver& d = m.drivers[0];
  EXPECT_FALSE(d.from.has_value());  // the drawn angle
  EXPECT_DOUBLE_EQ(*d.to, kPi / 2);
  EXPECT_DOUBLE_EQ(d.speed, kDeg);  // 1 deg/s
  EXPECT_EQ(m.sweep.steps, 361);
  EXPECT_DOUBLE_EQ(m.sweep.duration, 1.0);
}

TEST(ModelFile, SpeedsAndAccelerations) {
  const Model m = parse_model(kFourBar + "units: {angle: rad}\n" +
                              "drivers:\n"
                              "  - {angle: crank, from: 0, to: 1, speed: 2, accel: -3}\n"
                              "  - {angle: rocker, speed: -90 deg/s, accel: 2 rad/s^2}\n"
                              "  - {angle: coupler, speed: '60 rpm', accel: 180 deg/s^2}\n"
                              "  - {distance: [O, B], speed: 5, accel: 7}\n"
                              "  - {distance: [A, Q], speed: 20 mm/s, accel: '0.5 in/s^2'}\n"
                              "  - {distance: [Q, A]}\n")
                      .model;
  ASSERT_EQ(m.drivers.size(), 6u);
  EXPECT_DOUBLE_EQ(*m.drivers[0].to, 1.0);
  EXPECT_DOUBLE_EQ(m.drivers[0].speed, 2.0);
  EXPECT_DOUBLE_EQ(m.drivers[0].accel, -3.0);
  EXPECT_DOUBLE_EQ(m.drivers[1].speed, -kPi / 2);
  EXPECT_DOUBLE_EQ(m.drivers[1].accel, 2.0);
  EXPECT_DOUBLE_EQ(m.drivers[2].speed, 2 * kPi);
  EXPECT_DOUBLE_EQ(m.drivers[2].accel, kPi);
  EXPECT_DOUBLE_EQ(m.drivers[3].speed, 5.0);  // length unit is m: 5 m/s
  EXPECT_DOUBLE_EQ(m.drivers[3].accel, 7.0);
  EXPECT_DOUBLE_EQ(m.drivers[4].speed, 0.02);
  EXPECT_DOUBLE_EQ(m.drivers[4].accel, 0.0127);
  EXPECT_DOUBLE_EQ(m.drivers[5].speed, 1.0);  // default: 1 length unit per second
}

TEST(ModelFile, NumbersAreInModelUnits) {
  const Model m = parse_model(kSliderCrank + "units: {length: in, angle: rad}\n" +
                              "sliders:\n"
                              "  - {body: piston, point: C, along: [O, X]}\n"
                              "drivers:\n"
                              "  - {slide: piston, from: 150, to: 200, speed: 50}\n"
                              "  - {distance: [O, C]}\n"
                              "lengths: {rod: 1.5e2}\n")
                      .model;
  EXPECT_DOUBLE_EQ(m.points[3].position.x(), 150 * 0.0254);
  ASSERT_EQ(m.sliders.size(), 1u);
  EXPECT_EQ(m.sliders[0].body, 2);
  EXPECT_EQ(m.sliders[0].point, 3);
  EXPECT_EQ(m.sliders[0].along, (std::array<int, 2>{0, 1}));
  const Driver& slide = m.drivers[0];
  EXPECT_EQ(slide.kind, DriverKind::Slide);
  EXPECT_EQ(slide.slider, 0);
  EXPECT_DOUBLE_EQ(*slide.from, 150 * 0.0254);
  EXPECT_DOUBLE_EQ(*slide.to, 200 * 0.0254);
  EXPECT_DOUBLE_EQ(slide.speed, 50 * 0.0254);
  EXPECT_DOUBLE_EQ(m.drivers[1].speed, 0.0254);
  EXPECT_DOUBLE_EQ(*m.bodies[1].length, 150 * 0.0254);
}

TEST(ModelFile, DefaultDriverNames) {
  const Model m = parse_model(kSliderCrank +
                              "sliders:\n"
                              "  - {body: piston, point: C, along: [O, X]}\n"
                              "drivers:\n"
                              "  - {angle: crank}\n"
                              "  - {angle: rod, relative_to: crank}\n"
                              "  - {distance: [A, X]}\n"
                              "  - {slide: piston}\n"
                              "  - {angle: rod, name: rod angle}\n")
                      .model;
  ASSERT_EQ(m.drivers.size(), 5u);
  EXPECT_EQ(m.drivers[0].name, "crank");
  EXPECT_EQ(m.drivers[1].name, "rod/crank");
  EXPECT_EQ(m.drivers[1].body, 1);
  EXPECT_EQ(m.drivers[1].relative_to, 0);
  EXPECT_EQ(m.drivers[2].name, "A-X");
  EXPECT_EQ(m.drivers[2].kind, DriverKind::Distance);
  EXPECT_EQ(m.drivers[2].points, (std::array<int, 2>{2, 1}));
  EXPECT_EQ(m.drivers[3].name, "piston");
  EXPECT_EQ(m.drivers[4].name, "rod angle");
}

TEST(ModelFile, Slots) {
  const Model m = parse_model(kSlottedLever + "  - {point: A, along: [Q, E]}\n").model;
  ASSERT_EQ(m.slots.size(), 1u);
  EXPECT_EQ(m.slots[0].point, 1);
  EXPECT_EQ(m.slots[0].along, (std::array<int, 2>{2, 3}));
}

TEST(ModelFile, TimeLaws) {
  const Model m = parse_model(kFourBar +
                              "drivers:\n"
                              "  - {angle: crank, law: \"30*sin(2*pi*t)\"}\n"
                              "sweep: {duration: 0.5, step: 0.01}\n")
                      .model;
  ASSERT_TRUE(m.drivers[0].law.has_value());
  EXPECT_EQ(m.drivers[0].law->text(), "30*sin(2*pi*t)");
  EXPECT_NEAR(m.drivers[0].law->value(0.25), kPi / 6, 1e-12);  // 30 deg in rad
  EXPECT_FALSE(m.drivers[0].from.has_value());
  EXPECT_TRUE(m.has_time_law());
  EXPECT_DOUBLE_EQ(m.sweep.duration, 0.5);
  EXPECT_DOUBLE_EQ(*m.sweep.time_step, 0.01);

  // A law of a length driver is in length units; other drivers may keep a `from`.
  const Model n = parse_model(kFourBar + "units: {length: mm}\n" +
                              "drivers:\n"
                              "  - angle: crank\n"
                              "    law: |\n"
                              "      2*t\n"
                              "  - {distance: [O, B], law: 10 + t}\n"
                              "  - {angle: rocker, from: 5, speed: 2 rpm}\n"
                              "sweep: {duration: 2, steps: 41}\n")
                      .model;
  EXPECT_NEAR(n.drivers[0].law->value(3.0), 6 * kDeg, 1e-12);
  EXPECT_NEAR(n.drivers[1].law->value(2.0), 0.012, 1e-15);
  EXPECT_DOUBLE_EQ(*n.drivers[2].from, 5 * kDeg);
  EXPECT_EQ(n.sweep.steps, 41);
  EXPECT_DOUBLE_EQ(n.sweep.duration, 2.0);
  EXPECT_DOUBLE_EQ(*n.sweep.time_step, 0.05);
}

TEST(ModelFile, EmptySectionsAreEmpty) {
  const Model m = parse_model(kFourBar + "name:\nunits:\nlengths:\nsliders:\nslots:\ndrivers:\nsweep:\n").model;
  EXPECT_EQ(m.name, "");
  EXPECT_TRUE(m.drivers.empty());
  EXPECT_TRUE(m.sliders.empty());
  EXPECT_EQ(m.sweep.steps, 361);
}

TEST(ModelFile, NamesMayLookLikeOtherTypes) {
  const Model m = parse_model(
                      "points:\n  1: [0, 0]\n  yes: [1, 0]\n  '~': [2, 0]\nground: [1]\n"
                      "bodies:\n  2: [1, yes, '~']\n")
                      .model;
  EXPECT_EQ(m.points[1].name, "yes");
  EXPECT_EQ(m.points[2].name, "~");
  EXPECT_EQ(m.bodies[0].name, "2");
  EXPECT_EQ(m.bodies[0].points, (std::vector<int>{0, 1, 2}));
}

TEST(ModelFile, DescriptionIsAccepted) {
  EXPECT_NO_THROW(parse_model("description: |\n  A long text\n  over lines.\n" + kFourBar));
}

// ---- errors, each at its exact place ----

TEST(ModelFileErrors, ErrorFormat) {
  EXPECT_STREQ(ModelFileError("f.yaml", SourceMark{3, 7}, "bad").what(), "f.yaml:3:7: bad");
  EXPECT_STREQ(ModelFileError("f.yaml", SourceMark{}, "bad").what(), "f.yaml: bad");
  const ModelFileError e("f.yaml", SourceMark{2, 1}, "worse");
  EXPECT_EQ(e.file(), "f.yaml");
  EXPECT_EQ(e.mark().line, 2);
  EXPECT_EQ(e.message(), "worse");
}

// Nesting deeper than yaml-cpp follows: the message gives the file's own depth, at the bracket
// that reaches it (the reader's limit is a count of its calls, not of levels: 499 '[' fail and
// 498 pass).
TEST(ModelFileErrors, NestingTooDeepSaysHowDeepAndWhere) {
  const auto nested = [](int levels, const std::string& open, const std::string& close) {
    std::string text = "points: ";
    for (int i = 0; i < levels; ++i) text += open;
    for (int i = 0; i < levels; ++i) text += close;
    return text + "\n";
  };
  EXPECT_TRUE(fails_at(nested(600, "[", "]"), "1:" + std::to_string(8 + 600),
                       "invalid YAML: lists and mappings nested 600 levels deep here, deeper than the reader follows"));
  EXPECT_TRUE(fails_at(nested(600, "{a: ", "}"), "1:" + std::to_string(8 + 4 * 599 + 1),
                       "invalid YAML: lists and mappings nested 600 levels deep here"));
  // Within the reader's depth, the nesting is the model's mistake, told at its key.
  EXPECT_TRUE(fails_at(nested(400, "[", "]"), "1:9", "`points` must be a mapping"));
}

TEST(ModelFileErrors, MalformedYaml) {
  // An unclosed bracket or quote: at the opener, not where yaml-cpp next looked (the next line).
  EXPECT_TRUE(fails_at("points:\n  O: [0, 0\n  A: [1, 0]\n", "2:6",
                       "invalid YAML: this '[' is never closed by a ']' (end of sequence flow not found)"));
  EXPECT_TRUE(fails_at("units: {length: mm\npoints:\n  O: [0, 0]\n", "1:8",
                       "invalid YAML: this '{' is never closed by a '}' (end of map flow not found)"));
  EXPECT_TRUE(fails_at("name: \"four-bar\ndescription: \"x\"\npoints:\n  O: [0, 0]\n", "1:7",
                       "invalid YAML: this \" is not closed on its line"));
  EXPECT_TRUE(fails_at("points:\n\tO: [0, 0]\n", "2:1",
                       "invalid YAML: tab characters are not allowed in YAML indentation; indent with spaces"));
  EXPECT_TRUE(fails_at("name: t\npoints:\n  O2: [0, 0]\n \tA: [1, 0]\n", "4:2",
                       "tab characters are not allowed in YAML indentation"));
  // A tab after the indentation, where YAML allows it, is no error by itself.
  EXPECT_TRUE(fails_at("name:\tt\npoints:\n  O: [0, 0\n", "3:6", "invalid YAML: this '[' is never closed"));
  EXPECT_TRUE(fails_at("points:\n  O: [0, 0]\n A: [1, 0]\n", "3:2", "invalid YAML: end of map not found"));
  EXPECT_TRUE(fails_at(R"({"points": {"A": [0, 0] "B": [1, 1]}})", "1:25", "invalid YAML: end of map flow not found"));
  // Past YAML's 1024 characters a key is a syntax error to yaml-cpp ("end of map flow not
  // found", "illegal map value" at its end): said as the name's own limit, at the key.
  const std::string key(1100, 'P');
  const std::string too_long = "a key or name may have at most 256 characters (this one has 1100)";
  EXPECT_TRUE(fails_at(R"({"points": {")" + key + R"(": [0, 0]}})", "1:13", too_long));
  EXPECT_TRUE(fails_at(R"({"points":{")" + key + R"(":[0, 0]}})", "1:12", too_long));
  EXPECT_TRUE(fails_at("points:\n  " + key + ": [0, 0]\n", "2:3", too_long));
  EXPECT_TRUE(fails_at("points:\n  O: [0, 0]\n  \"" + key + "\": [0, 0]\n", "3:3", too_long));
}

TEST(ModelFileErrors, NotAModel) {
  EXPECT_TRUE(fails_at("", "1:1", "the file holds no model (it is empty or only comments)"));
  EXPECT_TRUE(fails_at("# just a comment\n\n", "1:1", "the file holds no model"));
  EXPECT_TRUE(fails_at("---\n", "1:1", "the file holds no model"));
  EXPECT_TRUE(fails_at("- O\n- A\n", "1:1",
                       "a model file is a mapping of sections (points:, bodies:, drivers:, ...), not a list"));
  EXPECT_TRUE(fails_at("hello\n", "1:1", "not 'hello'"));
  EXPECT_TRUE(fails_at(kFourBar + "---\npoints: {}\n", "12:1", "a model file holds a single YAML document"));
  EXPECT_TRUE(fails_at("name: x\n", "1:1", "the model has no `points:` section"));
  EXPECT_TRUE(fails_at("name: x\npoints:\n", "2:1", "`points` is empty"));
  EXPECT_TRUE(fails_at("points: {}\n", "1:1", "`points` is empty"));
}

// Coordinates and lengths past what the drawing can resolve: a far point made a 150 mm link
// "zero length", 1e308 and a 1e12 mm length were reported as a wrong number of freedoms at 1:1.
TEST(ModelFileErrors, SizesTheDrawingCannotResolve) {
  const auto model = [](const std::string& a, const std::string& extra = "") {
    return "units: {length: mm, angle: deg}\npoints: {O2: [0, 0], O4: [200, 0], A: " + a +
           ", B: [160, 150]}\nground: [O2, O4]\nbodies: {crank: [O2, A], coupler: [A, B], rocker: [O4, B]}\n"
           "drivers: [{angle: crank, from: 0, to: 360}]\n" +
           extra;
  };
  EXPECT_TRUE(fails_at(model("[1e15, 0]"), "4:43",
                       "body 'rocker' is 155.242 mm long, less than a billionth of the drawing's size (1e+15 mm), so "
                       "its points O4 and B count as coinciding"));
  EXPECT_TRUE(fails_at(model("[1e308, 0]"), "2:36", "point 'A' has a coordinate beyond 1e100 mm"));
  EXPECT_TRUE(
      fails_at(model("[0, 80]", "lengths: {crank: 1e12}\n"), "4:10",
               "the length of body 'crank', 1e+12 mm, is more than a million times the drawing's size (250 mm)"));
  EXPECT_NO_THROW(parse_model(model("[0, 80]", "lengths: {crank: 1e3}\n"), "m.yaml"));
}

// A centre of mass 1e300 m away was taken by the simulation for a body without inertia (its
// moment about the frame overflowed); it is refused at the body, as a point that far is.
TEST(ModelFileErrors, ACentreOfMassTheDynamicsCannotResolve) {
  const auto model = [](const std::string& body) {
    return "units: {length: m, angle: deg}\npoints: {O: [0, 0], A: [0.5, 0]}\nground: [O]\n"
           "bodies:\n  bar: " +
           body + "\ndrivers: [{angle: bar, free: true}]\n";
  };
  EXPECT_TRUE(fails_at(model("{points: [O, A], mass: 1, inertia: 0.02, cg: [1e300, 0]}"), "5:3",
                       "the centre of mass of body 'bar' has a coordinate beyond 1e100 m"));
  EXPECT_TRUE(fails_at(model("{points: [O, A], mass: 1e200, inertia: 0.02, cg: [1e90, 0]}"), "5:3",
                       "the centre of mass of body 'bar' is too far from its points for its mass"));
  EXPECT_NO_THROW(parse_model(model("{points: [O, A], mass: 1, inertia: 0.02, cg: [1e90, 0]}"), "m.yaml"));
}

// A NUL made yaml-cpp take the file for UTF-16 and quote it back as garbled text, or say
// "unknown escape character" a line too late; UTF-16 without a byte-order mark was read as a model.
TEST(ModelFileErrors, ControlCharactersAreNotText) {
  using namespace std::string_literals;
  EXPECT_TRUE(fails_at("name: x\nO4: [200, 0]\0\n"s, "2:13", "not text: byte 0x00 here is a control character"));
  EXPECT_TRUE(fails_at("\0\x01\x02name: x\n"s, "1:1", "byte 0x00"));
  EXPECT_TRUE(fails_at("n\0a\0m\0e\0:\0 \0x\0\n\0"s, "1:2", "(UTF-16 or a binary file?)"));
  EXPECT_TRUE(fails_at("name: \x07\n", "1:7", "byte 0x07"));
  EXPECT_TRUE(fails_at("name: x\x7f\n", "1:8", "byte 0x7F"));
  // The first of a control character and a byte that is no UTF-8 is the one reported.
  EXPECT_TRUE(fails_at("a: \xff\x01\n", "1:4", "not valid UTF-8"));
  EXPECT_TRUE(fails_at("a: \x01\xff\n", "1:4", "control character"));
}

TEST(ModelFileErrors, UnknownKeys) {
  EXPECT_TRUE(fails_at(kFourBar + "lenghts: {crank: 8}\n", "11:1",
                       "unknown key 'lenghts' at the top level; did you mean 'lengths'?"));
  EXPECT_TRUE(fails_at(kFourBar + "colour: red\n", "11:1",
                       "unknown key 'colour' at the top level (allowed: name, description, units, points, ground, "
                       "bodies, lengths, sliders, slots, drivers, sweep, gravity, materials, forces, torques, "
                       "springs, friction, simulation)"));
  EXPECT_TRUE(fails_at(kFourBar + "Points: {}\n", "11:1", "did you mean 'points'?"));
  EXPECT_TRUE(
      fails_at(kFourBar + "units: {lenght: mm}\n", "11:9", "unknown key 'lenght' in `units`; did you mean 'length'?"));
  EXPECT_TRUE(fails_at(kFourBar + "drivers:\n  - {angle: crank, sped: 10}\n", "12:20",
                       "unknown key 'sped' in a driver; did you mean 'speed'?"));
  EXPECT_TRUE(fails_at(kFourBar + "drivers:\n  - {angle: crank, velocity: 10}\n", "12:20",
                       "unknown key 'velocity' in a driver (allowed: name, angle, relative_to"));
  EXPECT_TRUE(
      fails_at(kFourBar + "sweep: {stpes: 10}\n", "11:9", "unknown key 'stpes' in `sweep`; did you mean 'steps'?"));
  EXPECT_TRUE(fails_at(kSliderCrank + "sliders:\n  - {body: piston, pointt: C, along: [O, X]}\n", "12:20",
                       "unknown key 'pointt' in a slider; did you mean 'point'?"));
  EXPECT_TRUE(fails_at(kSlottedLever + "  - {point: A, alng: [Q, E]}\n", "11:16",
                       "unknown key 'alng' in a slot; did you mean 'along'?"));
}

TEST(ModelFileErrors, UnknownNames) {
  EXPECT_TRUE(fails_at("points:\n  O: [0, 0]\n  A: [10, 0]\nground: [O]\nbodies:\n  crank: [O, Z]\n", "6:14",
                       "unknown point 'Z' (points are: O, A)"));
  EXPECT_TRUE(fails_at("points:\n  O2: [0, 0]\n  A: [10, 0]\nground: [O3]\n", "4:10",
                       "unknown point 'O3'; did you mean 'O2'?"));
  EXPECT_TRUE(fails_at("points:\n  O2: [0, 0]\n  A: [10, 0]\nground: [o2]\n", "4:10", "did you mean 'O2'?"));
  EXPECT_TRUE(
      fails_at(kFourBar + "drivers:\n  - {angle: crnk}\n", "12:13", "unknown body 'crnk'; did you mean 'crank'?"));
  EXPECT_TRUE(fails_at(kFourBar + "drivers:\n  - {angle: wheel}\n", "12:13",
                       "unknown body 'wheel' (bodies are: crank, coupler, rocker)"));
  EXPECT_TRUE(
      fails_at(kFourBar + "drivers:\n  - {angle: crank, relative_to: frame}\n", "12:33", "unknown body 'frame'"));
  EXPECT_TRUE(fails_at(kFourBar + "lengths: {cranck: 10}\n", "11:11", "unknown body 'cranck'; did you mean 'crank'?"));
  EXPECT_TRUE(
      fails_at(kFourBar + "drivers:\n  - {distance: [A, Z]}\n", "12:20", "unknown point 'Z' (points are: O, A, B, Q)"));
  EXPECT_TRUE(fails_at("points:\n  O: [0, 0]\nground: [O]\ndrivers:\n  - {angle: crank}\n", "5:13",
                       "unknown body 'crank' (there are no bodies)"));
  EXPECT_TRUE(fails_at(kSliderCrank + "sliders:\n  - {body: pistn, point: C, along: [O, X]}\n", "12:12",
                       "unknown body 'pistn'; did you mean 'piston'?"));
  EXPECT_TRUE(
      fails_at(kSliderCrank + "sliders:\n  - {body: piston, point: C, along: [O, Y]}\n", "12:41", "unknown point 'Y'"));
  EXPECT_TRUE(fails_at(
      kSliderCrank + "sliders:\n  - {body: piston, point: C, along: [O, X]}\n" + "drivers:\n  - {slide: rod}\n",
      "14:13", "body 'rod' has no slider (`slide` names the body of a slider)"));
}

TEST(ModelFileErrors, ManyNamesAreAbbreviated) {
  std::string text = "points:\n";
  for (int i = 0; i < 20; ++i) text += "  P" + std::to_string(i) + ": [" + std::to_string(i) + ", 0]\n";
  text += "ground: [Zed]\n";
  EXPECT_TRUE(fails_at(text, "22:10", "(points are: P0, P1, P2, P3, P4, P5, P6, P7, P8, P9, P10, P11, ...)"));
}

TEST(ModelFileErrors, DuplicateKeysAndNames) {
  EXPECT_TRUE(fails_at("points:\n  O: [0, 0]\npoints:\n  A: [0, 0]\n", "3:1",
                       "duplicate key 'points' (first given on line 1)"));
  EXPECT_TRUE(fails_at("points:\n  O: [0, 0]\n  A: [10, 0]\n  A: [20, 0]\n", "4:3",
                       "point 'A' is defined twice (first given on line 3)"));
  EXPECT_TRUE(fails_at(R"({"points": {"A": [0, 0], "A": [1, 1]}})", "1:26", "point 'A' is defined twice"));
  EXPECT_TRUE(
      fails_at(kFourBar + "  crank: [A, B]\n", "11:3", "body 'crank' is defined twice (first given on line 8)"));
  EXPECT_TRUE(fails_at(kFourBar + "drivers:\n  - {angle: crank, from: 0, from: 10}\n", "12:29",
                       "duplicate key 'from' (first given on line 12)"));
  EXPECT_TRUE(fails_at(kFourBar + "lengths:\n  crank: 10\n  crank: 12\n", "13:3",
                       "the length of body 'crank' is defined twice"));
  EXPECT_TRUE(fails_at(kFourBar + "units: {angle: rad, angle: deg}\n", "11:21", "duplicate key 'angle'"));
  EXPECT_TRUE(fails_at(kFourBar + "drivers:\n  - {angle: crank, from: 0}\n  - {angle: crank, from: 10}\n", "13:5",
                       "two drivers are named 'crank': give one a `name:`"));
  EXPECT_TRUE(fails_at(kFourBar + "drivers:\n  - {angle: crank, name: x}\n  - {angle: rocker, name: x}\n", "13:5",
                       "two drivers are named 'x'"));
  EXPECT_TRUE(fails_at("points:\n  O: [0, 0]\n  Q: [1, 0]\nground: [O, Q, O]\n", "4:16",
                       "point 'O' is listed twice under `ground`"));
}

TEST(ModelFileErrors, BadKeys) {
  EXPECT_TRUE(fails_at("points:\n  ~: [0, 0]\n", "2:3", "a key or name cannot be empty or null"));
  EXPECT_TRUE(fails_at("points:\n  '': [0, 0]\n", "2:3", "a key or name cannot be empty"));
  EXPECT_TRUE(fails_at("points:\n  ? [a, b]\n  : [0, 0]\n", "2:5", "a key or name must be a single word, not a list"));
}

TEST(ModelFileErrors, Bodies) {
  EXPECT_TRUE(fails_at(kFourBar + "  wheel: []\n", "11:3", "body 'wheel' has no points"));
  EXPECT_TRUE(fails_at("points:\n  O2: [0, 0]\n  A: [0, 0]\nground: [O2]\nbodies:\n  crank: [O2, A]\n", "6:3",
                       "body 'crank' has zero length: points O2 and A coincide"));
  EXPECT_TRUE(fails_at(kFourBar + "  frame: [O, Q]\n", "11:3",
                       "body 'frame' has only ground points, so it cannot move: list its points under ground instead"));
  EXPECT_TRUE(fails_at(kFourBar + "  wheel: [A, B, A]\n", "11:3", "body 'wheel' lists point 'A' twice"));
  EXPECT_TRUE(fails_at(kSliderCrank, "10:3", "body 'piston' has a single point, so its orientation is undefined"));
  EXPECT_TRUE(fails_at(kFourBar + "  wheel: A\n", "11:10",
                       "body 'wheel' needs a list of its points, like [A, B], or a mapping with `points:`, not 'A'"));
  EXPECT_TRUE(fails_at(kFourBar + "  wheel:\n", "11:3",
                       "body 'wheel' needs a list of its points, like [A, B], or a mapping with `points:`, not "
                       "nothing"));
  EXPECT_TRUE(
      fails_at(kFourBar + "  wheel: [A, {B: 1}]\n", "11:14", "a point reference must be a name, not a mapping"));
  EXPECT_TRUE(fails_at("points:\n  O: [0, 0]\nbodies: [O]\n", "3:9",
                       "`bodies` must be a mapping of body names to lists of points, not a list"));
}

TEST(ModelFileErrors, PointNotAttached) {
  EXPECT_TRUE(fails_at("points:\n  O: [0, 0]\n  A: [10, 0]\n  Q: [5, 5]\nground: [O]\nbodies:\n  crank: [O, A]\n",
                       "4:3", "point 'Q' is not attached to any body or to ground"));
}

TEST(ModelFileErrors, Lengths) {
  EXPECT_TRUE(fails_at(kFourBar + "  tri: [A, B, Q]\nlengths: {tri: 5}\n", "12:11",
                       "body 'tri' has 3 points: `lengths` applies only to bodies with two points"));
  EXPECT_TRUE(fails_at(kFourBar + "lengths: {crank: -5}\n", "11:18", "the length of body 'crank' must be positive"));
  EXPECT_TRUE(fails_at(kFourBar + "lengths: {crank: 0}\n", "11:18", "must be positive"));
  EXPECT_TRUE(fails_at(kFourBar + "lengths: {crank: long}\n", "11:18", "a length must be a number, not 'long'"));
  EXPECT_TRUE(
      fails_at(kFourBar + "lengths: [5]\n", "11:10", "`lengths` must be a mapping like {crank: 80}, not a list"));
}

TEST(ModelFileErrors, Sliders) {
  const std::string head = kSliderCrank + "sliders:\n";  // items on line 12
  EXPECT_TRUE(fails_at(head + "  - {body: piston, point: C, along: [X, A]}\n", "12:5",
                       "the guide points of a slider must belong to one other body or to ground"));
  EXPECT_TRUE(fails_at(head + "  - {body: piston, point: C, along: [O, O]}\n", "12:5",
                       "the guide of the slider of body 'piston' uses point 'O' twice"));
  EXPECT_TRUE(fails_at(head + "  - {body: piston, point: A, along: [O, X]}\n", "12:5",
                       "moves point 'A', which is not one of the points of body 'piston'"));
  EXPECT_TRUE(fails_at(head + "  - {body: piston, point: C, along: [C, X]}\n", "12:5", "cannot also be a guide point"));
  EXPECT_TRUE(
      fails_at(head + "  - {body: piston, point: C, along: [O, X]}\n  - {body: piston, point: C, along: [X, O]}\n",
               "13:5", "body 'piston' has two sliders"));
  EXPECT_TRUE(fails_at(head + "  - {body: piston, point: C, along: [O, X, A]}\n", "12:37",
                       "`along` needs two point names, like [O2, X], not a list"));
  EXPECT_TRUE(fails_at(head + "  - {body: piston, point: C, along: O}\n", "12:37", "`along` needs two point names"));
  EXPECT_TRUE(fails_at(head + "  - {body: piston, point: C}\n", "12:5", "a slider needs `along`"));
  EXPECT_TRUE(
      fails_at(head + "  - piston\n", "12:5", "a slider is a mapping like {body: piston, point: C, along: [O2, X]}"));
  EXPECT_TRUE(fails_at(kSliderCrank + "sliders: {body: piston}\n", "11:10", "`sliders` must be a list like"));
}

TEST(ModelFileErrors, Slots) {
  EXPECT_TRUE(fails_at(kSlottedLever + "  - {point: A, along: [O, E]}\n", "11:5",
                       "the guide points of a slot must belong to one body or to ground"));
  EXPECT_TRUE(
      fails_at(kSlottedLever + "  - {point: E, along: [Q, E]}\n", "11:5", "cannot be one of its own guide points"));
  EXPECT_TRUE(fails_at(kSlottedLever + "  - {along: [Q, E]}\n", "11:5", "a slot needs `point`"));
  EXPECT_TRUE(fails_at(kSlottedLever + "  - {point: A, along: {Q: E}}\n", "11:23", "`along` needs two point names"));
}

TEST(ModelFileErrors, Units) {
  EXPECT_TRUE(
      fails_at(kFourBar + "units: {length: mmm}\n", "11:17", "unknown length unit 'mmm' (use m, mm, cm, in or ft)"));
  EXPECT_TRUE(fails_at(kFourBar + "units: {angle: grad}\n", "11:16", "unknown angle unit 'grad' (use deg or rad)"));
  EXPECT_TRUE(fails_at(kFourBar + "units: [mm, deg]\n", "11:8",
                       "`units` must be a mapping like {length: mm, angle: deg}, not a list"));
  EXPECT_TRUE(fails_at(kFourBar + "units: {length: [mm]}\n", "11:17", "the length unit must be text, not a list"));
}

TEST(ModelFileErrors, Speeds) {
  const std::string head = kFourBar + "drivers:\n";  // items on line 12
  EXPECT_TRUE(
      fails_at(head + "  - {angle: crank, speed: 0.5 m/s}\n", "12:27",
               "'0.5 m/s' is a linear speed but driver 'crank' is an angle: use a unit such as rpm, deg/s or rad/s"));
  EXPECT_TRUE(fails_at(head + "  - {distance: [A, Q], speed: 10 rpm}\n", "12:31",
                       "'10 rpm' is an angular speed but driver 'A-Q' is a length"));
  EXPECT_TRUE(fails_at(head + "  - {angle: crank, accel: 2 m/s^2}\n", "12:27", "'2 m/s^2' is a linear acceleration"));
  EXPECT_TRUE(fails_at(head + "  - {distance: [A, Q], accel: 2 rad/s^2}\n", "12:31", "is an angular acceleration"));
  EXPECT_TRUE(fails_at(head + "  - {angle: crank, speed: 3 furlongs/s}\n", "12:27", "unknown unit"));
  EXPECT_TRUE(fails_at(head + "  - {angle: crank, speed: fast}\n", "12:27", "expected a number followed by a unit"));
  EXPECT_TRUE(fails_at(head + "  - {angle: crank, accel: 100 rpm}\n", "12:27", "needs a unit per time"));
  // Units are case-sensitive, and a unit in the wrong case gets its right spelling.
  EXPECT_TRUE(fails_at(head + "  - {angle: crank, speed: 120 RPM}\n", "12:27",
                       "'120 RPM': units are case-sensitive: did you mean '120 rpm'?"));
  EXPECT_TRUE(fails_at(head + "  - {angle: crank, accel: 2 Deg/S^2}\n", "12:27",
                       "'2 Deg/S^2': units are case-sensitive: did you mean '2 deg/s^2'?"));
  EXPECT_TRUE(fails_at(head + "  - {angle: crank, speed: [1, 2]}\n", "12:27",
                       "the speed must be a number or a quantity like '1750 rpm', not a list"));
  EXPECT_TRUE(
      fails_at(head + "  - {angle: crank, speed: .nan}\n", "12:27", "the speed must be a finite number, not '.nan'"));
  EXPECT_TRUE(fails_at(head + "  - {angle: crank, speed: 0}\n", "12:5", "driver 'crank': the speed must not be zero"));
  EXPECT_TRUE(fails_at(head + "  - {angle: crank, speed: 0 rpm}\n", "12:5", "the speed must not be zero"));
}

TEST(ModelFileErrors, Drivers) {
  const std::string head = kFourBar + "drivers:\n";  // items on line 12
  EXPECT_TRUE(fails_at(head + "  - {angle: crank, distance: [O, A]}\n", "12:20",
                       "a driver has exactly one of `angle`, `distance` or `slide`; this one already has `angle`"));
  EXPECT_TRUE(fails_at(head + "  - {from: 0}\n", "12:5",
                       "a driver needs one of `angle: <body>`, `distance: [P, Q]` or `slide: <body>`"));
  EXPECT_TRUE(fails_at(head + "  - {distance: [O, B], relative_to: crank}\n", "12:24",
                       "`relative_to` applies only to `angle` drivers"));
  EXPECT_TRUE(
      fails_at(head + "  - {angle: crank, relative_to: crank}\n", "12:5", "cannot be relative to its own body"));
  EXPECT_TRUE(fails_at(head + "  - {distance: [A, A]}\n", "12:5", "measures the distance from point 'A' to itself"));
  EXPECT_TRUE(fails_at(head + "  - {distance: [O, A]}\n", "12:5",
                       "driver 'O-A' drives the distance between two points of body 'crank', which cannot change"));
  EXPECT_TRUE(fails_at(head + "  - {angle: crank, name: ''}\n", "12:26", "a driver name cannot be empty"));
  EXPECT_TRUE(fails_at(head + "  - crank\n", "12:5",
                       "a driver is a mapping like {angle: crank, from: 0, to: 360}, not 'crank'"));
  EXPECT_TRUE(fails_at(kFourBar + "drivers: {angle: crank}\n", "11:10", "`drivers` must be a list like"));
  EXPECT_TRUE(
      fails_at(head + "  - {angle: crank, from: zero}\n", "12:26", "`from` (deg) must be a number, not 'zero'"));
  EXPECT_TRUE(
      fails_at(head + "  - {angle: crank, from: .inf}\n", "12:26", "`from` (deg) must be a finite number, not '.inf'"));
  EXPECT_TRUE(fails_at(head + "  - {distance: [A, Q], to: -.Inf}\n", "12:28", "`to` (m) must be a finite number"));
  // 1e20 deg is 1.7e18 rad, where neighbouring doubles are 256 rad apart: `check` gave a time ratio of inf.
  EXPECT_TRUE(fails_at(head + "  - {angle: crank, from: 1e20, to: 1e20}\n", "12:26",
                       "`from` is 1e20 deg, too large for a driver angle: the largest is 57295779.5 deg (a million "
                       "radians), past which the digits of a double no longer hold the motion (at this value "
                       "neighbouring doubles are 256 rad apart); take whole turns off it"));
  EXPECT_TRUE(fails_at(head + "  - {angle: crank, from: 0, to: -6e7}\n", "12:33",
                       "`to` is -6e7 deg, too large for a driver angle"));
  EXPECT_NO_THROW(parse_model(head + "  - {angle: crank, from: 5.7e7, to: 5.7e7}\n", "m.yaml"));
}

TEST(ModelFileErrors, Laws) {
  const std::string head = kFourBar + "drivers:\n";  // items on line 12
  // The '$' is character 15 of the law, which starts after the quote in column 25.
  EXPECT_TRUE(fails_at(head + "  - {angle: crank, law: \"30*sin(2*pi*t) $ 2\"}\n", "12:41",
                       "in the law '30*sin(2*pi*t) $ 2': unexpected"));
  EXPECT_TRUE(fails_at(head + "  - angle: crank\n    law: 30*sin(2*pi*t) $ 2\n", "13:25", "unexpected"));
  EXPECT_TRUE(fails_at(head + "  - angle: crank\n    law: '30*t $'\n", "13:16", "unexpected"));
  // An escape takes four characters in the file for one in the law.
  EXPECT_TRUE(fails_at(head + "  - angle: crank\n    law: \"\\x33*t $\"\n", "13:18", "in the law '3*t $'"));
  // Block scalars are not mapped: the error points at the scalar and names the character.
  EXPECT_TRUE(fails_at(head + "  - angle: crank\n    law: |\n      30*t $\n", "13:10", "(at character 6 of the law)"));
  EXPECT_TRUE(fails_at(head + "  - {angle: crank, from: 0, law: t}\n", "12:20",
                       "driver 'crank' follows a `law`, which sets its motion, so it takes no `from`"));
  EXPECT_TRUE(fails_at(head + "  - {angle: crank, law: t, to: 1}\n", "12:28", "takes no `to`"));
  EXPECT_TRUE(fails_at(head + "  - {angle: crank, law: t, speed: 1}\n", "12:28", "takes no `speed`"));
  EXPECT_TRUE(fails_at(head + "  - {angle: crank, law: [t]}\n", "12:25", "a law must be an expression in t"));
  EXPECT_TRUE(fails_at(head + "  - {angle: crank, law: t}\n  - {angle: rocker, to: 10}\n", "13:5",
                       "driver 'rocker': `to` has no meaning when another driver follows a time law"));
}

TEST(ModelFileErrors, Sweep) {
  const std::string head = kFourBar + "drivers:\n  - {angle: crank, to: 90}\n";  // sweep on line 13
  const std::string timed = kFourBar + "drivers:\n  - {angle: crank, law: 10*t}\n";
  EXPECT_TRUE(fails_at(head + "sweep: {steps: 0}\n", "13:16", "the sweep needs at least 1 step"));
  EXPECT_EQ(parse_model(head + "sweep: {steps: 1}\n").model.sweep.steps, 1);
  EXPECT_TRUE(fails_at(head + "sweep: {steps: 2.5}\n", "13:16", "`steps` must be a whole number"));
  // 1e10 is whole: what is wrong is its size.
  EXPECT_TRUE(
      fails_at(head + "sweep: {steps: 1e10}\n", "13:16", "`steps` must be a whole number of at most a billion"));
  EXPECT_TRUE(fails_at(head + "sweep: {steps: many}\n", "13:16", "`steps` must be a number, not 'many'"));
  EXPECT_TRUE(
      fails_at(head + "sweep: {steps: 10, step: 0.1}\n", "13:20", "give the sweep either `steps` or `step`, not both"));
  EXPECT_TRUE(
      fails_at(head + "sweep: {duration: 1}\n", "13:9", "`duration` applies only when a driver follows a `law`"));
  EXPECT_TRUE(fails_at(head + "sweep: {step: 0.1}\n", "13:9", "`step` applies only when a driver follows a `law`"));
  EXPECT_TRUE(fails_at(timed + "sweep: {duration: -1}\n", "13:19", "the sweep duration must be positive"));
  EXPECT_TRUE(
      fails_at(timed + "sweep: {duration: 0.1, step: 0.5}\n", "13:30", "the sweep `step` is longer than its duration"));
  EXPECT_TRUE(fails_at(timed + "sweep: {step: 0}\n", "13:15", "the sweep `step` must be positive"));
  EXPECT_TRUE(fails_at(timed + "sweep: {duration: .inf}\n", "13:19", "`duration` (s) must be a finite number"));
  EXPECT_TRUE(fails_at(head + "sweep: [10]\n", "13:8", "`sweep` must be a mapping like {steps: 361}"));
}

TEST(ModelFileErrors, Points) {
  EXPECT_TRUE(fails_at("points:\n  O: [.nan, 0]\n", "2:7", "x must be a finite number, not '.nan'"));
  EXPECT_TRUE(fails_at("points:\n  O: [0, -.inf]\n", "2:10", "y must be a finite number, not '-.inf'"));
  EXPECT_TRUE(fails_at("points:\n  O: [1e999, 0]\n", "2:7", "x must be a finite number, not '1e999'"));
  EXPECT_TRUE(fails_at("points:\n  O: [zero, 0]\n", "2:7", "x must be a number, not 'zero'"));
  EXPECT_TRUE(fails_at("points:\n  O: [[0], 0]\n", "2:7", "x must be a number, not a list"));
  EXPECT_TRUE(fails_at("points:\n  O: 5\n", "2:6", "a point needs [x, y]: point 'O' has '5'"));
  EXPECT_TRUE(fails_at("points:\n  O: [0, 0, 0]\n", "2:6", "a point needs [x, y]: point 'O' has a list"));
  EXPECT_TRUE(fails_at("points:\n  O:\n  A: [1, 0]\n", "2:3", "a point needs [x, y]: point 'O' has nothing"));
  EXPECT_TRUE(fails_at("points: [O, A]\n", "1:9", "`points` must be a mapping of point names to [x, y], not a list"));
}

TEST(ModelFileErrors, OtherWrongTypes) {
  EXPECT_TRUE(fails_at("points:\n  O: [0, 0]\nground: O\n", "3:9", "`ground` must be a list like [O2, O4], not 'O'"));
  EXPECT_TRUE(fails_at("name: [a]\n" + kFourBar, "1:7", "the model name must be text, not a list"));
  EXPECT_TRUE(fails_at("description: {a: b}\n" + kFourBar, "1:14", "the description must be text, not a mapping"));
}

// ---- files and locating later errors ----

class ModelFileOnDisk : public ::testing::Test {
 protected:
  void SetUp() override {
    // Tests may run in parallel processes: one directory per test and process.
    dir_ = std::filesystem::path(::testing::TempDir()) /
           ("nbar_model_file_test_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
            "_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    const std::filesystem::path path = dir_ / name;
    std::ofstream(path) << text;
    return path.string();
  }
  std::filesystem::path dir_;
};

TEST_F(ModelFileOnDisk, LoadsAFile) {
  const std::string path = write("four-bar.yaml", kExample);
  const LoadedModel loaded = load_model_file(path);
  EXPECT_EQ(loaded.source.file, path);
  EXPECT_EQ(loaded.model.points.size(), 5u);
}

TEST_F(ModelFileOnDisk, ErrorsNameTheFile) {
  const std::string path = write("bad.yaml", kFourBar + "colour: red\n");
  try {
    load_model_file(path);
    FAIL() << "expected an error";
  } catch (const ModelFileError& e) {
    EXPECT_THAT(e.what(), StartsWith(path + ":11:1: unknown key 'colour'"));
    EXPECT_EQ(e.file(), path);
  }
}

TEST_F(ModelFileOnDisk, MissingFile) {
  const std::string path = (dir_ / "nowhere.yaml").string();
  try {
    load_model_file(path);
    FAIL() << "expected an error";
  } catch (const ModelFileError& e) {
    EXPECT_EQ(std::string(e.what()), path + ": cannot read: No such file or directory");
    EXPECT_EQ(e.mark().line, 0);
  }
}

TEST_F(ModelFileOnDisk, Directory) {
  try {
    load_model_file(dir_.string());
    FAIL() << "expected an error";
  } catch (const ModelFileError& e) {
    EXPECT_EQ(std::string(e.what()), dir_.string() + ": cannot read: Is a directory");
  }
}

// A device or a pipe has no size to check before reading and no end: the reader stops one byte
// past the limit (it read /dev/zero until the kernel killed it at 22 GB).
TEST_F(ModelFileOnDisk, AnEndlessFileIsReadOnlyToTheLimit) {
  try {
    load_model_file("/dev/zero");
    FAIL() << "expected an error";
  } catch (const ModelFileError& e) {
    EXPECT_EQ(std::string(e.what()),
              "/dev/zero:1:1: the file has more than 16777216 bytes; nbar reads at most 16777216");
  }
  const FileText zeros = read_file_text("/dev/zero", 100'000);
  EXPECT_TRUE(zeros.too_long);
  EXPECT_EQ(zeros.text.size(), 100'000u);
  const std::string path = write("four-bar.yaml", kExample);
  const FileText whole = read_file_text(path, std::string(kExample).size());
  EXPECT_FALSE(whole.too_long);
  EXPECT_FALSE(whole.error);
  EXPECT_EQ(whole.text, kExample);
  EXPECT_TRUE(read_file_text(path, std::string(kExample).size() - 1).too_long);
  EXPECT_EQ(read_file_text(dir_).error, std::errc::is_a_directory);
}

TEST(ModelFileLocate, LocatesLaterErrors) {
  const LoadedModel loaded = parse_model(kExample, "example.yaml");
  using Kind = EntityRef::Kind;
  EXPECT_EQ(locate(loaded.source, ModelError({Kind::Driver, 0}, "cannot assemble")),
            "example.yaml:16:5: cannot assemble");
  EXPECT_EQ(locate(loaded.source, ModelError({Kind::Body, 2}, "locked")), "example.yaml:13:3: locked");
  EXPECT_EQ(locate(loaded.source, ModelError({Kind::Point, 3}, "far")), "example.yaml:7:3: far");
  EXPECT_EQ(locate(loaded.source, ModelError({Kind::Sweep, -1}, "short")), "example.yaml:17:1: short");
  EXPECT_EQ(locate(loaded.source, ModelError({Kind::Model, -1}, "stuck")), "example.yaml:1:1: stuck");
  // Anything the map does not know falls back to the model.
  EXPECT_EQ(locate(loaded.source, ModelError({Kind::Slider, 0}, "none")), "example.yaml:1:1: none");
  EXPECT_EQ(locate(loaded.source, ModelError({Kind::Point, 42}, "none")), "example.yaml:1:1: none");

  SourceMap empty;
  empty.file = "code";
  EXPECT_EQ(locate(empty, ModelError({Kind::Body, 0}, "oops")), "code: oops");
}

TEST(ModelFileLocate, SlidersAndSlots) {
  const LoadedModel a = parse_model(kSliderCrank + "sliders:\n  - {body: piston, point: C, along: [O, X]}\n");
  EXPECT_EQ(a.source.find({EntityRef::Kind::Slider, 0}).line, 12);
  EXPECT_EQ(a.source.find({EntityRef::Kind::Slider, 0}).column, 5);
  const LoadedModel b = parse_model(kSlottedLever + "  - point: A\n    along: [Q, E]\n");
  EXPECT_EQ(b.source.find({EntityRef::Kind::Slot, 0}).line, 11);
  EXPECT_EQ(b.source.find({EntityRef::Kind::Slot, 0}).column, 5);
}

}  // namespace
}  // namespace nbar::io
