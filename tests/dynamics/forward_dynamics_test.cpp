// Forward dynamics against references derived here by hand: a parallelogram with a redundant
// third crank swinging as one pendulum (its equation in the crank angle, integrated by RK4 below),
// a damped, spring-loaded pendulum settling where its potential is stationary, and a fully driven
// mechanism following its kinematics. The four-bar, slider-crank and double pendulum against
// Lagrange's equations are tests/dynamics/simulate_reference.py (through the CLI).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

#include "bench_models.hpp"
#include "dynamics/forward_dynamics_testing.hpp"
#include "dynamics/simulation_support.hpp"
#include "nbar/dynamics/forward_dynamics.hpp"
#include "nbar/io/model_file.hpp"
#include "nbar/kinematics/position.hpp"

namespace nbar {
namespace {

using test_support::angle_of;
using test_support::mechanism_of;
using test_support::rk4;

// Three equal cranks (0.1 m, 0.4 kg, 2e-4 kg m^2 about their middles) carry a coupler of 1.5 kg,
// which translates: the whole is one pendulum in the crank angle th,
//   (3 (I + m r^2/4) + M r^2) th'' = -(3 m r/2 + M r) g cos th.
// The third crank repeats a constraint (rank-deficient Jacobian); the motion is still unique.
TEST(ForwardDynamics, RedundantParallelogramSwingsAsOnePendulum) {
  const Mechanism mech = mechanism_of(R"(
units: {length: m, angle: deg}
points:
  O1: [0, 0]
  O2: [0.3, 0]
  O3: [0.15, 0.12]
  A1: [0.1, 0]
  A2: [0.4, 0]
  A3: [0.25, 0.12]
ground: [O1, O2, O3]
gravity: [0, -9.81]
bodies:
  crank1: {points: [O1, A1], mass: 0.4, inertia: 2e-4, cg: [0.05, 0]}
  crank2: {points: [O2, A2], mass: 0.4, inertia: 2e-4, cg: [0.35, 0]}
  crank3: {points: [O3, A3], mass: 0.4, inertia: 2e-4, cg: [0.2, 0.12]}
  coupler: {points: [A1, A2, A3], mass: 1.5, cg: [0.25, 0.05]}
drivers:
  - {angle: crank1, free: true, initial_speed: 30}
)");
  ASSERT_FALSE(mech.mobility().redundant.empty());
  SimulationOptions options;
  options.end_time = 2.0;
  options.output_step = 0.5;
  options.relative_tolerance = 1e-12;
  const Simulation sim = simulate(mech, options);
  ASSERT_TRUE(sim.complete) << sim.stop_reason;
  const double r = 0.1, m = 0.4, I = 2e-4, M = 1.5, g = 9.81;
  const auto pendulum = [&](double th, double) {
    return -(3 * m * r / 2 + M * r) * g * std::cos(th) / (3 * (I + m * r * r / 4) + M * r * r);
  };
  ASSERT_EQ(sim.samples.size(), 5u);
  for (const Sample& s : sim.samples) {
    const auto [th, w] = rk4(pendulum, 0.0, 30 * M_PI / 180, s.time, 20000);
    EXPECT_NEAR(std::remainder(angle_of(mech, s, "crank1") - th, 2 * M_PI), 0.0, 1e-9) << "t = " << s.time;
    EXPECT_NEAR(std::remainder(angle_of(mech, s, "crank3") - th, 2 * M_PI), 0.0, 1e-9) << "t = " << s.time;
  }
  EXPECT_LT(sim.statistics.drift.position, 1e-12);
  EXPECT_LT(sim.statistics.drift.velocity, 1e-9);
  EXPECT_LT(std::abs(sim.energies.back().balance), 1e-9);
}

// A 0.5 m bar pinned at O, held by a preloaded spring to S and damped: it settles where
// V'(th) = m g (L/2) cos th + (k (l - l0) + P) dl/dth = 0, l = |A(th) - S|.
TEST(ForwardDynamics, DampedSpringPendulumSettlesWherePotentialIsStationary) {
  const Mechanism mech = mechanism_of(R"(
units: {length: m, angle: rad}
points:
  O: [0, 0]
  S: [0.5, 0.5]
  A: [0.5, 0]
ground: [O, S]
gravity: [0, -9.81]
bodies:
  bar: {points: [O, A], mass: 2, inertia: 0.04, cg: [0.25, 0]}
springs:
  - {between: [A, S], stiffness: 100, free_length: 0.2, preload: 5, damping: 4}
drivers:
  - {angle: bar, free: true}
)");
  SimulationOptions options;
  options.end_time = 30.0;
  options.output_step = 1.0;
  options.relative_tolerance = 1e-10;
  const Simulation sim = simulate(mech, options);
  ASSERT_TRUE(sim.complete) << sim.stop_reason;
  const double m = 2, L = 0.5, g = 9.81, k = 100, l0 = 0.2, P = 5;
  const auto slope = [&](double th) {
    const Eigen::Vector2d a(L * std::cos(th), L * std::sin(th)), da(-L * std::sin(th), L * std::cos(th));
    const Eigen::Vector2d d = a - Eigen::Vector2d(0.5, 0.5);
    return m * g * L / 2 * std::cos(th) + (k * (d.norm() - l0) + P) * d.dot(da) / d.norm();
  };
  const double settled = angle_of(mech, sim.samples.back(), "bar");
  double th = settled;  // Newton on V'(th) = 0 from there, by central differences of V'
  for (int i = 0; i < 20; ++i) th -= slope(th) / ((slope(th + 1e-6) - slope(th - 1e-6)) / 2e-6);
  EXPECT_NEAR(settled, th, 1e-7);
  EXPECT_GT((slope(th + 1e-4) - slope(th - 1e-4)) / 2e-4, 0.0);  // a minimum of V
  EXPECT_GT(std::abs(settled), 0.05);                            // it did move from the drawn pose
  // The energy balance holds with the dissipated work in it.
  const SimulationEnergy& end = sim.energies.back();
  EXPECT_GT(end.dissipated, 0.1);
  EXPECT_LT(std::abs(end.balance), 1e-7 * end.dissipated);
}

// With no driver free, the simulation is the kinematics in time: positions as solve_at_time's.
TEST(ForwardDynamics, FullyDrivenMechanismFollowsItsKinematics) {
  const Mechanism mech = mechanism_of(R"(
units: {length: mm, angle: deg}
points: {O2: [0, 0], O4: [200, 0], A: [80, 0], B: [190, 150]}
ground: [O2, O4]
gravity: [0, -9.81]
bodies:
  crank: {points: [O2, A], mass: 0.5, inertia: 3e-4, cg: [40, 0]}
  coupler: {points: [A, B], mass: 1.0, inertia: 2e-3, cg: [135, 75]}
  rocker: [O4, B]
drivers:
  - {angle: crank, from: 0, speed: 120 rpm}
)");
  SimulationOptions options;
  options.end_time = 1.0;
  options.output_step = 0.25;
  options.relative_tolerance = 1e-11;
  const Simulation sim = simulate(mech, options);
  ASSERT_TRUE(sim.complete) << sim.stop_reason;
  State state(mech);
  double t = 0.0;
  for (const Sample& s : sim.samples) {
    // Newton from the last pose in small moves, so that it stays on the drawn branch.
    for (; t < s.time - 1e-12; t += 0.01) solve_at_time(mech, state, t, 0);
    const Sample kinematic = solve_at_time(mech, state, s.time, 2);
    EXPECT_LT((s.taylor - kinematic.taylor).cwiseAbs().maxCoeff(), 1e-9) << "t = " << s.time;
  }
  // The motor's work is the rest of the balance: the crank turns at constant speed, so over whole
  // turns (t = 0.5 s, 1 s) kinetic and potential energy are back where they started.
  EXPECT_NEAR(sim.energies.back().work_in, 0.0, 1e-9);
  EXPECT_LT(std::abs(sim.energies.back().balance), 1e-9);
  // Within a turn it gives and takes the change of the kinetic and potential energy (its power
  // lambda . Phi_t through the driver's row), at every row.
  EXPECT_GT(std::abs(sim.energies[1].work_in), 1e-3);
  for (const SimulationEnergy& e : sim.energies) EXPECT_LT(std::abs(e.balance), 1e-9);
}

TEST(ForwardDynamics, AFreeMotionWithoutInertiaIsRefusedAtItsDriver) {
  const Mechanism mech = mechanism_of(R"(
points: {O2: [0, 0], O4: [200, 0], A: [80, 0], B: [190, 150]}
ground: [O2, O4]
bodies: {crank: [O2, A], coupler: [A, B], rocker: [O4, B]}
drivers:
  - {angle: crank, free: true}
)");
  try {
    simulate(mech, SimulationOptions{});
    FAIL() << "simulated a mechanism without mass";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::InvalidModel);
    EXPECT_EQ(e.where().kind, EntityRef::Kind::Driver);
    EXPECT_NE(e.message().find("no inertia"), std::string::npos) << e.message();
  }
}

TEST(ForwardDynamics, ARunThatCannotContinueKeepsItsRows) {
  const Mechanism mech = mechanism_of(R"(
units: {length: m}
points: {O: [0, 0], A: [0.3, 0]}
ground: [O]
gravity: [0, -9.81]
bodies:
  bar: {points: [O, A], mass: 1, cg: [0.15, 0]}
drivers:
  - {angle: bar, free: true}
)");
  SimulationOptions options;
  options.end_time = 10.0;
  options.output_step = 0.001;
  options.max_steps = 50;
  const Simulation sim = simulate(mech, options);
  EXPECT_FALSE(sim.complete);
  EXPECT_NE(sim.stop_reason.find("more than 50 steps"), std::string::npos) << sim.stop_reason;
  ASSERT_GT(sim.samples.size(), 1u);
  EXPECT_LT(sim.samples.back().time, 10.0);
}

// A block falls along a vertical guide from y = 0.3 m at 0.5 m/s: y(t) = 0.3 - 0.5 t - g t^2 / 2,
// so it passes y = -0.2 at the root of g t^2 / 2 + 0.5 t - 0.5 = 0. The run ends there, with the
// event's row at that time, found on the continuous output to 1e-12 s.
TEST(ForwardDynamics, AStopConditionEndsTheRunAtItsCrossingTime) {
  const Mechanism mech = mechanism_of(R"(
units: {length: m, angle: deg}
points: {Y1: [0, 1], Y2: [0, -1], C: [0, 0.3]}
ground: [Y1, Y2]
gravity: [0, -9.81]
bodies:
  block: {points: [C], mass: 2}
sliders:
  - {body: block, point: C, along: [Y1, Y2]}
drivers:
  - {slide: block, free: true, initial_speed: 0.5}
)");
  SimulationOptions options;
  options.end_time = 1.0;
  options.output_step = 0.01;
  options.relative_tolerance = 1e-10;
  options.stop_when = parse_stop_condition("C.y < -0.2");
  ASSERT_TRUE(options.stop_when);
  const Simulation sim = simulate(mech, options);
  ASSERT_TRUE(sim.complete) << sim.stop_reason;
  const double g = 9.81, expected = (-0.5 + std::sqrt(0.25 + 4 * (g / 2) * 0.5)) / g;
  ASSERT_EQ(sim.events.size(), 1u);
  const SimulationEvent& event = sim.events.front();
  EXPECT_EQ(event.kind, SimulationEvent::Kind::stop_when);
  EXPECT_NEAR(event.time, expected, 1e-10);
  EXPECT_EQ(event.row, static_cast<int>(sim.samples.size()) - 1);
  EXPECT_DOUBLE_EQ(sim.samples.back().time, event.time);
  EXPECT_NEAR(sim.samples.back().positions()(1), -0.2, 1e-9);
  EXPECT_LT(sim.samples[sim.samples.size() - 2].time, event.time);  // no row after the event
  EXPECT_NE(event.message.find("C.y < -0.2"), std::string::npos) << event.message;
}

// A flywheel on a motor's torque-speed line, T = T0 (1 - w / w0): I w' = T, so
// w = w0 (1 - exp(-t / tau)) with tau = I w0 / T0, and theta = w0 (t - tau (1 - exp(-t / tau))).
// Rows half a second apart are many turns apart: the angles keep their whole turns (they were
// unwrapped from row to row, and lost them), and a stop condition on the angle fires.
TEST(ForwardDynamics, AnglesKeepTheirWholeTurnsBetweenRowsFarApart) {
  const Mechanism mech = mechanism_of(R"(
units: {length: m, angle: deg}
points: {O: [0, 0], A: [0.1, 0]}
ground: [O]
bodies:
  wheel: {points: [O, A], mass: 1, cg: O, inertia: 0.01}
torques:
  - {body: wheel, torque: 2, no_load_speed: 100 rad/s}
drivers:
  - {angle: wheel, free: true}
)");
  const double w0 = 100, tau = 0.01 * w0 / 2;
  const auto theta = [&](double t) { return w0 * (t - tau * (1 - std::exp(-t / tau))); };
  SimulationOptions options;
  options.end_time = 2.0;
  options.output_step = 0.5;
  options.relative_tolerance = 1e-10;
  const Simulation sim = simulate(mech, options);
  ASSERT_TRUE(sim.complete) << sim.stop_reason;
  const ResultTable table = simulation_table(mech, sim);
  const auto column = [&](const std::string& name) {
    const auto at = std::find(table.columns.begin(), table.columns.end(), name);
    EXPECT_NE(at, table.columns.end()) << name;
    return static_cast<std::size_t>(at - table.columns.begin());
  };
  const std::size_t driver = column("wheel"), body = column("wheel.angle");
  ASSERT_EQ(table.rows.size(), 5u);
  // Within 1e-8 of the angle (rtol 1e-10 over 2 s): a lost turn is 360 deg.
  for (std::size_t i = 0; i < table.rows.size(); ++i) {
    const double expected = theta(0.5 * static_cast<double>(i)) * 180 / M_PI;  // 8646.84 deg at 2 s
    EXPECT_NEAR(table.rows[i][driver], expected, 1e-8 * expected) << "row " << i;
    EXPECT_NEAR(table.rows[i][body], expected, 1e-8 * expected) << "row " << i;
  }
  // theta = 5000 deg between the rows at 1 and 1.5 s, found by bisection on the closed form.
  double low = 1.0, high = 1.5;
  while (high - low > 1e-13) (theta(0.5 * (low + high)) * 180 / M_PI < 5000 ? low : high) = 0.5 * (low + high);
  options.stop_when = parse_stop_condition("wheel > 5000");
  const Simulation stopped = simulate(mech, options);
  ASSERT_EQ(stopped.events.size(), 1u);
  EXPECT_NEAR(stopped.events.front().time, low, 1e-9);
}

// A pendulum whose driver starts half a turn and more from its drawn angle (drawn at 0, started
// at 100 deg) starts there, as a sweep does: Newton straight from the drawing found the other
// solution of the driver's row, the bar at -80 deg.
TEST(ForwardDynamics, AStartFarFromTheDrawingIsReachedOnTheDrawnBranch) {
  const Mechanism mech = mechanism_of(R"(
units: {length: m, angle: deg}
points: {O: [0, 0], A: [1, 0]}
ground: [O]
gravity: [0, -9.81]
bodies:
  bar: {points: [O, A], mass: 1, cg: [0.5, 0], inertia: 0.0833333333333333333}
drivers:
  - {angle: bar, from: 100, free: true}
)");
  SimulationOptions options;
  options.end_time = 0.01;
  options.output_step = 0.01;
  const Simulation sim = simulate(mech, options);
  ASSERT_TRUE(sim.complete) << sim.stop_reason;
  const Sample& first = sim.samples.front();
  EXPECT_NEAR(first.driver_values[0], 100 * M_PI / 180, 1e-12);
  const Eigen::Vector2d a = mech.point_position(mech.model().find_point("A"), first.positions());
  EXPECT_NEAR(a.x(), std::cos(100 * M_PI / 180), 1e-12);
  EXPECT_NEAR(a.y(), std::sin(100 * M_PI / 180), 1e-12);
  // Released from rest past the top, it falls on: theta'' = -(m g d / I_O) cos(theta) > 0 there.
  EXPECT_GT(sim.samples.back().driver_values[0], first.driver_values[0]);
}

TEST(ForwardDynamics, AStopConditionIsReadAndItsColumnChecked) {
  const auto condition = parse_stop_condition("  slider.x>=0.25 ");
  ASSERT_TRUE(condition);
  EXPECT_EQ(condition->column, "slider.x");
  EXPECT_TRUE(condition->above);
  EXPECT_EQ(condition->value, 0.25);
  EXPECT_FALSE(parse_stop_condition("slider.x = 2"));
  EXPECT_FALSE(parse_stop_condition("slider.x > 2 mm"));
  EXPECT_FALSE(parse_stop_condition("< 2"));
  EXPECT_FALSE(parse_stop_condition("a < b < 2"));
  const Mechanism mech = mechanism_of(R"(
units: {length: m}
points: {O: [0, 0], A: [0.3, 0]}
ground: [O]
gravity: [0, -9.81]
bodies:
  bar: {points: [O, A], mass: 1, cg: [0.15, 0]}
drivers:
  - {angle: bar, free: true}
)");
  // The error a run with the stop condition `text` gives (BadInput), before any step.
  const auto refused = [&](const std::string& text) {
    SimulationOptions options;
    options.stop_when = parse_stop_condition(text);
    try {
      simulate(mech, options);
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::BadInput) << text;
      return e.message();
    }
    ADD_FAILURE() << "ran with the stop condition " << text;
    return std::string();
  };
  const std::string no_column = refused("A.z > 1");
  EXPECT_NE(no_column.find("no column 'A.z'"), std::string::npos) << no_column;
  // A's own columns are offered, and only they.
  EXPECT_NE(no_column.find("the columns of A are A.x, A.y"), std::string::npos) << no_column;
  EXPECT_EQ(no_column.find("bar."), std::string::npos) << no_column;
  const std::string no_point = refused("Q.x > 1");
  EXPECT_NE(no_point.find("the simulation's table has step, t, bar, O.x"), std::string::npos) << no_point;
  // The row's number has no value between rows: it never crossed (a run to the end), now refused.
  const std::string step = refused("step > 3");
  EXPECT_NE(step.find("watches `step`, the row's number"), std::string::npos) << step;
}

