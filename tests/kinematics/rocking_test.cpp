// Rocking sweeps (`at_limits: reverse`): the input turns back at the mechanism's limits. Checked
// against the double-rocker's toggle from the law of cosines (its input's time law is then a
// triangle wave known in closed form), against find_path_limits' values, and against the motion
// itself: a cycle closes on its start, the second cycle repeats the first, and the input's speed
// changes sign with its size kept at each turn.
#include "example_models.hpp"
#include "test_constants.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>

#include <cmath>
#include <numbers>

#include "../io/model_file_support.hpp"
#include "four_bar_closed_form.hpp"
#include "nbar/analysis/summary.hpp"
#include "nbar/io/model_file.hpp"
#include "nbar/kinematics/limits.hpp"
#include "nbar/kinematics/mechanism.hpp"
#include "nbar/kinematics/sweep.hpp"

namespace nbar {
namespace {

using test_support::example_model;

using nbar::test_constants::kDeg;
using nbar::test_constants::kPi;

Model rocking(Model m, std::optional<int> cycles) {
  m.drivers[0].at_limits = AtLimits::Reverse;
  m.drivers[0].cycles = cycles;
  return m;
}

// The largest difference of two samples' positions, of the model's size.
double pose_gap(const Mechanism& mech, const Sample& a, const Sample& b) {
  return (a.positions() - b.positions()).cwiseAbs().maxCoeff() / mech.characteristic_length();
}

// The double-rocker's toggle (coupler and output in line, stretched): |O4 A| = coupler + output,
// with the lengths of the drawn links (120, 100 and 150 mm to the drawing's 6 decimals).
double double_rocker_toggle(const Model& m) {
  const auto at = [&](const char* name) {
    for (const Point& p : m.points)
      if (p.name == name) return p.position;
    ADD_FAILURE() << name;
    return Eigen::Vector2d();
  };
  const double input = (at("A") - at("O2")).norm(), ground = (at("O4") - at("O2")).norm();
  const double stretched = (at("B") - at("A")).norm() + (at("B") - at("O4")).norm();
  return std::acos((input * input + ground * ground - stretched * stretched) / (2 * input * ground));
}

TEST(Rocking, DoubleRockerTurnsAtItsTogglesOnATriangleWave) {
  const Mechanism mech(rocking(example_model("fourbar-double-rocker.yaml"), 2));
  SweepOptions options;
  options.steps = 401;
  const SweepResult sweep = run_sweep(mech, options);
  ASSERT_TRUE(sweep.complete) << sweep.stop_reason;
  ASSERT_EQ(sweep.samples.size(), 401u);
  const double toggle = double_rocker_toggle(mech.model());  // 99.7151 deg
  ASSERT_EQ(sweep.reversals.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i)
    EXPECT_NEAR(sweep.reversals[i].driver_value, i % 2 == 0 ? toggle : -toggle, 1e-12) << i;
  // One cycle: from -80 deg up to the toggle, down to the other, up to -80 deg, at 30 deg/s.
  const double start = -80 * kDeg, speed = 30 * kDeg;
  const double cycle = (toggle - start) + 2 * toggle + (start + toggle);
  EXPECT_NEAR(sweep.samples.back().time, 2 * cycle / speed, 1e-12);
  EXPECT_NEAR(sweep.reversals[0].time, (toggle - start) / speed, 1e-12);
  for (const Sample& s : sweep.samples) {
    // The triangle wave, folded by hand: travel from the start, then reflected at the toggles.
    const double travel = std::fmod(s.time * speed, cycle);
    double expected = start + travel;
    if (expected > toggle) expected = 2 * toggle - expected;
    if (expected < -toggle) expected = -2 * toggle - expected;
    ASSERT_NEAR(s.driver_values[0], expected, 1e-12) << "step " << s.step;
  }
}

TEST(Rocking, ReversesWhereFindPathLimitsPutsTheLimits) {
  for (const char* name :
       {"fourbar-double-rocker.yaml", "watt-sixbar-limited.yaml", "stephenson-sixbar-limited.yaml"}) {
    const Model plain = example_model(name);
    const PathLimits limits = find_path_limits(Mechanism(plain));
    ASSERT_TRUE(limits.ahead.limit()) << name;
    const Mechanism mech(rocking(plain, 1));
    SweepOptions options;
    options.steps = 201;
    const SweepResult sweep = run_sweep(mech, options);
    ASSERT_TRUE(sweep.complete) << name << ": " << sweep.stop_reason;
    ASSERT_GE(sweep.reversals.size(), 2u) << name;
    const double ahead = limits.ahead.limit()->driver_values[0];
    EXPECT_NEAR(sweep.reversals.front().driver_value, ahead, 1e-9 * std::abs(ahead)) << name;
    // The last turn of a cycle is the limit behind the start: the path comes back through it.
    ASSERT_TRUE(limits.behind.limit()) << name;
    const double behind = limits.behind.limit()->driver_values[0];
    EXPECT_NEAR(sweep.reversals.back().driver_value, behind, 1e-9 * std::abs(behind)) << name;
    // A full cycle closes on itself.
    EXPECT_LT(pose_gap(mech, sweep.samples.front(), sweep.samples.back()), 1e-12) << name;
  }
}

TEST(Rocking, TheSecondCycleRepeatsTheFirst) {
  for (const char* name :
       {"fourbar-double-rocker.yaml", "watt-sixbar-limited.yaml", "stephenson-sixbar-limited.yaml"}) {
    const Mechanism mech(rocking(example_model(name), 2));
    SweepOptions options;
    options.steps = 2 * 150 + 1;
    const SweepResult sweep = run_sweep(mech, options);
    ASSERT_TRUE(sweep.complete) << name << ": " << sweep.stop_reason;
    double gap = 0, velocity_gap = 0, velocity_size = 0;
    for (int i = 0; i <= 150; ++i) {
      const Sample &first = sweep.samples[i], &second = sweep.samples[i + 150];
      gap = std::max(gap, pose_gap(mech, first, second));
      velocity_gap = std::max(velocity_gap, (first.derivative(1) - second.derivative(1)).cwiseAbs().maxCoeff());
      velocity_size = std::max(velocity_size, first.derivative(1).cwiseAbs().maxCoeff());
      ASSERT_EQ(second.reversals - first.reversals, sweep.reversals.size() / 2) << name << " step " << i;
    }
    EXPECT_LT(gap, 1e-12) << name;
    EXPECT_LT(velocity_gap, 1e-9 * velocity_size) << name;
  }
}

TEST(Rocking, TheInputsSpeedChangesSignWithItsSizeKept) {
  const Mechanism mech(rocking(example_model("watt-sixbar-limited.yaml"), 1));
  SweepOptions options;
  options.steps = 100;  // 101 would put samples 25 and 75 on the turns (the cycle is symmetric)
  const SweepResult sweep = run_sweep(mech, options);
  ASSERT_TRUE(sweep.complete) << sweep.stop_reason;
  const int input = mech.model().drivers[0].body;
  ASSERT_EQ(sweep.reversals.size(), 2u);
  for (const Reversal& r : sweep.reversals) {
    ASSERT_FALSE(r.at_sample);
    const Sample &before = sweep.samples[r.after_step], &after = sweep.samples[r.after_step + 1];
    EXPECT_EQ(after.reversals, before.reversals + 1);
    const double omega_before = body_angle_motion(mech, before, input)[1];
    const double omega_after = body_angle_motion(mech, after, input)[1];
    EXPECT_NEAR(omega_before, -omega_after, 1e-12 * std::abs(omega_before));
    EXPECT_NEAR(std::abs(omega_before), 30 * kDeg, 1e-12);
    // The turn lies between the two samples in time and in the input.
    EXPECT_LT(before.time, r.time);
    EXPECT_GT(after.time, r.time);
    EXPECT_GT(std::abs(r.driver_value), std::abs(before.driver_values[0]));
    EXPECT_GT(std::abs(r.driver_value), std::abs(after.driver_values[0]));
  }
}

TEST(Rocking, ASampleOnATurnHasTheLimitsPoseAndNoDerivatives) {
  // The Watt six-bar's cycle is symmetric (0, up to L, down to -L, back to 0): 201 samples put
  // steps 50 and 150 on its turns, where the dyad C-E-D lies straight.
  const Mechanism mech(rocking(example_model("watt-sixbar-limited.yaml"), 1));
  SweepOptions options;
  options.steps = 201;
  const SweepResult sweep = run_sweep(mech, options);
  ASSERT_TRUE(sweep.complete) << sweep.stop_reason;
  ASSERT_EQ(sweep.reversals.size(), 2u);
  const Model& m = mech.model();
  const auto at = [&](const Sample& s, const char* name) {
    for (std::size_t p = 0; p < m.points.size(); ++p)
      if (m.points[p].name == name) return mech.point_position(static_cast<int>(p), s.positions());
    ADD_FAILURE() << name;
    return Eigen::Vector2d();
  };
  for (int k = 0; k < 2; ++k) {
    const Reversal& r = sweep.reversals[k];
    EXPECT_TRUE(r.at_sample);
    EXPECT_EQ(r.after_step, 50 + 100 * k);
    const Sample& s = sweep.samples[r.after_step];
    EXPECT_EQ(s.driver_values[0], r.driver_value);
    EXPECT_EQ(s.reversals, k + 1);
    EXPECT_EQ(sweep.samples[r.after_step - 1].reversals, k);
    // Straight: |CE| + |ED| = |CD|, to rounding of the 140 mm dyad.
    const Eigen::Vector2d c = at(s, "C"), e = at(s, "E"), d = at(s, "D");
    EXPECT_NEAR((e - c).norm() + (d - e).norm(), (d - c).norm(), 1e-12);
    EXPECT_TRUE(s.positions().allFinite());
    EXPECT_TRUE(std::isnan(s.derivative(1)[0]));
  }
  bool warned = false;
  for (const Warning& w : sweep.warnings) warned = warned || (w.code == "sample_on_turn" && w.step == 50);
  EXPECT_TRUE(warned);
}

TEST(Rocking, TravelFromToTurnsBackAndGoesOn) {
  // Without cycles the input travels |to - from| in all: 0 to 15 deg and then 40 deg more.
  Model m = rocking(example_model("watt-sixbar-limited.yaml"), std::nullopt);
  m.drivers[0].to = 55 * kDeg;
  const Mechanism mech(m);
  const SweepResult sweep = run_sweep(mech);
  ASSERT_TRUE(sweep.complete) << sweep.stop_reason;
  EXPECT_NEAR(sweep.samples.back().time, 55.0 / 30.0, 1e-12);
  ASSERT_EQ(sweep.reversals.size(), 2u);
  const double limit = sweep.reversals[0].driver_value;  // 15.2758 deg, and -15.2758 deg after
  EXPECT_NEAR(sweep.samples.back().driver_values[0], -limit + (55 * kDeg - limit - 2 * limit), 1e-12);
}

TEST(Rocking, AnInputThatTurnsFullyNeverReverses) {
  const Model plain = example_model("fourbar-crank-rocker.yaml");
  const Mechanism mech(rocking(plain, std::nullopt));
  const SweepResult sweep = run_sweep(mech), ordinary = run_sweep(Mechanism(plain));
  ASSERT_FALSE(sweep.warnings.empty());
  EXPECT_EQ(sweep.warnings.front().code, "never_reverses");
  EXPECT_NE(sweep.warnings.front().message.find("never reverses"), std::string::npos);
  EXPECT_TRUE(sweep.reversals.empty());
  ASSERT_EQ(sweep.samples.size(), ordinary.samples.size());
  EXPECT_EQ(sweep.samples.back().positions(), ordinary.samples.back().positions());
  const ModelSummary summary = summarize(mech);
  ASSERT_TRUE(summary.rocking);
  EXPECT_NE(summary.rocking->find("never reverses"), std::string::npos);
  bool warned = false;
  for (const Warning& w : summary.warnings) warned = warned || w.code == "never_reverses";
  EXPECT_TRUE(warned);
}

TEST(Rocking, CheckSaysWhereItTurnsAndWarnsNotOfAStop) {
  Model m = rocking(example_model("watt-sixbar-limited.yaml"), 1);
  m.drivers[0].to = 20 * kDeg;  // past the limit: an ordinary sweep would stop there
  const ModelSummary summary = summarize(Mechanism(m));
  ASSERT_TRUE(summary.rocking);
  EXPECT_NE(summary.rocking->find("turns back at 15.2758 deg"), std::string::npos) << *summary.rocking;
  for (const Warning& w : summary.warnings) EXPECT_NE(w.code, "input_limited") << w.message;
}

// A parallelogram (crank = rocker = 100 mm, coupler = frame = 200 mm) driven by its diagonal
// |A O4|, drawn with the crank at 60 deg. As the crank passes 0 deg the diagonal is shortest,
// d - a = 100 mm, so the input turns back there; but there the parallelogram also lies flat, a
// change point where it may go on as a parallelogram or as an antiparallelogram (coupler and
// rocker in line at B, over O4): four branches meet, and a turn there cannot say which it takes.
const std::string kParallelogramByItsDiagonal =
    "units: {length: mm, angle: deg}\n"
    "points: {O2: [0, 0], O4: [200, 0], A: [50, 86.602540378443865], B: [250, 86.602540378443865]}\n"
    "ground: [O2, O4]\n"
    "bodies: {crank: [O2, A], coupler: [A, B], rocker: [O4, B]}\n"
    "drivers:\n"
    "  - {distance: [A, O4], speed: -10 mm/s, at_limits: reverse, cycles: 1, name: diagonal}\n";

TEST(Rocking, ATurnAtAChangePointIsRefusedAndSaysWhichAndWhere) {
  const Mechanism mech(io::parse_model(kParallelogramByItsDiagonal).model);
  std::string message;
  try {
    run_sweep(mech);
    ADD_FAILURE() << "the sweep rocked through a change point";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::StoppedAtLimit);
    message = e.message();
  }
  EXPECT_NE(message.find("driver 'diagonal' cannot rock: its path turns back at 100 mm, which is a change point"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("coupler and rocker in line at B"), std::string::npos) << message;
  // check says the same, as a warning, before any sweep.
  const ModelSummary summary = summarize(mech);
  ASSERT_TRUE(summary.rocking);
  EXPECT_EQ(*summary.rocking, message);
  // The limit search finds both at the same place: d - a = 100 mm, the crank at 0 deg.
  Model stopping = mech.model();
  stopping.drivers[0].at_limits = AtLimits::Stop;
  stopping.drivers[0].cycles.reset();
  stopping.drivers[0].to = 0.050;  // down towards 50 mm: past the limit, where the sweep stops
  const PathLimits limits = find_path_limits(Mechanism(stopping));
  ASSERT_TRUE(limits.stop);
  EXPECT_NEAR(limits.stop->driver_values[0], 0.100, 1e-9 * 0.100);
  ASSERT_EQ(limits.ahead.singularities.size(), 2u);
  EXPECT_EQ(limits.ahead.singularities[0].kind, PathSingularityKind::ChangePoint);
  EXPECT_EQ(limits.ahead.singularities[1].kind, PathSingularityKind::Limit);
  for (const PathSingularity& s : limits.ahead.singularities) {
    EXPECT_NEAR(s.driver_values[0], 0.100, 1e-9 * 0.100);
    const Eigen::Vector2d a = mech.point_position(mech.model().find_point("A"), s.q);
    // Located to about 3e-7 of the model's size along the path: the crank's angle to that over its length.
    EXPECT_NEAR(std::atan2(a.y(), a.x()), 0.0, 1e-5);
  }
}

// A double-rocker's limit is not a change point: its branches do not cross there.
TEST(Rocking, ASimpleLimitIsNotTakenForAChangePoint) {
  const PathLimits limits = find_path_limits(Mechanism(example_model("fourbar-double-rocker.yaml")));
  for (const PathReach* reach : {&limits.ahead, &limits.behind})
    for (const PathSingularity& s : reach->singularities) EXPECT_EQ(s.kind, PathSingularityKind::Limit);
}

// draw --at on a rocking path: the pose where the motion first has the value. The double-rocker
// starts at -80 deg going up, turns at +L (99.7151 deg) onto its other branch (B across the line
// O4-A from where it was drawn), comes down to -L and back onto the drawn branch. So 0 deg is first
// met on the drawn branch, -90 deg on the way down, on the other one; 120 deg never.
TEST(Rocking, APoseAtAValueIsWhereTheMotionFirstHasIt) {
  const Mechanism mech(rocking(example_model("fourbar-double-rocker.yaml"), 1));
  const Model& m = mech.model();
  const RockingPlan plan = plan_rocking(mech);
  const double toggle = double_rocker_toggle(m), speed = 30 * kDeg;
  const test_support::FourBarClosedForm four_bar(m);
  const double input = four_bar.input, drawn_side = four_bar.drawn_side;
  const auto pin_b = [&](double theta, double side) { return four_bar.pin_b(theta, side); };
  const int b = m.find_point("B");
  const Sample up = rocking_sample_at(mech, plan, 0.0, 1);
  EXPECT_EQ(up.reversals, 0);
  EXPECT_NEAR(up.time, 80 * kDeg / speed, 1e-12);
  EXPECT_LT((mech.point_position(b, up.positions()) - pin_b(0.0, drawn_side)).norm(), 1e-12);
  EXPECT_NEAR(up.derivative(1)[mech.column_of(m.find_point("A")) + 1], input * speed, 1e-12);  // A.vy, rising
  const Sample down = rocking_sample_at(mech, plan, -90 * kDeg, 1);
  EXPECT_EQ(down.reversals, 1);
  EXPECT_NEAR(down.time, ((toggle + 80 * kDeg) + (toggle + 90 * kDeg)) / speed, 1e-9);
  EXPECT_LT((mech.point_position(b, down.positions()) - pin_b(-90 * kDeg, -drawn_side)).norm(), 1e-12);
  // Coming down the input turns clockwise: A, straight below O2 at -90 deg, moves towards -x.
  EXPECT_NEAR(down.derivative(1)[mech.column_of(m.find_point("A"))], -input * speed, 1e-12);
  try {
    rocking_sample_at(mech, plan, 120 * kDeg, 0);
    ADD_FAILURE() << "a pose past the limits";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::StoppedAtLimit);
    EXPECT_EQ(e.message(),
              "driver 'input' rocks between -99.7151 deg and 99.7151 deg (`at_limits: reverse`): it never "
              "reaches 120 deg");
  }
}

using io::test_support::fails_at;

const std::string kDoubleRocker =
    "units: {length: mm, angle: deg}\n"                                                             // 1
    "points: {O2: [0, 0], O4: [200, 0], A: [20.837781, -118.17693], B: [51.787322, -23.086837]}\n"  // 2
    "ground: [O2, O4]\n"                                                                            // 3
    "bodies: {input: [O2, A], coupler: [A, B], output: [O4, B]}\n"                                  // 4
    "drivers:\n";                                                                                   // 5

TEST(Rocking, ModelFileOptions) {
  const Model m =
      io::parse_model(kDoubleRocker + "  - {angle: input, from: -80, at_limits: reverse, cycles: 3}\n").model;
  EXPECT_EQ(m.drivers[0].at_limits, AtLimits::Reverse);
  EXPECT_EQ(m.drivers[0].cycles, 3);
  EXPECT_EQ(io::parse_model(kDoubleRocker + "  - {angle: input, at_limits: stop}\n").model.drivers[0].at_limits,
            AtLimits::Stop);
  EXPECT_TRUE(fails_at(kDoubleRocker + "  - {angle: input, at_limits: bounce}\n", "6:31",
                       "`at_limits` is `stop` (the sweep ends at a limit) or `reverse`"));
  EXPECT_TRUE(fails_at(kDoubleRocker + "  - {angle: input, cycles: 2}\n", "6:20", "it needs `at_limits: reverse`"));
  EXPECT_TRUE(fails_at(kDoubleRocker + "  - {angle: input, at_limits: reverse, cycles: 1.5}\n", "6:48",
                       "`cycles` is a whole number from 1 to 10000"));
  EXPECT_TRUE(fails_at(kDoubleRocker + "  - {angle: input, at_limits: reverse, accel: 1}\n", "6:5",
                       "at a steady speed: it takes no `accel`"));
  EXPECT_TRUE(fails_at(kDoubleRocker + "  - {angle: input, at_limits: reverse}\n  - {angle: output}\n", "6:5",
                       "which needs it to be the model's only driver (this model has 2)"));
}

}  // namespace
}  // namespace nbar
