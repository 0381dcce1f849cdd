// The tolerance is relative to the linkage's own size, the extent of the points its joints use,
// not to points that only ride along (issue 37): a centre of mass drawn as a point 470 m from a
// 5 m linkage loosened its joints from 2e-13 to 1.4e-12 m when the whole drawing set it.
#include <gtest/gtest.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <limits>

#include "kinematics/helpers/kinematics_support.hpp"

namespace nbar {
namespace {

using ktest::add_body;
using ktest::add_point;
using ktest::kPi;

// A crank-rocker of about 5 m in metres: ground 4, crank 1.5, coupler 4, rocker 3.5, drawn with the
// crank along +x and B above the ground line; with `far_point`, a centre of mass drawn on the
// coupler as a point 470 m away.
Model five_metre_four_bar(bool far_point) {
  Model m;
  m.name = far_point ? "four-bar and a far point" : "four-bar";
  const int o2 = add_point(m, "O2", {0, 0}, true);
  const int o4 = add_point(m, "O4", {4, 0}, true);
  const int a = add_point(m, "A", {1.5, 0});
  const int b = add_point(m, "B", {3.5, std::sqrt(12.0)});
  add_body(m, "crank", {o2, a});
  if (far_point) {
    const int g = add_point(m, "G", {300.0, 361.8});
    add_body(m, "coupler", {a, b, g});
  } else {
    add_body(m, "coupler", {a, b});
  }
  add_body(m, "rocker", {o4, b});
  m.drivers.push_back(ktest::angle_driver("crank", 0, 0.0, 2 * kPi, 1.0));
  m.sweep.steps = 37;
  return m;
}

TEST(LinkageSize, ARidingPointDoesNotSetTheSizeOrTheTolerance) {
  const Mechanism plain(five_metre_four_bar(false)), far(five_metre_four_bar(true));
  EXPECT_DOUBLE_EQ(plain.characteristic_length(), std::hypot(4.0, std::sqrt(12.0)));
  EXPECT_EQ(far.characteristic_length(), plain.characteristic_length());
  EXPECT_EQ(far.tolerance(), plain.tolerance());
  EXPECT_DOUBLE_EQ(plain.tolerance(), 1e-12 * plain.characteristic_length());
}

// Far beyond a thousand times the linkage's size a riding point's own rows could not meet 1e-12 of
// the linkage (their rounding grows with its distance): the tolerance grows with it from there.
TEST(LinkageSize, APointFurtherThanAThousandSizesLoosensTheTolerance) {
  Model m = five_metre_four_bar(true);
  m.points[4].position = {12e3, 16e3};  // 20 km
  const Mechanism mech(m);
  EXPECT_DOUBLE_EQ(mech.characteristic_length(), std::hypot(4.0, std::sqrt(12.0)));
  EXPECT_NEAR(mech.tolerance(), 1e-12 * 1e-3 * std::hypot(12e3, 16e3), 1e-3 * mech.tolerance());
  const SweepResult sweep = run_sweep(mech, ktest::sweep_options(2));
  EXPECT_TRUE(sweep.complete) << sweep.stop_reason;
}

// The largest distance of the joints A and B from Norton's closed form over a full turn.
double joint_error(const Mechanism& mech, const SweepResult& sweep) {
  const ktest::NortonFourBar closed{1.5, 4.0, 3.5, 4.0};
  const int a = mech.column_of(2), b = mech.column_of(3);
  const auto b_exact = [&](double theta, bool open) {
    return Eigen::Vector2d(Eigen::Vector2d(4, 0) + ktest::polar(3.5, closed.solve(theta, 1.0, 0.0, open).theta4));
  };
  // The branch drawn: B above the ground line with the crank along +x.
  const bool open = (b_exact(0.0, true) - Eigen::Vector2d(3.5, std::sqrt(12.0))).norm() < 1e-9;
  double worst = 0.0;
  for (const Sample& s : sweep.samples) {
    const double theta = s.driver_values[0];
    const Eigen::Vector2d a_exact = ktest::polar(1.5, theta);
    worst = std::max({worst, (s.taylor.col(0).segment<2>(a) - a_exact).norm(),
                      (s.taylor.col(0).segment<2>(b) - b_exact(theta, open)).norm()});
  }
  return worst;
}

TEST(LinkageSize, AFarRidingPointLeavesTheJointsAsExact) {
  const Mechanism plain(five_metre_four_bar(false)), far(five_metre_four_bar(true));
  const SweepResult without = run_sweep(plain, ktest::sweep_options(2));
  const SweepResult with = run_sweep(far, ktest::sweep_options(2));
  ASSERT_TRUE(without.complete && with.complete);
  const double size = plain.characteristic_length();
  const double error_without = joint_error(plain, without), error_with = joint_error(far, with);
  std::printf("joints against the closed form: %.2e m alone, %.2e m with the far point (linkage %.3g m)\n",
              error_without, error_with, size);
  EXPECT_LE(error_without, 1e-14 * size);
  EXPECT_LE(error_with, 1e-14 * size);
  // The joints agree between the two to their rounding, sample by sample.
  double apart = 0.0;
  for (std::size_t i = 0; i < with.samples.size(); ++i)
    apart =
        std::max(apart, (with.samples[i].taylor.col(0).segment<4>(0) - without.samples[i].taylor.col(0).segment<4>(0))
                            .lpNorm<Eigen::Infinity>());
  EXPECT_LE(apart, 1e-14 * size);
  // The far point is where the coupler's frame puts it, to its own rounding.
  const double distance = std::hypot(300.0, 361.8);
  for (const Sample& s : with.samples) {
    const Eigen::Vector2d a = s.taylor.col(0).segment<2>(0), b = s.taylor.col(0).segment<2>(2);
    const Eigen::Vector2d g = s.taylor.col(0).segment<2>(4);
    EXPECT_NEAR((g - a).norm(), (Eigen::Vector2d(300.0, 361.8) - Eigen::Vector2d(1.5, 0)).norm(),
                100 * std::numeric_limits<double>::epsilon() * distance);
    EXPECT_NEAR((g - b).norm(), (Eigen::Vector2d(300.0, 361.8) - Eigen::Vector2d(3.5, std::sqrt(12.0))).norm(),
                100 * std::numeric_limits<double>::epsilon() * distance);
  }
}

}  // namespace
}  // namespace nbar