// A run that only kinematic drivers move, to a limit of its motion (a parallelogram's crank
// driven down to the ground line, its change point, 1 s from 60 deg): said at the driver, where
// it was said at the model's `sweep:`; and without masses, as that limit, where it was "a free
// motion has no inertia".
TEST(ForwardDynamics, AFullyDrivenRunStopsAtItsLimitAtTheDriver) {
  const std::string linkage = R"(
units: {length: m, angle: deg}
points: {O2: [0, 0], O4: [0.2, 0], A: [0.05, 0.0866], B: [0.25, 0.0866]}
ground: [O2, O4]
drivers:
  - {angle: crank, from: 60, speed: -60 deg/s}
)";
  SimulationOptions options;
  options.end_time = 2.0;
  options.output_step = 0.01;
  for (const bool massive : {true, false}) {
    const Mechanism mech = mechanism_of(linkage + (massive ? R"(
bodies:
  crank: {points: [O2, A], mass: 0.1, cg: [0.025, 0.0433], inertia: 1e-4}
  coupler: {points: [A, B], mass: 0.2, cg: [0.15, 0.0866], inertia: 1e-3}
  rocker: {points: [O4, B], mass: 0.1, cg: [0.225, 0.0433], inertia: 1e-4}
)"
                                                           : R"(
bodies: {crank: [O2, A], coupler: [A, B], rocker: [O4, B]}
)"));
    const Simulation sim = simulate(mech, options);
    ASSERT_FALSE(sim.complete) << massive;
    const std::string expected = massive ? "the mechanism reached a toggle" : "it reached a limit of its motion";
    EXPECT_NE(sim.stop_reason.find(expected), std::string::npos) << sim.stop_reason;
    EXPECT_EQ(sim.stop_reason.find("no inertia"), std::string::npos) << sim.stop_reason;
    EXPECT_EQ(sim.stop_where.kind, EntityRef::Kind::Driver);
    EXPECT_EQ(sim.stop_where.index, 0);
    EXPECT_NEAR(sim.samples.back().time, 1.0, 0.05) << massive;  // the rows kept up to there
  }
}

