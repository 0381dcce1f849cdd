// find_path_limits (limits.hpp): the limits of whole mechanisms on their sweep's own path,
// against independent references (a dyad stretched straight, found by intersecting circles and
// bisecting; the four-bar's toggle from the law of cosines) and against the sweep itself: every
// limit it reports is where the sweep stops, to 1e-9 of the input.
#include "example_models.hpp"
#include "test_constants.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>

#include <cmath>
#include <filesystem>
#include <functional>
#include <numbers>

#include "nbar/analysis/summary.hpp"
#include "nbar/io/model_file.hpp"
#include "nbar/kinematics/continuation.hpp"
#include "nbar/kinematics/limits.hpp"
#include "nbar/kinematics/mechanism.hpp"
#include "nbar/kinematics/sweep.hpp"

namespace nbar {
namespace {

using test_support::example_model;

using nbar::test_constants::kPi;

Eigen::Vector2d at(const Model& m, const std::string& name) {
  for (const Point& p : m.points)
    if (p.name == name) return p.position;
  ADD_FAILURE() << "no point " << name;
  return {};
}

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// The point at distance r1 from p and r2 from q on the side `sign` of p -> q.
Eigen::Vector2d circles(const Eigen::Vector2d& p, double r1, const Eigen::Vector2d& q, double r2, double sign) {
  const Eigen::Vector2d u = q - p;
  const double d = u.norm(), a = (r1 * r1 - r2 * r2 + d * d) / (2 * d);
  const double h = std::sqrt(std::max(0.0, r1 * r1 - a * a));
  return p + a * u / d + sign * h * Eigen::Vector2d(-u.y(), u.x()) / d;
}

// A point carried by the frame (o, x): its coordinates in that frame from the drawn pose.
struct Carried {
  double along = 0, across = 0;
  Carried(const Eigen::Vector2d& o, const Eigen::Vector2d& x, const Eigen::Vector2d& p) {
    const Eigen::Vector2d u = (x - o).normalized();
    along = u.dot(p - o);
    across = cross(u, p - o);
  }
  Eigen::Vector2d place(const Eigen::Vector2d& o, const Eigen::Vector2d& x) const {
    const Eigen::Vector2d u = (x - o).normalized();
    return o + along * u + across * Eigen::Vector2d(-u.y(), u.x());
  }
};

// The four-bar O2-A-B-O4 of the six-bars, posed by the input angle on the drawn branch.
struct FourBar {
  Eigen::Vector2d o2, o4;
  double a, b, c, sign;
  explicit FourBar(const Model& m)
      : o2(at(m, "O2")),
        o4(at(m, "O4")),
        a((at(m, "A") - o2).norm()),
        b((at(m, "B") - at(m, "A")).norm()),
        c((at(m, "B") - o4).norm()),
        sign(cross(o4 - at(m, "A"), at(m, "B") - at(m, "A")) > 0 ? 1.0 : -1.0) {}
  Eigen::Vector2d pin_a(double theta) const { return o2 + a * Eigen::Vector2d(std::cos(theta), std::sin(theta)); }
  Eigen::Vector2d pin_b(double theta) const { return circles(pin_a(theta), b, o4, c, sign); }
};

double bisect(const std::function<double(double)>& f, double lo, double hi) {
  const bool rising = f(hi) > 0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    ((f(mid) > 0) == rising ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

// The sweep from the model's start to `to` (SI) on its first driver: whether it gets there.
bool sweep_reaches(Model m, double to) {
  m.drivers[0].to = to;
  m.drivers[0].speed = std::copysign(std::abs(m.drivers[0].speed), to - *m.drivers[0].from);
  m.sweep.steps = 20001;  // the tracker gives up within 1e-7 of a sample interval of a limit
  return run_sweep(Mechanism(std::move(m)), {}).complete;
}

// Every limit found on the path is where the sweep stops, to 1e-9 of the input.
void expect_met_by_the_sweep(const Model& m, const PathSingularity& limit) {
  const double x = limit.driver_values[0], slack = 1e-9 * std::max(1.0, std::abs(x));
  EXPECT_TRUE(sweep_reaches(m, x - std::copysign(slack, x - *m.drivers[0].from))) << x;
  EXPECT_FALSE(sweep_reaches(m, x + std::copysign(slack, x - *m.drivers[0].from))) << x;
}

// The example driven from 0 to `to` degrees.
Model driven_to(const std::string& name, double to) {
  Model m = example_model(name);
  m.drivers[0].to = to * kPi / 180;
  m.drivers[0].speed = std::copysign(m.drivers[0].speed, to);
  return m;
}

TEST(MechanismLimits, WattSixBarStopsWhereItsDyadStretchesNotAtItsFourBarsToggles) {
  const Model m = driven_to("watt-sixbar-limited.yaml", 60);
  const FourBar four(m);
  const Carried c(at(m, "A"), at(m, "B"), at(m, "C")), d(at(m, "O4"), at(m, "B"), at(m, "D"));
  const double reach = (at(m, "E") - at(m, "C")).norm() + (at(m, "D") - at(m, "E")).norm();
  const auto gap = [&](double theta) {
    const Eigen::Vector2d b = four.pin_b(theta);
    return (d.place(four.o4, b) - c.place(four.pin_a(theta), b)).norm() - reach;
  };
  const double reference = bisect(gap, 0.0, 60 * kPi / 180);

  const Mechanism mech(m);
  const PathLimits limits = find_path_limits(mech);
  ASSERT_TRUE(limits.stop.has_value());
  EXPECT_NEAR(limits.stop->driver_values[0], reference, 1e-9 * reference);
  EXPECT_EQ(limits.stop->involved, "link5 and link6 in line at E (four-bar loop rocker-link6-link5)");
  // The dyad is symmetric about the start: the limit behind is the mirror one.
  ASSERT_NE(limits.behind.limit(), nullptr);
  EXPECT_NEAR(limits.behind.limit()->driver_values[0], bisect(gap, -60 * kPi / 180, 0.0), 1e-9 * reference);
  expect_met_by_the_sweep(m, *limits.stop);
  expect_met_by_the_sweep(m, *limits.behind.limit());

  // check warns with the true value, not the four-bar's toggle (99.7 deg).
  const ModelSummary summary = summarize(mech);
  ASSERT_EQ(summary.warnings.size(), 1u);
  EXPECT_NE(summary.warnings[0].message.find("the sweep will stop at 15.2758 deg"), std::string::npos)
      << summary.warnings[0].message;
}

// The dump truck's cylinder (its pin-to-pin length the driver) is shortest where its eye E, on the
// bed turning about the hinge H, lines up with its base C0: |C0 H| - |H E|. The path's limit behind
// is that length, and the sweep toward it stops there.
TEST(MechanismLimits, ADumpTrucksCylinderIsShortestWhereItsEyeLinesUpWithTheHinge) {
  const Model m = example_model("dump-truck-tipper.yaml");
  const double reference = (at(m, "C0") - at(m, "H")).norm() - (at(m, "E") - at(m, "H")).norm();
  const PathLimits limits = find_path_limits(Mechanism(m));
  EXPECT_FALSE(limits.stop.has_value());  // the sweep lengthens the cylinder, away from it
  ASSERT_NE(limits.behind.limit(), nullptr);
  EXPECT_NEAR(limits.behind.limit()->driver_values[0], reference, 1e-9 * reference);
  expect_met_by_the_sweep(m, *limits.behind.limit());
}

TEST(MechanismLimits, StephensonSixBarIsLimitedOneWayByItsDyadAndTheOtherByItsFourBar) {
  const Model m = driven_to("stephenson-sixbar-limited.yaml", -60);
  const FourBar four(m);
  const Carried c(at(m, "A"), at(m, "B"), at(m, "C"));
  const double reach = (at(m, "D") - at(m, "C")).norm() + (at(m, "O6") - at(m, "D")).norm();
  const auto gap = [&](double theta) {
    return (at(m, "O6") - c.place(four.pin_a(theta), four.pin_b(theta))).norm() - reach;
  };
  const double dyad = bisect(gap, -60 * kPi / 180, 0.0);
  // Behind: the four-bar's own toggle, coupler and rocker in line: |O4 A| = b + c.
  const double d = (four.o4 - four.o2).norm();
  const double toggle = std::acos((four.a * four.a + d * d - (four.b + four.c) * (four.b + four.c)) / (2 * four.a * d));

  const Mechanism mech(m);
  const PathLimits limits = find_path_limits(mech);
  ASSERT_TRUE(limits.stop.has_value());
  EXPECT_NEAR(limits.stop->driver_values[0], dyad, 1e-9 * std::abs(dyad));
  EXPECT_EQ(limits.stop->involved, "link5 and output in line at D");
  ASSERT_NE(limits.behind.limit(), nullptr);
  EXPECT_NEAR(limits.behind.limit()->driver_values[0], toggle, 1e-9 * toggle);
  EXPECT_EQ(limits.behind.limit()->involved, "coupler and rocker in line at B (four-bar loop input-coupler-rocker)");
  expect_met_by_the_sweep(m, *limits.stop);
  expect_met_by_the_sweep(m, *limits.behind.limit());
  // Swept the other way, from 0 to 90 deg, the path meets the four-bar's toggle at 99.7 deg only
  // beyond its end: no warning, and the sweep completes.
  const Mechanism other_mech(driven_to("stephenson-sixbar-limited.yaml", 90));
  EXPECT_FALSE(find_path_limits(other_mech).stop.has_value());
  EXPECT_TRUE(summarize(other_mech).warnings.empty());
  EXPECT_TRUE(run_sweep(other_mech, {}).complete);
}

TEST(MechanismLimits, DoubleRockersLimitsAreItsToggles) {
  const Model m = example_model("fourbar-double-rocker.yaml");
  const FourBar four(m);
  const double d = (four.o4 - four.o2).norm();
  const double toggle = std::acos((four.a * four.a + d * d - (four.b + four.c) * (four.b + four.c)) / (2 * four.a * d));
  const PathLimits limits = find_path_limits(Mechanism(m));
  EXPECT_FALSE(limits.stop.has_value());  // the example sweeps -80 to 80 deg, inside them
  ASSERT_NE(limits.ahead.limit(), nullptr);
  ASSERT_NE(limits.behind.limit(), nullptr);
  EXPECT_NEAR(limits.ahead.limit()->driver_values[0], toggle, 1e-9 * toggle);
  EXPECT_NEAR(limits.behind.limit()->driver_values[0], -toggle, 1e-9 * toggle);
  expect_met_by_the_sweep(m, *limits.ahead.limit());
  expect_met_by_the_sweep(m, *limits.behind.limit());
}

TEST(MechanismLimits, CranksThatTurnFullyHaveNone) {
  for (const char* name :
       {"fourbar-crank-rocker.yaml", "watt-sixbar.yaml", "stephenson-sixbar.yaml", "machine-18.yaml"}) {
    const PathLimits limits = find_path_limits(Mechanism(example_model(name)));
    EXPECT_TRUE(limits.ahead.turns_fully && limits.behind.turns_fully) << name;
    EXPECT_EQ(limits.ahead.limit(), nullptr) << name;
    EXPECT_EQ(limits.behind.limit(), nullptr) << name;
  }
}

TEST(MechanismLimits, TheLimitedExamplesSweepInsideTheirLimitsWithoutWarning) {
  for (const char* name : {"watt-sixbar-limited.yaml", "stephenson-sixbar-limited.yaml"}) {
    const Mechanism mech(example_model(name));
    const ModelSummary summary = summarize(mech);
    EXPECT_TRUE(summary.warnings.empty()) << name;
    ASSERT_TRUE(summary.limits.has_value()) << name;
    EXPECT_FALSE(summary.limits->stop.has_value()) << name;
    EXPECT_TRUE(run_sweep(mech, {}).complete) << name;
  }
}

TEST(MechanismLimits, AParallelogramsFlatPositionsAreChangePointsNotLimits) {
  const PathLimits limits = find_path_limits(Mechanism(example_model("parallelogram-redundant.yaml")));
  ASSERT_FALSE(limits.ahead.singularities.empty());
  for (const PathSingularity& s : limits.ahead.singularities) {
    EXPECT_EQ(s.kind, PathSingularityKind::ChangePoint);
    // Flat: the crank's angle a multiple of 180 deg.
    EXPECT_NEAR(std::remainder(s.driver_values[0], kPi), 0.0, 1e-9);
  }
}

// Every limit check reports for a bundled example (find_path_limits, both ways: the summary's list
// and its warnings come from it) is where the sweep stops, to 1e-9 of the input: the one-driver
// models driven at a speed, with a rocking driver swept as an ordinary one.
TEST(MechanismLimits, EveryLimitOfTheBundledExamplesIsWhereTheSweepStops) {
  int limits_met = 0;
  for (const auto& entry : std::filesystem::directory_iterator(NBAR_EXAMPLES_DIR)) {
    if (entry.path().extension() != ".yaml") continue;
    Model m = io::load_model_file(entry.path().string()).model;
    if (m.drivers.size() != 1 || m.drivers[0].law || m.drivers[0].accel != 0.0) continue;
    m.drivers[0].at_limits = AtLimits::Stop;
    m.drivers[0].cycles.reset();
    if (!m.drivers[0].from) m.drivers[0].from = Mechanism(m).drawn_driver_values()[0];
    const PathLimits limits = find_path_limits(Mechanism(m));
    for (const PathReach* reach : {&limits.ahead, &limits.behind}) {
      EXPECT_TRUE(reach->undecided.empty()) << entry.path() << ": " << reach->undecided;
      if (const PathSingularity* limit = reach->limit()) {
        SCOPED_TRACE(entry.path().filename().string());
        expect_met_by_the_sweep(m, *limit);
        ++limits_met;
      }
    }
  }
  // Both ways for the double-rocker and the two limited six-bars, behind for the dump truck and the
  // scissor lift (the others turn fully, are driven by laws or by several drivers, or, as the
  // rocking copy of the double-rocker without `to`, have no sweep range to search from).
  EXPECT_EQ(limits_met, 8);
}

// The scissor lift's way ahead passes the pose where all its arms stand upright (a change point of
// its parallelogram), which the follower approaches with steps shrinking with the conditioning:
// the longest search of the bundled examples. Its limit behind (the foot at 800 mm, where arm1
// and arm2 fold in line: 600 mm arms, cross pins at mid-length) is the reference.
TEST(MechanismLimits, TheExamplesSearchWellInsideTheDefaultBudget) {
  for (const char* name : {"scissor-lift.yaml", "machine-18.yaml", "watt-sixbar.yaml", "fourbar-oscillating.yaml"}) {
    const PathLimits limits = find_path_limits(Mechanism(example_model(name)));
    EXPECT_GT(limits.work, 0.0) << name;
    EXPECT_LT(limits.work, kDefaultLimitSearchWork / 20) << name;
    EXPECT_TRUE(limits.ahead.undecided.empty() && limits.behind.undecided.empty()) << name;
  }
  const PathLimits scissor = find_path_limits(Mechanism(example_model("scissor-lift.yaml")));
  ASSERT_NE(scissor.behind.limit(), nullptr);
  EXPECT_NEAR(scissor.behind.limit()->driver_values[0], 0.8, 1e-9);
}

// A search past its budget stops within a step of it and says so, with where it stopped; the
// summary carries the same words, and what the search found before it is kept.
TEST(MechanismLimits, ASearchPastItsBudgetStopsThereAndSaysWhere) {
  const Mechanism mech(example_model("scissor-lift.yaml"));
  const PathLimits full = find_path_limits(mech);
  for (double budget : {2e5, 3e6, 0.5 * full.work}) {
    LimitSearchOptions options;
    options.work_budget = budget;
    const PathLimits limits = find_path_limits(mech, options);
    EXPECT_LE(limits.work, budget + 1e6) << budget;
    const PathReach& undecided = limits.ahead.undecided.empty() ? limits.behind : limits.ahead;
    const std::string& why = undecided.undecided;
    EXPECT_NE(why.find("work budget"), std::string::npos) << budget << ": " << why;
    // Where: the input's value in the model's unit, and the bodies nearest a singular position
    // there, told as for a limit found (PathSingularity::involved).
    ASSERT_TRUE(undecided.undecided_at) << why;
    const PathSingularity& at = *undecided.undecided_at;
    EXPECT_NE(why.find(", at actuator = " + format_driver_value(mech.model(), 0, at.driver_values[0]) +
                       " (nearest a singular position there: " + at.involved + ")"),
              std::string::npos)
        << why;
    EXPECT_FALSE(at.bodies.empty()) << why;
    // The pose it stopped at is on the path: the model's rows hold there, the slide at its value.
    State state(mech);
    state.q = at.q;
    const Sample solved = solve_at(mech, state, at.driver_values, 0);
    EXPECT_LT((solved.positions() - at.q).norm(), 1e-9 * mech.characteristic_length()) << why;
    // Between the foot's limit behind (800 mm) and a turn past its start (900 mm) ahead.
    EXPECT_GT(at.driver_values[0], 0.8 - 1e-9);
  }
  const ModelSummary summary = summarize(mech, kDefaultMaxSweepSamples, 3e6);
  ASSERT_TRUE(summary.limits.has_value());
  EXPECT_NE(summary.limits->ahead.undecided.find("work budget"), std::string::npos);
}

}  // namespace
}  // namespace nbar
