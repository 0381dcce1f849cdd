// Plates bounded by circular arcs (bulges, as DXF writes them): the exact mass properties
// against closed forms worked by hand, against a fine polygonisation, and the consumers that
// need straight edges (validation, sections) seeing the true outline.
#include "nbar/model/diagnostics.hpp"
#include "nbar/model/geometry.hpp"
#include "nbar/stress/section.hpp"
#include "test_constants.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace nbar {
namespace {

using Eigen::Vector2d;
using nbar::test_constants::kPi;
using ::testing::HasSubstr;

void expect_props(const AreaProperties& a, double area, const Vector2d& centroid, double ixx, double iyy, double ixy,
                  double size, double rel) {
  const double l2 = size * size, l4 = l2 * l2;
  EXPECT_NEAR(a.area, area, rel * l2);
  EXPECT_NEAR(a.centroid.x(), centroid.x(), rel * size);
  EXPECT_NEAR(a.centroid.y(), centroid.y(), rel * size);
  EXPECT_NEAR(a.ixx, ixx, rel * l4);
  EXPECT_NEAR(a.iyy, iyy, rel * l4);
  EXPECT_NEAR(a.ixy, ixy, rel * l4);
}

void expect_same(const AreaProperties& a, const AreaProperties& e, double size, double rel) {
  expect_props(a, e.area, e.centroid, e.ixx, e.iyy, e.ixy, size, rel);
}

// A slot: the rectangle [0, L] x [-R, R] with half discs on both ends, counterclockwise.
Region stadium(double length, double radius) {
  Region r;
  r.outline = {{0, -radius}, {length, -radius}, {length, radius}, {0, radius}};
  r.outline_bulges = {0, 1, 0, 1};
  return r;
}

TEST(ArcArea, HalfDiscByBulge) {
  const double R = 0.05;
  Region r;
  r.outline = {{R, 0}, {-R, 0}};  // the arc from (R, 0) over the top, then the diameter back
  r.outline_bulges = {1, 0};
  EXPECT_NO_THROW(check_region(r));
  const double ybar = 4 * R / (3 * kPi);
  expect_props(area_properties(r), kPi * R * R / 2, {0, ybar}, (kPi / 8 - 8 / (9 * kPi)) * std::pow(R, 4),
               kPi * std::pow(R, 4) / 8, 0, R, 1e-13);
}

TEST(ArcArea, StadiumClosedForm) {
  const double L = 0.2, R = 0.03;
  const Region r = stadium(L, R);
  EXPECT_NO_THROW(check_region(r));
  // Each end is a half disc: about its flat side πR⁴/8, its centroid 4R/3π beyond it.
  const double half = kPi * R * R / 2, e = 4 * R / (3 * kPi);
  const double end_iyy = kPi * std::pow(R, 4) / 8 - half * e * e + half * std::pow(L / 2 + e, 2);
  expect_props(area_properties(r), 2 * R * L + kPi * R * R, {L / 2, 0},
               L * std::pow(2 * R, 3) / 12 + kPi * std::pow(R, 4) / 4, 2 * R * std::pow(L, 3) / 12 + 2 * end_iyy, 0, L,
               1e-13);
}

TEST(ArcArea, ClockwiseStadiumWeighsTheSame) {
  Region r;
  r.outline = {{0, 0.03}, {0.2, 0.03}, {0.2, -0.03}, {0, -0.03}};
  r.outline_bulges = {0, -1, 0, -1};  // clockwise: an outward arc bulges to the left
  EXPECT_NO_THROW(check_region(r));
  expect_same(area_properties(r), area_properties(stadium(0.2, 0.03)), 0.2, 1e-13);
}

TEST(ArcArea, QuarterDiscThroughAPoint) {
  const double R = 2.0;
  const Vector2d a(R, 0), b(0, R), m(R / std::sqrt(2.0), R / std::sqrt(2.0));
  EXPECT_NEAR(bulge_through(a, b, m), std::tan(kPi / 8), 1e-15);
  EXPECT_NEAR(bulge_through(b, a, m), -std::tan(kPi / 8), 1e-15);
  Region r;
  r.outline = {{0, 0}, a, b};
  r.outline_bulges = {0, bulge_through(a, b, m), 0};
  const double c = 4 * R / (3 * kPi), quarter = kPi * R * R / 4;
  const double i0 = kPi * std::pow(R, 4) / 16;  // about either straight side
  expect_props(area_properties(r), quarter, {c, c}, i0 - quarter * c * c, i0 - quarter * c * c,
               std::pow(R, 4) / 8 - quarter * c * c, R, 1e-13);
}

TEST(ArcArea, MajorSegmentAndArcGeometry) {
  // Bulge 2: an arc of 4 atan 2 (253.7°) over a chord of 2, radius 1.25.
  const double beta = 2, theta = 4 * std::atan(beta), rho = 1.25;
  const Arc arc = arc_from_bulge({-1, 0}, {1, 0}, beta);
  EXPECT_NEAR(arc.radius, rho, 1e-15);
  EXPECT_NEAR(arc.sweep, theta, 1e-15);
  EXPECT_NEAR(arc.centre.x(), 0, 1e-15);
  EXPECT_NEAR(arc.centre.y(), -0.75, 1e-15);  // below the chord: the arc goes round underneath
  Region r;
  r.outline = {{-1, 0}, {1, 0}};
  r.outline_bulges = {beta, 0};
  EXPECT_NO_THROW(check_region(r));
  const AreaProperties a = area_properties(r);
  EXPECT_NEAR(a.area, rho * rho / 2 * (theta - std::sin(theta)), 1e-14);
  // The segment's centroid from the centre: 4 r sin³(θ/2) / (3 (θ − sin θ)), towards the arc.
  const double from_centre = 4 * rho * std::pow(std::sin(theta / 2), 3) / (3 * (theta - std::sin(theta)));
  EXPECT_NEAR(a.centroid.y(), -0.75 - from_centre, 1e-14);
}

TEST(ArcArea, AgreesWithAFinePolygonisation) {
  // A plate with a rounded end, a concave notch and a slot-shaped hole with arcs.
  Region r;
  r.outline = {{0, 0}, {0.1, 0}, {0.1, 0.04}, {0.05, 0.04}, {0.03, 0.04}, {0, 0.04}};
  r.outline_bulges = {0, 1, 0, -0.6, 0, 0.3};
  r.polygon_holes = {{{0.06, 0.015}, {0.08, 0.015}, {0.08, 0.025}, {0.06, 0.025}}};
  r.polygon_hole_bulges = {{0, 1, 0, 1}};
  ASSERT_NO_THROW(check_region(r));
  const AreaProperties exact = area_properties(r);
  const AreaProperties fine = area_properties(polygonised(r, 1e-8));
  expect_same(exact, fine, 0.1, 1e-6);
  // The default polygonisation loses less than its tolerance (1e-5 of the 0.132 m box diagonal)
  // times the arcs' length (under 0.4 m) in area.
  expect_same(exact, area_properties(straight_edged(r)), 0.1, 1e-4);
  EXPECT_NEAR(area_properties(straight_edged(r)).area, exact.area, kRelativeChordTolerance * 0.132 * 0.4);
}

TEST(ArcArea, PolygonisedChordsStayWithinTheTolerance) {
  const Region r = stadium(0.2, 0.03);
  const double tolerance = 1e-4;
  const Region p = polygonised(r, tolerance);
  for (std::size_t i = 0; i + 1 < p.outline.size(); ++i) {
    const Vector2d a = p.outline[i], b = p.outline[i + 1];
    const Vector2d centre = a.x() > 0.1 ? Vector2d(0.2, 0) : Vector2d(0, 0);
    if (a.y() == b.y()) continue;  // the straight sides
    EXPECT_NEAR((a - centre).norm(), 0.03, 1e-15);
    EXPECT_LE(0.03 - ((a + b) / 2 - centre).norm(), tolerance);  // the chord's middle, the farthest from the arc
  }
}

TEST(ArcSection, CutsTheTrueArc) {
  // A cut across the rounded end, R/2 beyond its centre: the chord 2 sqrt(R² − (R/2)²).
  const double L = 0.2, R = 0.03;
  const auto intervals = section_intervals(stadium(L, R), {L + R / 2, 0}, {0, 1});
  ASSERT_EQ(intervals.size(), 1u);
  const double width = intervals[0].second - intervals[0].first;
  // The chords stray at most tol from the arc, radially; the cut meets the arc at 60 degrees
  // from the slot's axis, where a radial miss of tol moves the crossing by tol / sin 60°.
  const double tol = kRelativeChordTolerance * std::hypot(L + 2 * R, 2 * R);
  const double exact = 2 * std::sqrt(R * R - R * R / 4);
  EXPECT_NEAR(width, exact, 2 * tol / std::sin(kPi / 3));
  EXPECT_LE(width, exact);  // chords inside the convex arc
  // The part beyond the cut: the circular segment at h = R/2, less at most tol along its arc.
  const AreaProperties beyond = clipped_area_properties(stadium(L, R), {L + R / 2, 0}, {1, 0});
  const double theta = 2 * std::acos(0.5);
  EXPECT_NEAR(beyond.area, R * R / 2 * (theta - std::sin(theta)), tol * R * theta);
}

TEST(ArcCheck, ArcCrossingAnEdgeIsNamedByTheUsersEdges) {
  Region r;
  r.outline = {{0, 0}, {4, 0}, {4, 10}, {0, 10}};
  r.outline_bulges = {0, -1, 0, 0};  // edge 1-2 bulges inwards, 5 deep, past the far side
  try {
    check_region(r);
    FAIL() << "accepted an outline whose arc crosses an edge";
  } catch (const nbar::Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("the outline intersects itself: edge 1-2 meets edge 3-0"));
  }
}

