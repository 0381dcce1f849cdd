// Synthesis task files: the bundled examples, and every mistake reported at its line and column.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include <unistd.h>

#include "nbar/io/synthesis_task.hpp"

namespace {

namespace fs = std::filesystem;
using nbar::io::SynthesisKind;
using nbar::io::SynthesisTask;
using ::testing::HasSubstr;

constexpr double kDegree = std::numbers::pi / 180;
const std::string kDir = std::string(NBAR_EXAMPLES_DIR) + "/synthesis/";

// The message of the error a task text raises ("" when it parses).
std::string error_of(const std::string& text) {
  try {
    nbar::io::parse_synthesis_task(text, "task.yaml");
  } catch (const nbar::io::ModelFileError& e) {
    return e.what();
  }
  return "";
}

TEST(SynthesisTask, EveryExampleParses) {
  int count = 0;
  for (const auto& entry : fs::recursive_directory_iterator(kDir)) {
    if (entry.path().extension() != ".yaml") continue;  // path/d-shape.csv is a task's curve
    SCOPED_TRACE(entry.path().string());
    EXPECT_NO_THROW(nbar::io::load_synthesis_task(entry.path().string()));
    ++count;
  }
  EXPECT_GE(count, 5);
}

TEST(SynthesisTask, FivePoint) {
  const SynthesisTask t = nbar::io::load_synthesis_task(kDir + "five-point-crank-rocker.yaml");
  EXPECT_EQ(t.kind, SynthesisKind::FivePoint);
  EXPECT_EQ(nbar::io::to_string(t.kind), "five-point");
  EXPECT_EQ(t.units.length, "mm");
  EXPECT_EQ(t.pivot_a, Eigen::Vector2d(0, 0));
  EXPECT_EQ(t.pivot_b, Eigen::Vector2d(200, 0));  // task units: the solvers work in them
  ASSERT_EQ(t.points.size(), 5u);
  EXPECT_EQ(t.points[2], Eigen::Vector2d(44.303, 194.508));
  EXPECT_EQ(t.where.line, 14);  // `points`, where the solver's complaints go
}

TEST(SynthesisTask, NinePoint) {
  const SynthesisTask t = nbar::io::load_synthesis_task(kDir + "nine-point-crank-rocker.yaml");
  EXPECT_EQ(t.kind, SynthesisKind::NinePoint);
  EXPECT_EQ(nbar::io::to_string(t.kind), "nine-point");
  ASSERT_EQ(t.points.size(), 9u);
  EXPECT_EQ(t.points[8], Eigen::Vector2d(49.680, 126.456));
  EXPECT_EQ(t.where.line, 11);  // `points`
}

// Nine points: too few, repeated, on one line; each at the place to fix.
TEST(SynthesisTask, NinePointMistakes) {
  const std::string head = "task: nine-point\npoints:\n";
  std::string eight = head;
  for (int i = 0; i < 8; ++i) eight += "  - [" + std::to_string(i) + ", " + std::to_string(i * i) + "]\n";
  EXPECT_EQ(error_of(eight), "task.yaml:3:3: a nine-point task needs exactly 9 points for the coupler point, not 8");
  std::string repeated = eight + "  - [2, 4]\n";
  EXPECT_EQ(error_of(repeated), "task.yaml:11:5: points 3 and 9 coincide: the nine points must be distinct");
  std::string line = head;
  for (int i = 0; i < 9; ++i) line += "  - [" + std::to_string(i) + ", " + std::to_string(2 * i + 1) + "]\n";
  EXPECT_EQ(error_of(line),
            "task.yaml:3:3: the nine points lie on one straight line, which is no four-bar's coupler "
            "curve: move some off the line");
  EXPECT_EQ(error_of(eight + "  - 3\n"), "task.yaml:11:5: point 9 needs two numbers, like [x, y], not '3'");
  // On one circle (3-4-5 triangles' corners on the circle of radius 5 about (1, 2)).
  const std::string circle = head +
                             "  - [6, 2]\n  - [5, 5]\n  - [4, 6]\n  - [1, 7]\n  - [-2, 6]\n  - [-3, 5]\n"
                             "  - [-4, 2]\n  - [-3, -1]\n  - [1, -3]\n";
  EXPECT_EQ(error_of(circle),
            "task.yaml:3:3: the nine points lie on one circle (centre (1, 2), radius 5 m): a crank of "
            "that radius about its centre, whose moving pivot is the coupler point, passes through "
            "them with any second dyad, so there are infinitely many four-bars; move some off the "
            "circle");
  EXPECT_EQ(
      error_of("task: nine-point\npivots: {a: [0, 0], b: [1, 0]}\n"),
      "task.yaml:2:1: unknown key 'pivots' in a nine-point task (allowed: task, name, description, units, points)");
}

TEST(SynthesisTask, Burmester) {
  const SynthesisTask three = nbar::io::load_synthesis_task(kDir + "burmester-three-positions.yaml");
  EXPECT_EQ(three.kind, SynthesisKind::Burmester);
  ASSERT_EQ(three.poses.size(), 3u);
  EXPECT_NEAR(three.poses[1].angle, 55.771 * kDegree, 1e-15);
  EXPECT_EQ(three.poses[1].point, Eigen::Vector2d(22.802, 111.483));
  EXPECT_EQ(three.given, nbar::synthesis::PivotChoice::Fixed);
  EXPECT_EQ(three.given_b, Eigen::Vector2d(200, 0));

  const SynthesisTask four = nbar::io::load_synthesis_task(kDir + "burmester-four-positions.yaml");
  EXPECT_EQ(four.poses.size(), 4u);
  EXPECT_EQ(four.curves.radius, 400);
  EXPECT_EQ(four.curves.step, 0);
  EXPECT_EQ(four.samples, 24);

  const SynthesisTask moving = nbar::io::parse_synthesis_task(R"(task: burmester
units: {angle: rad}
poses:
  - {point: [0, 0], angle: 0}
  - {point: [1, 0], angle: 0.5}
  - {point: [2, 1], angle: 1}
moving_pivots: {a: [0, -1], b: [1, -1]}
)");
  EXPECT_EQ(moving.given, nbar::synthesis::PivotChoice::Moving);
  EXPECT_EQ(moving.poses[2].angle, 1.0);
  EXPECT_EQ(moving.given_a, Eigen::Vector2d(0, -1));
}

TEST(SynthesisTask, FunctionWithLog10) {
  const SynthesisTask t = nbar::io::load_synthesis_task(kDir + "function-log10.yaml");
  EXPECT_EQ(t.kind, SynthesisKind::Function);
  EXPECT_EQ(t.function_text, "log10(x)");
  ASSERT_TRUE(t.function);
  EXPECT_NEAR(t.function->value(2.0), std::log10(2.0), 1e-15);
  EXPECT_EQ(t.x_start, 1);
  EXPECT_EQ(t.x_end, 2);
  EXPECT_NEAR(t.input_from, 90 * kDegree, 1e-15);
  EXPECT_NEAR(t.output_to, 120 * kDegree, 1e-15);
  EXPECT_EQ(t.precision_points, 3);
  EXPECT_TRUE(t.chebyshev);
  EXPECT_EQ(t.frame, 100);

  const SynthesisTask nested = nbar::io::parse_synthesis_task(R"(task: function
function: "2^log10(x*log10 (100*x)) + x"
x: [1, 3]
input_range: [0, 90]
output_range: [0, 60]
points: 5
spacing: even
)");
  const double x = 2.5;
  EXPECT_NEAR(nested.function->value(x), std::pow(2.0, std::log10(x * std::log10(100 * x))) + x, 1e-14);
  EXPECT_EQ(nested.precision_points, 5);
  EXPECT_FALSE(nested.chebyshev);
}

// Every task file shown in docs/synthesis.md (the YAML blocks that start with `task:`) reads.
TEST(SynthesisTask, TheDocumentationsExamplesParse) {
  std::ifstream in(std::string(NBAR_EXAMPLES_DIR) + "/../docs/synthesis.md");
  ASSERT_TRUE(in) << "cannot read docs/synthesis.md";
  std::string line, block;
  bool inside = false;
  int tasks = 0;
  while (std::getline(in, line)) {
    if (!inside && line == "```yaml") {
      inside = true;
      block.clear();
    } else if (inside && line == "```") {
      inside = false;
      if (block.rfind("task:", 0) != 0) continue;
      ++tasks;
      EXPECT_EQ(error_of(block), "") << block;
    } else if (inside) {
      block += line + "\n";
    }
  }
  EXPECT_EQ(tasks, 5);  // five-point, Burmester, function, nine-point and path
}

TEST(SynthesisTask, DocumentErrors) {
  EXPECT_THAT(error_of(""), HasSubstr("task.yaml:1:1: the file holds no task"));
  EXPECT_THAT(error_of("task: [five-point\n"), HasSubstr("task.yaml:1:7: invalid YAML: this '[' is never closed"));
  EXPECT_EQ(error_of("- task: five-point\n"),
            "task.yaml:1:1: a task file is a mapping of keys (task:, ...), not a list");
  EXPECT_EQ(
      error_of("name: x\n"),
      "task.yaml:1:1: a task file needs `task: five-point`, `task: nine-point`, `task: burmester`, `task: function` or "
      "`task: path`");
  EXPECT_EQ(error_of("name: x\ntask: six-point\n"),
            "task.yaml:2:7: unknown task 'six-point' (tasks are: five-point, nine-point, burmester, function, path)");
  EXPECT_EQ(error_of("task: five-point\ntask: burmester\n"),
            "task.yaml:2:1: duplicate key 'task' (first given on line 1)");
  EXPECT_EQ(error_of("task: five-point\nposes: []\n"),
            "task.yaml:2:1: unknown key 'poses' in a five-point task (allowed: task, name, description, units, pivots, "
            "points)");
  EXPECT_EQ(error_of("task: five-point\nunits: {length: furlong}\n"),
            "task.yaml:2:17: unknown length unit 'furlong' (use m, mm, cm, in or ft)");
}

const std::string kFivePoint = R"(task: five-point
pivots: {a: [0, 0], b: [1, 0]}
points:
  - [0, 1]
  - [0.5, 1.2]
  - [1, 1.1]
  - [1.2, 0.6]
  - [0.3, 0.4]
)";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

