// Plate geometry against closed forms worked by hand, against brute-force quadrature, and as
// properties over random plates: the two sides of any cut add up to the whole, and the results
// move rigidly with the plate.
#include "nbar/model/geometry.hpp"
#include "model/region_support.hpp"
#include "nbar/model/diagnostics.hpp"
#include "test_constants.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace nbar {
namespace {

using Eigen::Vector2d;
using Polygon = std::vector<Vector2d>;
using nbar::test_constants::kPi;
using ::testing::HasSubstr;

Polygon rectangle(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

Polygon reversed(Polygon p) {
  std::reverse(p.begin(), p.end());
  return p;
}

Vector2d rotate(const Vector2d& v, double angle) {
  return {std::cos(angle) * v.x() - std::sin(angle) * v.y(), std::sin(angle) * v.x() + std::cos(angle) * v.y()};
}

// Built member by member: a hand computation to compare against.
AreaProperties props(double area, Vector2d centroid, double ixx, double iyy, double ixy) {
  AreaProperties p;
  p.area = area;
  p.centroid = centroid;
  p.ixx = ixx;
  p.iyy = iyy;
  p.ixy = ixy;
  return p;
}

// `size` is the length scale of the plate: areas compare to size^2, moments to size^4.
void expect_near(const AreaProperties& a, const AreaProperties& e, double size, double rel = 1e-12) {
  const double l2 = size * size, l4 = l2 * l2;
  EXPECT_NEAR(a.area, e.area, rel * l2);
  EXPECT_NEAR(a.centroid.x(), e.centroid.x(), rel * size);
  EXPECT_NEAR(a.centroid.y(), e.centroid.y(), rel * size);
  EXPECT_NEAR(a.ixx, e.ixx, rel * l4);
  EXPECT_NEAR(a.iyy, e.iyy, rel * l4);
  EXPECT_NEAR(a.ixy, e.ixy, rel * l4);
}

// Rectangle b x h centred at c, turned by angle: the rotation formulas for second moments,
// written out (not through transformed()).
AreaProperties rotated_rectangle(double b, double h, const Vector2d& c, double angle) {
  const double ix = b * h * h * h / 12, iy = h * b * b * b / 12;  // ∫y², ∫x² in the rectangle's frame
  const double cs = std::cos(angle), sn = std::sin(angle);
  return props(b * h, c, cs * cs * ix + sn * sn * iy, sn * sn * ix + cs * cs * iy, sn * cs * (iy - ix));
}

Region plate(Polygon outline) {
  Region r;
  r.outline = std::move(outline);
  return r;
}

// ---- closed forms ----

TEST(AreaProperties, Rectangle) {
  const double b = 0.3, h = 0.12;
  const AreaProperties a = area_properties(plate(rectangle(1, -2, 1 + b, -2 + h)));
  expect_near(a, props(b * h, {1 + b / 2, -2 + h / 2}, b * h * h * h / 12, h * b * b * b / 12, 0), b);
  EXPECT_DOUBLE_EQ(a.polar(), a.ixx + a.iyy);
}

TEST(AreaProperties, OrientationAndStartingVertexDoNotMatter) {
  const Polygon ccw{{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 3}, {0, 3}};
  const AreaProperties ref = area_properties(plate(ccw));
  expect_near(area_properties(plate(reversed(ccw))), ref, 4);
  Polygon shifted = ccw;
  std::rotate(shifted.begin(), shifted.begin() + 2, shifted.end());
  expect_near(area_properties(plate(shifted)), ref, 4);
  expect_near(area_properties(plate(reversed(shifted))), ref, 4);
}

TEST(AreaProperties, RotatedRectangleHasAProductOfInertia) {
  const double b = 0.5, h = 0.1;
  const Vector2d c(0.2, -0.7);
  for (const double angle : {0.3, 1.0, kPi / 4, 2.5, -0.8}) {
    Polygon poly;
    for (const Vector2d& v : rectangle(-b / 2, -h / 2, b / 2, h / 2)) poly.push_back(c + rotate(v, angle));
    const AreaProperties a = area_properties(plate(poly));
    expect_near(a, rotated_rectangle(b, h, c, angle), b);
    EXPECT_GT(std::abs(a.ixy), 1e-5);
    // The principal moments do not change with the angle.
    const double mean = (a.ixx + a.iyy) / 2, radius = std::hypot((a.ixx - a.iyy) / 2, a.ixy);
    EXPECT_NEAR(mean + radius, h * b * b * b / 12, 1e-15);
    EXPECT_NEAR(mean - radius, b * h * h * h / 12, 1e-15);
  }
}

TEST(AreaProperties, RightTriangle) {
  const double b = 3, h = 2;
  const AreaProperties a = area_properties(plate({{0, 0}, {b, 0}, {0, h}}));
  expect_near(a, props(b * h / 2, {b / 3, h / 3}, b * h * h * h / 36, h * b * b * b / 36, -b * b * h * h / 72), b);
}

TEST(AreaProperties, GeneralTriangle) {
  // About its centroid a triangle's second-moment tensor is (A/12) Σ d_i d_iᵀ, d_i the vertices
  // from the centroid.
  const Polygon t{{0.3, -0.2}, {1.7, 0.4}, {-0.4, 1.1}};
  const Vector2d c = (t[0] + t[1] + t[2]) / 3;
  const double area = std::abs((t[1] - t[0]).x() * (t[2] - t[0]).y() - (t[1] - t[0]).y() * (t[2] - t[0]).x()) / 2;
  double sxx = 0, syy = 0, sxy = 0;
  for (const Vector2d& v : t) {
    const Vector2d d = v - c;
    sxx += d.x() * d.x(), syy += d.y() * d.y(), sxy += d.x() * d.y();
  }
  const AreaProperties e = props(area, c, area / 12 * syy, area / 12 * sxx, area / 12 * sxy);
  expect_near(area_properties(plate(t)), e, 2);
  expect_near(area_properties(plate(reversed(t))), e, 2);
}

TEST(AreaProperties, LShapeByHand) {
  // [0,2]x[0,1] and [0,1]x[1,3]: areas 2 and 2, centroids (1, 0.5) and (0.5, 2), so the
  // centroid is (0.75, 1.25) and each part is 0.25, 0.75 away from it.
  const AreaProperties a = area_properties(plate({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 3}, {0, 3}}));
  const double ixx = (2.0 * 1 / 12 + 2 * 0.75 * 0.75) + (1.0 * 8 / 12 + 2 * 0.75 * 0.75);
  const double iyy = (1.0 * 8 / 12 + 2 * 0.25 * 0.25) + (2.0 * 1 / 12 + 2 * 0.25 * 0.25);
  const double ixy = 2 * (0.25 * -0.75) + 2 * (-0.25 * 0.75);
  expect_near(a, props(4, {0.75, 1.25}, ixx, iyy, ixy), 3);
  EXPECT_NEAR(ixx, 37.0 / 12, 1e-15);
  EXPECT_NEAR(iyy, 13.0 / 12, 1e-15);
  EXPECT_NEAR(ixy, -0.75, 1e-15);
}

TEST(AreaProperties, SquareWithOffCentreRoundHole) {
  const double side = 0.1, r = 0.02;
  const Vector2d hole(0.06, 0.045);
  Region reg = plate(rectangle(0, 0, side, side));
  reg.circle_holes.push_back({hole, r});
  const double as = side * side, ah = kPi * r * r, area = as - ah;
  const Vector2d c = (as * Vector2d(side / 2, side / 2) - ah * hole) / area;
  const double is = side * side * side * side / 12, ih = kPi * r * r * r * r / 4;
  const Vector2d ds = Vector2d(side / 2, side / 2) - c, dh = hole - c;
  const AreaProperties e =
      props(area, c, is + as * ds.y() * ds.y() - ih - ah * dh.y() * dh.y(),
            is + as * ds.x() * ds.x() - ih - ah * dh.x() * dh.x(), as * ds.x() * ds.y() - ah * dh.x() * dh.y());
  expect_near(area_properties(reg), e, side);
  // A centred hole: the plain a² − πr² and a⁴/12 − πr⁴/4.
  Region centred = plate(rectangle(-side / 2, -side / 2, side / 2, side / 2));
  centred.circle_holes.push_back({{0, 0}, r});
  expect_near(area_properties(centred), props(area, {0, 0}, is - ih, is - ih, 0), side);
}

TEST(AreaProperties, PolygonHoleInEitherOrientation) {
  // A 4x3 plate with a 1x1 window whose centre is at (3, 2).
  const AreaProperties outer = props(12, {2, 1.5}, 4.0 * 27 / 12, 3.0 * 64 / 12, 0);
  const AreaProperties window = props(1, {3, 2}, 1.0 / 12, 1.0 / 12, 0);
  const double area = 11;
  const Vector2d c = (12 * Vector2d(2, 1.5) - Vector2d(3, 2)) / area;
  const Vector2d d1 = outer.centroid - c, d2 = window.centroid - c;
  const AreaProperties e =
      props(area, c, outer.ixx + 12 * d1.y() * d1.y() - window.ixx - d2.y() * d2.y(),
            outer.iyy + 12 * d1.x() * d1.x() - window.iyy - d2.x() * d2.x(), 12 * d1.x() * d1.y() - d2.x() * d2.y());
  for (const bool flip : {false, true}) {
    Region r = plate(rectangle(0, 0, 4, 3));
    r.polygon_holes.push_back(flip ? reversed(rectangle(2.5, 1.5, 3.5, 2.5)) : rectangle(2.5, 1.5, 3.5, 2.5));
    expect_near(area_properties(r), e, 4);
    expect_near(area_properties(r), subtract(outer, window), 4);
  }
}

TEST(MakeBar, TwoHolesByHand) {
  const double len = 0.2, w = 0.03, m = 0.025, rp = 0.01, rq = 0.006;
  const Region bar = make_bar({0, 0}, {len, 0}, w, m, rp, rq);
  EXPECT_NO_THROW(check_region(bar));
  ASSERT_EQ(bar.outline.size(), 4u);
  ASSERT_EQ(bar.circle_holes.size(), 2u);
  const double total = len + 2 * m, ap = kPi * rp * rp, aq = kPi * rq * rq;
  const double area = total * w - ap - aq;
  const double cx = (total * w * len / 2 - aq * len) / area;
  const double ixx = total * w * w * w / 12 - kPi * std::pow(rp, 4) / 4 - kPi * std::pow(rq, 4) / 4;
  const double iyy = w * total * total * total / 12 + total * w * std::pow(len / 2 - cx, 2) -
                     (kPi * std::pow(rp, 4) / 4 + ap * cx * cx) -
                     (kPi * std::pow(rq, 4) / 4 + aq * std::pow(len - cx, 2));
  const AreaProperties e = props(area, {cx, 0}, ixx, iyy, 0);
  expect_near(area_properties(bar), e, len);

  // The same bar laid along another direction: the rotation formulas.
  const double angle = 2.2;
  const Vector2d p(0.4, -0.1), dir(std::cos(angle), std::sin(angle));
  const AreaProperties turned = area_properties(make_bar(p, p + len * dir, w, m, rp, rq));
  const double cs = std::cos(angle), sn = std::sin(angle);
  expect_near(
      turned,
      props(area, p + cx * dir, cs * cs * ixx + sn * sn * iyy, sn * sn * ixx + cs * cs * iyy, sn * cs * (iyy - ixx)),
      len);
  expect_near(turned, transformed(e, angle, p), len);
}

TEST(MakeBar, WithoutHolesOrMargin) {
  const Region bar = make_bar({1, 1}, {1, 3}, 0.5, 0, 0, 0);
  EXPECT_TRUE(bar.circle_holes.empty());
  expect_near(area_properties(bar), props(1, {1, 2}, 0.5 * 8 / 12, 2 * 0.125 / 12, 0), 2);
}

TEST(MakeBar, RejectsBarsThatAreNotPlates) {
  const auto message = [](auto&& make) {
    try {
      make();
    } catch (const nbar::Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const Vector2d o(0, 0), x(1, 0);
  EXPECT_THAT(message([&] { make_bar(o, o, 0.1, 0.1, 0, 0); }), HasSubstr("coincide"));
  EXPECT_THAT(message([&] { make_bar(o, x, 0, 0.1, 0, 0); }), HasSubstr("width must be positive"));
  EXPECT_THAT(message([&] { make_bar(o, x, 0.1, -0.1, 0, 0); }), HasSubstr("margin must not be negative"));
  EXPECT_THAT(message([&] { make_bar(o, x, 0.1, 0.1, -0.01, 0); }), HasSubstr("negative"));
  EXPECT_THAT(message([&] { make_bar(o, x, 0.1, 0.1, 0.05, 0); }), HasSubstr("does not fit"));
  EXPECT_THAT(message([&] { make_bar(o, x, 0.1, 0.02, 0.03, 0); }), HasSubstr("does not fit"));
  EXPECT_THAT(message([&] { make_bar(o, {0.05, 0}, 0.1, 0.1, 0.03, 0.03); }), HasSubstr("overlap"));
  EXPECT_THAT(message([&] { make_bar(o, x, std::nan(""), 0.1, 0, 0); }), HasSubstr("finite"));
}

// ---- helpers ----

TEST(AreaHelpers, CombineSubtractAndParallelAxis) {
  const AreaProperties left = area_properties(plate(rectangle(0, 0, 1, 2)));
  const AreaProperties right = area_properties(plate(rectangle(1, 0, 3, 1)));
  const AreaProperties both = area_properties(plate({{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 2}, {0, 2}}));
  expect_near(combine(left, right), both, 3);
  expect_near(subtract(both, right), left, 3);
  expect_near(subtract(both, both), AreaProperties{}, 3);

  const SecondMoments at_origin = second_moments_about(left, {0, 0});
  EXPECT_NEAR(at_origin.ixx, 1.0 * 8 / 3, 1e-14);  // b h³ / 3 about the base
  EXPECT_NEAR(at_origin.iyy, 2.0 / 3, 1e-14);
  EXPECT_NEAR(at_origin.ixy, 1.0, 1e-14);  // b² h² / 4
  EXPECT_NEAR(at_origin.polar(), 10.0 / 3, 1e-14);
}

TEST(AreaHelpers, PlateMass) {
  const AreaProperties a = area_properties(plate(rectangle(0, 0, 0.2, 0.04)));
  const PlateMass m = plate_mass(a, 7850, 0.005);
  EXPECT_NEAR(m.mass, 7850 * 0.005 * 0.2 * 0.04, 1e-12);
  // A thin rectangle: m (b² + h²) / 12 about its centre.
  EXPECT_NEAR(m.inertia, m.mass * (0.04 + 0.0016) / 12, 1e-15);
  EXPECT_NEAR(m.centre.x(), 0.1, 1e-15);
  EXPECT_NEAR(m.centre.y(), 0.02, 1e-15);
  EXPECT_THROW(plate_mass(a, -1, 0.005), nbar::Error);
  EXPECT_THROW(plate_mass(a, 7850, 0), nbar::Error);
  EXPECT_NO_THROW(plate_mass(a, 0, 0.005));
}

// ---- clipping ----

TEST(ClippedAreaProperties, RectangleGivesTheSmallerRectangle) {
  const Region r = plate(rectangle(0, 0, 4, 2));
  // x >= 1, with a normal that is not of unit length.
  expect_near(clipped_area_properties(r, {1, 5}, {3, 0}), area_properties(plate(rectangle(1, 0, 4, 2))), 4);
  // y <= 0.5
  expect_near(clipped_area_properties(r, {-7, 0.5}, {0, -0.2}), area_properties(plate(rectangle(0, 0, 4, 0.5))), 4);
  // A line missing the plate keeps all of it or nothing.
  expect_near(clipped_area_properties(r, {-1, 0}, {1, 0}), area_properties(r), 4);
  expect_near(clipped_area_properties(r, {-1, 0}, {-1, 0}), AreaProperties{}, 4);
  // A cut along an edge.
  expect_near(clipped_area_properties(r, {4, 0}, {1, 0}), AreaProperties{}, 4);
  expect_near(clipped_area_properties(r, {4, 0}, {-1, 0}), area_properties(r), 4);
  // The diagonal: the lower-right triangle.
  expect_near(clipped_area_properties(r, {0, 0}, {1, -2}), area_properties(plate({{0, 0}, {4, 0}, {4, 2}})), 4);
  EXPECT_THROW(clipped_area_properties(r, {0, 0}, {0, 0}), nbar::Error);
}

TEST(ClippedAreaProperties, NonConvexPlateCutAcrossBothArms) {
  // A U: the cut y >= 2 leaves the two arms' tops, [0,1]x[2,3] and [2,3]x[2,3].
  const Region u = plate({{0, 0}, {3, 0}, {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}});
  const AreaProperties arms =
      combine(area_properties(plate(rectangle(0, 2, 1, 3))), area_properties(plate(rectangle(2, 2, 3, 3))));
  expect_near(clipped_area_properties(u, {0, 2}, {0, 1}), arms, 3);
  expect_near(clipped_area_properties(plate(reversed(u.outline)), {0, 2}, {0, 1}), arms, 3);
  // Exactly through the inner corners (y = 1).
  const AreaProperties top =
      combine(area_properties(plate(rectangle(0, 1, 1, 3))), area_properties(plate(rectangle(2, 1, 3, 3))));
  expect_near(clipped_area_properties(u, {5, 1}, {0, 1}), top, 3);
  expect_near(clipped_area_properties(u, {5, 1}, {0, -1}), area_properties(plate(rectangle(0, 0, 3, 1))), 3);
}

// The circular segment {u >= r cos θ} of a disc: Roark's formulas in the half-angle θ, about the
// disc's centre, in the segment's own axes (u along its axis, v along the chord).
struct SegmentByHand {
  double area, u_bar, iuu, ivv;  // ∫u² and ∫v² about the disc's centre
};
SegmentByHand segment_by_hand(double r, double theta) {
  const double sn = std::sin(theta), cs = std::cos(theta);
  const double area = r * r * (theta - sn * cs);
  return {area, 2 * r * sn * sn * sn / (3 * (theta - sn * cs)),
          std::pow(r, 4) / 4 * (theta - sn * cs + 2 * sn * sn * sn * cs),
          std::pow(r, 4) / 12 * (3 * theta - 3 * sn * cs - 2 * sn * sn * sn * cs)};
}

TEST(ClippedAreaProperties, CutThroughARoundHoleRemovesACircularSegment) {
  // A square plate with a round hole at the origin, cut by the line x = h: the part x >= h is
  // the rectangle [h, a] x [-a, a] minus the segment of the hole beyond x = h.
  const double a = 1, r = 0.4;
  Region reg = plate(rectangle(-a, -a, a, a));
  reg.circle_holes.push_back({{0, 0}, r});
  for (const double h : {-0.39, -0.3, -0.1, 0.0, 0.05, 0.2, 0.35, 0.399}) {
    SCOPED_TRACE(h);
    // Both sides of the cut, each against its own hand computation.
    for (const int side : {1, -1}) {
      const double theta = std::acos(side * h / r);
      const SegmentByHand g = segment_by_hand(r, theta);
      const double w = side > 0 ? a - h : h + a;  // width of the rectangle kept
      const double rect_area = 2 * a * w, rect_x = side * (a - w / 2);
      const double area = rect_area - g.area;
      const double cx = (rect_area * rect_x - g.area * side * g.u_bar) / area;
      // About the hole's centre, then to the centroid.
      const double sxx = 2 * a * w * w * w / 12 + rect_area * rect_x * rect_x - g.iuu;
      const double syy = w * std::pow(2 * a, 3) / 12 - g.ivv;
      const AreaProperties e = props(area, {cx, 0}, syy, sxx - area * cx * cx, 0);
      const AreaProperties got = clipped_area_properties(reg, {h, 0.3}, {side * 2.0, 0});
      expect_near(got, e, a);
      // The same cut on the plate turned by 40° about the hole.
      Region turned = reg;
      for (Vector2d& v : turned.outline) v = rotate(v, 0.7);
      const AreaProperties got_turned =
          clipped_area_properties(turned, rotate({h, 0.3}, 0.7), rotate({side * 2.0, 0}, 0.7));
      expect_near(got_turned, transformed(e, 0.7, {0, 0}), a);
    }
  }
}

TEST(ClippedAreaProperties, CutThroughThePolygonHole) {
  Region r = plate(rectangle(0, 0, 4, 3));
  r.polygon_holes.push_back(reversed(rectangle(1, 1, 3, 2)));
  // y >= 1.5: [0,4]x[1.5,3] minus [1,3]x[1.5,2].
  const AreaProperties e =
      subtract(area_properties(plate(rectangle(0, 1.5, 4, 3))), area_properties(plate(rectangle(1, 1.5, 3, 2))));
  expect_near(clipped_area_properties(r, {0, 1.5}, {0, 1}), e, 4);
}

// Midpoint-rule quadrature over a fine grid, using only point-in-region tests: independent of
// every formula under test, and accurate to about a cell along the boundary.
using test_support::inside_polygon;
using test_support::inside_region;

TEST(ClippedAreaProperties, AgreesWithQuadrature) {
  Region r = plate({{0, 0}, {0.3, 0}, {0.3, 0.08}, {0.12, 0.1}, {0.05, 0.2}, {0, 0.2}});
  r.circle_holes.push_back({{0.25, 0.04}, 0.025});
  r.circle_holes.push_back({{0.04, 0.15}, 0.02});
  r.polygon_holes.push_back({{0.08, 0.03}, {0.16, 0.03}, {0.1, 0.08}});
  ASSERT_NO_THROW(check_region(r));
  // The second cut crosses the round hole at (0.25, 0.04) and the triangular one.
  for (const auto& [p, n] :
       {std::pair{Vector2d(0.1, 0.05), Vector2d(1, 0.6)}, std::pair{Vector2d(0.25, 0.045), Vector2d(0.1, 1.4)}}) {
    const int cells = 1500;
    const double h = 0.3 / cells;
    double a = 0, sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
    for (int i = 0; i < cells; ++i) {
      for (int j = 0; j < cells; ++j) {
        const Vector2d x((i + 0.5) * h, (j + 0.5) * h);
        if (n.dot(x - p) < 0 || !inside_region(r, x)) continue;
        a += 1, sx += x.x(), sy += x.y(), sxx += x.x() * x.x(), syy += x.y() * x.y(), sxy += x.x() * x.y();
      }
    }
    const double da = h * h;
    const Vector2d c(sx / a, sy / a);
    const AreaProperties q = props(a * da, c, (syy - a * c.y() * c.y()) * da, (sxx - a * c.x() * c.x()) * da,
                                   (sxy - a * c.x() * c.y()) * da);
    const AreaProperties got = clipped_area_properties(r, p, n);
    EXPECT_NEAR(got.area, q.area, 2e-3 * q.area);
    EXPECT_NEAR(got.centroid.x(), q.centroid.x(), 2e-4);
    EXPECT_NEAR(got.centroid.y(), q.centroid.y(), 2e-4);
    EXPECT_NEAR(got.ixx, q.ixx, 4e-3 * q.ixx);
    EXPECT_NEAR(got.iyy, q.iyy, 4e-3 * q.iyy);
    EXPECT_NEAR(got.ixy, q.ixy, 4e-3 * std::sqrt(q.ixx * q.iyy));
  }
}

// ---- check_region ----

std::string region_error(const Region& r) {
  try {
    check_region(r);
  } catch (const nbar::Error& e) {
    return e.what();
  }
  return "valid";
}

// The first self-intersection named, over random polygons (many of them crossing themselves),
// is the first pair (i, j > i + 1) of non-adjacent edges that meet, as a scan of every pair
// finds it: the sweep over x that finds it must name the same edges.
TEST(GeometryValidation, SelfIntersectionNamesTheFirstCrossingPairOfAScan) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(0.0, 10.0);
  const auto orient = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
    return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
  };
  // Random coordinates put no three points on one line: strict crossings only.
  const auto cross = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                         const Eigen::Vector2d& d) {
    return orient(a, b, c) * orient(a, b, d) < 0 && orient(c, d, a) * orient(c, d, b) < 0;
  };
  int crossing = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const std::size_t n = 4 + trial % 40;
    Polygon poly(n);
    for (auto& p : poly) p = {coordinate(random), coordinate(random)};
    std::string expected = "valid";
    for (std::size_t i = 0; i < n && expected == "valid"; ++i)
      for (std::size_t j = i + 2; j < n && expected == "valid"; ++j) {
        if (i == 0 && j == n - 1) continue;
        if (cross(poly[i], poly[(i + 1) % n], poly[j], poly[(j + 1) % n]))
          expected = "the outline intersects itself: edge " + std::to_string(i) + "-" + std::to_string((i + 1) % n) +
                     " meets edge " + std::to_string(j) + "-" + std::to_string((j + 1) % n);
      }
    if (expected == "valid") continue;
    ++crossing;
    EXPECT_THAT(region_error(plate(poly)), HasSubstr(expected)) << "trial " << trial;
  }
  EXPECT_GT(crossing, 200);
}

