// Checking synthesised four-bars: targets taken from known linkages' coupler curves, in order,
// shuffled, on the other circuit and across a toggle.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "nbar/kinematics/mechanism.hpp"
#include "nbar/kinematics/sweep.hpp"
#include "nbar/synthesis/fourbar_design.hpp"

namespace {

using Eigen::Vector2d;
using nbar::synthesis::DesignCheck;
using nbar::synthesis::FourBarDesign;
using nbar::synthesis::RotationTarget;
using nbar::synthesis::Target;

constexpr double kPi = std::numbers::pi;
double deg(double d) { return d * kPi / 180.0; }

// A four-bar with fixed pivots at (0, 0) and (d, 0); the coupler point sits `along` the
// coupler from A towards B and `left` of it.
struct Linkage {
  double a, b, c, d, along, left;

  // sign: +1 with B left of the line from A to O4 (loops.hpp branch_sign), -1 right.
  struct Pose {
    Vector2d a, b, p;
    double coupler_angle;
  };
  Pose pose(double theta, int sign) const {
    const Vector2d o4(d, 0);
    Pose pose;
    pose.a = a * Vector2d(std::cos(theta), std::sin(theta));
    // B: the intersection of the circles about A (radius b) and O4 (radius c).
    const Vector2d f = o4 - pose.a;
    const double dist = f.norm();
    const double l = (b * b - c * c + dist * dist) / (2 * dist);
    const double h = std::sqrt(b * b - l * l);
    pose.b = pose.a + (l / dist) * f + sign * (h / dist) * Vector2d(-f.y(), f.x());
    const Vector2d u = (pose.b - pose.a) / b;
    pose.p = pose.a + along * u + left * Vector2d(-u.y(), u.x());
    pose.coupler_angle = std::atan2(u.y(), u.x());
    return pose;
  }
  FourBarDesign design(double theta, int sign) const {
    const Pose p = pose(theta, sign);
    return {Vector2d(0, 0), Vector2d(d, 0), p.a, p.b, p.p};
  }
  std::vector<Target> path(const std::vector<double>& thetas, const std::vector<int>& signs) const {
    std::vector<Target> out;
    for (std::size_t i = 0; i < thetas.size(); ++i) out.push_back({pose(thetas[i], signs[i]).p, std::nullopt});
    return out;
  }
  // Extreme transmission angles of a crank-rocker, at crank angles 0 and 180 deg.
  double mu(double sign) const { return std::acos((b * b + c * c - a * a - d * d + sign * 2 * a * d) / (2 * b * c)); }
  // The transmission angle (coupler-output) at crank angle theta.
  double mu_at(double theta) const {
    const double f2 = a * a + d * d - 2 * a * d * std::cos(theta);
    return std::acos((b * b + c * c - f2) / (2 * b * c));
  }
};

// Norton's kind of crank-rocker (the bundled example): frame 200, crank 80, coupler 180, rocker 150.
const Linkage kCrankRocker{80, 180, 150, 200, 60, 110};
// The bundled non-Grashof double-rocker: frame 200, input 120, coupler 100, output 150;
// toggles at +-99.72 deg.
const Linkage kTripleRocker{120, 100, 150, 200, 50, 40};

const std::vector<double> kCrankAngles{deg(-90), deg(-20), deg(60), deg(150), deg(200)};

TEST(FourBarDesign, TargetsInOrderOnACrankRockerHaveNoDefects) {
  const FourBarDesign design = kCrankRocker.design(kCrankAngles[0], 1);
  const DesignCheck c = nbar::synthesis::check_design(design, kCrankRocker.path(kCrankAngles, {1, 1, 1, 1, 1}));
  ASSERT_TRUE(c.invalid.empty()) << c.invalid;
  EXPECT_TRUE(c.defect_free());
  EXPECT_EQ(nbar::synthesis::describe_defects(c), "none");
  EXPECT_EQ(c.grashof.kind, nbar::GrashofClass::CrankRocker);
  EXPECT_TRUE(c.input_turns_fully);
  EXPECT_NEAR(c.frame, 200, 1e-12);
  EXPECT_NEAR(c.input, 80, 1e-12);
  EXPECT_NEAR(c.coupler, 180, 1e-12);
  EXPECT_NEAR(c.output, 150, 1e-12);
  EXPECT_EQ(c.direction, 1);
  EXPECT_NEAR(c.travel, deg(290), 1e-9);
  ASSERT_EQ(c.targets.size(), 5u);
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_TRUE(c.targets[i].on_branch && c.targets[i].reached) << i;
    EXPECT_NEAR(c.targets[i].input_angle, kCrankAngles[i], 1e-9) << i;
    EXPECT_EQ(c.targets[i].branch, 1);
  }
  EXPECT_LT(c.max_error, 1e-11);
  // The motion from -90 to 200 deg passes crank angle 0, where mu is smallest: 41.41 deg.
  EXPECT_NEAR(kCrankRocker.mu(1), deg(41.40962210927086), 1e-12);
  EXPECT_NEAR(c.min_transmission, kCrankRocker.mu(1), 1e-12);
  EXPECT_NEAR(c.min_transmission_full, kCrankRocker.mu(1), 1e-12);
  // The exported sweep: a full turn from the first target, counter-clockwise.
  EXPECT_NEAR(c.motion.from, kCrankAngles[0], 1e-12);
  EXPECT_NEAR(c.motion.to, kCrankAngles[0] + 2 * kPi, 1e-12);
}