TEST(SynthesisTask, FivePointErrors) {
  EXPECT_EQ(error_of(kFivePoint), "");
  EXPECT_EQ(error_of(replaced(kFivePoint, "  - [0.3, 0.4]\n", "")),
            "task.yaml:4:3: a five-point task needs exactly 5 points for the coupler point, not 4");
  EXPECT_EQ(error_of(replaced(kFivePoint, "b: [1, 0]", "b: [0, 0]")),
            "task.yaml:2:24: the fixed pivots a and b coincide: a four-bar needs two distinct fixed pivots");
  EXPECT_EQ(error_of(replaced(kFivePoint, "[1.2, 0.6]", "[0.5, 1.2]")),
            "task.yaml:7:5: points 2 and 4 coincide: the five points must be distinct");
  EXPECT_EQ(error_of(replaced(kFivePoint, "[1, 1.1]", "[1, abc]")),
            "task.yaml:6:9: point 3 must be a number, not 'abc'");
  EXPECT_EQ(error_of(replaced(kFivePoint, "[1, 1.1]", "[1, .nan]")),
            "task.yaml:6:9: point 3 must be a finite number, not '.nan'");
  EXPECT_EQ(error_of(replaced(kFivePoint, "[1, 1.1]", "[1]")),
            "task.yaml:6:5: point 3 needs two numbers, like [x, y], not a list of 1");
  EXPECT_EQ(error_of(replaced(kFivePoint, "{a: [0, 0], ", "{")), "task.yaml:2:9: `pivots` needs `a`");
  EXPECT_EQ(error_of(replaced(kFivePoint, "pivots: {a: [0, 0], b: [1, 0]}\n", "")),
            "task.yaml:1:1: a five-point task needs `pivots`");
  EXPECT_EQ(error_of(replaced(kFivePoint, "{a: [0, 0], b: [1, 0]}", "{a: [0, 0], c: [1, 0]}")),
            "task.yaml:2:21: unknown key 'c' in `pivots` (allowed: a, b)");
}

