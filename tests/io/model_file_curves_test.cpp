// Curves in a shape's outline: parametric curves, function profiles (the thesis tool's
// upper and lower profiles and its "f{a, b, steps}"), splines; mass properties exact on the
// polygon and within the stated accuracy of the curve.
#include "io/model_file_support.hpp"
#include "nbar/io/model_file.hpp"
#include "nbar/model/curves.hpp"
#include "nbar/model/geometry.hpp"
#include "test_constants.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

namespace nbar::io {
namespace {

using nbar::test_constants::kPi;
using test_support::fails_at;

// A link in metres (as the thesis tool works) whose plate is given from line 8 onwards.
std::string link(const std::string& shape_lines) {
  return "units: {length: m}\n"              // 1
         "points: {O: [0, 0], A: [0, 2]}\n"  // 2
         "ground: [O]\n"                     // 3
         "bodies:\n"                         // 4
         "  link:\n"                         // 5
         "    points: [O, A]\n"              // 6
         "    thickness: 0.01\n"             // 7
         "    material: steel\n"             // 8
         "    shape:\n" +                    // 9
         shape_lines;                        // 10...
}

AreaProperties plate(const std::string& shape_lines) {
  return area_properties(*parse_model(link(shape_lines), "m.yaml").model.bodies[0].shape);
}

// The thesis tool's worked example: the lower profile x^2{0, 2, 15}, the upper 4{0, 2, 2},
// joints at (0, 0) and (0, 2). Its polygon has the parabola's 16 points (15 steps, f(2)
// added) and the upper line's 3, the two meeting at (2, 4); its area is 8 minus the
// trapezoid rule's area under x^2.
TEST(ModelFileCurves, ThesisFunctionProfileExample) {
  const Model m = parse_model(link("      lower: \"x^2{0, 2, 15}\"\n      upper: \"4{0, 2, 2}\"\n"), "m.yaml").model;
  const Region& r = *m.bodies[0].shape;
  ASSERT_EQ(r.outline.size(), 18u);  // 16 below, (1, 4) and (0, 4) above
  EXPECT_TRUE(r.outline_bulges.empty());
  const double h = 2.0 / 15;
  double under = 0, moment_x = 0;
  for (int k = 0; k < 15; ++k) {
    const double x0 = k * h, x1 = x0 + h;
    under += h * (x0 * x0 + x1 * x1) / 2;
    // ∫ x over the trapezoid under the chord from (x0, x0²) to (x1, x1²).
    const double f0 = x0 * x0, f1 = x1 * x1, slope = (f1 - f0) / h;
    moment_x += (f0 - slope * x0) * (x1 * x1 - x0 * x0) / 2 + slope * (x1 * x1 * x1 - x0 * x0 * x0) / 3;
  }
  const AreaProperties a = area_properties(r);
  EXPECT_NEAR(a.area, 8 - under, 1e-14);
  EXPECT_NEAR(a.area, 5.327407407407, 1e-12);  // 16/3 - 2 (2/15)^2 / 6
  EXPECT_NEAR(a.centroid.x(), (8 - moment_x) / (8 - under), 1e-14);
  // The same profile without steps, adaptive: within the stated accuracy of the exact curve,
  // area 16/3, centroid (3/4, 12/5).
  const AreaProperties exact = plate("      lower: {y: \"x^2\", x: [0, 2]}\n      upper: {y: \"4\", x: [0, 2]}\n");
  const double tolerance = kRelativeCurveTolerance * std::sqrt(2.0 * 2 + 4 * 4);
  const double parabola_length = 4.646783762432936;  // ∫ sqrt(1 + 4x²) dx over [0, 2]
  EXPECT_LT(std::abs(exact.area - 16.0 / 3), 2.0 / 3 * tolerance * parabola_length);
  EXPECT_NEAR(exact.centroid.x(), 0.75, 1e-3);
  EXPECT_NEAR(exact.centroid.y(), 2.4, 1e-3);
}

TEST(ModelFileCurves, ParametricEllipseAndMixedItems) {
  // An ellipse 0.4 x 0.2 m by its parametric form: area π a b within the stated accuracy.
  const AreaProperties e = plate("      outline: [{x: \"0.2*cos(s)\", y: \"0.1*sin(s) + 1\", s: [0, 2*pi]}]\n");
  const double tolerance = kRelativeCurveTolerance * std::sqrt(0.4 * 0.4 + 0.2 * 0.2);
  EXPECT_LT(std::abs(e.area - kPi * 0.02), 2.0 / 3 * tolerance * 0.9689);  // perimeter 0.9689 m
  EXPECT_NEAR(e.centroid.y(), 1.0, 1e-12);
  // A D shape: a straight edge, then a half circle as a curve from (1, 0) round to (-1, 0).
  const AreaProperties d = plate("      outline: [[-1, 0], {x: \"cos(s)\", y: \"sin(s)\", s: [0, pi], steps: 400}]\n");
  EXPECT_NEAR(d.area, kPi / 2, 1e-4);
  // y = f(x) and x = f(y) profiles in one outline: under y = 1 - x^2 and above y = 0.
  const AreaProperties p = plate("      outline: [{y: \"1 - x^2\", x: [1, -1]}]\n");
  EXPECT_NEAR(p.area, 4.0 / 3, 1e-3);
  const AreaProperties q = plate("      outline: [{x: \"y^2 - 1\", y: [-1, 1]}]\n");
  EXPECT_NEAR(q.area, 4.0 / 3, 1e-3);
}

TEST(ModelFileCurves, SplineOutlines) {
  // A closed spline through a square's corners and edge midpoints... of a circle's 12 points.
  std::string points;
  for (int k = 0; k <= 12; ++k) {
    const double t = 2 * kPi * (k % 12) / 12;
    points +=
        (k ? ", " : "") + std::string("[") + std::to_string(std::cos(t)) + ", " + std::to_string(std::sin(t)) + "]";
  }
  const AreaProperties closed = plate("      outline: [{spline: [" + points + "]}]\n");
  EXPECT_NEAR(closed.area, kPi, 5e-3);
  EXPECT_NEAR(closed.centroid.norm(), 0, 1e-4);
  // An open spline through points on a line, closed by two vertices: a rectangle.
  const AreaProperties open = plate("      outline: [{spline: [[0, 0], [1, 0], [3, 0]]}, [3, 1], [0, 1]]\n");
  EXPECT_NEAR(open.area, 3.0, 1e-12);
}

TEST(ModelFileCurves, Errors) {
  EXPECT_TRUE(fails_at(link("      outline: [{x: \"cos(s\", y: \"sin(s)\", s: [0, 6]}]\n"), "10:27", "expected"));
  EXPECT_TRUE(fails_at(link("      outline: [{y: \"sqrt(x)\", x: [-1, 1]}, [0, 3]]\n"), "10:17",
                       "this curve: law 'sqrt(x)' is undefined at x = -1"));
  EXPECT_TRUE(fails_at(link("      outline: [{y: \"x^2\"}, [0, 3]]\n"), "10:17", "needs its interval"));
  EXPECT_TRUE(
      fails_at(link("      outline: [{y: \"x^2{0, 2}\"}, [0, 3]]\n"), "10:21", "braces hold {from, to, steps}"));
  EXPECT_TRUE(fails_at(link("      outline: [{x: \"s\", y: \"s\", s: [0, 1], bend: 2}, [0, 3]]\n"), "10:45", "bend"));
  EXPECT_TRUE(fails_at(link("      lower: \"x^2{0, 2, 15}\"\n"), "10:7", "needs both `lower` and `upper`"));
  // The upper profile dips below the lower one: the outline crosses itself, at the items' lines.
  EXPECT_TRUE(
      fails_at(link("      lower: \"x^2{0, 2, 15}\"\n      upper: \"1{0, 2, 2}\"\n"), "10:14", "intersects itself"));
  EXPECT_TRUE(fails_at(link("      lower: \"x^2{0, 2, 15}\"\n      upper: \"1{0, 2, 2}\"\n"), "10:14",
                       "(of the item at line 11)"));
}

}  // namespace
}  // namespace nbar::io
