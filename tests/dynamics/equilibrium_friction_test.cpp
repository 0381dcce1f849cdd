// The static equilibrium (`nbar equilibrium`) against closed forms and against the resting place
// of a damped simulation, and joint friction against its equations integrated here: a pendulum
// with viscous friction at its pivot, and a block on an inclined guide with Coulomb friction that
// slides at g (sin a - mu cos a) or, below the friction angle, only creeps.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <sstream>
#include <string>

#include "dynamics/simulation_support.hpp"
#include "nbar/dynamics/equilibrium.hpp"
#include "nbar/dynamics/forward_dynamics.hpp"
#include "nbar/io/model_file.hpp"

namespace nbar {
namespace {

using test_support::angle_of;
using test_support::mechanism_of;
using test_support::rk4;

// A bar of 2 kg and 0.5 m (its centre of mass in the middle) on a pivot at O, under gravity and a
// constant torque T: V = m g (L/2) sin(th) - T th, so the equilibria are cos(th) = T / (m g L/2),
// stable where V'' = -m g (L/2) sin(th) > 0 (below the pivot), with that stiffness.
std::string exact(double value) {
  std::ostringstream s;
  s.precision(17);
  s << value;
  return s.str();
}

std::string pendulum_with_torque(double drawn_angle) {
  const double L = 0.5;
  return "units: {length: m, angle: rad}\npoints:\n  O: [0, 0]\n  A: [" + exact(L * std::cos(drawn_angle)) + ", " +
         exact(L * std::sin(drawn_angle)) + R"(]
ground: [O]
gravity: [0, -9.81]
bodies:
  bar: {points: [O, A], mass: 2, inertia: 0.04, cg: [0.5, 0.5]}
torques:
  - {body: bar, torque: 3}
drivers:
  - {angle: bar, free: true}
)";
}

TEST(Equilibrium, APendulumUnderATorqueRestsWhereItsClosedFormSays) {
  // cg given in the drawing: the bar's middle for the drawn angle (rewritten below).
  for (const double drawn : {-0.3, 1.2}) {
    std::string text = pendulum_with_torque(drawn);
    const std::string middle = "[" + exact(0.25 * std::cos(drawn)) + ", " + exact(0.25 * std::sin(drawn)) + "]";
    text.replace(text.find("[0.5, 0.5]"), 10, middle);
    const Mechanism mech = mechanism_of(text);
    const Equilibrium e = find_equilibrium(mech);
    const double weight_arm = 2 * 9.81 * 0.25, T = 3;
    const double expected = (drawn < 0 ? -1 : 1) * std::acos(T / weight_arm);
    ASSERT_EQ(e.free_drivers.size(), 1u);
    EXPECT_NEAR(e.pose.driver_values[0], expected, 1e-10) << "from " << drawn;
    EXPECT_NEAR(angle_of(mech, e.pose, "bar"), expected, 1e-10);
    EXPECT_LT(e.residual, 1e-9);
    ASSERT_EQ(e.eigenvalues.size(), 1u);
    const double stiffness = -weight_arm * std::sin(expected);  // V''
    EXPECT_NEAR(e.eigenvalues[0], stiffness, 1e-5 * std::abs(stiffness));
    EXPECT_EQ(e.stability, drawn < 0 ? Stability::stable : Stability::unstable);
  }
}

// A block of 2 kg hanging on a vertical guide from a spring of 400 N/m, free length 0.3 m and a
// preload of 4 N: it rests where k (l - l0) + P = m g, stable with stiffness k.
TEST(Equilibrium, ABlockOnASpringRestsAtItsStaticDeflection) {
  const Mechanism mech = mechanism_of(R"(
units: {length: m, angle: deg}
points: {Y1: [0, 1.5], Y2: [0, -1], S: [0, 1], C: [0, 0.5]}
ground: [Y1, Y2, S]
gravity: [0, -9.81]
bodies:
  block: {points: [C], mass: 2}
sliders:
  - {body: block, point: C, along: [Y1, Y2]}
springs:
  - {between: [S, C], stiffness: 400, free_length: 0.3, preload: 4}
drivers:
  - {slide: block, free: true}
)");
  const Equilibrium e = find_equilibrium(mech);
  const double length = 0.3 + (2 * 9.81 - 4) / 400;  // from S at y = 1
  EXPECT_NEAR(e.pose.positions()(1), 1 - length, 1e-12);
  EXPECT_NEAR(e.pose.driver_values[0], length + 0.5, 1e-12);  // measured from Y1 along the guide
  ASSERT_EQ(e.eigenvalues.size(), 1u);
  EXPECT_NEAR(e.eigenvalues[0], 400, 1e-4);
  EXPECT_EQ(e.stability, Stability::stable);
}

// A four-bar with a spring and a damper, released: the simulation settles where
// `find_equilibrium` says, to 1e-7 rad (the motion decays by about 150 every 10 s).
TEST(Equilibrium, ADampedFourBarSettlesAtTheEquilibrium) {
  const Mechanism mech = mechanism_of(R"(
units: {length: m, angle: rad}
points:
  O2: [0, 0]
  O4: [0.2, 0]
  A: [0.04, 0.07]
  B: [0.17, 0.15]
  S: [0.3, 0.25]
ground: [O2, O4, S]
gravity: [0, -9.81]
bodies:
  crank: {points: [O2, A], mass: 0.3, inertia: 2e-4, cg: [0.02, 0.035]}
  coupler: {points: [A, B], mass: 0.5, inertia: 8e-4, cg: [0.105, 0.11]}
  rocker: {points: [O4, B], mass: 0.4, inertia: 5e-4, cg: [0.185, 0.075]}
springs:
  - {between: [B, S], stiffness: 300, free_length: 0.05, damping: 20}
drivers:
  - {angle: crank, free: true}
)");
  const Equilibrium e = find_equilibrium(mech);
  EXPECT_EQ(e.stability, Stability::stable);
  EXPECT_LT(e.residual, 1e-10);
  EXPECT_TRUE(e.warnings.empty());
  SimulationOptions options;
  options.end_time = 60.0;
  options.output_step = 20.0;
  options.relative_tolerance = 1e-11;
  const Simulation sim = simulate(mech, options);
  ASSERT_TRUE(sim.complete) << sim.stop_reason;
  const Sample& last = sim.samples.back();
  EXPECT_NEAR(last.driver_values[0], e.pose.driver_values[0], 1e-7);
  EXPECT_GT(std::abs(last.driver_values[0] - sim.samples.front().driver_values[0]), 0.05);  // it moved
  for (int i = 0; i < last.positions().size(); ++i) EXPECT_NEAR(last.positions()(i), e.pose.positions()(i), 1e-8);
}

TEST(Equilibrium, NoEquilibriumAndNothingFreeAreLocatedErrors) {
  const std::string crank = R"(
points: {O: [0, 0], A: [10, 0]}
ground: [O]
bodies:
  crank: {points: [O, A], mass: 1, inertia: 1e-4}
torques:
  - {body: crank, torque: 2}
drivers:
  - {angle: crank, free: true}
)";
  try {
    find_equilibrium(mechanism_of(crank));
    FAIL() << "a constant torque on a free crank has no equilibrium";
  } catch (const Error& e) {
    EXPECT_NE(e.message().find("there is no equilibrium"), std::string::npos) << e.message();
    EXPECT_EQ(e.where().kind, EntityRef::Kind::Driver);
  }
  std::string held = crank;
  held.replace(held.find(", free: true"), 12, "");
  EXPECT_THROW(find_equilibrium(mechanism_of(held)), Error);
  // Without any load the crank is at rest anywhere: neutral.
  std::string unloaded = crank;
  unloaded.replace(unloaded.find("torques:"), unloaded.find("drivers:") - unloaded.find("torques:"), "");
  const Equilibrium e = find_equilibrium(mechanism_of(unloaded));
  EXPECT_EQ(e.stability, Stability::neutral);
  EXPECT_EQ(e.residual, 0.0);
}