// A parallelogram (cranks 0.1 m, 0.4 kg, 2e-4 kg m^2; a translating coupler of 1.5 kg) released
// at rest from 60 deg is one pendulum in the crank angle,
//   (2 (I + m r^2/4) + M r^2) th'' = -(m r + M r) g cos th,
// until th = 0, where all four links lie on one line: its constraints lose rank (the change
// point to the crossed branch). The run stops there, at the time the pendulum takes to reach
// th = 0 (integrated here); reversed there, it swings back to 60 deg at twice that time. The
// integrated motion keeps its constraints to a drift d of about 1e-13 m, and near a change point
// the positions with |Phi| = d are not the two branches crossing but a hyperbola's two arms, which
// pass the crossing at about sqrt(d L) ~ 1e-7 m: that, not the root-finding (1e-12 s), bounds
// how well a toggle's time is known, here to about 1e-7 s (docs/dynamics.md, Events).
const char* const kParallelogramReleased = R"(
units: {length: m, angle: deg}
points:
  O1: [0, 0]
  O2: [0.3, 0]
  A1: [0.05, 0.086602540378443865]
  A2: [0.35, 0.086602540378443865]
ground: [O1, O2]
gravity: [0, -9.81]
bodies:
  crank1: {points: [O1, A1], mass: 0.4, inertia: 2e-4, cg: [0.025, 0.043301270189221932]}
  crank2: {points: [O2, A2], mass: 0.4, inertia: 2e-4, cg: [0.325, 0.043301270189221932]}
  coupler: {points: [A1, A2], mass: 1.5, inertia: 0.01, cg: [0.2, 0.1]}
drivers:
  - {angle: crank1, free: true}
)";

// The time the parallelogram's pendulum takes from `from` (60 deg) at rest to th = 0: RK4 steps
// of 1e-5 s up to the crossing, then the last step's length by the secant method.
double parallelogram_crossing_time(double from = M_PI / 3) {
  const double r = 0.1, m = 0.4, I = 2e-4, M = 1.5, g = 9.81;
  const auto accel = [&](double th) {
    return -(m * r + M * r) * g * std::cos(th) / (2 * (I + m * r * r / 4) + M * r * r);
  };
  const auto step = [&](double th, double w, double h) {
    const double k1 = w, l1 = accel(th);
    const double k2 = w + h / 2 * l1, l2 = accel(th + h / 2 * k1);
    const double k3 = w + h / 2 * l2, l3 = accel(th + h / 2 * k2);
    const double k4 = w + h * l3, l4 = accel(th + h * k3);
    return std::make_pair(th + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4), w + h / 6 * (l1 + 2 * l2 + 2 * l3 + l4));
  };
  double th = from, w = 0.0, t = 0.0;
  const double h = 1e-5;
  for (;;) {
    const auto [th1, w1] = step(th, w, h);
    if (th1 <= 0) break;
    th = th1, w = w1, t += h;
  }
  double a = 0.0, b = h, fa = th, fb = step(th, w, h).first;
  for (int i = 0; i < 50 && std::abs(b - a) > 1e-16; ++i) {
    const double c = b - fb * (b - a) / (fb - fa);
    a = b, fa = fb, b = c, fb = step(th, w, c).first;
  }
  return t + b;
}

// The parallelogram's kinetic energy at crank angle th from its energy, and the norm of its
// coordinates' accelerations (A1 and A2 move alike, each r sqrt(th''^2 + th'^4)).
void expect_parallelogram_pendulum(const Sample& row, const SimulationEnergy& energy, double th) {
  const double r = 0.1, m = 0.4, I = 2e-4, M = 1.5, g = 9.81;
  const double inertia = 2 * (I + m * r * r / 4) + M * r * r;
  const double kinetic = (m + M) * r * g * (std::sin(M_PI / 3) - std::sin(th));
  const double rate_squared = 2 * kinetic / inertia, rate2 = -(m + M) * r * g * std::cos(th) / inertia;
  EXPECT_NEAR(energy.kinetic, kinetic, 1e-6 * kinetic) << "t = " << row.time;
  const double accelerations = std::sqrt(2.0) * r * std::hypot(rate2, rate_squared);
  EXPECT_NEAR(row.derivative(2).norm(), accelerations, 1e-5 * accelerations) << "t = " << row.time;
}

