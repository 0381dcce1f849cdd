// Curves turned into outline vertices: the adaptive sampling keeps the accuracy it states,
// splines pass through their points and are exact where a cubic is, and a rational B-spline
// draws a circle exactly.
#include "nbar/model/curves.hpp"
#include "nbar/model/diagnostics.hpp"
#include "nbar/model/geometry.hpp"
#include "test_constants.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace nbar {
namespace {

using Eigen::Vector2d;
using nbar::test_constants::kPi;

double polygon_area(const std::vector<Vector2d>& v) {
  Region r;
  r.outline = v;
  return std::abs(area_properties(r).area);
}

TEST(Curves, AdaptiveCircleStaysWithinTheTolerance) {
  const double radius = 50, tolerance = 1e-3;
  const auto circle = [&](double s) { return Vector2d(radius * std::cos(s), radius * std::sin(s)); };
  std::vector<Vector2d> v = sample_curve(circle, 0, 2 * kPi, tolerance);
  ASSERT_EQ(v.back(), circle(2 * kPi));
  v.pop_back();
  // Every chord's sagitta r (1 - cos(θ/2)) is within the tolerance, and not far below it:
  // halving stops one step after the bound is met.
  double worst = 0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const double chord = (v[(i + 1) % v.size()] - v[i]).norm();
    worst = std::max(worst, radius - std::sqrt(radius * radius - chord * chord / 4));
  }
  EXPECT_LE(worst, tolerance);
  EXPECT_GT(worst, tolerance / 4);
  // The area falls short of π r² by less than the stated (2/3) tolerance × length.
  const double shortfall = kPi * radius * radius - polygon_area(v);
  EXPECT_GT(shortfall, 0);
  EXPECT_LT(shortfall, 2.0 / 3 * tolerance * 2 * kPi * radius);
}

TEST(Curves, UniformStepsAreTheThesisConvention) {
  // x^2{0, 2, 15}: 15 equal steps, f(2) included: 16 vertices.
  const auto parabola = [](double x) { return Vector2d(x, x * x); };
  const std::vector<Vector2d> v = sample_curve_uniform(parabola, 0, 2, 15);
  ASSERT_EQ(v.size(), 16u);
  EXPECT_DOUBLE_EQ(v[1].x(), 2.0 / 15);
  EXPECT_EQ(v.back(), Vector2d(2, 4));
}

TEST(Curves, CurveThatNeverSettlesIsRefused) {
  const auto wild = [](double s) { return Vector2d(s, s > 0 ? std::sin(1 / s) : 0.0); };
  EXPECT_THROW(sample_curve(wild, 0, 1, 1e-9), nbar::Error);
  EXPECT_THROW(sample_curve(wild, 0, 1, 0), nbar::Error);
}

TEST(Curves, SplineThroughPointsOnALineIsTheLine) {
  const CubicSpline line({{0, 0}, {1, 2}, {3, 6}, {4, 8}}, false);
  for (double s = 0; s <= line.end(); s += 0.37) {
    const Vector2d p = line(s);
    EXPECT_NEAR(p.y(), 2 * p.x(), 1e-12);
  }
  EXPECT_NEAR((line(line.knots()[2]) - Vector2d(3, 6)).norm(), 0, 1e-12);
}

TEST(Curves, PeriodicSplineThroughACirclesPointsIsCloseToTheCircle) {
  std::vector<Vector2d> points;
  for (int k = 0; k < 24; ++k) points.emplace_back(10 * std::cos(2 * kPi * k / 24), 10 * std::sin(2 * kPi * k / 24));
  const CubicSpline closed(points, true);
  std::vector<Vector2d> v = sample_spline(closed, 1e-5);
  v.pop_back();  // the first point again
  double worst = 0;
  for (const Vector2d& p : v) worst = std::max(worst, std::abs(p.norm() - 10));
  EXPECT_LT(worst, 2e-4);  // a 24-point interpolating spline of a circle: ~1e-4 of the radius
  EXPECT_NEAR(polygon_area(v), kPi * 100, 0.02);
  EXPECT_THROW(CubicSpline({{0, 0}, {0, 0}, {1, 1}}, false), nbar::Error);
}

TEST(Curves, RationalQuadraticBSplineIsAnExactQuarterCircle) {
  const double w = std::sqrt(0.5);
  const BSpline quarter(2, {{1, 0}, {1, 1}, {0, 1}}, {0, 0, 0, 1, 1, 1}, {1, w, 1});
  for (double u = 0; u <= 1; u += 0.125) EXPECT_NEAR(quarter(u).norm(), 1.0, 1e-15);
  EXPECT_NEAR((quarter(1) - Vector2d(0, 1)).norm(), 0, 1e-15);
  EXPECT_THROW(BSpline(2, {{1, 0}, {1, 1}, {0, 1}}, {0, 0, 1, 1}, {}), nbar::Error);
}

TEST(Curves, CubicBezierEnds) {
  const Vector2d a(0, 0), b(1, 2), c(3, 2), d(4, 0);
  EXPECT_EQ(cubic_bezier(a, b, c, d, 0), a);
  EXPECT_EQ(cubic_bezier(a, b, c, d, 1), d);
  EXPECT_NEAR(cubic_bezier(a, b, c, d, 0.5).y(), 1.5, 1e-15);  // (3·2 + 3·2)/8
}

}  // namespace
}  // namespace nbar