// A parallelogram (0.1 m cranks, 0.3 m frame) whose first crank's pin a spring of zero free length
// pulls towards S. With S on the frame's line at (0.1, 0) the potential is least where the crank
// lies along the frame (th = 0 by symmetry): the change point, where the parallelogram and
// crossed branches meet and the loads do not determine the motion. With S below the line at
// (0.0866, -0.05) the equilibrium is at th = -30 deg (the pin on the spring's anchor), which Newton
// reaches from the drawing at +5 deg through the change point, the Jacobian's determinant
// changing sign. The crank-rocker of the damped test, far from its toggles, says nothing.
std::string parallelogram_with_spring_to(const std::string& anchor, double drawn_deg) {
  const double th = drawn_deg * M_PI / 180;
  return R"(units: {length: m, angle: deg}
points:
  O1: [0, 0]
  O2: [0.3, 0]
  A1: [)" + exact(0.1 * std::cos(th)) + ", " + exact(0.1 * std::sin(th)) + R"(]
  A2: [)" + exact(0.3 + 0.1 * std::cos(th)) + ", " + exact(0.1 * std::sin(th)) + R"(]
  S: )" + anchor + R"(
ground: [O1, O2, S]
bodies:
  crank1: {points: [O1, A1], mass: 0.4, inertia: 2e-4}
  crank2: {points: [O2, A2], mass: 0.4, inertia: 2e-4}
  coupler: {points: [A1, A2], mass: 1.5, inertia: 0.01}
springs:
  - {between: [S, A1], stiffness: 100, free_length: 0}
drivers:
  - {angle: crank1, free: true}
)";
}