// The answer of a run whose output rows a second thread made, against the same run on one
// thread: equal to the last bit, rows, events, statistics and stop alike.
void expect_same_run(const Simulation& threaded, const Simulation& alone) {
  EXPECT_EQ(threaded.complete, alone.complete);
  EXPECT_EQ(threaded.cancelled, alone.cancelled);
  EXPECT_EQ(threaded.stop_reason, alone.stop_reason);
  EXPECT_EQ(threaded.stop_where.kind, alone.stop_where.kind);
  EXPECT_EQ(threaded.stop_where.index, alone.stop_where.index);
  ASSERT_EQ(threaded.samples.size(), alone.samples.size());
  ASSERT_EQ(threaded.energies.size(), alone.energies.size());
  for (std::size_t i = 0; i < alone.samples.size(); ++i) {
    const Sample &a = threaded.samples[i], &b = alone.samples[i];
    ASSERT_EQ(a.time, b.time) << "row " << i;
    EXPECT_EQ(a.step, b.step) << "row " << i;
    EXPECT_TRUE(a.taylor == b.taylor) << "row " << i << " at t = " << b.time;
    EXPECT_EQ(a.driver_values, b.driver_values) << "row " << i;
    EXPECT_EQ(a.body_angles, b.body_angles) << "row " << i;
    EXPECT_EQ(a.residual, b.residual) << "row " << i;
    const SimulationEnergy &e = threaded.energies[i], &f = alone.energies[i];
    EXPECT_TRUE(e.kinetic == f.kinetic && e.gravity == f.gravity && e.spring == f.spring &&
                e.dissipated == f.dissipated && e.work_in == f.work_in && e.balance == f.balance)
        << "row " << i;
  }
  ASSERT_EQ(threaded.events.size(), alone.events.size());
  for (std::size_t i = 0; i < alone.events.size(); ++i) {
    EXPECT_EQ(threaded.events[i].kind, alone.events[i].kind);
    EXPECT_EQ(threaded.events[i].time, alone.events[i].time);
    EXPECT_EQ(threaded.events[i].row, alone.events[i].row);
    EXPECT_EQ(threaded.events[i].message, alone.events[i].message);
  }
  const SimulationStatistics &a = threaded.statistics, &b = alone.statistics;
  EXPECT_EQ(a.accepted_steps, b.accepted_steps);
  EXPECT_EQ(a.rejected_steps, b.rejected_steps);
  EXPECT_EQ(a.evaluations, b.evaluations);
  EXPECT_EQ(a.smallest_step, b.smallest_step);
  EXPECT_EQ(a.largest_step, b.largest_step);
  EXPECT_EQ(a.largest_energy_error, b.largest_energy_error);
  EXPECT_EQ(a.drift.position, b.drift.position);
  EXPECT_EQ(a.drift.velocity, b.drift.velocity);
  EXPECT_EQ(a.drift.acceleration, b.drift.acceleration);
}

// The largest |energy balance| of the rows farther than `window` (s) from every event.
double energy_error_away_from_events(const Simulation& sim, double window) {
  double most = 0.0;
  for (std::size_t i = 0; i < sim.samples.size(); ++i) {
    const double t = sim.samples[i].time;
    const bool near = std::any_of(sim.events.begin(), sim.events.end(),
                                  [&](const SimulationEvent& e) { return std::abs(e.time - t) <= window; });
    if (!near) most = std::max(most, std::abs(sim.energies[i].balance));
  }
  return most;
}

Simulation simulate_on(unsigned threads, const Mechanism& mech, SimulationOptions options) {
  options.threads = threads;
  return simulate(mech, options);
}

// The run on two threads with the steps' thread making every other job's rows (the row thread
// only keeping them in their place), which it otherwise does only while the row thread is behind.
Simulation simulate_with_rows_on_both_threads(const Mechanism& mech, const SimulationOptions& options) {
  testing::make_every_other_job_on_the_steps_thread(true);
  Simulation sim = simulate_on(0, mech, options);
  testing::make_every_other_job_on_the_steps_thread(false);
  return sim;
}

// A double crank turns far from any toggle: the gate that decides whether a step is watched for
// one (and taken by the 5(4) pair, not DOP853) stays closed. Gated by the square Jacobian's LU
// pivot ratio, which follows the links' directions, it opened on a sixth of the steps of this
// four-bar (the benchmark's, 10 s): 1 160 steps. Gated by its conditioning with rows of unit
// length: 960, every one DOP853's.
TEST(ForwardDynamics, ADoubleCrankFarFromTogglesIsNotWatchedAsNearOne) {
  nbar::Model model = nbar_bench::steel_chain(1);
  for (Driver& d : model.drivers) d.free = true;
  const Mechanism mech(model);
  SimulationOptions options;
  options.end_time = 10.0;
  options.output_step = 0.01;
  options.relative_tolerance = 1e-8;
  const Simulation sim = simulate(mech, options);
  ASSERT_TRUE(sim.complete) << sim.stop_reason;
  const SimulationStatistics& s = sim.statistics;
  EXPECT_LT(s.accepted_steps + s.rejected_steps, 1000);
  // Every step DOP853's: eleven stages, and where accepted its extension's three and the projected
  // end's one (the 5(4) pair's: five and one); the start's and the first step size's two.
  EXPECT_EQ(s.evaluations, 2 + 15 * s.accepted_steps + 11 * s.rejected_steps);
}

// The run on two threads (as `threaded`), on one, and with the rows made on both.
void expect_same_on_every_thread(const Simulation& threaded, const Mechanism& mech, const SimulationOptions& options) {
  expect_same_run(threaded, simulate_on(1, mech, options));
  expect_same_run(threaded, simulate_with_rows_on_both_threads(mech, options));
}

// Rows made on a second thread (the default where the machine has two cores), or on the steps'
// thread while that one is behind, are those of one thread: a parallelogram reversing at its
// change points, a stop condition, a run stopped by its step count (a row where it got to, after
// the rows handed over), and a row that stops the run (a torque law undefined at exactly
// t = 0.25 s, a row's time, and nowhere else: the steps pass it, the row cannot be made, and the
// run stops there with the rows before it).
TEST(ForwardDynamics, RowsMadeOnASecondThreadAreThoseOfOne) {
  SimulationOptions options;
  options.end_time = 1.0;
  options.output_step = 1e-3;
  options.relative_tolerance = 1e-10;
  options.at_toggle = AtToggle::reverse;
  if (!rows_on_second_thread(options)) GTEST_SKIP() << "one core here: no second thread to compare";
  const Mechanism parallelogram = mechanism_of(kParallelogramReleased);
  const Simulation reversing = simulate_on(0, parallelogram, options);
  EXPECT_GE(reversing.events.size(), 3u);
  expect_same_on_every_thread(reversing, parallelogram, options);

  options.at_toggle = AtToggle::stop;
  options.stop_when = parse_stop_condition("crank1 < 20");
  const Simulation stopped = simulate_on(0, parallelogram, options);
  ASSERT_EQ(stopped.events.size(), 1u);
  EXPECT_EQ(stopped.events[0].kind, SimulationEvent::Kind::stop_when);
  expect_same_on_every_thread(stopped, parallelogram, options);

  options.stop_when.reset();
  options.max_steps = 8;
  const Simulation too_many = simulate_on(0, parallelogram, options);
  ASSERT_FALSE(too_many.complete);
  EXPECT_NE(too_many.stop_reason.find("more than 8 steps"), std::string::npos) << too_many.stop_reason;
  expect_same_on_every_thread(too_many, parallelogram, options);
  options.max_steps = SimulationOptions{}.max_steps;

  const Mechanism bar = mechanism_of(R"yaml(
units: {length: m, angle: deg}
points: {O: [0, 0], A: [0.5, 0]}
ground: [O]
gravity: [0, -9.81]
bodies:
  bar: {points: [O, A], mass: 1, inertia: 0.02}
torques:
  - {body: bar, torque: "1/(t - 0.25) - 1/(t - 0.25)"}
drivers:
  - {angle: bar, free: true}
)yaml");
  options.stop_when.reset();
  const Simulation undefined = simulate_on(0, bar, options);
  ASSERT_FALSE(undefined.complete);
  EXPECT_EQ(undefined.stop_where.kind, EntityRef::Kind::Torque);
  EXPECT_NEAR(undefined.samples.back().time, 0.249, 1e-12);
  expect_same_on_every_thread(undefined, bar, options);

  // Andrews' squeezer (14 coordinates: the sparse solves' iterations, which start from the last
  // multipliers and choose their penalty at the first factorisation): still the same rows.
  const Mechanism squeezer(
      io::load_model_file(std::string(NBAR_SOURCE_DIR) + "/tests/dynamics/andrews_squeezer.yaml").model);
  options.end_time = 0.03;
  options.output_step = 2e-4;
  const Simulation squeezed = simulate_on(0, squeezer, options);
  ASSERT_TRUE(squeezed.complete) << squeezed.stop_reason;
  expect_same_on_every_thread(squeezed, squeezer, options);
}