TEST(FourBarDesign, MinimumTransmissionOverAShorterMotionIsAtItsEnd) {
  // 30 to 250 deg misses crank angle 0; the worst is at 30 deg (47.88 deg), better than at
  // 180 deg (180 - 115.80 = 64.20 deg).
  const std::vector<double> thetas{deg(30), deg(80), deg(130), deg(180), deg(250)};
  const DesignCheck c =
      nbar::synthesis::check_design(kCrankRocker.design(thetas[0], 1), kCrankRocker.path(thetas, {1, 1, 1, 1, 1}));
  EXPECT_TRUE(c.defect_free());
  EXPECT_NEAR(c.min_transmission, kCrankRocker.mu_at(deg(30)), 1e-12);
  EXPECT_NEAR(c.min_transmission, deg(47.88), 0.01);
  EXPECT_NEAR(kPi - kCrankRocker.mu(-1), deg(64.20), 0.01);
  EXPECT_NEAR(c.min_transmission_full, kCrankRocker.mu(1), 1e-12);
}

TEST(FourBarDesign, TargetsInReverseOrderTurnTheCrankClockwise) {
  const std::vector<double> thetas{kCrankAngles[0], kCrankAngles[4], kCrankAngles[3], kCrankAngles[2], kCrankAngles[1]};
  const DesignCheck c =
      nbar::synthesis::check_design(kCrankRocker.design(thetas[0], 1), kCrankRocker.path(thetas, {1, 1, 1, 1, 1}));
  EXPECT_TRUE(c.defect_free());
  EXPECT_EQ(c.direction, -1);
  EXPECT_NEAR(c.travel, deg(290), 1e-9);
  EXPECT_NEAR(c.targets[1].input_angle, deg(-160), 1e-9);
  EXPECT_NEAR(c.targets[4].input_angle, deg(-380), 1e-9);
  EXPECT_LT(c.max_error, 1e-11);
}

TEST(FourBarDesign, ShuffledTargetsAreAnOrderDefect) {
  const std::vector<double> thetas{kCrankAngles[0], kCrankAngles[2], kCrankAngles[1], kCrankAngles[3], kCrankAngles[4]};
  const DesignCheck c =
      nbar::synthesis::check_design(kCrankRocker.design(thetas[0], 1), kCrankRocker.path(thetas, {1, 1, 1, 1, 1}));
  EXPECT_TRUE(c.order_defect);
  EXPECT_FALSE(c.branch_defect);
  EXPECT_FALSE(c.defect_free());
  EXPECT_EQ(nbar::synthesis::describe_defects(c), "order");
  // Every target is still met, going round more than once.
  for (const auto& t : c.targets) EXPECT_TRUE(t.reached);
  EXPECT_LT(c.max_error, 1e-11);
}

TEST(FourBarDesign, TargetsOnTheOtherCircuitAreACircuitDefect) {
  const DesignCheck c = nbar::synthesis::check_design(kCrankRocker.design(kCrankAngles[0], 1),
                                                      kCrankRocker.path(kCrankAngles, {1, -1, -1, -1, -1}));
  EXPECT_TRUE(c.branch_defect);
  EXPECT_TRUE(c.circuit_defect);
  EXPECT_FALSE(c.toggle_between);
  EXPECT_FALSE(c.defect_free());
  EXPECT_TRUE(c.targets[0].on_branch);
  for (std::size_t i = 1; i < 5; ++i) {
    EXPECT_FALSE(c.targets[i].on_branch) << i;
    EXPECT_FALSE(c.targets[i].reached) << i;
    EXPECT_EQ(c.targets[i].branch, -1) << i;
    EXPECT_LT(c.targets[i].error, 1e-9) << i;  // the other circuit does pass through them
  }
  EXPECT_EQ(nbar::synthesis::describe_defects(c), "circuit");
}