TEST(Equilibrium, AnEquilibriumAtOrPastAToggleIsSaid) {
  const Equilibrium at = find_equilibrium(mechanism_of(parallelogram_with_spring_to("[0.1, 0]", 60)));
  EXPECT_NEAR(at.pose.driver_values[0], 0.0, 1e-10);
  ASSERT_EQ(at.warnings.size(), 1u);
  EXPECT_EQ(at.warnings[0].code, "equilibrium_at_toggle");
  EXPECT_NE(at.warnings[0].message.find("crank1 = "), std::string::npos) << at.warnings[0].message;

  const Equilibrium past = find_equilibrium(mechanism_of(parallelogram_with_spring_to("[0.0866025403784, -0.05]", 5)));
  EXPECT_NEAR(past.pose.driver_values[0], -M_PI / 6, 1e-9);
  ASSERT_EQ(past.warnings.size(), 1u);
  EXPECT_EQ(past.warnings[0].code, "equilibrium_past_toggle");
  // Drawn on the same side as the equilibrium, nothing is passed.
  EXPECT_TRUE(find_equilibrium(mechanism_of(parallelogram_with_spring_to("[0.0866025403784, -0.05]", -5)))
                  .warnings.empty());
}

// A slider-crank whose rod is as long as its crank (0.1 m), drawn at 60 deg, a spring of free
// length 0.5 m pulling the piston towards x = 0: Newton goes through the change point at 90 deg
// (the piston at the crank's pivot) to rest on the other branch, the rod folded back onto the
// crank (crank 90.066 deg, the piston at x = 0). The determinant's sign does not change there;
// the Jacobian is singular on the way, which the path from the start, followed and its least
// condition refined, finds.
TEST(Equilibrium, AChangePointPassedWithoutASignChangeIsSaid) {
  const Equilibrium e = find_equilibrium(mechanism_of(R"(units: {length: m, angle: deg}
points: {O2: [0, 0], G1: [-1, 0], G2: [1, 0], S: [0.5, 0], A: [0.05, 0.0866025403784439], C: [0.1, 0]}
ground: [O2, G1, G2, S]
bodies:
  crank: {points: [O2, A], mass: 0.5, inertia: 1e-3}
  rod: {points: [A, C], mass: 0.3, inertia: 5e-4}
  piston: {points: [C], mass: 0.4}
sliders:
  - {body: piston, point: C, along: [G1, G2]}
springs:
  - {between: [S, C], stiffness: 1000, free_length: 0.5}
drivers:
  - {angle: crank, free: true}
)"));
  EXPECT_GT(e.pose.driver_values[0], M_PI / 2);
  ASSERT_EQ(e.warnings.size(), 1u);
  EXPECT_EQ(e.warnings[0].code, "equilibrium_past_toggle");
}

// A bar pendulum (m = 2 kg, L = 0.5 m, I_cg = 0.04 kg m^2) with viscous friction c at its pivot:
// (I_cg + m L^2/4) th'' = -m g (L/2) cos(th) - c th', integrated here by RK4.
TEST(JointFriction, AViscousPivotSlowsAPendulumAsItsEquationSays) {
  const Mechanism mech = mechanism_of(R"(
units: {length: m, angle: rad}
points: {O: [0, 0], A: [0.5, 0]}
ground: [O]
gravity: [0, -9.81]
bodies:
  bar: {points: [O, A], mass: 2, inertia: 0.04, cg: [0.25, 0]}
friction:
  - {joint: O, viscous: 0.3}
drivers:
  - {angle: bar, free: true, initial_speed: 1}
)");
  SimulationOptions options;
  options.end_time = 2.0;
  options.output_step = 0.5;
  options.relative_tolerance = 1e-12;
  const Simulation sim = simulate(mech, options);
  ASSERT_TRUE(sim.complete) << sim.stop_reason;
  const double m = 2, L = 0.5, g = 9.81, c = 0.3, inertia = 0.04 + m * L * L / 4;
  const auto pendulum = [&](double th, double w) { return (-m * g * L / 2 * std::cos(th) - c * w) / inertia; };
  for (const Sample& s : sim.samples) {
    const auto [th, w] = rk4(pendulum, 0.0, 1.0, s.time, 20000);
    EXPECT_NEAR(angle_of(mech, s, "bar"), th, 1e-9) << "t = " << s.time;
  }
  const SimulationEnergy& end = sim.energies.back();
  EXPECT_GT(end.dissipated, 0.1);
  EXPECT_LT(std::abs(end.balance), 1e-8 * end.dissipated);
}

// A block of m = 2 kg on a guide inclined at 30 degrees, with a Coulomb friction force F = mu m g
// cos(a) (the normal force is m g cos(a) throughout).
std::string block_on_incline(double friction_force) {
  return R"(
units: {length: m, angle: deg}
points: {G1: [0, 0], G2: [0.866025403784439, -0.5], C: [0.1732050807568877, -0.1]}
ground: [G1, G2]
gravity: [0, -9.81]
bodies:
  block: {points: [C], mass: 2}
sliders:
  - {body: block, point: C, along: [G1, G2]}
friction:
  - {slider: block, coulomb: )" +
         exact(friction_force) + R"(, creep_speed: 0.001}
drivers:
  - {slide: block, free: true}
)";
}