TEST(ForwardDynamics, AToggleStopsTheRunAtItsTime) {
  const Mechanism mech = mechanism_of(kParallelogramReleased);
  SimulationOptions options;
  options.end_time = 1.0;
  options.output_step = 0.01;
  options.relative_tolerance = 1e-12;
  const Simulation sim = simulate(mech, options);
  EXPECT_FALSE(sim.complete);
  ASSERT_EQ(sim.events.size(), 1u);
  const double expected = parallelogram_crossing_time();
  EXPECT_GT(expected, 0.1);
  EXPECT_LT(expected, 0.3);
  EXPECT_EQ(sim.events[0].kind, SimulationEvent::Kind::toggle);
  EXPECT_NEAR(sim.events[0].time, expected, 2e-7);
  EXPECT_NE(sim.stop_reason.find("toggle"), std::string::npos) << sim.stop_reason;
  EXPECT_EQ(sim.stop_where.kind, EntityRef::Kind::Driver);
  // The toggle's row is the last regular state before it, 1e-4 of the drawing (0.36 m) back or
  // up to twice that: there the speeds and accelerations are the pendulum's.
  EXPECT_EQ(sim.events[0].row, static_cast<int>(sim.samples.size()) - 1);
  const Sample& last = sim.samples.back();
  EXPECT_GT(last.time, sim.events[0].time - 1e-4);
  EXPECT_LT(last.time, sim.events[0].time);
  const double th = angle_of(mech, last, "crank1");
  EXPECT_GT(th, 0.36e-4 / 0.1);
  EXPECT_LT(th, 2 * 0.36e-4 / 0.1);
  expect_parallelogram_pendulum(last, sim.energies.back(), th);
}

TEST(ForwardDynamics, AToggleCanReverseTheMotion) {
  const Mechanism mech = mechanism_of(kParallelogramReleased);
  const double crossing = parallelogram_crossing_time();
  SimulationOptions options;
  options.end_time = 2 * crossing;  // back at the start: 60 deg, at rest
  options.output_step = 0.01;
  options.relative_tolerance = 1e-12;
  options.at_toggle = AtToggle::reverse;
  const Simulation sim = simulate(mech, options);
  ASSERT_TRUE(sim.complete) << sim.stop_reason;
  ASSERT_EQ(sim.events.size(), 1u);
  EXPECT_NEAR(sim.events[0].time, crossing, 2e-7);
  const Sample& end = sim.samples.back();
  EXPECT_DOUBLE_EQ(end.time, 2 * crossing);
  EXPECT_NEAR(angle_of(mech, end, "crank1"), M_PI / 3, 1e-8);
  EXPECT_LT(end.derivative(1).norm(), 3e-6);  // at rest again (m/s), but for the toggle's time
  EXPECT_LT(std::abs(sim.energies.back().balance), 1e-9);
}

// Gravity alone does no work but through the potential: the work column stays exactly zero (the
// constraint forces' power, taken as (M q'' - Q) . q', once gathered the stages' speeds' drift,
// -1e-8 J in 0.16 s at rtol 1e-8, and put the balance 1.2e-8 J off; now 5e-9 at most).
TEST(ForwardDynamics, ConstraintsDoNoWorkWithoutKinematicDrivers) {
  SimulationOptions options;
  options.end_time = 0.16;
  options.output_step = 0.01;
  const Simulation sim = simulate(mechanism_of(kParallelogramReleased), options);
  ASSERT_TRUE(sim.complete) << sim.stop_reason;
  for (const SimulationEnergy& e : sim.energies) EXPECT_EQ(e.work_in, 0.0);
  EXPECT_LT(sim.statistics.largest_energy_error, 8e-9);
}

// A torque law with a pole (1/(t - 0.5) N m on a free bar) makes the steps collapse at 0.5 s: the
// run stops there at the law, which it names with its size, not at the free driver (which the
// message blamed for a motion "too fast or not smooth"). A torque without a pole runs.
TEST(ForwardDynamics, StepsCollapsingAtALawsPoleStopAtTheLaw) {
  const auto bar = [](const std::string& torque) {
    return mechanism_of(R"(
units: {length: m, angle: deg}
points: {O: [0, 0], A: [0.5, 0]}
ground: [O]
bodies:
  bar: {points: [O, A], mass: 1, inertia: 0.02}
torques:
  - {body: bar, torque: ")" +
                        torque + R"("}
drivers:
  - {angle: bar, free: true}
)");
  };
  SimulationOptions options;
  options.end_time = 1.0;
  options.output_step = 0.01;
  const Simulation pole = simulate(bar("1/(t - 0.5)"), options);
  ASSERT_FALSE(pole.complete);
  EXPECT_EQ(pole.stop_where.kind, EntityRef::Kind::Torque);
  EXPECT_EQ(pole.stop_where.index, 0);
  EXPECT_EQ(pole.stop_where.law, 0);  // shown at the law's text
  EXPECT_NE(pole.stop_reason.find("law '1/(t - 0.5)' is "), std::string::npos) << pole.stop_reason;
  EXPECT_NE(pole.stop_reason.find("against 2 at the start"), std::string::npos) << pole.stop_reason;
  EXPECT_NEAR(pole.samples.back().time, 0.49, 1e-12);  // the rows before it
  EXPECT_TRUE(simulate(bar("1/(t + 0.5)"), options).complete);
}

