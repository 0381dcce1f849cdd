// Sections of plates along a line: the material intervals by hand (through holes, vertices,
// non-convex outlines), beam-section properties against the closed forms, and, over random
// plates and lines, intervals that really are material with boundary at their ends.
#include "nbar/stress/section.hpp"
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
#include <stdexcept>
#include <string>
#include <vector>

namespace nbar {
namespace {

using Eigen::Vector2d;
using Polygon = std::vector<Vector2d>;
using Intervals = std::vector<std::pair<double, double>>;
using nbar::test_constants::kPi;
using ::testing::HasSubstr;

Polygon rectangle(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

Region plate(Polygon outline) {
  Region r;
  r.outline = std::move(outline);
  return r;
}

void expect_intervals(const Intervals& got, const Intervals& expected, double tol = 1e-14) {
  ASSERT_EQ(got.size(), expected.size()) << "got " << ::testing::PrintToString(got);
  for (std::size_t i = 0; i < got.size(); ++i) {
    EXPECT_NEAR(got[i].first, expected[i].first, tol) << "interval " << i;
    EXPECT_NEAR(got[i].second, expected[i].second, tol) << "interval " << i;
  }
}

// ---- intervals ----

TEST(SectionIntervals, AcrossARectangle) {
  const double h = 0.05;
  const Region r = plate(rectangle(0, 0, 0.3, h));
  expect_intervals(section_intervals(r, {0.1, 0}, {0, 1}), {{0, h}});
  expect_intervals(section_intervals(r, {0.1, -1}, {0, 1}), {{1, 1 + h}});
  expect_intervals(section_intervals(r, {0.1, 0}, {0, -1}), {{-h, 0}});
  // s counts lengths of d: a longer d gives shorter parameters.
  expect_intervals(section_intervals(r, {0.1, 0}, {0, 2}), {{0, h / 2}});
  // Clockwise outline: the same material.
  Polygon cw = r.outline;
  std::reverse(cw.begin(), cw.end());
  expect_intervals(section_intervals(plate(cw), {0.1, 0}, {0, 1}), {{0, h}});
  // Slanted: the cut across the plate at 45° is √2 h long.
  expect_intervals(section_intervals(r, {0.1, 0}, Vector2d(1, 1).normalized()), {{0, std::sqrt(2.0) * h}});
}

TEST(SectionIntervals, ThroughARoundHoleGivesTwoIntervals) {
  Region r = plate(rectangle(0, 0, 4, 4));
  r.circle_holes.push_back({{2, 2}, 1});
  expect_intervals(section_intervals(r, {2, 0}, {0, 1}), {{0, 1}, {3, 4}});
  // Off centre: the chord's half-length is √(1 − 0.6²) = 0.8.
  expect_intervals(section_intervals(r, {2.6, 0}, {0, 1}), {{0, 1.2}, {2.8, 4}});
  // Tangent to the hole: nothing is taken out.
  expect_intervals(section_intervals(r, {3, 0}, {0, 1}), {{0, 4}});
  // Missing it.
  expect_intervals(section_intervals(r, {0.5, 0}, {0, 1}), {{0, 4}});
}

TEST(SectionIntervals, ThroughAPolygonHole) {
  Region r = plate(rectangle(0, 0, 4, 4));
  r.polygon_holes.push_back(rectangle(1, 1, 3, 2));
  expect_intervals(section_intervals(r, {0, 1.5}, {1, 0}), {{0, 1}, {3, 4}});
  // Along the diagonal, entering the hole at its corner (1, 1) and leaving at (2, 2).
  const double root2 = std::sqrt(2.0);
  expect_intervals(section_intervals(r, {0, 0}, Vector2d(1, 1) / root2), {{0, root2}, {2 * root2, 4 * root2}}, 1e-14);
}

TEST(SectionIntervals, ThroughVertices) {
  const Region square = plate(rectangle(0, 0, 1, 1));
  const double root2 = std::sqrt(2.0);
  expect_intervals(section_intervals(square, {0, 0}, Vector2d(1, 1) / root2), {{0, root2}}, 1e-15);
  expect_intervals(section_intervals(square, {1, 1}, Vector2d(-1, -1) / root2), {{0, root2}}, 1e-15);
  // Only grazing a corner from outside: no material.
  expect_intervals(section_intervals(square, {1, 1}, Vector2d(1, -1) / root2), {});
  expect_intervals(section_intervals(square, {0, 1}, Vector2d(-1, -1) / root2), {});
  // A diamond cut through its side vertices.
  expect_intervals(section_intervals(plate({{0, -1}, {2, 0}, {0, 1}, {-2, 0}}), {-5, 0}, {1, 0}), {{3, 7}});
}

TEST(SectionIntervals, NonConvexOutline) {
  // A U: across both arms, then along the line through the inner corners.
  const Region u = plate({{0, 0}, {3, 0}, {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}});
  expect_intervals(section_intervals(u, {-1, 2}, {1, 0}), {{1, 2}, {3, 4}});
  expect_intervals(section_intervals(u, {1.5, 0}, {0, 1}), {{0, 1}});
  expect_intervals(section_intervals(u, {2.5, 0}, {0, 1}), {{0, 3}});
  // A line along edges gets the limit from the right of d: below y = 1 the base, above it the arms.
  expect_intervals(section_intervals(u, {0, 1}, {1, 0}), {{0, 3}});
  expect_intervals(section_intervals(u, {3, 1}, {-1, 0}), {{0, 1}, {2, 3}});
}

TEST(SectionIntervals, AlongAnEdgeTakesTheLimitFromTheRight) {
  const Region square = plate(rectangle(0, 0, 1, 1));
  expect_intervals(section_intervals(square, {0, 0}, {1, 0}), {});          // the plate is to the left
  expect_intervals(section_intervals(square, {0, 0}, {-1, 0}), {{-1, 0}});  // the plate is to the right
}

TEST(SectionIntervals, MissingThePlate) {
  const Region r = plate(rectangle(0, 0, 1, 1));
  expect_intervals(section_intervals(r, {2, 0}, {0, 1}), {});
  const SectionProperties s = section_properties({}, 0.01);
  EXPECT_EQ(s.area, 0);
  EXPECT_EQ(s.inertia, 0);
  EXPECT_EQ(s.max_first_moment, 0);
}

TEST(SectionIntervals, RejectsADegenerateLine) {
  const Region r = plate(rectangle(0, 0, 1, 1));
  EXPECT_THROW(section_intervals(r, {0, 0}, {0, 0}), nbar::Error);
  EXPECT_THROW(section_intervals(r, {std::nan(""), 0}, {0, 1}), nbar::Error);
}

// ---- section properties ----

TEST(SectionProperties, RectangularSection) {
  const double t = 0.006, h = 0.04, s0 = 0.3;
  const SectionProperties s = section_properties({{s0, s0 + h}}, t);
  EXPECT_NEAR(s.area, t * h, 1e-18);
  EXPECT_NEAR(s.centroid, s0 + h / 2, 1e-15);
  EXPECT_NEAR(s.inertia, t * h * h * h / 12, 1e-20);
  EXPECT_NEAR(s.max_first_moment, t * h * h / 8, 1e-20);
  EXPECT_NEAR(s.shear_level, s0 + h / 2, 1e-15);
  EXPECT_EQ(s.s_min, s0);
  EXPECT_EQ(s.s_max, s0 + h);
  // τ_max = V Q / (I t) = 1.5 V / A, the textbook rectangle result.
  const double v = 1000;
  EXPECT_NEAR(v * s.max_first_moment / (s.inertia * t), 1.5 * v / s.area, 1e-6);
}

TEST(SectionProperties, SymmetricSectionAroundAHole) {
  // [0, 1] and [3, 4]: centroid 2 in the gap; I = 2 t ∫_1^2 u² du = 14 t / 3;
  // Q(2) = t ∫_0^1 (s − 2) ds = −1.5 t, the same anywhere in the gap.
  const double t = 0.01;
  const SectionProperties s = section_properties({{0, 1}, {3, 4}}, t);
  EXPECT_NEAR(s.area, 2 * t, 1e-16);
  EXPECT_NEAR(s.centroid, 2, 1e-15);
  EXPECT_NEAR(s.inertia, 14 * t / 3, 1e-15);
  EXPECT_NEAR(s.max_first_moment, 1.5 * t, 1e-16);
  EXPECT_EQ(s.shear_level, 1);  // the nearer edge of the gap; the lower on a tie
  EXPECT_EQ(s.s_min, 0);
  EXPECT_EQ(s.s_max, 4);
}

TEST(SectionProperties, UnsymmetricSectionByHand) {
  // [0, 1] and [2, 5]: length 4, centroid (0.5 · 1 + 3.5 · 3) / 4 = 2.75, inside [2, 5];
  // I = ∫_0^1 (s − 2.75)² + ∫_2^5 (s − 2.75)² = (15.4375 + 11.8125) / 3;
  // Q(2.75) = (0.5 − 2.75) · 1 − 0.75² / 2 = −2.53125.
  const double t = 2;
  const SectionProperties s = section_properties({{0, 1}, {2, 5}}, t);
  EXPECT_NEAR(s.area, 8, 1e-14);
  EXPECT_NEAR(s.centroid, 2.75, 1e-15);
  EXPECT_NEAR(s.inertia, t * 27.25 / 3, 1e-13);
  EXPECT_NEAR(s.max_first_moment, t * 2.53125, 1e-14);
  EXPECT_NEAR(s.shear_level, 2.75, 1e-15);
  // [0, 1] and [1.5, 2.7]: centroid (0.5 + 2.1 · 1.2) / 2.2 = 1.3727 in the gap, nearer 1.5.
  const SectionProperties g = section_properties({{0, 1}, {1.5, 2.7}}, 1);
  EXPECT_NEAR(g.centroid, (0.5 + 2.1 * 1.2) / 2.2, 1e-15);
  EXPECT_EQ(g.shear_level, 1.5);
  EXPECT_NEAR(g.max_first_moment, 1 * (g.centroid - 0.5), 1e-15);
}

TEST(SectionProperties, TouchingIntervalsAreOneInterval) {
  const SectionProperties a = section_properties({{0, 1}, {1, 2}}, 0.5);
  const SectionProperties b = section_properties({{0, 2}}, 0.5);
  EXPECT_NEAR(a.area, b.area, 1e-15);
  EXPECT_NEAR(a.centroid, b.centroid, 1e-15);
  EXPECT_NEAR(a.inertia, b.inertia, 1e-15);
  EXPECT_NEAR(a.max_first_moment, b.max_first_moment, 1e-15);
}

TEST(SectionProperties, OfAPlateWithAHole) {
  // A bar 40 mm wide with a 16 mm hole, 5 mm thick, cut across through the hole's centre.
  const Region bar = make_bar({0, 0}, {0.2, 0}, 0.04, 0.03, 0.008, 0);
  const SectionProperties s = section_properties(section_intervals(bar, {0, -1}, {0, 1}), 0.005);
  const double t = 0.005;
  EXPECT_NEAR(s.area, t * (0.04 - 0.016), 1e-15);
  EXPECT_NEAR(s.centroid, 1, 1e-15);
  EXPECT_NEAR(s.inertia, t * (std::pow(0.04, 3) - std::pow(0.016, 3)) / 12, 1e-18);
  EXPECT_NEAR(s.s_min, 0.98, 1e-15);
  EXPECT_NEAR(s.s_max, 1.02, 1e-15);
  EXPECT_NEAR(s.max_first_moment, t * (0.02 * 0.02 - 0.008 * 0.008) / 2, 1e-18);
}

std::string properties_error(const Intervals& v, double t) {
  try {
    section_properties(v, t);
  } catch (const nbar::Error& e) {
    return e.what();
  }
  return "valid";
}

TEST(SectionProperties, RejectsBadInput) {
  EXPECT_THAT(properties_error({{0, 1}}, 0), HasSubstr("thickness must be positive"));
  EXPECT_THAT(properties_error({{0, 1}}, -1), HasSubstr("thickness"));
  EXPECT_THAT(properties_error({{0, 1}, {3, 2}}, 1), HasSubstr("interval 1 [3, 2]"));
  EXPECT_THAT(properties_error({{0, 2}, {1, 3}}, 1), HasSubstr("interval 1 [1, 3]"));
  EXPECT_THAT(properties_error({{2, 3}, {0, 1}}, 1), HasSubstr("interval 1 [0, 1]"));
  EXPECT_THAT(properties_error({{0, std::numeric_limits<double>::infinity()}}, 1), HasSubstr("interval 0"));
}

// ---- properties over random plates, lines and sections ----

double gen_real(double lo, double hi) { return lo + (hi - lo) * *rc::gen::inRange(0, 1001) / 1000.0; }

Polygon gen_star(const Vector2d& c, int n, double lo, double hi) {
  const double phase = gen_real(0, 2 * kPi);
  Polygon p;
  for (int k = 0; k < n; ++k) {
    const double a = phase + 2 * kPi * (k + gen_real(0, 0.4)) / n;  // gaps < π: c stays inside
    p.push_back(c + gen_real(lo, hi) * Vector2d(std::cos(a), std::sin(a)));
  }
  if (*rc::gen::arbitrary<bool>()) std::reverse(p.begin(), p.end());
  return p;
}

double distance_to_segment(const Vector2d& x, const Vector2d& a, const Vector2d& b) {
  const double t = std::clamp((x - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
  return (x - a - t * (b - a)).norm();
}

double distance_to_polygon(const Polygon& p, const Vector2d& x) {
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < p.size(); ++i) d = std::min(d, distance_to_segment(x, p[i], p[(i + 1) % p.size()]));
  return d;
}

using test_support::inside_polygon;
using test_support::inside_region;

double distance_to_boundary(const Region& r, const Vector2d& x) {
  double d = distance_to_polygon(r.outline, x);
  for (const Polygon& h : r.polygon_holes) d = std::min(d, distance_to_polygon(h, x));
  for (const Circle& c : r.circle_holes) d = std::min(d, std::abs((x - c.centre).norm() - c.radius));
  return d;
}

// A valid plate by construction: a star-shaped outline about c, holes in separate sectors of
// the largest disc about c inside it.
Region gen_plate(double& size) {
  size = gen_real(0.01, 2);
  const Vector2d c(gen_real(-1, 1), gen_real(-1, 1));
  Region r;
  r.outline = gen_star(c, *rc::gen::inRange(3, 13), 0.6 * size, size);
  const double inner = distance_to_polygon(r.outline, c);
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
  return r;
}

RC_GTEST_PROP(SectionProperty, IntervalsAreTheMaterialAlongTheLine, ()) {
  double size = 0;
  const Region r = gen_plate(size);
  check_region(r);
  Vector2d centre = Vector2d::Zero();
  for (const Vector2d& v : r.outline) centre += v;
  centre /= static_cast<double>(r.outline.size());
  // Through the plate's middle, a hole's centre, or a vertex, at any angle.
  Vector2d p = centre + size * Vector2d(gen_real(-0.8, 0.8), gen_real(-0.8, 0.8));
  if (*rc::gen::arbitrary<bool>()) p = r.outline[*rc::gen::inRange<std::size_t>(0, r.outline.size())];
  if (!r.circle_holes.empty() && *rc::gen::arbitrary<bool>()) p = r.circle_holes[0].centre;
  const double angle = gen_real(0, 2 * kPi);
  const Vector2d d(std::cos(angle), std::sin(angle));
  const Intervals v = section_intervals(r, p, d);
  const double tol = 1e-9 * size;
  const auto at = [&](double s) { return Vector2d(p + s * d); };
  for (std::size_t i = 0; i < v.size(); ++i) {
    RC_ASSERT(v[i].first < v[i].second);
    if (i > 0) RC_ASSERT(v[i - 1].second < v[i].first);
    // Ends on the boundary; the middle in the material, and so are points along the interval
    // clear of the boundary.
    RC_ASSERT(distance_to_boundary(r, at(v[i].first)) <= tol);
    RC_ASSERT(distance_to_boundary(r, at(v[i].second)) <= tol);
    for (int k = 1; k < 8; ++k) {
      const Vector2d x = at(v[i].first + (v[i].second - v[i].first) * k / 8);
      if (distance_to_boundary(r, x) > tol) RC_ASSERT(inside_region(r, x));
    }
  }
  // Gaps, and the line beyond the ends, are not material.
  std::vector<double> outside;
  for (std::size_t i = 0; i + 1 < v.size(); ++i) outside.push_back((v[i].second + v[i + 1].first) / 2);
  const double lo = v.empty() ? -3 * size : v.front().first, hi = v.empty() ? 3 * size : v.back().second;
  outside.push_back(lo - size * gen_real(0.001, 2));
  outside.push_back(hi + size * gen_real(0.001, 2));
  if (v.empty()) outside.push_back(gen_real(-1.5, 1.5) * size);
  for (double s : outside) {
    if (distance_to_boundary(r, at(s)) > tol) RC_ASSERT(!inside_region(r, at(s)));
  }
}

RC_GTEST_PROP(SectionProperty, QIsLargestAtTheReportedLevel, ()) {
  Intervals v;
  double s = gen_real(-1, 1);
  const int count = *rc::gen::inRange(1, 6);
  for (int i = 0; i < count; ++i) {
    const double len = gen_real(0.001, 1);
    v.emplace_back(s, s + len);
    s += len + gen_real(0, 0.5);
  }
  const double t = gen_real(0.001, 0.02);
  const SectionProperties sp = section_properties(v, t);
  const auto q = [&](double level) {
    double sum = 0;
    for (const auto& [a, b] : v) {
      const double top = std::min(b, level);
      if (top > a) sum += ((top - sp.centroid) * (top - sp.centroid) - (a - sp.centroid) * (a - sp.centroid)) / 2;
    }
    return t * sum;
  };
  double length = 0, first = 0, second = 0;  // about s = 0
  for (const auto& [a, b] : v) {
    length += b - a;
    first += (b * b - a * a) / 2;
    second += (b * b * b - a * a * a) / 3;
  }
  RC_ASSERT(std::abs(sp.area - t * length) <= 1e-14);
  RC_ASSERT(std::abs(sp.centroid - first / length) <= 1e-12);
  RC_ASSERT(std::abs(sp.inertia - t * (second - length * sp.centroid * sp.centroid)) <= 1e-12 * t);
  RC_ASSERT(sp.s_min == v.front().first);
  RC_ASSERT(sp.s_max == v.back().second);
  // Q vanishes past the last fibre (it is a first moment about the centroid).
  RC_ASSERT(std::abs(q(sp.s_max)) <= 1e-12 * t);
  RC_ASSERT(std::abs(std::abs(q(sp.shear_level)) - sp.max_first_moment) <= 1e-12 * t);
  const bool in_material = std::any_of(
      v.begin(), v.end(), [&](const auto& i) { return i.first <= sp.shear_level && sp.shear_level <= i.second; });
  RC_ASSERT(in_material);
  for (int k = 0; k <= 400; ++k) {
    const double level = sp.s_min + (sp.s_max - sp.s_min) * k / 400;
    RC_ASSERT(std::abs(q(level)) <= sp.max_first_moment + 1e-12 * t);
  }
}

}  // namespace
}  // namespace nbar