TEST(ArcCheck, HoleMustClearTheArcNotItsChord) {
  Region r = stadium(0.2, 0.03);
  r.circle_holes = {{{0.215, 0}, 0.01}};  // beyond the chord polygon, inside the rounded end
  EXPECT_NO_THROW(check_region(r));
  r.circle_holes = {{{0.225, 0}, 0.01}};  // reaches 0.235 > 0.23, the arc's far end
  EXPECT_THROW(check_region(r), nbar::Error);
}

TEST(ArcCheck, BadBulges) {
  Region r = stadium(0.2, 0.03);
  r.outline_bulges = {0, 1, 0};
  EXPECT_THROW(check_region(r), nbar::Error);
  r.outline_bulges = {0, std::nan(""), 0, 1};
  EXPECT_THROW(check_region(r), nbar::Error);
  Region two;
  two.outline = {{0, 0}, {1, 0}};
  EXPECT_THROW(check_region(two), nbar::Error);  // two vertices and no arc: no area
  r.outline_bulges = {0, 1e300, 0, 1};
  EXPECT_THROW(check_region(r), nbar::Error);
  r.outline_bulges = {0, std::numeric_limits<double>::infinity(), 0, 1};
  EXPECT_THROW(check_region(r), nbar::Error);
  EXPECT_THROW(bulge_through({0, 0}, {1, 0}, {2, 0}), nbar::Error);
  EXPECT_THROW(bulge_through({0, 0}, {1, 0}, {1, 0}), nbar::Error);
}

}  // namespace
}  // namespace nbar