// A five-bar whose driven link is pushed into the stretched pose at t = 1 s (the law brings it to
// 93.8 deg, where the other side lines up) while the other link is free: the steps shrink without
// end next to the singular Jacobian. The run stops there promptly, at the prescribed driver (it
// ground on for 10 million steps, 3.5 minutes, and stopped at the free one).
TEST(ForwardDynamics, APrescribedMotionIntoAToggleStopsAtItsDriver) {
  const Mechanism mech = mechanism_of(R"(
units: {length: mm, angle: deg}
points: {O1: [0, 0], O5: [100, 0], A: [60, 0], B: [100, 40], P: [60.0, 40.0]}
ground: [O1, O5]
gravity: [0, -9.81]
bodies:
  left: {points: [O1, A], mass: 0.2, inertia: 1e-5}
  right: {points: [O5, B], mass: 0.2, inertia: 1e-5}
  distal_left: {points: [A, P], mass: 0.2, inertia: 1e-5}
  distal_right: {points: [B, P], mass: 0.2, inertia: 1e-5}
drivers:
  - {name: theta_left, angle: left, law: "93.82255372927435*(1-cos(pi*t))/2"}
  - {name: theta_right, angle: right, free: true}
)");
  SimulationOptions options;
  options.end_time = 1.5;
  options.output_step = 0.01;
  options.max_steps = 1'000'000;
  const Simulation sim = simulate(mech, options);
  ASSERT_FALSE(sim.complete);
  EXPECT_NE(sim.stop_reason.find("next to a singular position"), std::string::npos) << sim.stop_reason;
  EXPECT_NE(sim.stop_reason.find("driver 'theta_left'"), std::string::npos) << sim.stop_reason;
  EXPECT_EQ(sim.stop_where.kind, EntityRef::Kind::Driver);
  EXPECT_EQ(sim.stop_where.index, 0);
  EXPECT_LT(sim.statistics.accepted_steps + sim.statistics.rejected_steps, 200'000);
  EXPECT_NEAR(sim.samples.back().time, 0.99, 1e-12);
}

// The table's energy balance is the run's, however small: the tables' noise rule (a value below
// 1e-12 of its unit's largest is 0) printed a balance of 1e-12 J as 0.
TEST(ForwardDynamics, TheTablesEnergyBalanceIsNeverRoundedToZero) {
  const Mechanism mech = mechanism_of(kParallelogramReleased);
  SimulationOptions options;
  options.end_time = 0.1;
  options.output_step = 0.01;
  options.relative_tolerance = 1e-12;
  const Simulation sim = simulate(mech, options);
  const ResultTable table = simulation_table(mech, sim);
  ASSERT_EQ(table.columns.back(), "energy.balance");
  int tiny = 0;
  for (std::size_t i = 0; i < table.rows.size(); ++i) {
    EXPECT_EQ(table.rows[i].back(), sim.energies[i].balance) << "row " << i;
    if (sim.energies[i].balance != 0.0 && std::abs(sim.energies[i].balance) < 1e-12 * 1.8) ++tiny;
  }
  EXPECT_GT(tiny, 0);  // the rows the rule would have zeroed
}

// The reversal at the change point mirrors the motion from a regular state before it: at rtol
// 1e-8 and output steps of 0.01 and 0.002 s, where a state reversed at the toggle itself met it
// again at once and went through onto the crossed branch (0.17 J of 0.26 lost), the run reverses
// at the crossing times 1, 3, 5 (the swing's period is twice the crossing time), keeps its
// energy, and every row around the reversals is the pendulum's.
TEST(ForwardDynamics, AReversalAtAChangePointSwingsBackEveryTime) {
  const Mechanism mech = mechanism_of(kParallelogramReleased);
  const double crossing = parallelogram_crossing_time();
  for (const double dt : {0.01, 0.002}) {
    SimulationOptions options;
    options.end_time = 1.0;
    options.output_step = dt;
    options.relative_tolerance = 1e-8;
    options.at_toggle = AtToggle::reverse;
    const Simulation sim = simulate(mech, options);
    ASSERT_TRUE(sim.complete) << sim.stop_reason;
    ASSERT_EQ(sim.events.size(), 3u) << "dt " << dt;
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(sim.events[k].time, (2 * k + 1) * crossing, 1e-6) << "dt " << dt;
    EXPECT_LT(sim.statistics.largest_energy_error, 1e-6);
    for (std::size_t i = 1; i < sim.samples.size(); ++i) {
      ASSERT_GT(sim.samples[i].time, sim.samples[i - 1].time);
      const double th = angle_of(mech, sim.samples[i], "crank1");
      if (th < 0.02) expect_parallelogram_pendulum(sim.samples[i], sim.energies[i], th);
    }
  }
}

// The parallelogram's model with `extra` appended (a section) and its driver given `driver`.
Mechanism parallelogram_with(const std::string& driver, const std::string& extra = "") {
  std::string text = kParallelogramReleased;
  const std::string plain = "  - {angle: crank1, free: true}\n";
  text.replace(text.find(plain), plain.size(), "  - {angle: crank1, free: true" + driver + "}\n");
  return mechanism_of(text + extra);
}

// Loads of the positions are mirrored exactly: with a constant torque on a crank the energy
// balance holds over eight reversals (the work integral kept at the toggle's value was 0.003 J off,
// of 2.86 J).
// Viscous friction at a pivot: the way back loses what the way in did (the balance holds, where
// mirrored losses left 0.04 J over 2537 reversals), and once the bounces are smaller than 3e-4 of
// the drawing the run stops, saying so (it chattered on in ever shorter bounces).
TEST(ForwardDynamics, AReversalMirrorsTheLoadsWorkAndStopsWhereTheBouncesDieOut) {
  SimulationOptions options;
  options.end_time = 2.0;
  options.output_step = 0.01;
  options.relative_tolerance = 1e-10;
  options.at_toggle = AtToggle::reverse;
  const Simulation torqued = simulate(parallelogram_with("", "torques: [{body: crank1, torque: -1}]\n"), options);
  ASSERT_TRUE(torqued.complete) << torqued.stop_reason;
  EXPECT_EQ(torqued.events.size(), 8u);
  // 2e-10 J on the rows away from the toggles; 1.1e-8 J on a row 1e-4 s past one, from the cubic
  // that stands for the motion next to the toggle (window_row).
  EXPECT_LT(torqued.statistics.largest_energy_error, 3e-8);

  options.end_time = 20.0;
  const Simulation damped = simulate(parallelogram_with("", "friction: [{joint: O1, viscous: 0.05}]\n"), options);
  ASSERT_FALSE(damped.complete);
  EXPECT_NE(damped.stop_reason.find("bounces this small are below what a reversal can follow"), std::string::npos)
      << damped.stop_reason;
  EXPECT_GT(damped.events.size(), 20u);
  EXPECT_LT(damped.samples.back().time, 5.0);
  EXPECT_LT(damped.statistics.largest_energy_error, 1e-6);
  for (std::size_t i = 1; i < damped.samples.size(); ++i) ASSERT_GT(damped.samples[i].time, damped.samples[i - 1].time);
}

// Without gravity the parallelogram's cranks turn at their initial 100 deg/s into the change point
// at 0.1 s, an output row's time, and back. The rows next to the toggle (that one and the one
// before it) said 59.9 and 226 deg/s for the two cranks, 38 % of the energy lost; they come from
// the cubic through the toggle now, and every row says 100 deg/s.
TEST(ForwardDynamics, RowsNextToAToggleKeepTheSpeeds) {
  const Mechanism mech = mechanism_of(R"(
units: {length: m, angle: deg}
points:
  O1: [0, 0]
  O2: [0.3, 0]
  A1: [0.0984807753012208, 0.017364817766693033]
  A2: [0.3984807753012208, 0.017364817766693033]
ground: [O1, O2]
bodies:
  crank1: {points: [O1, A1], mass: 0.4, inertia: 2e-4}
  crank2: {points: [O2, A2], mass: 0.4, inertia: 2e-4}
  coupler: {points: [A1, A2], mass: 1.5, inertia: 0.01}
drivers:
  - {angle: crank1, free: true, initial_speed: -100 deg/s}
)");
  SimulationOptions options;
  options.end_time = 0.13;
  options.output_step = 0.01;
  options.at_toggle = AtToggle::reverse;
  const Simulation sim = simulate(mech, options);
  ASSERT_TRUE(sim.complete) << sim.stop_reason;
  ASSERT_EQ(sim.events.size(), 1u);
  EXPECT_NEAR(sim.events[0].time, 0.1, 1e-7);
  const double kinetic = sim.energies.front().kinetic;
  for (std::size_t i = 0; i < sim.samples.size(); ++i) {
    EXPECT_NEAR(sim.energies[i].kinetic, kinetic, 1e-7 * kinetic) << "t = " << sim.samples[i].time;
    const Eigen::VectorXd speeds = sim.samples[i].derivative(1);
    EXPECT_NEAR(speeds.norm(), std::sqrt(2.0) * 0.1 * 100 * M_PI / 180, 1e-8) << "t = " << sim.samples[i].time;
  }
}

// Released 1 degree from the change point: the toggle's row is a regular state on the way (no
// second row at t = 0, which a start standing in for it gave), the events alternate as the swing
// does, and the energy holds.
TEST(ForwardDynamics, AStartNearAToggleBouncesWithRowsInOrder) {
  SimulationOptions options;
  options.end_time = 0.5;
  options.output_step = 0.05;
  options.at_toggle = AtToggle::reverse;
  const Simulation sim = simulate(parallelogram_with(", from: 1"), options);
  ASSERT_TRUE(sim.complete) << sim.stop_reason;
  ASSERT_GT(sim.events.size(), 10u);
  const double period = 2 * sim.events[0].time;  // from rest at 1 deg to the toggle and back
  for (std::size_t k = 1; k < sim.events.size(); ++k)
    EXPECT_NEAR(sim.events[k].time - sim.events[k - 1].time, period, 1e-6) << "event " << k;
  for (std::size_t i = 1; i < sim.samples.size(); ++i) ASSERT_GT(sim.samples[i].time, sim.samples[i - 1].time);
  for (const SimulationEvent& e : sim.events) EXPECT_LT(sim.samples[e.row].time, e.time);
  EXPECT_LT(sim.statistics.largest_energy_error, 1e-7);
  // From 0.01 deg the toggle is nearer than a regular state can be: the start is the toggle's row
  // (it was written a second time at t = 0).
  options.at_toggle = AtToggle::stop;
  const Simulation near = simulate(parallelogram_with(", from: 0.01"), options);
  ASSERT_FALSE(near.complete);
  ASSERT_EQ(near.events.size(), 1u);
  EXPECT_EQ(near.events[0].row, 0);
  EXPECT_EQ(near.samples.size(), 1u);
}

// Released at the change point itself: the run says it starts at a toggle, and watches for
// toggles from its first regular state (a scale taken at the singular start saw none after it).
TEST(ForwardDynamics, AStartAtAToggleIsSaidAndLaterTogglesAreStillSeen) {
  SimulationOptions options;
  options.end_time = 1.0;
  options.output_step = 0.01;
  const Simulation sim = simulate(parallelogram_with(", from: 0"), options);
  ASSERT_EQ(sim.warnings.size(), 1u);
  EXPECT_EQ(sim.warnings[0].code, "start_at_toggle");
  EXPECT_EQ(simulate(parallelogram_with(", from: 1"), options).warnings.size(), 0u);
}

// A kite four-bar (crank as long as the frame, coupler as long as the rocker), no gravity, its
// crank turning at -200 deg/s from 60 deg into the change point at 0, where the crank's pin meets
// the rocker's pivot. On the kite's branch B stays on the perpendicular bisector of A and O4, so
// the motion is one coordinate's, th' = sqrt(2 T / I(th)), and the time to the change point is
// the quadrature of sqrt(I(th) / 2 T) from 0 to 60 deg. Each body's centre of mass is its first
// point (the default): T = (I_crank th'^2 + m_coupler |A'|^2 + I_coupler w_coupler^2 +
// I_rocker w_rocker^2) / 2, the derivatives by central differences (which at 0 itself would
// straddle the bisector's normal turning over).
constexpr const char* kKiteTurningIn = R"(
units: {length: mm, angle: deg}
points:
  O2: [0, 0]
  O4: [100, 0]
  A: [50.000000000000014, 86.60254037844386]
  B: [287.13203435596427, 165.77575732838082]
ground: [O2, O4]
bodies:
  crank: {points: [O2, A], mass: 0.3, inertia: 3e-4}
  coupler: {points: [A, B], mass: 0.5, inertia: 3e-3}
  rocker: {points: [O4, B], mass: 0.5, inertia: 3e-3}
drivers:
  - {angle: crank, free: true, initial_speed: -200 deg/s}
)";

