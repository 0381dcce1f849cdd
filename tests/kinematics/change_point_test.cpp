// A parallelogram four-bar (crank = rocker, coupler = frame) has change points where it lies
// flat (crank at 0 and 180 deg): there it may go on as a parallelogram or as an antiparallelogram,
// and the Jacobian is singular. Driven through them it must stay the parallelogram it was
// drawn as (the branch the motion is analytic on), whether a sample lands on a change point,
// just beside it, or a long step jumps over it. The reference is exact: the rocker turns with
// the crank, angle for angle, and the coupler stays parallel to the frame.
#include "helpers/kinematics_support.hpp"
#include "test_constants.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

namespace nbar::ktest {
namespace {

using nbar::test_constants::kDeg;

struct Parallelogram {
  Model model;
  int crank = -1, coupler = -1, rocker = -1;
};

// Crank 100 mm, frame 200 mm, drawn at crank 90 deg, turned once from there.
Parallelogram parallelogram(double speed, double accel) {
  Parallelogram p;
  Model& m = p.model;
  const int o2 = add_point(m, "O2", {0, 0}, true);
  const int o4 = add_point(m, "O4", {0.2, 0}, true);
  const int a = add_point(m, "A", {0, 0.1});
  const int b = add_point(m, "B", {0.2, 0.1});
  p.crank = add_body(m, "crank", {o2, a});
  p.coupler = add_body(m, "coupler", {a, b});
  p.rocker = add_body(m, "rocker", {o4, b});
  m.drivers.push_back(angle_driver("crank", p.crank, 90 * kDeg, 450 * kDeg, speed, accel));
  return p;
}

// Every sample: rocker angle and its derivatives equal the crank's, the coupler flat.
void expect_parallelogram(const Mechanism& mech, const Parallelogram& p, const SweepResult& r, int steps) {
  ASSERT_TRUE(r.complete) << steps << " steps: " << r.stop_reason;
  ASSERT_EQ(static_cast<int>(r.samples.size()), steps);
  for (const Sample& s : r.samples) {
    const std::vector<double> crank = body_angle_motion(mech, s, p.crank);
    const std::vector<double> rocker = body_angle_motion(mech, s, p.rocker);
    const std::vector<double> coupler = body_angle_motion(mech, s, p.coupler);
    const double omega = std::abs(crank[1]), scale = omega * omega + std::abs(crank[2]);
    ASSERT_LT(std::abs(angle_difference(rocker[0], crank[0])), 1e-8) << steps << " steps, step " << s.step;
    ASSERT_LT(std::abs(angle_difference(coupler[0], 0.0)), 1e-8) << steps << " steps, step " << s.step;
    ASSERT_NEAR(rocker[1], crank[1], 1e-6 * omega) << steps << " steps, step " << s.step;
    ASSERT_NEAR(rocker[2], crank[2], 1e-4 * scale) << steps << " steps, step " << s.step;
    ASSERT_NEAR(coupler[1], 0.0, 1e-6 * omega) << steps << " steps, step " << s.step;
  }
}

// The samples that land on a change point (crank at 180 or 360 deg) are said so, each once.
void expect_warnings_at_change_points(const SweepResult& r, int steps) {
  std::set<int> on_change_point;
  for (int i = 1; i < steps; ++i) {
    const double crank = 90.0 + 360.0 * i / (steps - 1);
    if (std::abs(std::remainder(crank, 180.0)) < 1e-9) on_change_point.insert(i);
  }
  std::set<int> warned;
  for (const Warning& w : r.warnings) {
    if (w.code != "change_point_at_sample") continue;
    EXPECT_TRUE(warned.insert(w.step).second) << "twice: " << w.message;
    EXPECT_NE(w.message.find("relative"), std::string::npos) << w.message;
  }
  EXPECT_EQ(warned, on_change_point) << steps << " steps";
  for (const Warning& w : r.warnings)
    EXPECT_TRUE(w.code == "change_point_at_sample" || w.code == "change_point_passed") << w.message;
}

TEST(ChangePoint, AParallelogramStaysAParallelogramWhateverTheSteps) {
  const Parallelogram p = parallelogram(2 * kPi, 0.0);
  const Mechanism mech(p.model);
  // 5, 9, 13, 100, 361, 721, 3601 put samples on the change points; 360 and 1000 do not.
  for (int steps : {5, 9, 13, 100, 360, 361, 721, 1000, 3601}) {
    const SweepResult r = run_sweep(mech, sweep_options(2, steps));
    expect_parallelogram(mech, p, r, steps);
    expect_warnings_at_change_points(r, steps);
  }
}

// Every number of steps from 5 to 400: the samples fall on, near and far from the change points in
// every way, and steps are halved onto them. (Before the Hermite predictor and the tightened
// corrections, 35 of these 395 sweeps stopped at a change point or left the parallelogram.)
TEST(ChangePoint, AParallelogramStaysAParallelogramForEveryNumberOfStepsTo400) {
  const Parallelogram p = parallelogram(2 * kPi, 0.0);
  const Mechanism mech(p.model);
  for (int steps = 5; steps <= 400; ++steps) {
    const SweepResult r = run_sweep(mech, sweep_options(2, steps));
    expect_parallelogram(mech, p, r, steps);
    if (::testing::Test::HasFatalFailure()) return;
  }
}

// With an acceleration the sweep's parameter is its fraction, not time: the derivatives in
// time on a change point come from the series in the fraction, composed with the motion.
TEST(ChangePoint, DerivativesInTimeOnAChangePointWithAnAcceleratingCrank) {
  const Parallelogram p = parallelogram(2 * kPi, 3.0);
  const Mechanism mech(p.model);
  for (int steps : {13, 361}) {
    const SweepResult r = run_sweep(mech, sweep_options(3, steps));
    expect_parallelogram(mech, p, r, steps);
    expect_warnings_at_change_points(r, steps);
  }
}

}  // namespace
}  // namespace nbar::ktest
