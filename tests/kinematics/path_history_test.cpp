// The predictor from two points' series: exact on polynomials of degree 5 (the Hermite
// interpolant's), of error h^6 on others, and used only while the state is the point the last
// step reached.
#include "kinematics/path_history.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>

namespace nbar {
namespace {

// Taylor coefficients 0..2 at s of q(s) = (p(s), sin(s)) with p a polynomial of degree 5.
Eigen::MatrixXd series_at(double s) {
  const double c[6] = {0.3, -1.2, 0.7, 2.0, -0.4, 0.15};
  Eigen::MatrixXd m(2, 3);
  double p = 0.0, dp = 0.0, d2p = 0.0;
  for (int j = 5; j >= 0; --j) {
    d2p = d2p * s + 2.0 * dp;
    dp = dp * s + p;
    p = p * s + c[j];
  }
  m << p, dp, d2p / 2.0, std::sin(s), std::cos(s), -std::sin(s) / 2.0;
  return m;
}

TEST(PathHistory, PredictsFromTheLastTwoPointsSeries) {
  for (const double step : {0.3, 0.1, 0.03}) {
    for (const double reach : {0.5, 1.0, 1.9}) {
      PathHistory history;
      const double s0 = 1.0 - step, s1 = 1.0, h = reach * step;
      history.push(s0, series_at(s0));
      history.mark_current(s1, series_at(s1));
      Eigen::VectorXd q;
      ASSERT_TRUE(history.predict(s1, series_at(s1), h, q));
      const Eigen::MatrixXd truth = series_at(s1 + h);
      // Degree 5: exact but for rounding.
      EXPECT_NEAR(q[0], truth(0, 0), 1e-13 * std::abs(truth(0, 0))) << "step " << step << ", reach " << reach;
      // sin: the error falls as the sixth power of the step, far below the current series' alone
      // (third power).
      const double taylor = series_at(s1)(1, 0) + h * series_at(s1)(1, 1) + h * h * series_at(s1)(1, 2);
      const double error = std::abs(q[1] - truth(1, 0));
      EXPECT_LT(error, 0.02 * std::pow(h, 6) * std::pow(1.0 + 1.0 / reach, 3) + 1e-15);
      EXPECT_LT(error, 0.1 * std::abs(taylor - truth(1, 0)));
    }
  }
}

TEST(PathHistory, IsUsedOnlyFromThePointTheLastStepReached) {
  PathHistory history;
  Eigen::VectorXd q;
  EXPECT_FALSE(history.predict(1.0, series_at(1.0), 0.1, q));  // no past point
  history.push(0.9, series_at(0.9));
  history.mark_current(1.0, series_at(1.0));
  EXPECT_TRUE(history.predict(1.0, series_at(1.0), 0.1, q));
  EXPECT_FALSE(history.predict(1.05, series_at(1.0), 0.1, q));  // another parameter
  Eigen::MatrixXd moved = series_at(1.0);
  moved(0, 0) += 1e-15;
  EXPECT_FALSE(history.predict(1.0, moved, 0.1, q));  // another pose
  Eigen::MatrixXd other_path = series_at(1.0);
  other_path(1, 1) *= 2.0;
  EXPECT_FALSE(history.predict(1.0, other_path, 0.1, q));       // the same pose on another path
  EXPECT_FALSE(history.predict(1.0, series_at(1.0), -0.1, q));  // backwards, towards the past point
  EXPECT_FALSE(history.predict(1.0, series_at(1.0), 0.25, q));  // more than twice the last step
  history.clear();
  EXPECT_FALSE(history.predict(1.0, series_at(1.0), 0.1, q));
}

// A sweep hands its series over (take) instead of having them copied (push): the same prediction,
// bit for bit, and the caller gets back storage it may overwrite, the past point's kept apart.
TEST(PathHistory, TakingTheSeriesPredictsAsCopyingThem) {
  PathHistory copied, taken;
  copied.push(0.8, series_at(0.8));
  Eigen::MatrixXd handed = series_at(0.8);
  taken.take(0.8, handed);
  handed.setConstant(7.0);  // what the next step's series would overwrite
  copied.push(0.9, series_at(0.9));
  handed = series_at(0.9);
  taken.take(0.9, handed);
  handed.setConstant(-3.0);
  copied.mark_current(1.0, series_at(1.0));
  taken.mark_current(1.0, series_at(1.0));
  Eigen::VectorXd from_copy, from_taken;
  ASSERT_TRUE(copied.predict(1.0, series_at(1.0), 0.1, from_copy));
  ASSERT_TRUE(taken.predict(1.0, series_at(1.0), 0.1, from_taken));
  ASSERT_EQ(from_taken.size(), 2);
  EXPECT_EQ(from_taken[0], from_copy[0]);
  EXPECT_EQ(from_taken[1], from_copy[1]);
}

// A step compiled for its number of coordinates (track() for 2, 4, 6 or 8) uses the history
// sized the same way: the same prediction, bit for bit, and the same refusals.
TEST(PathHistory, SizedWhenCompiledPredictsAsAnySize) {
  const auto bits = [](double x) {
    std::uint64_t b;
    std::memcpy(&b, &x, sizeof b);
    return b;
  };
  for (const double reach : {0.5, 1.0, 1.9}) {
    PathHistory any, sized;
    any.push(0.9, series_at(0.9));
    sized.push(0.9, series_at(0.9));
    any.mark_current(1.0, series_at(1.0));
    sized.mark_current<2>(1.0, series_at(1.0));
    Eigen::VectorXd from_any, from_sized;
    ASSERT_TRUE(any.predict(1.0, series_at(1.0), 0.1 * reach, from_any));
    ASSERT_TRUE(sized.predict<2>(1.0, series_at(1.0), 0.1 * reach, from_sized));
    ASSERT_EQ(from_sized.size(), 2);
    EXPECT_EQ(bits(from_sized[0]), bits(from_any[0])) << "reach " << reach;
    EXPECT_EQ(bits(from_sized[1]), bits(from_any[1])) << "reach " << reach;
  }
  PathHistory sized;
  sized.push(0.9, series_at(0.9));
  sized.mark_current<2>(1.0, series_at(1.0));
  Eigen::VectorXd q;
  Eigen::MatrixXd moved = series_at(1.0);
  moved(1, 0) = std::nextafter(moved(1, 0), 2.0);
  EXPECT_FALSE(sized.predict<2>(1.0, moved, 0.1, q));  // the last coordinate moved by one bit
  Eigen::MatrixXd other_path = series_at(1.0);
  other_path(1, 1) = std::nextafter(other_path(1, 1), 2.0);
  EXPECT_FALSE(sized.predict<2>(1.0, other_path, 0.1, q));  // its rate by one bit
  // A step compiled for another size than the series' predicts nothing from them, even from the
  // point the history continues from; a history marked by such a step is marked as by any size.
  EXPECT_FALSE(sized.predict<4>(1.0, series_at(1.0), 0.1, q));
  EXPECT_TRUE(sized.predict<2>(1.0, series_at(1.0), 0.1, q));
  PathHistory marked_wrong;
  marked_wrong.push(0.9, series_at(0.9));
  marked_wrong.mark_current<4>(1.0, series_at(1.0));
  Eigen::VectorXd from_wrong;
  ASSERT_TRUE(marked_wrong.predict(1.0, series_at(1.0), 0.1, from_wrong));
  EXPECT_EQ(bits(from_wrong[1]), bits(q[1]));
}

}  // namespace
}  // namespace nbar