TEST(FourBarDesign, TargetsAcrossAToggleOfANonGrashofLinkage) {
  // The input rocks up to 99.72 deg; the last two targets are on the way back, on the other
  // branch.
  const std::vector<double> thetas{deg(-60), deg(-20), deg(40), deg(60), deg(20)};
  const DesignCheck c =
      nbar::synthesis::check_design(kTripleRocker.design(thetas[0], 1), kTripleRocker.path(thetas, {1, 1, 1, -1, -1}));
  EXPECT_EQ(c.grashof.kind, nbar::GrashofClass::TripleRocker);
  EXPECT_FALSE(c.input_turns_fully);
  EXPECT_TRUE(c.branch_defect);
  EXPECT_TRUE(c.toggle_between);
  EXPECT_FALSE(c.circuit_defect);
  EXPECT_FALSE(c.defect_free());
  EXPECT_TRUE(c.targets[2].reached);
  EXPECT_FALSE(c.targets[3].on_branch);
  EXPECT_FALSE(c.targets[4].on_branch);
  EXPECT_EQ(nbar::synthesis::describe_defects(c), "branch");
  EXPECT_EQ(c.min_transmission_full, 0.0);  // a rocker input meets its toggles
}

TEST(FourBarDesign, TargetsOnOneBranchOfANonGrashofLinkage) {
  const std::vector<double> thetas{deg(-60), deg(-20), deg(40), deg(80)};
  const DesignCheck c =
      nbar::synthesis::check_design(kTripleRocker.design(thetas[0], 1), kTripleRocker.path(thetas, {1, 1, 1, 1}));
  EXPECT_TRUE(c.defect_free());
  EXPECT_EQ(c.direction, 1);
  EXPECT_NEAR(c.targets[3].input_angle, deg(80), 1e-9);
  EXPECT_LT(c.max_error, 1e-11);
  // The exported sweep runs from the first target to the last.
  EXPECT_NEAR(c.motion.from, deg(-60), 1e-12);
  EXPECT_NEAR(c.motion.to, deg(80), 1e-9);
  EXPECT_EQ(c.motion.steps, 141);
  // Over -60..80 deg the extremes of |A - O4| are at the ends and at 0 deg.
  double expected = 10;
  for (double t : {deg(-60), 0.0, deg(80)}) {
    const double mu = kTripleRocker.mu_at(t);
    expected = std::min({expected, mu, kPi - mu});
  }
  EXPECT_NEAR(c.min_transmission, expected, 1e-12);
  // Backwards through the same targets: an order defect (the input would have to reverse).
  const DesignCheck back = nbar::synthesis::check_design(
      kTripleRocker.design(thetas[0], 1), kTripleRocker.path({deg(-60), deg(40), deg(-20), deg(80)}, {1, 1, 1, 1}));
  EXPECT_TRUE(back.order_defect);
  EXPECT_FALSE(back.branch_defect);
}

TEST(FourBarDesign, MotionTargetsCarryTheCouplerRotation) {
  std::vector<Target> targets;
  const auto first = kCrankRocker.pose(kCrankAngles[0], 1);
  for (double t : kCrankAngles) {
    const auto p = kCrankRocker.pose(t, 1);
    targets.push_back({p.p, p.coupler_angle - first.coupler_angle});
  }
  const DesignCheck c = nbar::synthesis::check_design(kCrankRocker.design(kCrankAngles[0], 1), targets);
  EXPECT_TRUE(c.defect_free());
  EXPECT_LT(c.max_error, 1e-11);
  EXPECT_LT(c.max_rotation_error, 1e-9);
  // A wrong rotation at one target: the pose with that rotation is elsewhere.
  targets[2].rotation = *targets[2].rotation + 0.3;
  const DesignCheck wrong = nbar::synthesis::check_design(kCrankRocker.design(kCrankAngles[0], 1), targets);
  EXPECT_GT(wrong.max_error + wrong.max_rotation_error, 1e-3);
}

TEST(FourBarDesign, FunctionTargetsCoupleInputAndOutputRotations) {
  std::vector<RotationTarget> targets;
  const auto first = kCrankRocker.pose(deg(20), 1);
  const double psi0 = std::atan2(first.b.y(), first.b.x() - 200);
  for (double t : {20.0, 45.0, 70.0, 95.0}) {
    const auto p = kCrankRocker.pose(deg(t), 1);
    targets.push_back({deg(t - 20), std::atan2(p.b.y(), p.b.x() - 200) - psi0});
  }
  const DesignCheck c = nbar::synthesis::check_design(kCrankRocker.design(deg(20), 1), targets);
  EXPECT_TRUE(c.defect_free());
  EXPECT_LT(c.max_error, 1e-10);  // radians of output rotation
  EXPECT_NEAR(c.targets[3].input_angle, deg(95), 1e-12);
}