TEST(CheckRegion, AcceptsValidPlates) {
  Region r = plate(reversed({{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 3}, {0, 3}}));
  r.circle_holes.push_back({{0.5, 2.5}, 0.3});
  r.circle_holes.push_back({{3.5, 0.5}, 0.3});
  r.polygon_holes.push_back({{0.2, 0.2}, {0.8, 0.2}, {0.5, 0.8}});
  EXPECT_EQ(region_error(r), "valid");
  // Collinear consecutive vertices going on in the same direction are fine.
  EXPECT_EQ(region_error(plate({{0, 0}, {1, 0}, {2, 0}, {2, 1}})), "valid");
}

TEST(CheckRegion, ReportsEachProblem) {
  const Polygon square = rectangle(0, 0, 1, 1);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const auto with = [&](auto&& edit) {
    Region r = plate(square);
    edit(r);
    return region_error(r);
  };

  EXPECT_THAT(region_error(plate({{0, 0}, {1, 0}})),
              HasSubstr("the outline has 2 vertices; a polygon needs at least 3"));
  EXPECT_THAT(region_error(plate({})), HasSubstr("the outline has 0 vertices"));
  EXPECT_THAT(region_error(plate({{0, 0}, {1, nan}, {1, 1}})), HasSubstr("the outline vertex 1 is not finite"));
  EXPECT_THAT(region_error(plate({{0, 0}, {inf, 0}, {1, 1}})), HasSubstr("vertex 1 is not finite"));
  EXPECT_THAT(region_error(plate({{0, 0}, {1, 0}, {2, 0}})), HasSubstr("the outline has zero area"));
  EXPECT_THAT(region_error(plate({{0, 0}, {1, 0}, {1, 0}, {0, 1}})),
              HasSubstr("the outline vertices 1 and 2 coincide at (1, 0)"));
  EXPECT_THAT(region_error(plate({{0, 0}, {1, 1}, {1, 0}, {0, 1}})),
              HasSubstr("the outline intersects itself: edge 0-1 meets edge 2-3"));
  // Touching itself at a vertex is not simple either.
  EXPECT_THAT(region_error(plate({{0, 0}, {2, 0}, {1, 1}, {2, 2}, {0, 2}, {1, 1}})), HasSubstr("intersects itself"));
  EXPECT_THAT(region_error(plate({{0, 0}, {2, 0}, {1, 0}, {1, 1}})), HasSubstr("doubles back on itself at vertex 1"));

  EXPECT_THAT(with([](Region& r) {
                r.circle_holes.push_back({{0.5, 0.5}, 0});
              }),
              HasSubstr("circle hole 0 (centre (0.5, 0.5), radius 0) has a non-positive radius"));
  EXPECT_THAT(with([](Region& r) { r.circle_holes.push_back({{0.5, 0.5}, -0.1}); }), HasSubstr("non-positive radius"));
  EXPECT_THAT(with([&](Region& r) { r.circle_holes.push_back({{0.5, nan}, 0.1}); }), HasSubstr("is not finite"));
  EXPECT_THAT(with([](Region& r) {
                r.circle_holes.push_back({{1.5, 0.5}, 0.1});
              }),
              HasSubstr("circle hole 0 (centre (1.5, 0.5), radius 0.1) is outside the outline"));
  EXPECT_THAT(with([](Region& r) {
                r.circle_holes.push_back({{0.5, 0.5}, 0.5});
              }),
              HasSubstr("radius 0.5) meets the outline"));
  EXPECT_THAT(with([](Region& r) { r.circle_holes.push_back({{0.95, 0.5}, 0.1}); }), HasSubstr("meets the outline"));
  EXPECT_THAT(with([](Region& r) { r.polygon_holes.push_back(rectangle(2, 2, 3, 3)); }),
              HasSubstr("polygon hole 0 is outside the outline"));
  EXPECT_THAT(with([](Region& r) { r.polygon_holes.push_back(rectangle(0.5, 0.5, 1.5, 0.7)); }),
              HasSubstr("polygon hole 0 meets the outline"));
  EXPECT_THAT(with([](Region& r) { r.polygon_holes.push_back(rectangle(0, 0.2, 0.5, 0.7)); }),
              HasSubstr("polygon hole 0 meets the outline"));
  EXPECT_THAT(with([](Region& r) {
                r.polygon_holes.push_back({{0.2, 0.2}, {0.4, 0.2}});
              }),
              HasSubstr("polygon hole 0 has 2 vertices"));
  EXPECT_THAT(with([](Region& r) {
                r.polygon_holes.push_back(rectangle(0.1, 0.1, 0.3, 0.3));
                r.polygon_holes.push_back({{0.2, 0.6}, {0.4, 0.6}, {0.2, 0.8}, {0.4, 0.8}});
              }),
              HasSubstr("polygon hole 1 intersects itself"));

  EXPECT_THAT(with([](Region& r) {
                r.circle_holes.push_back({{0.3, 0.5}, 0.15});
                r.circle_holes.push_back({{0.6, 0.5}, 0.15});
              }),
              HasSubstr("circle hole 0 (centre (0.3, 0.5), radius 0.15) and circle hole 1 (centre (0.6, 0.5), "
                        "radius 0.15) overlap"));
  EXPECT_THAT(with([](Region& r) {
                r.polygon_holes.push_back(rectangle(0.1, 0.1, 0.5, 0.5));
                r.polygon_holes.push_back(rectangle(0.2, 0.2, 0.3, 0.3));  // inside the first
              }),
              HasSubstr("polygon hole 0 and polygon hole 1 overlap"));
  EXPECT_THAT(with([](Region& r) {
                r.polygon_holes.push_back(rectangle(0.1, 0.1, 0.5, 0.5));
                r.polygon_holes.push_back(rectangle(0.5, 0.2, 0.8, 0.3));  // sharing an edge
              }),
              HasSubstr("polygon hole 0 and polygon hole 1 overlap"));
  EXPECT_THAT(with([](Region& r) {
                r.polygon_holes.push_back(rectangle(0.1, 0.1, 0.5, 0.5));
                r.circle_holes.push_back({{0.3, 0.3}, 0.05});  // inside the polygon hole
              }),
              HasSubstr("polygon hole 0 and circle hole 0 (centre (0.3, 0.3), radius 0.05) overlap"));
  EXPECT_THAT(with([](Region& r) {
                r.polygon_holes.push_back(rectangle(0.4, 0.4, 0.5, 0.5));
                r.circle_holes.push_back({{0.45, 0.45}, 0.2});  // swallowing the polygon hole
              }),
              HasSubstr("polygon hole 0 and circle hole 0"));
  EXPECT_THAT(with([](Region& r) {
                r.polygon_holes.push_back(rectangle(0.1, 0.1, 0.5, 0.5));
                r.circle_holes.push_back({{0.7, 0.3}, 0.2});  // touching its edge
              }),
              HasSubstr("overlap"));
}