TEST(JointFriction, ABlockSlidesDownAnInclineAtTheClosedFormAcceleration) {
  const double m = 2, g = 9.81, a = M_PI / 6, mu = 0.3, F = mu * m * g * std::cos(a), creep = 0.001;
  const Mechanism mech = mechanism_of(block_on_incline(F));
  SimulationOptions options;
  options.end_time = 1.0;
  options.output_step = 0.25;
  options.relative_tolerance = 1e-10;
  const Simulation sim = simulate(mech, options);
  ASSERT_TRUE(sim.complete) << sim.stop_reason;
  // The regularised equation, integrated here, and the closed form g (sin a - mu cos a) t^2 / 2,
  // which it approaches once the speed is well above the creep speed.
  const auto sliding = [&](double, double v) { return g * std::sin(a) - F / m * std::tanh(v / creep); };
  const double start = 0.2;
  for (const Sample& s : sim.samples) {
    const double travelled = s.driver_values[0] - start;
    const auto [reference, speed] = rk4(sliding, 0.0, 0.0, s.time, 200000);
    EXPECT_NEAR(travelled, reference, 1e-8) << "t = " << s.time;
    // Below the speed creep the friction is less than F: at most (F/m) (creep/a) ln 2 of speed gained.
    const double accel = g * (std::sin(a) - mu * std::cos(a)), lead = F / m * creep / accel * std::log(2.0);
    EXPECT_GE(travelled, 0.5 * accel * s.time * s.time - 1e-12) << "t = " << s.time;
    EXPECT_LE(travelled, 0.5 * accel * s.time * s.time + lead * s.time + 1e-12) << "t = " << s.time;
  }
  const SimulationEnergy& end = sim.energies.back();
  EXPECT_NEAR(end.dissipated, F * (sim.samples.back().driver_values[0] - start), 1e-3 * end.dissipated);
  EXPECT_LT(std::abs(end.balance), 1e-7 * end.dissipated);
}

TEST(JointFriction, ABlockBelowTheFrictionAngleOnlyCreeps) {
  const double m = 2, g = 9.81, a = M_PI / 6, mu = 0.8, F = mu * m * g * std::cos(a), creep = 0.001;
  const Mechanism mech = mechanism_of(block_on_incline(F));
  SimulationOptions options;
  options.end_time = 1.0;
  options.output_step = 0.5;
  options.relative_tolerance = 1e-9;
  const Simulation sim = simulate(mech, options);
  ASSERT_TRUE(sim.complete) << sim.stop_reason;
  // It creeps at the speed where tanh balances gravity's pull: creep atanh(tan(a) / mu).
  const double creep_speed = creep * std::atanh(std::tan(a) / mu);
  const double travelled = sim.samples.back().driver_values[0] - 0.2;
  EXPECT_NEAR(travelled, creep_speed * 1.0, 0.05 * creep_speed);
  EXPECT_LT(travelled, 1e-3);
  EXPECT_LT(std::abs(sim.energies.back().balance), 1e-6 * m * g);
}