const std::string kThreePoses = R"(task: burmester
poses:
  - {point: [0, 0], angle: 0}
  - {point: [1, 0], angle: 30}
  - {point: [2, 1], angle: 60}
fixed_pivots: {a: [0, -1], b: [2, -1]}
)";

TEST(SynthesisTask, BurmesterErrors) {
  EXPECT_EQ(error_of(kThreePoses), "");
  EXPECT_EQ(error_of(replaced(kThreePoses, "  - {point: [2, 1], angle: 60}\n", "")),
            "task.yaml:3:3: a burmester task needs 3, 4 or 5 poses, not 2");
  EXPECT_EQ(error_of(replaced(kThreePoses, "fixed_pivots: {a: [0, -1], b: [2, -1]}\n", "")),
            "task.yaml:3:3: with 3 poses, choose two pivots: `fixed_pivots: {a: [x, y], b: [x, y]}` or "
            "`moving_pivots: {a: [x, y], b: [x, y]}` (on the coupler, in the first pose)");
  EXPECT_EQ(error_of(kThreePoses + "moving_pivots: {a: [0, 0], b: [1, 0]}\n"),
            "task.yaml:7:1: give either `fixed_pivots` or `moving_pivots`, not both");
  EXPECT_EQ(error_of(replaced(kThreePoses, ", angle: 30}", "}")), "task.yaml:4:5: a pose needs `angle`");
  EXPECT_EQ(error_of(replaced(kThreePoses, "{point: [2, 1], angle: 60}", "{point: [1, 0], angle: 30}")),
            "task.yaml:5:5: poses 2 and 3 are the same");
  EXPECT_EQ(error_of(kThreePoses + "samples: 10\n"),
            "task.yaml:7:1: `samples` applies to 4 poses only (the Burmester curves)");
  const std::string five = replaced(kThreePoses, "fixed_pivots: {a: [0, -1], b: [2, -1]}\n",
                                    "  - {point: [3, 3], angle: 90}\n  - {point: [2, 4], angle: 120}\n");
  EXPECT_EQ(error_of(five), "");
  EXPECT_EQ(error_of(five + "fixed_pivots: {a: [0, 0], b: [1, 0]}\n"),
            "task.yaml:8:1: `fixed_pivots` applies to 3 poses only; with 5 poses the pivots follow from the poses");
  const std::string four = replaced(five, "  - {point: [2, 4], angle: 120}\n", "");
  EXPECT_EQ(error_of(four + "samples: 1\n"), "task.yaml:7:10: `samples` must be a whole number from 2 to 200");
  EXPECT_EQ(error_of(four + "curves: {radius: -1}\n"), "task.yaml:7:18: the radius must be positive");
  // Poses 1.65831 m (RMS) from their centroid: a radius of 1e300 m leaves no curve to trace.
  EXPECT_EQ(error_of(four + "curves: {radius: 1e300}\n"),
            "task.yaml:7:18: the radius 1e+300 m is more than 10^6 times the size of the poses (1.65831 m, the RMS "
            "distance of their points from the centroid): no curve can be traced in so wide a window; give at most "
            "1.65831e+06 m, or leave `radius` out for 1.5 times the farthest pose or pole");
  EXPECT_EQ(error_of(four + "curves: {radius: 1.6e6}\n"), "");
}

