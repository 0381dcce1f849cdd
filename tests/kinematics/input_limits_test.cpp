// input_limits (loops.hpp): the closed-form range of a four-bar's input against an
// independent search: the loop closed by intersecting circles in coordinates, marched from the
// given angle in small steps until it no longer closes, then bisected.
#include "test_constants.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>

#include <cmath>
#include <numbers>
#include <random>

#include "nbar/kinematics/loops.hpp"

namespace {

using nbar::test_constants::kPi;

struct Linkage {
  double d, a, b, c, frame_angle;
  Eigen::Vector2d o2{0.3, -0.2};
  // Whether coupler and output reach each other with the input at theta: circles about A
  // (radius b) and O4 (radius c) intersect.
  bool closes(double theta) const {
    const Eigen::Vector2d o4 = o2 + d * Eigen::Vector2d(std::cos(frame_angle), std::sin(frame_angle));
    const Eigen::Vector2d pa = o2 + a * Eigen::Vector2d(std::cos(theta), std::sin(theta));
    const double f = (o4 - pa).norm();
    return f <= b + c && f >= std::abs(b - c);
  }
  // The limit reached turning from `at` in `direction`, or nan after a full turn.
  double search(double at, int direction) const {
    const double step = 1e-3;
    double inside = at;
    for (int i = 1; i * step <= 2 * kPi + step; ++i) {
      const double next = at + direction * i * step;
      if (!closes(next)) {
        double in = inside, out = next;
        for (int k = 0; k < 60; ++k) {
          const double mid = 0.5 * (in + out);
          (closes(mid) ? in : out) = mid;
        }
        return 0.5 * (in + out);
      }
      inside = next;
    }
    return std::nan("");
  }
};

TEST(InputLimits, AgreeWithAMarchingSearchOnRandomLinkages) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> length(0.2, 3.0), angle(-kPi, kPi), turn(-3, 3);
  int limited = 0, full = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const Linkage l{length(rng), length(rng), length(rng), length(rng), angle(rng)};
    // An input angle where the loop closes, in some turn.
    double at = 0;
    bool found = false;
    for (int k = 0; k < 50 && !found; ++k) {
      at = angle(rng);
      found = l.closes(at);
    }
    if (!found) continue;
    at += 2 * kPi * std::round(turn(rng));
    const nbar::InputLimits r = nbar::input_limits(l.d, l.a, l.b, l.c, l.frame_angle, at);
    ASSERT_TRUE(r.closes);
    const double down = l.search(at, -1), up = l.search(at, 1);
    if (std::isnan(up)) {
      EXPECT_TRUE(r.full) << "trial " << trial;
      ++full;
      continue;
    }
    ASSERT_FALSE(r.full) << "trial " << trial;
    ++limited;
    EXPECT_LE(r.from, at);
    EXPECT_GE(r.to, at);
    EXPECT_NEAR(r.from, down, 1e-6) << "trial " << trial;
    EXPECT_NEAR(r.to, up, 1e-6) << "trial " << trial;
  }
  EXPECT_GT(limited, 100);
  EXPECT_GT(full, 20);
}

TEST(InputLimits, KnownCases) {
  // Crank-rocker (frame 200, crank 80, coupler 180, rocker 150): the crank turns fully.
  EXPECT_TRUE(nbar::input_limits(200, 80, 180, 150, 0, 0).full);
  // Crank 130: s + l = p + q (a change point within rounding); a shorter coupler makes it a triple-rocker.
  // Frame 200, input 130, coupler 179, output 150: the diagonal reaches b + c = 329 < a + d at
  // cos(alpha) = (130^2 + 200^2 - 329^2) / (2 130 200).
  const double hi = std::acos((130.0 * 130 + 200.0 * 200 - 329.0 * 329) / (2 * 130.0 * 200));
  const nbar::InputLimits r = nbar::input_limits(200, 130, 179, 150, 0, 0.1);
  ASSERT_FALSE(r.full);
  EXPECT_NEAR(r.from, -hi, 1e-12);
  EXPECT_NEAR(r.to, hi, 1e-12);
  // The frame turned and the input given a turn later: the same range, moved with them.
  const nbar::InputLimits turned = nbar::input_limits(200, 130, 179, 150, 1.0, 1.1 + 2 * kPi);
  EXPECT_NEAR(turned.from, 1.0 - hi + 2 * kPi, 1e-12);
  EXPECT_NEAR(turned.to, 1.0 + hi + 2 * kPi, 1e-12);
  // Where the loop cannot close at all.
  EXPECT_FALSE(nbar::input_limits(200, 130, 179, 150, 0, kPi).closes);
}

}  // namespace
