// One pose at a time: solve_at agrees with the sweep and with Norton's closed form, states can
// be copied as snapshots, and a pose along the sweep is reached on the sweep's branch.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "bench_models.hpp"
#include "helpers/kinematics_support.hpp"
#include "kinematics/workspace.hpp"
#include "nbar/analysis/pose.hpp"

namespace nbar::ktest {
namespace {

double largest(const Eigen::MatrixXd& m) { return m.cwiseAbs().maxCoeff(); }

TEST(SolveAt, AgreesWithTheSweepAtItsSamples) {
  const Mechanism mech(nbar_bench::four_bar_model());
  SweepOptions options = sweep_options(3, 13);
  const SweepResult sweep = run_sweep(mech, options);
  ASSERT_TRUE(sweep.complete);
  State state(mech);
  for (const Sample& s : sweep.samples) {
    // Newton from the previous pose follows the branch, as a user stepping the crank would.
    const Sample one = solve_at(mech, state, s.driver_values, 3);
    ASSERT_EQ(one.taylor.cols(), 4);
    EXPECT_LT(largest(one.taylor - s.taylor), 2e-11 * largest(s.taylor)) << "sample " << s.step;
    for (int k = 0; k <= 3; ++k)
      EXPECT_LT((one.derivative(k) - s.derivative(k)).cwiseAbs().maxCoeff(), 1e-10 * largest(s.derivative(k)) + 1e-300);
  }
}

TEST(SolveAt, DerivativesAreFactorialTimesTaylorCoefficients) {
  const Mechanism mech(nbar_bench::four_bar_model());
  const SweepResult sweep = run_sweep(mech, sweep_options(3, 5));
  const Sample& s = sweep.samples[2];
  const int point = 3;  // a moving point: compare with point_motion, written independently
  const Motion2 motion = point_motion(mech, s, point);
  const int col = mech.column_of(point);
  ASSERT_GE(col, 0);
  for (int k = 0; k <= 3; ++k) {
    EXPECT_DOUBLE_EQ(s.derivative(col, k), motion.x[k]) << k;
    EXPECT_DOUBLE_EQ(s.derivative(k)(col + 1), motion.y[k]) << k;
  }
}

TEST(SolveAt, TimeLawModelsArePosedByTime) {
  Model m = nbar_bench::four_bar_model();
  m.drivers[0].law = Law::parse("0.3*sin(2*pi*t)");
  m.drivers[0].from.reset();
  m.drivers[0].to.reset();
  const Mechanism mech(m);
  State state(mech);
  EXPECT_THROW(solve_at(mech, state, {0.1}, 2), Error);
  const Sample s = solve_at_time(mech, state, 0.125, 2);
  // The crank's angle and rate follow the law: theta = 0.3 sin(2 pi t).
  const std::vector<double> angle = body_angle_motion(mech, s, 0);
  EXPECT_NEAR(angle[0], 0.3 * std::sin(2 * kPi * 0.125), 1e-12);
  EXPECT_NEAR(angle[1], 0.3 * 2 * kPi * std::cos(2 * kPi * 0.125), 1e-10);
  EXPECT_NEAR(angle[2], -0.3 * 4 * kPi * kPi * std::sin(2 * kPi * 0.125), 1e-8);
}

void expect_copy_is_a_snapshot(const Mechanism& mech, LinearSolver::Method method) {
  State state(mech);
  const std::vector<double> start = sweep_start_values(mech);
  const Sample before = solve_at(mech, state, start, 2);
  ASSERT_EQ(state.workspace().solver().method(), method);
  const State snapshot = state;  // copy
  std::vector<double> moved = start;
  moved[0] += 0.3;
  solve_at(mech, state, moved, 2);  // the original moves on
  ASSERT_GT((state.q - before.taylor.col(0)).norm(), 1e-6);

  // The copy kept its pose and its own factorisation: the series from it equal the original's.
  State copy = snapshot;
  EXPECT_EQ(copy.q, before.taylor.col(0));
  Eigen::MatrixXd series;
  std::vector<DriverState> drivers = copy.drivers;
  compute_series(mech, copy, drivers, 3, series);
  EXPECT_LT(largest(series - before.taylor), 1e-13 * largest(before.taylor));
  // Assignment too.
  State assigned(mech);
  assigned = snapshot;
  compute_series(mech, assigned, drivers, 3, series);
  EXPECT_LT(largest(series - before.taylor), 1e-13 * largest(before.taylor));
  // A State moved into another takes its workspace along: the factorisation is still there.
  State taken = std::move(assigned);
  compute_series(mech, taken, drivers, 3, series);
  EXPECT_LT(largest(series - before.taylor), 1e-13 * largest(before.taylor));
  State reassigned(mech);
  reassigned = std::move(taken);
  compute_series(mech, reassigned, drivers, 3, series);
  EXPECT_LT(largest(series - before.taylor), 1e-13 * largest(before.taylor));
}

TEST(State, CopiesAreSnapshotsSmall) {
  expect_copy_is_a_snapshot(Mechanism(nbar_bench::four_bar_model()), LinearSolver::Method::LU);
}

TEST(State, CopiesAreSnapshotsLarge) {
  const Mechanism chain(nbar_bench::chain_model(12));
  ASSERT_GT(chain.coordinate_count(), LinearSolver::kDenseConditionLimit);
  expect_copy_is_a_snapshot(chain, LinearSolver::Method::LU);
}

TEST(PoseAt, ReachesTheValueOnTheSweepsBranch) {
  const Mechanism mech(nbar_bench::four_bar_model());
  const SweepResult sweep = run_sweep(mech, sweep_options(2, 13));  // every 30 degrees
  const Sample& at_90 = sweep.samples[3];
  const double degrees = mech.model().units.angle_scale;
  const Sample pose = pose_at(mech, at_90.driver_values[0] / degrees, 2);
  EXPECT_LT(largest(pose.taylor - at_90.taylor), 1e-11 * largest(at_90.taylor));
  EXPECT_NEAR(pose.time, at_90.time, 1e-12);
}

std::string pose_error(const Mechanism& mech, double value) {
  try {
    pose_at(mech, value);
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::BadInput);
    return e.what();
  }
  return "no error";
}

// A value that is no number used to spin for ever (NaN) or to give the start pose (infinity); one
// a million turns away was blamed on a toggle the crank-rocker does not have.
TEST(PoseAt, RefusesValuesItCannotReach) {
  const Mechanism mech(nbar_bench::four_bar_model());
  EXPECT_THAT(pose_error(mech, std::nan("")), ::testing::HasSubstr("must be a finite number, not nan"));
  EXPECT_THAT(pose_error(mech, INFINITY), ::testing::HasSubstr("must be a finite number, not inf"));
  EXPECT_THAT(pose_error(mech, -INFINITY), ::testing::HasSubstr("not -inf"));
  EXPECT_THAT(pose_error(mech, 1e9), ::testing::HasSubstr("turns from the sweep's start; a pose is limited to 1000"));
  EXPECT_EQ(pose_error(mech, 360.0 * 999), "no error");
}

// The residual is the largest |row|, and a NaN in any row makes it infinite: a pose where one
// constraint cannot be evaluated is never taken as solved. (Its rows are evaluated in an order of
// their own: a NaN after the first row once went unseen.)
TEST(MaxResidual, IsInfiniteWhenAnyRowIsNaN) {
  const Mechanism mech(nbar_bench::four_bar_model());
  State state(mech);
  int worst = -1;
  const double drawn = max_residual(mech, state, &worst);
  ASSERT_TRUE(std::isfinite(drawn));
  for (Eigen::Index i = 0; i < state.q.size(); ++i) {
    State broken(mech);
    broken.q[i] = std::nan("");
    worst = -1;
    EXPECT_EQ(max_residual(mech, broken, &worst), HUGE_VAL) << "coordinate " << i;
    ASSERT_GE(worst, 0);
    EXPECT_TRUE(std::isnan(broken.workspace().phi[worst])) << "coordinate " << i;
  }
  // Without a NaN: the largest |row|, and the first row of that size.
  state.q[0] += 1e-3;
  const double r = max_residual(mech, state, &worst);
  EXPECT_EQ(r, state.workspace().phi.cwiseAbs().maxCoeff());
  EXPECT_EQ(std::abs(state.workspace().phi[worst]), r);
}

}  // namespace
}  // namespace nbar::ktest
