// Designs from every synthesis method, driven through their precision positions by the
// kinematics engine (check_design): they must hit them exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "nbar/synthesis/burmester.hpp"
#include "nbar/synthesis/five_point.hpp"
#include "nbar/synthesis/fourbar_design.hpp"
#include "nbar/synthesis/function_generation.hpp"
#include "synthesis/fourbar_support.hpp"

namespace nbar::synthesis {
namespace {

using test_support::coupler_pose_at;

// A crank-rocker (frame 4, crank 1.2, coupler 3.5, rocker 2.8, roughly).
FourBarDesign known_fourbar() {
  FourBarDesign d;
  d.ground_a = {0.3, -0.2};
  d.ground_b = {4.1, 0.4};
  d.moving_a = {0.3, 1.0};
  d.moving_b = {3.4, 3.1};
  d.coupler_point = {1.6, 3.2};
  return d;
}

std::vector<BodyPose> poses_of(const FourBarDesign& d, const std::vector<double>& cranks) {
  std::vector<BodyPose> poses;
  for (double c : cranks) {
    const auto pose = coupler_pose_at(d, c);
    poses.push_back({pose.point, pose.rotation});
  }
  return poses;
}

std::vector<Target> targets_of(const std::vector<BodyPose>& poses) {
  std::vector<Target> targets;
  for (const auto& p : poses) targets.push_back({p.point, p.angle - poses[0].angle});
  return targets;
}

double size_of(const FourBarDesign& d) {
  return std::max({(d.ground_b - d.ground_a).norm(), (d.moving_a - d.ground_a).norm(), (d.moving_b - d.moving_a).norm(),
                   (d.moving_b - d.ground_b).norm()});
}

TEST(SimulatedDesignsTest, ThreePositionBurmesterDesignHitsItsPoses) {
  const FourBarDesign known = known_fourbar();
  const auto poses = poses_of(known, {0.0, 0.6, 1.3});
  const std::array<BodyPose, 3> three{poses[0], poses[1], poses[2]};
  const FourBarDesign d =
      three_position_design(three, PivotChoice::Moving, Eigen::Vector2d(0.9, 2.0), Eigen::Vector2d(2.6, 2.9));
  const DesignCheck check = check_design(d, targets_of(poses));
  ASSERT_TRUE(check.invalid.empty()) << check.invalid;
  if (!check.defect_free()) GTEST_SKIP() << "this pivot choice has a defect: " << describe_defects(check);
  EXPECT_LT(check.max_error, 1e-9 * size_of(d));
  EXPECT_LT(check.max_rotation_error, 1e-9);
}

TEST(SimulatedDesignsTest, FivePositionBurmesterDesignsHitTheirPoses) {
  const FourBarDesign known = known_fourbar();
  const auto poses = poses_of(known, {0.0, 0.5, 1.1, 1.8, 2.4});
  const std::array<BodyPose, 5> five{poses[0], poses[1], poses[2], poses[3], poses[4]};
  const FivePositionResult result = five_position_burmester(five);
  ASSERT_FALSE(result.designs.empty());
  int simulated = 0;
  double worst = 0, worst_rotation = 0;
  for (const auto& b : result.designs) {
    const DesignCheck check = check_design(b.design, targets_of(poses));
    if (!check.invalid.empty() || !check.defect_free()) continue;  // defective: not every pose on its branch
    ++simulated;
    worst = std::max(worst, check.max_error / size_of(b.design));
    worst_rotation = std::max(worst_rotation, check.max_rotation_error);
  }
  std::printf("[ accuracy ] Burmester 5 poses, %d defect-free designs simulated: miss %.1e (relative), %.1e rad\n",
              simulated, worst, worst_rotation);
  EXPECT_GE(simulated, 1);  // the known linkage at least
  EXPECT_LT(worst, 1e-9);
  EXPECT_LT(worst_rotation, 1e-9);
}

TEST(SimulatedDesignsTest, FivePointDesignsPassThroughTheirPoints) {
  const FourBarDesign known = known_fourbar();
  FivePointTask task;
  task.pivot_a = known.ground_a;
  task.pivot_b = known.ground_b;
  std::vector<Target> targets;
  for (int i = 0; i < 5; ++i) {
    task.points[i] = coupler_pose_at(known, 0.45 * i).point;
    targets.push_back({task.points[i], std::nullopt});
  }
  const FivePointResult result = solve_five_point(task);
  int simulated = 0;
  double worst = 0;
  for (const auto& s : result.solutions) {
    if (!s.real) continue;
    const DesignCheck check = check_design(s.design, targets);
    if (!check.invalid.empty() || !check.defect_free()) continue;
    ++simulated;
    worst = std::max(worst, check.max_error / size_of(s.design));
  }
  std::printf("[ accuracy ] five-point, %d defect-free designs simulated: miss %.1e (relative)\n", simulated, worst);
  EXPECT_GE(simulated, 1);
  EXPECT_LT(worst, 1e-9);
}

TEST(SimulatedDesignsTest, FreudensteinDesignMeetsItsPrecisionPoints) {
  FunctionTask task;
  task.f = [](double x) { return std::log10(x); };
  task.x_start = 1;
  task.x_end = 2;
  const double deg = std::numbers::pi / 180;
  task.input_start = 45 * deg;
  task.input_range = 60 * deg;
  task.output_start = 90 * deg;
  task.output_range = 60 * deg;
  const std::vector<double> xs = chebyshev_spacing(1, 2, 3);
  const FunctionDesign design = freudenstein_design(task, xs);
  // input and output rotations from the first precision point, as the task maps them
  const std::vector<RotationTarget> targets = rotation_targets(task, xs);
  const double dphi = 60 * deg * (xs[2] - xs[0]);  // phi is linear in x: 60 deg over [1, 2]
  EXPECT_NEAR(targets[2].input, dphi, 1e-12);
  EXPECT_NEAR(targets[2].output, (std::log10(xs[2]) - std::log10(xs[0])) / std::log10(2.0) * 60 * deg, 1e-12);
  const DesignCheck check = check_design(design.design, targets);
  ASSERT_TRUE(check.invalid.empty()) << check.invalid;
  EXPECT_TRUE(check.defect_free()) << describe_defects(check);
  std::printf("[ accuracy ] Freudenstein, 3 precision points simulated: output off by %.1e rad\n", check.max_error);
  EXPECT_LT(check.max_error, 1e-9);
}

}  // namespace
}  // namespace nbar::synthesis