// A slider-crank started at its dead centre (`from: 0.4`, crank and rod in line) with the piston
// free: the piston's speed must be zero there (met otherwise only by a crank turning some 10^7
// deg/s, as the near-singular pose allows), so its initial speed of 0.5 m/s is projected away,
// with a warning saying by how much. Drawn elsewhere, the same speed is kept without a word.
std::string slider_crank_from(const std::string& from) {
  return R"(
units: {length: m, angle: deg}
points: {O: [0, 0], X: [1, 0], A: [0.06, 0.08], C: [0.3828427124746190, 0]}
ground: [O, X]
gravity: [0, -9.81]
bodies:
  crank: {points: [O, A], mass: 0.4, inertia: 2e-4, cg: [0.03, 0.04]}
  rod: {points: [A, C], mass: 0.6, inertia: 5e-3, cg: [0.2, 0.04]}
  piston: {points: [C], mass: 1}
sliders:
  - {body: piston, point: C, along: [O, X]}
lengths: {rod: 0.3}
drivers:
  - {slide: piston, )" +
         from + R"(free: true, initial_speed: 0.5}
)";
}

TEST(InitialSpeeds, ThoseTheConstraintsDoNotAllowAreProjectedAndSaid) {
  SimulationOptions options;
  options.end_time = 0.01;
  options.output_step = 0.01;
  const Simulation sim = simulate(mechanism_of(slider_crank_from("from: 0.4, ")), options);
  ASSERT_EQ(sim.warnings.size(), 1u);
  EXPECT_EQ(sim.warnings[0].code, "initial_speed_projected");
  EXPECT_NE(sim.warnings[0].message.find("a correction of 0.5 m/s"), std::string::npos) << sim.warnings[0].message;
  EXPECT_LT(sim.samples.front().derivative(1).cwiseAbs().maxCoeff(), 1e-6);
  const Simulation moving = simulate(mechanism_of(slider_crank_from("")), options);
  EXPECT_TRUE(moving.warnings.empty());
  EXPECT_NEAR(moving.samples.front().derivative(1)(2), 0.5, 1e-12);  // C.vx
}

TEST(JointFriction, TheModelFileSaysWhereItsFrictionIsWrong) {
  const std::string base = R"(
points: {O: [0, 0], A: [10, 0], B: [20, 5], C: [30, 0]}
ground: [O, C]
bodies: {crank: [O, A], coupler: [A, B], rocker: [C, B], extra: [A, C]}
drivers:
  - {angle: crank}
)";
  const auto error_of = [&](const std::string& friction) {
    try {
      io::parse_model(base + friction, "m.yaml");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error_of("friction:\n  - {joint: O, viscous: -1}\n"),
            "m.yaml:8:25: the viscous friction must not be negative");
  EXPECT_NE(error_of("friction:\n  - {joint: O, coulomb: 1e20}\n")
                .find("m.yaml:8:25: the Coulomb friction of 1e20 N m is out of range"),
            std::string::npos);
  EXPECT_NE(error_of("friction:\n  - {joint: A, viscous: 1}\n")
                .find("m.yaml:8:13: at point 'A' 3 links meet (crank, coupler, extra)"),
            std::string::npos);
  EXPECT_EQ(error_of("friction:\n  - {joint: A, links: [crank, rocker], viscous: 1}\n"),
            "m.yaml:8:31: 'rocker' does not meet at point 'A' (the links there: crank, coupler, extra)");
  EXPECT_EQ(error_of("friction:\n  - {joint: O, viscous: 1}\n"), "no error");
  EXPECT_EQ(error_of("friction:\n  - {slider: crank, viscous: 1}\n"),
            "m.yaml:8:14: body 'crank' has no slider (`sliders:` lists it first)");
  EXPECT_EQ(error_of("springs:\n  - {between: [A, C], stiffness: 1e15}\n"),
            "m.yaml:8:34: the stiffness is out of range (at most 1e12 N/m): the motion it gives is faster than any "
            "integration step");
  EXPECT_EQ(error_of("simulation: {to: -1}\n"),
            "m.yaml:7:18: the simulated time `to` must be a positive number of seconds");
  EXPECT_EQ(error_of("simulation: {stop_when: crank = 3}\n"),
            "m.yaml:7:25: `stop_when` is a column, < or > and a number, like 'slider.x > 200', not 'crank = 3'");
  const Model m =
      io::parse_model(base + "simulation: {to: 2, dt: 0.1, stop_when: 'crank > 30', at_toggle: reverse}\n").model;
  EXPECT_EQ(m.simulation.end_time, 2.0);
  EXPECT_EQ(m.simulation.output_step, 0.1);
  EXPECT_EQ(m.simulation.stop_when, std::string("crank > 30"));
  EXPECT_EQ(m.simulation.reverse_at_toggle, true);
}

}  // namespace
}  // namespace nbar