const std::string kFunction = R"yaml(task: function
function: "log10(x)"
x: [1, 2]
input_range: [45, 105]
output_range: [135, 225]
)yaml";

TEST(SynthesisTask, FunctionErrors) {
  EXPECT_EQ(error_of(kFunction), "");
  // Syntax errors point at their character, in what the user wrote.
  const std::string bad = error_of(replaced(kFunction, "\"log10(x)\"", "\"log10(x) + * 2\""));
  EXPECT_THAT(bad, testing::StartsWith("task.yaml:2:23: in the function 'log10(x) + * 2': ")) << bad;
  EXPECT_THAT(error_of(replaced(kFunction, "\"log10(x)\"", "log10(x) + foo(x)")),
              testing::StartsWith("task.yaml:2:22: in the function 'log10(x) + foo(x)': "));
  EXPECT_EQ(error_of(replaced(kFunction, "\"log10(x)\"", "sin(t)")),
            "task.yaml:2:15: in the function 'sin(t)': unknown name 't' (the variable is x)");
  EXPECT_EQ(error_of(replaced(kFunction, "[1, 2]", "[-1, 2]")),
            "task.yaml:2:11: the function 'log10(x)' is undefined at x = -1, inside the range of x");
  EXPECT_EQ(error_of(replaced(kFunction, "\"log10(x)\"", "\"x*(x - 3)\"")),
            "task.yaml:2:11: the function has the same value at both ends of the range of x, so it cannot be mapped "
            "onto the output's range");
  EXPECT_EQ(error_of(replaced(kFunction, "[1, 2]", "[2, 2]")),
            "task.yaml:3:4: the range of x is empty: give two different values");
  EXPECT_EQ(error_of(replaced(kFunction, "[45, 105]", "[45, 45]")),
            "task.yaml:4:14: `input_range` is empty: give the angles at the start and the end of the range");
  EXPECT_EQ(error_of(kFunction + "points: 2\n"), "task.yaml:6:9: `points` must be a whole number from 3 to 50");
  EXPECT_EQ(error_of(kFunction + "spacing: random\n"),
            "task.yaml:6:10: unknown spacing 'random' (use chebyshev or even)");
  EXPECT_EQ(error_of(kFunction + "frame: 0\n"), "task.yaml:6:8: the frame length must be positive");
  EXPECT_EQ(error_of(replaced(kFunction, "input_range: [45, 105]\n", "")),
            "task.yaml:1:1: a function task needs `input_range`");
}