double kite_time_to_change_point() {
  using V = Eigen::Vector2d;
  const V o4(0.1, 0.0);
  const auto pins = [&](double th) {
    const V a = 0.1 * V(std::cos(th), std::sin(th));
    const V along = (o4 - a).normalized(), normal(-along.y(), along.x());
    const double half = 0.5 * (o4 - a).norm();
    return std::array<V, 2>{a, 0.5 * (a + o4) + std::sqrt(0.25 * 0.25 - half * half) * normal};
  };
  const auto inertia = [&](double th) {  // 2 T at th' = 1
    const double d = 1e-6;
    const auto p = pins(th + d), m = pins(th - d);
    const V va = (p[0] - m[0]) / (2 * d);
    const auto angle = [](const V& u) { return std::atan2(u.y(), u.x()); };
    const double coupler = (angle(p[1] - p[0]) - angle(m[1] - m[0])) / (2 * d);
    const double rocker = (angle(p[1] - o4) - angle(m[1] - o4)) / (2 * d);
    return 3e-4 + 0.5 * va.squaredNorm() + 3e-3 * coupler * coupler + 3e-3 * rocker * rocker;
  };
  const double speed = 200 * M_PI / 180, energy2 = inertia(M_PI / 3) * speed * speed;
  const int n = 2000;  // Simpson's rule on [0, 60 deg]
  double sum = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double weight = i == 0 || i == n ? 1 : (i % 2 ? 4 : 2);
    const double th = std::max(i * (M_PI / 3) / n, 1e-5);  // the bisector's normal turns over at 0
    sum += weight * std::sqrt(inertia(th) / energy2);
  }
  return sum * (M_PI / 3) / n / 3;
}

// Over the tiny steps next to the kite's change point the toggle measure only dips (to 2.3e-6 of
// its size at rtol 1e-8), each step seeing it only falling or only rising: the run once went on
// unreported along the other branch, the crank stopped at 0 and the coupler and rocker turning
// together about O4. It stops at the change point at every tolerance, and with `reverse` the
// crank comes back to 60 deg at twice that time.
TEST(ForwardDynamics, AKitesChangePointIsSeenWhereTheMeasureOnlyDips) {
  const Mechanism mech = mechanism_of(kKiteTurningIn);
  const double reference = kite_time_to_change_point();
  EXPECT_NEAR(reference, 0.30074, 1e-4);  // about 60 deg at 200 deg/s
  for (const double rtol : {1e-6, 1e-8, 1e-10, 1e-12}) {
    SimulationOptions options;
    options.end_time = 1.0;
    options.output_step = 0.05;
    options.relative_tolerance = rtol;
    const Simulation sim = simulate(mech, options);
    EXPECT_FALSE(sim.complete) << "rtol " << rtol;
    ASSERT_EQ(sim.events.size(), 1u) << "rtol " << rtol;
    EXPECT_EQ(sim.events[0].kind, SimulationEvent::Kind::toggle);
    // The constraint drift blurs the rows' dependence to about 1e-6 there: at 3.5 rad/s, 3e-7 s.
    EXPECT_NEAR(sim.events[0].time, reference, 1e-6) << "rtol " << rtol;
    const double crank = angle_of(mech, sim.samples.back(), "crank");
    EXPECT_GT(crank, 0.0) << "rtol " << rtol;
    EXPECT_LT(crank, 1e-3) << "rtol " << rtol;
    if (rtol != 1e-12) continue;
    options.at_toggle = AtToggle::reverse;
    options.end_time = 2 * reference;
    const Simulation back = simulate(mech, options);
    ASSERT_TRUE(back.complete) << back.stop_reason;
    ASSERT_EQ(back.events.size(), 1u);
    EXPECT_NEAR(angle_of(mech, back.samples.back(), "crank"), M_PI / 3, 1e-5);
    EXPECT_LT(std::abs(back.energies.back().balance), 1e-9);
  }
}

// A near kite (rocker 1e-10 of its length short) at rtol 1e-6 with rows every 0.01 s: a point of
// the step the toggle's search looked at next to where the branches nearly meet could not be
// brought onto the constraints, and the run stopped with "the positions could not be brought back"
// instead of the toggle it reaches with rows every 0.05 s. Both row spacings now end the same
// way. How depends on the steps at this loose tolerance: the kite passes two near change points
// (0.3006704 s, where its rows come within 1.5e-5 of dependent, and 1.0933048 s, within 5.8e-6),
// and a step whose continuous output crosses the narrow gap between the branches there is a
// toggle (its measure changes sign), one that follows the branch around it is not. The steps of
// earlier versions stopped at either; these pass both, as the runs at rtol 1e-8 and tighter do,
// onto the folded branch: the crank held at A = O4 (8e-8 deg) while the rocker swings (rtol
// 1e-10 and 1e-12 agree on its angle at 1.05 s to 5e-7 deg).
TEST(ForwardDynamics, ANearKiteAtALooseToleranceEndsAlikeWhateverItsRows) {
  const Mechanism mech = mechanism_of(R"(
units: {length: m, angle: deg}
points:
  O2: [0, 0]
  O4: [0.1, 0]
  A: [0.05000000000000002, 0.08660254037844387]
  B: [0.28713203437616575, 0.16577575726787536]
ground: [O2, O4]
bodies:
  crank: {points: [O2, A], mass: 0.3, inertia: 0.00025}
  coupler: {points: [A, B], mass: 0.5, inertia: 0.0026041666666666665}
  rocker: {points: [O4, B], mass: 0.5, inertia: 0.002604166666145833}
lengths: {crank: 0.1, coupler: 0.25, rocker: 0.249999999975}
drivers:
  - {angle: crank, free: true, initial_speed: -200 deg/s}
)");
  const double rocker_at_1_05 = -170.16635;  // deg, at rtol 1e-10 and 1e-12
  std::vector<double> ends;
  for (const double dt : {0.05, 0.01}) {
    SimulationOptions options;
    options.end_time = 1.2;
    options.output_step = dt;
    options.relative_tolerance = 1e-6;
    const Simulation sim = simulate(mech, options);
    if (sim.complete) {
      ASSERT_TRUE(sim.events.empty());
      EXPECT_NEAR(angle_of(mech, sim.samples[static_cast<std::size_t>(std::lround(1.05 / dt))], "rocker") * 180 / M_PI,
                  rocker_at_1_05, 1e-3)
          << "dt " << dt;
    } else {
      ASSERT_EQ(sim.events.size(), 1u) << "dt " << dt << ": " << sim.stop_reason;
      EXPECT_NE(sim.stop_reason.find("toggle"), std::string::npos) << sim.stop_reason;
      const double at = sim.events[0].time;
      EXPECT_TRUE(std::abs(at - 0.3006704) < 1e-6 || std::abs(at - 1.0933048) < 1e-6) << "dt " << dt << ": " << at;
    }
    ends.push_back(sim.time_reached());
  }
  EXPECT_EQ(ends[0], ends[1]);  // the rows do not move the steps
  SimulationOptions accurate;
  accurate.end_time = 1.2;
  accurate.output_step = 0.05;
  accurate.relative_tolerance = 1e-8;
  const Simulation passed = simulate(mech, accurate);
  ASSERT_TRUE(passed.complete) << passed.stop_reason;
  EXPECT_NEAR(angle_of(mech, passed.samples[21], "rocker") * 180 / M_PI, rocker_at_1_05, 1e-4);
}