// ---- properties over random plates ----

// A length in [lo, hi] on a grid of 1/1000: rapidcheck shrinks integers well.
double gen_real(double lo, double hi) { return lo + (hi - lo) * *rc::gen::inRange(0, 1001) / 1000.0; }

// A polygon star-shaped about c: vertices at increasing angles, radii in [lo, hi]. Angular
// gaps under 1.4 * 2π/n < π keep c strictly inside, clear of every edge.
Polygon gen_star(const Vector2d& c, int n, double lo, double hi) {
  std::vector<double> angles;
  const double phase = gen_real(0, 2 * kPi);
  for (int k = 0; k < n; ++k) angles.push_back(phase + 2 * kPi * (k + gen_real(0, 0.4)) / n);
  Polygon p;
  for (const double a : angles) p.push_back(c + gen_real(lo, hi) * Vector2d(std::cos(a), std::sin(a)));
  if (*rc::gen::arbitrary<bool>()) std::reverse(p.begin(), p.end());
  return p;
}

double distance_to_segment(const Vector2d& x, const Vector2d& a, const Vector2d& b) {
  const double t = std::clamp((x - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
  return (x - a - t * (b - a)).norm();
}

// A valid plate by construction: a star polygon, holes in separate sectors of the largest disc
// about its centre that the outline contains.
struct RandomPlate {
  Region region;
  double size;
};
RandomPlate gen_plate() {
  const double size = gen_real(0.01, 2);
  const Vector2d c(gen_real(-1, 1), gen_real(-1, 1));
  Region r;
  r.outline = gen_star(c, *rc::gen::inRange(3, 13), 0.6 * size, size);
  double inner = size;
  for (std::size_t i = 0; i < r.outline.size(); ++i) {
    inner = std::min(inner, distance_to_segment(c, r.outline[i], r.outline[(i + 1) % r.outline.size()]));
  }
  const int holes = *rc::gen::inRange(0, 4);
  const double slot = 0.9 * inner / 2 * (holes >= 2 ? std::min(1.0, std::sin(kPi / holes)) : 1.0);
  const double phase = gen_real(0, 2 * kPi);
  for (int k = 0; k < holes; ++k) {
    const double a = phase + 2 * kPi * k / holes;
    const Vector2d at = c + inner / 2 * Vector2d(std::cos(a), std::sin(a));
    if (*rc::gen::arbitrary<bool>()) {
      r.circle_holes.push_back({at, gen_real(0.2, 1) * slot});
    } else {
      r.polygon_holes.push_back(gen_star(at, *rc::gen::inRange(3, 7), 0.3 * slot, slot));
    }
  }
  return {r, size};
}

// A line likely to hit something special: a vertex, a hole's centre, a hole's rim, or anywhere.
Vector2d gen_point_on_plate(const Region& r, double size) {
  Vector2d c = Vector2d::Zero();
  for (const Vector2d& v : r.outline) c += v;
  c /= static_cast<double>(r.outline.size());
  switch (*rc::gen::inRange(0, 4)) {
    case 0: return r.outline[*rc::gen::inRange<std::size_t>(0, r.outline.size())];
    case 1:
      if (!r.circle_holes.empty()) {
        const Circle& h = r.circle_holes[*rc::gen::inRange<std::size_t>(0, r.circle_holes.size())];
        const double a = gen_real(0, 2 * kPi);
        return *rc::gen::arbitrary<bool>() ? h.centre
                                           : Vector2d(h.centre + h.radius * Vector2d(std::cos(a), std::sin(a)));
      }
      [[fallthrough]];
    case 2:
      if (!r.polygon_holes.empty()) return r.polygon_holes[0][0];
      [[fallthrough]];
    default: return c + Vector2d(gen_real(-1.5, 1.5) * size, gen_real(-1.5, 1.5) * size);
  }
}

Vector2d gen_normal() {
  const double a = *rc::gen::arbitrary<bool>() ? kPi / 2 * *rc::gen::inRange(0, 4) : gen_real(0, 2 * kPi);
  return gen_real(0.1, 10) * Vector2d(std::cos(a), std::sin(a));
}

RC_GTEST_PROP(PlateProperties, GeneratedPlatesAreValid, ()) {
  const RandomPlate p = gen_plate();
  check_region(p.region);  // throws, failing the property, if the generator is wrong
  RC_ASSERT(area_properties(p.region).area > 0);
}

RC_GTEST_PROP(PlateProperties, TheTwoSidesOfACutMakeTheWhole, ()) {
  const RandomPlate plate_ = gen_plate();
  const Region& r = plate_.region;
  const double l = plate_.size, l2 = l * l, l3 = l2 * l, l4 = l2 * l2, tol = 1e-12;
  const Vector2d p = gen_point_on_plate(r, l), n = gen_normal();
  const AreaProperties whole = area_properties(r);
  const AreaProperties a = clipped_area_properties(r, p, n), b = clipped_area_properties(r, p, -n);
  RC_ASSERT(a.area >= 0);
  RC_ASSERT(b.area >= 0);
  RC_ASSERT(std::abs(a.area + b.area - whole.area) <= tol * l2);
  // First and second moments about a common point.
  const Vector2d o = whole.centroid;
  const Vector2d first = a.area * (a.centroid - o) + b.area * (b.centroid - o);
  RC_ASSERT(first.norm() <= tol * l3);
  const SecondMoments sa = second_moments_about(a, o), sb = second_moments_about(b, o);
  RC_ASSERT(std::abs(sa.ixx + sb.ixx - whole.ixx) <= tol * l4);
  RC_ASSERT(std::abs(sa.iyy + sb.iyy - whole.iyy) <= tol * l4);
  RC_ASSERT(std::abs(sa.ixy + sb.ixy - whole.ixy) <= tol * l4);
  // Centroidal second moments of a real area.
  for (const AreaProperties& part : {a, b}) {
    RC_ASSERT(part.ixx >= -tol * l4);
    RC_ASSERT(part.iyy >= -tol * l4);
    RC_ASSERT(std::abs(part.ixy) <= std::sqrt(std::max(0.0, part.ixx) * std::max(0.0, part.iyy)) + tol * l4);
  }
}

RC_GTEST_PROP(PlateProperties, MovingThePlateMovesItsProperties, ()) {
  const RandomPlate plate_ = gen_plate();
  const Region& r = plate_.region;
  const double l = plate_.size, tol = 1e-11;
  const double angle = gen_real(-kPi, kPi);
  const Vector2d shift(gen_real(-3, 3), gen_real(-3, 3));
  const auto move = [&](const Vector2d& v) { return Vector2d(rotate(v, angle) + shift); };
  Region moved = r;
  for (Vector2d& v : moved.outline) v = move(v);
  for (Polygon& h : moved.polygon_holes) {
    for (Vector2d& v : h) v = move(v);
  }
  for (Circle& c : moved.circle_holes) c.centre = move(c.centre);
  const Vector2d p = gen_point_on_plate(r, l), n = gen_normal();

  for (const auto& [got, before] :
       {std::pair{area_properties(moved), area_properties(r)},
        std::pair{clipped_area_properties(moved, move(p), rotate(n, angle)), clipped_area_properties(r, p, n)}}) {
    const AreaProperties e = transformed(before, angle, shift);
    const double l2 = l * l, l4 = l2 * l2;
    RC_ASSERT(std::abs(got.area - e.area) <= tol * l2);
    // As a first moment: the centroid of a sliver is only as good as its area allows.
    RC_ASSERT(got.area * (got.centroid - e.centroid).norm() <= tol * l2 * (l + 5));
    RC_ASSERT(std::abs(got.ixx - e.ixx) <= tol * l4);
    RC_ASSERT(std::abs(got.iyy - e.iyy) <= tol * l4);
    RC_ASSERT(std::abs(got.ixy - e.ixy) <= tol * l4);
  }
}

RC_GTEST_PROP(PlateProperties, AMirrorImageFlipsTheProductOfInertiaOnly, ()) {
  const RandomPlate plate_ = gen_plate();
  const Region& r = plate_.region;
  const auto mirror = [](const Vector2d& v) { return Vector2d(-v.x(), v.y()); };
  Region m = r;
  for (Vector2d& v : m.outline) v = mirror(v);
  for (Polygon& h : m.polygon_holes) {
    for (Vector2d& v : h) v = mirror(v);
  }
  for (Circle& c : m.circle_holes) c.centre = mirror(c.centre);
  const AreaProperties a = area_properties(r), b = area_properties(m);
  const double l2 = plate_.size * plate_.size, l4 = l2 * l2, tol = 1e-12;
  RC_ASSERT(std::abs(a.area - b.area) <= tol * l2);
  RC_ASSERT((mirror(a.centroid) - b.centroid).norm() <= tol * (plate_.size + 1));
  RC_ASSERT(std::abs(a.ixx - b.ixx) <= tol * l4);
  RC_ASSERT(std::abs(a.iyy - b.iyy) <= tol * l4);
  RC_ASSERT(std::abs(a.ixy + b.ixy) <= tol * l4);
}

}  // namespace
}  // namespace nbar