// As in model files, a misspelt key names the key it is a typo of, at every level.
TEST(SynthesisTask, MisspeltKeysSuggestTheRightOne) {
  EXPECT_EQ(error_of(replaced(kFivePoint, "pivots:", "pivot:")),
            "task.yaml:2:1: unknown key 'pivot' in a five-point task; did you mean 'pivots'?");
  EXPECT_EQ(error_of(kFunction + "spaceing: even\n"),
            "task.yaml:6:1: unknown key 'spaceing' in a function task; did you mean 'spacing'?");
  EXPECT_EQ(error_of("task: five-point\nunits: {lenght: mm}\n"),
            "task.yaml:2:9: unknown key 'lenght' in `units`; did you mean 'length'?");
  EXPECT_EQ(error_of(replaced(kThreePoses, "angle: 30", "angel: 30")),
            "task.yaml:4:21: unknown key 'angel' in `pose`; did you mean 'angle'?");
  const std::string four =
      replaced(kThreePoses, "fixed_pivots: {a: [0, -1], b: [2, -1]}\n", "  - {point: [3, 3], angle: 90}\n");
  EXPECT_EQ(error_of(four + "curves: {raduis: 5}\n"),
            "task.yaml:7:10: unknown key 'raduis' in `curves`; did you mean 'radius'?");
  // Nothing close enough: the allowed keys are listed instead.
  EXPECT_EQ(error_of(replaced(kFivePoint, "pivots:", "anchors:")),
            "task.yaml:2:1: unknown key 'anchors' in a five-point task (allowed: task, name, description, units, "
            "pivots, points)");
}