// A near kite of a 1 mm crank on 1 m links (its frame 1e-8 of the crank long) turning into its
// change point at rtol 1e-12: the steps collapse next to it, 1e-7 to 1e-6 from the rows'
// dependence, and the run stopped with "the step size fell ... the motion is too fast or not
// smooth". It is the toggle, reached where the steps cannot get nearer: stopped or reversed there.
TEST(ForwardDynamics, StepsCollapsingAtAToggleReachIt) {
  const Mechanism mech = mechanism_of(R"(
units: {length: m, angle: deg}
points:
  O2: [0, 0]
  O4: [0.00100000001, 0]
  A: [-0.001, 1.2246467991473531e-19]
  B: [5.000061212330021e-12, 0.99999949999987]
ground: [O2, O4]
bodies:
  crank: {points: [O2, A], mass: 0.3, inertia: 2.5e-08}
  coupler: {points: [A, B], mass: 0.5, inertia: 0.041666666666666664}
  rocker: {points: [O4, B], mass: 0.5, inertia: 0.041666666666666664}
lengths: {crank: 0.001, coupler: 1.0, rocker: 1.0}
drivers:
  - {angle: crank, free: true, initial_speed: -200 deg/s}
)");
  SimulationOptions options;
  options.end_time = 1.2;
  options.output_step = 0.01;
  options.relative_tolerance = 1e-12;
  const Simulation stopped = simulate(mech, options);
  ASSERT_EQ(stopped.events.size(), 1u) << stopped.stop_reason;
  EXPECT_NE(stopped.stop_reason.find("reached a toggle"), std::string::npos) << stopped.stop_reason;
  EXPECT_NEAR(stopped.events[0].time, 0.8999193, 1e-6);  // 180 deg at 200 deg/s, nearly
  options.at_toggle = AtToggle::reverse;
  const Simulation reversed = simulate(mech, options);
  ASSERT_TRUE(reversed.complete) << reversed.stop_reason;
  ASSERT_EQ(reversed.events.size(), 1u);
  // 1e-12 J away from the toggle; 1.1e-9 J on the row 8e-5 s past it, which the cubic of the
  // mirror window stands for (window_row: 3.5e-13 there at rtol 1e-12 with the 5(4) pair alone,
  // 8.8e-11 at 1e-13).
  EXPECT_LT(energy_error_away_from_events(reversed, 5e-4), 1e-11);
  EXPECT_LT(reversed.statistics.largest_energy_error, 1e-8);
}

// Released from rest 0.01 to 0.3 deg above its change point, the parallelogram's measure of the
// rows' dependence is nearly nothing at the start: judged against that size, the change point went
// by unreported (from 0.01 deg at rtol 1e-10 the run flipped between the parallel and crossed
// branches). Judged by the rows' dependence itself, it stops there at every tolerance, within
// twice the blur (1e-6 rad at the crossing's speed) of the pendulum's crossing time, the cranks
// still parallel.
TEST(ForwardDynamics, AChangePointNextToTheStartIsSeen) {
  for (const double from : {0.01, 0.1, 0.3}) {
    const Mechanism mech = parallelogram_with(", from: " + std::to_string(from));
    const double expected = parallelogram_crossing_time(from * M_PI / 180);
    // From the energy, (m + M) r g sin(from) = inertia w^2 / 2 (0.19 rad/s from 0.01 deg).
    const double crossing_speed = std::sqrt(2 * 1.9 * 0.1 * 9.81 * std::sin(from * M_PI / 180) / 0.0174);
    for (const double rtol : {1e-8, 1e-10, 1e-12}) {
      SimulationOptions options;
      options.end_time = 0.5;
      options.output_step = 0.02;
      options.relative_tolerance = rtol;
      const Simulation sim = simulate(mech, options);
      EXPECT_FALSE(sim.complete) << "from " << from << " rtol " << rtol;
      ASSERT_EQ(sim.events.size(), 1u) << "from " << from << " rtol " << rtol;
      EXPECT_EQ(sim.events[0].kind, SimulationEvent::Kind::toggle);
      EXPECT_NEAR(sim.events[0].time, expected, 2e-6 / crossing_speed) << "from " << from << " rtol " << rtol;
      for (const Sample& row : sim.samples)
        EXPECT_NEAR(angle_of(mech, row, "crank1"), angle_of(mech, row, "crank2"), 1e-9) << "t = " << row.time;
    }
  }
}

// Released 0.5 deg above its change point and reversed there at rtol 1e-12, the parallelogram's
// rows next to each reversal kept 0.003 J off its energy balance (of 0.016 J): they were a cubic
// Hermite to the integrator's own state at the toggle, whose speeds it keeps poorly there. From
// the regular row's Taylor expansion, every row's balance holds.
TEST(ForwardDynamics, ReversalsNextToTheStartKeepTheEnergy) {
  SimulationOptions options;
  options.end_time = 2.0;
  options.output_step = 0.003;
  options.relative_tolerance = 1e-12;
  options.at_toggle = AtToggle::reverse;
  const Simulation sim = simulate(parallelogram_with(", from: 0.5"), options);
  ASSERT_TRUE(sim.complete) << sim.stop_reason;
  EXPECT_GT(sim.events.size(), 50u);
  // Away from the reversals 1.5e-13 J (1e-11 with the 5(4) pair alone); the rows within 5e-4 s of
  // one, from the mirror window's cubic, 1.3e-9 J (4.7e-10).
  EXPECT_LT(energy_error_away_from_events(sim, 5e-4), 1e-11);
  EXPECT_LT(sim.statistics.largest_energy_error, 3e-9);
  // Reversal k at (2 k + 1) times the crossing: toggles taken where the rows came within the blur
  // (1.3e-6 rad early each) had the 78th 153 us early.
  const double crossing = parallelogram_crossing_time(0.5 * M_PI / 180);
  const std::size_t last = sim.events.size() - 1;
  EXPECT_NEAR(sim.events[last].time, (2 * static_cast<double>(last) + 1) * crossing, 3e-5);
}

// Andrews' squeezing mechanism (tests/dynamics/andrews_squeezer.yaml: the seven bodies, spring
// and driving torque of the DAE test sets) against the reference solution of the Test Set for IVP
// Solvers (Mazzia and Magherini, University of Bari, problem "andrews": PSIDE at tolerances of
// 1e-14): the seven angles beta, theta, gamma, phi, delta, Omega, epsilon at t = 0.03 s.
std::array<double, 7> andrews_angles(const Mechanism& mech, const Simulation& sim) {
  // Each body's direction, unwrapped row by row (beta turns 2.5 times in 0.03 s).
  std::array<double, 7> body{};
  for (std::size_t row = 0; row < sim.samples.size(); ++row)
    for (int k = 0; k < 7; ++k) {
      const double angle = angle_of(mech, sim.samples[row], "body" + std::to_string(k + 1));
      body[k] = row == 0 ? angle : angle + 2 * M_PI * std::round((body[k] - angle) / (2 * M_PI));
    }
  return {body[0],
          body[1] - body[0],
          body[2] + M_PI / 2,
          body[3] - body[4] + M_PI / 2,
          body[4],
          body[5] - body[6] - M_PI / 2,
          body[6] + M_PI / 2};
}

TEST(ForwardDynamics, AndrewsSqueezerMatchesTheTestSetsReferenceSolution) {
  const Mechanism mech(
      io::load_model_file(std::string(NBAR_SOURCE_DIR) + "/tests/dynamics/andrews_squeezer.yaml").model);
  const std::array<double, 7> reference = {1.581077119629904e+1,  -1.575637105984298e+1, 4.082224013073101e-2,
                                           -5.347301163226948e-1, 5.244099658805304e-1,  5.347301163226948e-1,
                                           1.048080741042263e+0};
  SimulationOptions options;
  options.end_time = 0.03;
  options.output_step = 0.0005;
  for (const double rtol : {1e-6, 1e-8, 1e-10, 1e-12}) {
    options.relative_tolerance = rtol;
    const Simulation sim = simulate(mech, options);
    ASSERT_TRUE(sim.complete) << sim.stop_reason;
    ASSERT_DOUBLE_EQ(sim.samples.back().time, 0.03);
    const std::array<double, 7> angles = andrews_angles(mech, sim);
    double digits = 16;
    for (int k = 0; k < 7; ++k)
      digits = std::min(digits, -std::log10(std::abs(angles[k] - reference[k]) / std::abs(reference[k])));
    std::printf("rtol %g: %.1f significant digits, %ld steps\n", rtol, digits, sim.statistics.accepted_steps);
    if (rtol == 1e-12) {
      EXPECT_GE(digits, 8.0);
    }
  }
}

}  // namespace
}  // namespace nbar
