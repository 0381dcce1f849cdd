// A triangle's angle from its sides (src/model/triangle.hpp) against closed forms, and where the
// law of cosines' acos fails: a needle-like triangle, whose angle is known from its construction.
#include "model/triangle.hpp"
#include "test_constants.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace nbar {
namespace {

using nbar::test_constants::kPi;

TEST(AngleOpposite, ClosedFormTriangles) {
  EXPECT_NEAR(angle_opposite(1.0, 1.0, 1.0), kPi / 3, 1e-15);
  EXPECT_NEAR(angle_opposite(5.0, 3.0, 4.0), kPi / 2, 1e-15);
  EXPECT_NEAR(angle_opposite(3.0, 5.0, 4.0), std::atan2(3.0, 4.0), 1e-15);
  EXPECT_NEAR(angle_opposite(4.0, 4.0, 3.0), std::acos(3.0 / 8.0), 1e-15);  // isosceles, sides in any order
  EXPECT_NEAR(angle_opposite(4.0, 3.0, 4.0), std::acos(3.0 / 8.0), 1e-15);
}

TEST(AngleOpposite, ATriangleThatCannotCloseGivesTheClampedAngle) {
  EXPECT_EQ(angle_opposite(0.5, 3.0, 4.0), 0.0);  // shorter than the adjacent sides' difference
  EXPECT_EQ(angle_opposite(1.0, 3.0, 4.0), 0.0);  // flat, folded
  EXPECT_EQ(angle_opposite(7.0, 3.0, 4.0), kPi);  // flat, stretched
  EXPECT_EQ(angle_opposite(9.0, 3.0, 4.0), kPi);
}

// Two sides of 0.1 m with an angle theta between them: the opposite side is 0.2 sin(theta / 2).
// The reference is the angle of that very double, by formulas that are well conditioned in it:
// 2 asin(opposite / 0.2) for a small angle, pi - 4 asin(sqrt((0.2 - opposite) / 0.4)) near pi
// (0.2 - opposite is exact there). Near 0 the acos of the law of cosines is off by about
// sqrt(1e-16) = 1e-8 rad; Kahan's formula keeps every digit.
TEST(AngleOpposite, NeedleLikeTrianglesKeepTheirDigits) {
  const double side = 0.1, sum = 2 * side;
  for (double theta : {1e-9, 1e-6, 1e-3, 0.5, kPi - 1e-3, kPi - 1e-6}) {
    const double opposite = sum * std::sin(theta / 2);
    const double exact = theta < kPi / 2 ? 2.0 * std::asin(opposite / sum)
                                         : kPi - 4.0 * std::asin(std::sqrt((sum - opposite) / (2 * sum)));
    EXPECT_NEAR(angle_opposite(opposite, side, side), exact, 1e-15 * exact) << theta;
  }
  const double tiny = 0.2 * std::sin(0.5e-9);
  const double by_acos = std::acos((0.01 + 0.01 - tiny * tiny) / (2 * 0.01));
  EXPECT_GT(std::abs(by_acos - 1e-9), 1e-10);  // the formula it replaces, for the record: wrong there
}

}  // namespace
}  // namespace nbar