TEST(FourBarDesign, AnInputAngleOutOfReachIsUnreached) {
  // The triple rocker's input stops at 99.72 deg: 120 deg is out of reach on any branch.
  const auto output_angle = [](double theta) {
    const Vector2d b = kTripleRocker.pose(theta, 1).b;
    return std::atan2(b.y(), b.x() - kTripleRocker.d);
  };
  const std::vector<RotationTarget> targets{
      {0, 0}, {deg(60), output_angle(0) - output_angle(deg(-60))}, {deg(180), 0.2}};
  const DesignCheck c = nbar::synthesis::check_design(kTripleRocker.design(deg(-60), 1), targets);
  EXPECT_TRUE(c.targets[1].reached);
  EXPECT_TRUE(c.unreached());
  EXPECT_FALSE(c.branch_defect);
  EXPECT_FALSE(c.targets[2].reached);
  EXPECT_FALSE(c.defect_free());
  EXPECT_EQ(nbar::synthesis::describe_defects(c), "unreached");
}

TEST(FourBarDesign, APathTargetOffTheCurveIsReportedAsAMiss) {
  std::vector<Target> targets = kCrankRocker.path(kCrankAngles, {1, 1, 1, 1, 1});
  targets[3].point += Vector2d(0.5, 0.0);
  const DesignCheck c = nbar::synthesis::check_design(kCrankRocker.design(kCrankAngles[0], 1), targets);
  EXPECT_TRUE(c.targets[3].reached);
  EXPECT_GT(c.targets[3].error, 0.01);
  EXPECT_LE(c.targets[3].error, 0.5 + 1e-9);
  EXPECT_NEAR(c.max_error, c.targets[3].error, 1e-15);
}

TEST(FourBarDesign, DegenerateDesignsAreInvalid) {
  FourBarDesign d = kCrankRocker.design(0.0, 1);
  d.ground_b = d.ground_a;
  const DesignCheck c = nbar::synthesis::check_design(d, kCrankRocker.path({0.0}, {1}));
  EXPECT_EQ(c.invalid, "the fixed pivots coincide");
  EXPECT_FALSE(c.defect_free());
  EXPECT_EQ(nbar::synthesis::describe_defects(c), "invalid: the fixed pivots coincide");
}

TEST(FourBarDesign, RankingPutsDefectFreeDesignsFirstThenTransmission) {
  std::vector<DesignCheck> checks(4);
  checks[0].order_defect = true;
  checks[0].min_transmission = 1.2;
  checks[1].min_transmission = 0.3;
  checks[2].min_transmission = 0.9;
  checks[3].invalid = "the coupler has zero length";
  const std::vector<int> order = nbar::synthesis::rank_designs(checks);
  EXPECT_EQ(order, (std::vector<int>{2, 1, 0, 3}));
}

TEST(FourBarDesign, ModelOfADesignSweepsThroughItsTargets) {
  const FourBarDesign design = kCrankRocker.design(kCrankAngles[0], 1);
  const DesignCheck c = nbar::synthesis::check_design(design, kCrankRocker.path(kCrankAngles, {1, 1, 1, 1, 1}));
  nbar::synthesis::InputMotion motion = c.motion;
  motion.steps = 3601;
  const nbar::Mechanism mech(nbar::synthesis::make_fourbar_model(design, "crank-rocker", {}, motion));
  EXPECT_EQ(mech.mobility().dof, 1);
  ASSERT_EQ(mech.four_bar_loops().size(), 1u);
  EXPECT_EQ(mech.four_bar_loops()[0].name, "input-coupler-output");
  const nbar::SweepResult sweep = nbar::run_sweep(mech, {.steps = std::nullopt, .order = 0});
  ASSERT_TRUE(sweep.complete) << sweep.stop_reason;
  // The engine's transmission angle over the turn agrees with the closed form.
  double worst = 10;
  for (const nbar::Sample& s : sweep.samples) {
    const double mu = nbar::transmission_angle(mech.four_bar_loops()[0], nbar::point_positions(mech, s.taylor.col(0)));
    worst = std::min({worst, mu, kPi - mu});
  }
  EXPECT_NEAR(worst, c.min_transmission_full, 1e-5);
}

}  // namespace