// A path task: twelve points on an ellipse.
const std::string kPath = R"(task: path
units: {length: mm, angle: deg}
points:
  - [50, 0]
  - [43.3, 10]
  - [25, 17.3]
  - [0, 20]
  - [-25, 17.3]
  - [-43.3, 10]
  - [-50, 0]
  - [-43.3, -10]
  - [-25, -17.3]
  - [0, -20]
  - [25, -17.3]
  - [43.3, -10]
constraints: {pivots: {min: [-100, -100], max: [100, 0]}, crank: true, min_transmission: 30, lengths: [5, 200]}
)";

TEST(SynthesisTask, PathWithPointsAndConstraints) {
  const SynthesisTask t = nbar::io::parse_synthesis_task(kPath, "task.yaml");
  EXPECT_EQ(t.kind, SynthesisKind::Path);
  ASSERT_EQ(t.points.size(), 12u);
  EXPECT_EQ(t.points[1], Eigen::Vector2d(43.3, 10));
  ASSERT_TRUE(t.constraints.region_min && t.constraints.region_max);
  EXPECT_EQ(*t.constraints.region_min, Eigen::Vector2d(-100, -100));
  EXPECT_EQ(*t.constraints.region_max, Eigen::Vector2d(100, 0));
  EXPECT_TRUE(t.constraints.crank);
  EXPECT_NEAR(t.constraints.min_transmission, 30 * kDegree, 1e-15);
  EXPECT_EQ(t.constraints.min_length, 5);
  EXPECT_EQ(t.constraints.max_length, 200);
  EXPECT_EQ(t.nine_point_starts, 0);
  EXPECT_EQ(nbar::io::parse_synthesis_task(kPath + "nine_point_starts: 2\n", "task.yaml").nine_point_starts, 2);
  EXPECT_EQ(error_of(kPath + "nine_point_starts: 11\n"),
            "task.yaml:17:20: `nine_point_starts` must be a whole number from 0 to 10");
}

TEST(SynthesisTask, PathFromACurveFile) {
  const SynthesisTask t = nbar::io::load_synthesis_task(kDir + "path/d-shape.yaml");
  EXPECT_EQ(t.kind, SynthesisKind::Path);
  ASSERT_EQ(t.points.size(), 24u);
  EXPECT_EQ(t.points[0], Eigen::Vector2d(0, 0));
  EXPECT_EQ(t.points[9], Eigen::Vector2d(120, 0));
  EXPECT_EQ(t.curve_file, kDir + "path/d-shape.csv");
}

TEST(SynthesisTask, PathErrors) {
  EXPECT_EQ(error_of(kPath), "");
  EXPECT_EQ(error_of(replaced(kPath, "  - [0, -20]\n  - [25, -17.3]\n  - [43.3, -10]\n", "")),
            "task.yaml:4:3: a path task needs at least 10 target points, not 9 (with 5 points and both pivots, use "
            "`task: five-point`)");
  EXPECT_EQ(error_of(replaced(kPath, "[-25, 17.3]", "[43.3, 10]")),
            "task.yaml:8:5: points 2 and 5 coincide: the coupler point meets each target once");
  EXPECT_EQ(error_of(replaced(kPath, "  - [43.3, -10]\n", "  - [43.3, -10]\n  - [50, 0]\n")),
            "task.yaml:16:5: points 1 and 13 coincide: the coupler point meets each target once (a closed curve is "
            "given once round: leave out the last point)");
  std::string line = "task: path\npoints:\n";
  for (int k = 0; k < 12; ++k) line += "  - [" + std::to_string(k) + ", " + std::to_string(3 * k - 1) + "]\n";
  EXPECT_EQ(error_of(line),
            "task.yaml:3:3: the target points lie on one straight line: a path task fits a "
            "four-bar's coupler curve to points spread over a curve");
  EXPECT_EQ(error_of(replaced(kPath, "[0, 20]", "[0, x]")), "task.yaml:7:9: point 4 must be a number, not 'x'");
  EXPECT_EQ(error_of(replaced(kPath, "units:", "curve: c.csv\nunits:")),
            "task.yaml:2:1: give the targets as `points` or as a `curve` file, not both");
  EXPECT_EQ(error_of("task: path\n"),
            "task.yaml:1:1: a path task needs its target points: `points: [[x, y], ...]` (10 or more) or "
            "`curve: FILE.csv`");
  EXPECT_EQ(error_of(replaced(kPath, "crank: true", "crank: yes please")),
            "task.yaml:16:66: `crank` is true or false, not 'yes please'");
  EXPECT_EQ(error_of(replaced(kPath, "min_transmission: 30", "min_transmission: 95")),
            "task.yaml:16:90: `min_transmission` must be at least 0 and less than a right angle (90 deg, the best a "
            "linkage can keep)");
  EXPECT_EQ(error_of(replaced(kPath, "max: [100, 0]", "max: [100, -100]")),
            "task.yaml:16:48: the pivots' region is empty: max must exceed min in x and in y");
  EXPECT_EQ(error_of(replaced(kPath, "lengths: [5, 200]", "lengths: [50, 20]")),
            "task.yaml:16:103: `lengths` is [min, max] with 0 <= min < max");
  EXPECT_EQ(
      error_of(replaced(kPath, "crank: true", "crank: true, grashof: 1")),
      "task.yaml:16:72: unknown key 'grashof' in `constraints` (allowed: pivots, crank, min_transmission, lengths)");
}

// A task parsed from text (a web client's, Python's task()) opens no file: `curve` is refused
// at its value, whether or not the file exists; loaded from a file, the same task reads it.
TEST(SynthesisTask, TaskFromTextReadsNoCurveFile) {
  const std::string text = "task: path\ncurve: " + kDir + "path/d-shape.csv\n";
  EXPECT_EQ(error_of(text),
            "task.yaml:2:8: `curve` reads a CSV file, which only a task read from a file may do: give "
            "the targets here as `points: [[x, y], ...]`");
  EXPECT_EQ(error_of("task: path\ncurve: /nonexistent.csv\n"),
            "task.yaml:2:8: `curve` reads a CSV file, which only a task read from a file may do: give the targets here "
            "as `points: [[x, y], ...]`");
  EXPECT_GE(nbar::io::load_synthesis_task(kDir + "path/d-shape.yaml").points.size(), 10u);
}

// The CSV's own mistakes are reported at its line and column.
// A target typed 1000 times too far ran a nine-point synthesis for minutes: refused at once, at it.
TEST(SynthesisTask, ATargetFarOutsideTheOthersScaleIsRefusedAtIt) {
  std::ifstream in(kDir + "nine-point-crank-rocker.yaml");
  std::string nine((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_NE(nine.find("[49.680, 126.456]"), std::string::npos);
  EXPECT_EQ(error_of(nine), "");
  nine.replace(nine.find("[49.680, 126.456]"), 17, "[49680, 126.456]");
  // The coordinate-wise median is (15.369, 186.731); the median distance from it 101.04 mm, point 9's 49 664.7.
  EXPECT_THAT(error_of(nine), HasSubstr("task.yaml:19:5: point 9 is 492 times as far from the middle of the targets as "
                                        "a typical one is; a coupler point's targets lie within 100 times that: check "
                                        "its digits and the units"));
  EXPECT_EQ(error_of(replaced(kPath, "[-25, 17.3]", "[-25, 1730]")), "");  // 69 times: a strange curve, not a typo
  EXPECT_THAT(error_of(replaced(kPath, "[-25, 17.3]", "[-25000, 17.3]")), HasSubstr("task.yaml:8:5: point 5 is "));
}

TEST(SynthesisTask, PathCurveFileErrors) {
  const fs::path dir = fs::temp_directory_path() / ("nbar_path_task_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const auto load_error = [&](const std::string& csv) {
    std::ofstream(dir / "c.csv") << csv;
    std::ofstream(dir / "t.yaml") << "task: path\ncurve: c.csv\n";
    try {
      nbar::io::load_synthesis_task((dir / "t.yaml").string());
    } catch (const nbar::io::ModelFileError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  std::string good = "x,y\n";
  for (int k = 0; k < 12; ++k)
    good += std::to_string(std::cos(k * 0.5)) + ", " + std::to_string(std::sin(k * 0.5)) + "\n";
  EXPECT_EQ(load_error(good), "");
  const std::string c = (dir / "c.csv").string(), t = (dir / "t.yaml").string();
  EXPECT_EQ(load_error(good + "1, 2, 3\n"), c + ":14:1: a line holds two numbers, x and y (found 3 fields)");
  EXPECT_EQ(load_error(good + "\n# a comment\n0.5; zero\n"), c + ":16:6: 'zero' is not a finite number (y)");
  EXPECT_EQ(load_error(good + "nan, 1\n"), c + ":14:1: 'nan' is not a finite number (x)");
  EXPECT_EQ(load_error(good + "1.000000, 0.000000\n"),
            c + ":14:1: points 1 and 13 coincide: the coupler point meets each target once (a closed curve is given "
                "once round: leave out the last point)");
  EXPECT_EQ(load_error("x,y\n1,2\n3,1\n"), t + ":2:8: a path task needs at least 10 target points (in " + c +
                                               "), not 2 (with 5 points and both pivots, use `task: five-point`)");
  std::ofstream(dir / "missing.yaml") << "task: path\ncurve: missing.csv\n";
  try {
    nbar::io::load_synthesis_task((dir / "missing.yaml").string());
    ADD_FAILURE() << "a missing curve file is an error";
  } catch (const nbar::io::ModelFileError& e) {
    EXPECT_THAT(e.what(), HasSubstr("missing.yaml:2:8: `curve`: cannot read " + (dir / "missing.csv").string() + ": "));
  }
  fs::remove_all(dir);
}

TEST(SynthesisTask, UnreadableFile) {
  try {
    nbar::io::load_synthesis_task("/nonexistent/task.yaml");
    FAIL();
  } catch (const nbar::io::ModelFileError& e) {
    EXPECT_EQ(std::string(e.what()), "/nonexistent/task.yaml: cannot read: No such file or directory");
  }
}

}  // namespace

namespace {

TEST(SynthesisTask, AnglesBeyondAMillionTurnsAreRefusedAtTheirPlace) {
  // 1e308 deg is 296 deg round, but in radians it keeps no digit of that: Burmester designed a
  // coupler turning 104 deg to it and called the design exact.
  const std::string burmester = R"(task: burmester
poses:
  - {point: [0, 0], angle: 0}
  - {point: [1, 0], angle: 10}
  - {point: [2, 1], angle: 1e308}
fixed_pivots: {a: [0, 5], b: [3, 5]}
)";
  EXPECT_THAT(error_of(burmester), HasSubstr("task.yaml:5:"));
  EXPECT_THAT(error_of(burmester), HasSubstr("the pose's angle is beyond a million turns"));
  EXPECT_EQ(error_of(replaced(burmester, "1e308", "360000000")), "");  // a million turns exactly
  const std::string function = R"yaml(task: function
function: "log10(x)"
x: [1, 2]
input_range: [0, 1e308]
output_range: [0, 60]
)yaml";
  EXPECT_THAT(error_of(function), HasSubstr("task.yaml:4:14: `input_range` is beyond a million turns"));
  // A frame of 1e308 gave "the coupler length squared comes out as -nan"; 1e-160 a design of
  // other proportions, silently.
  const std::string framed = replaced(function, "input_range: [0, 1e308]", "input_range: [0, 90]\nframe: 1e308");
  EXPECT_THAT(error_of(framed), HasSubstr("task.yaml:5:8: the frame length must be from 1e-100 to 1e100"));
  EXPECT_THAT(error_of(replaced(framed, "1e308", "1e-160")),
              HasSubstr("the frame length must be from 1e-100 to 1e100"));
  EXPECT_EQ(error_of(replaced(framed, "1e308", "1e20")), "");
}

}  // namespace
