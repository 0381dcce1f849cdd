// The equations of motion at a time of a simulation (`nbar explain --simulate`), checked against
// references made here: M against its closed form from each body's mass and inertia, Phi_q against
// central differences of Phi, and the system solved here against the accelerations of the
// simulation's own row at that time (a separate run to it). And a cancelled simulation: it keeps
// its rows, the same bit for bit as an uncancelled run's first rows.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "dynamics/simulation_support.hpp"
#include "kinematics/constraints.hpp"
#include "nbar/dynamics/equations_of_motion.hpp"
#include "nbar/dynamics/forward_dynamics.hpp"
#include "nbar/request/requests.hpp"

namespace nbar {
namespace {

using test_support::mechanism_of;

// A bar of 0.3 m and 1.2 kg swinging about O, released 20 deg below the horizontal at 1 rad/s,
// centre of mass at its middle, I_G = m L^2 / 12.
const char* const kPendulum = R"(
units: {length: m, angle: deg}
points: {O: [0, 0], A: [0.2819077862357725, -0.10260604299770061]}
ground: [O]
gravity: [0, -9.81]
bodies:
  bar: {points: [O, A], mass: 1.2, inertia: 0.009, cg: [0.14095389311788625, -0.051303021498850305]}
drivers:
  - {angle: bar, free: true, initial_speed: 1 rad/s}
)";

// The slider-crank of tests/dynamics/simulate_reference.py: crank 0.05 m, rod 0.18 m, piston on
// the x axis, a constant torque on the crank, a spring from the piston to a fixed point and
// gravity, so that Q has three origins.
const char* const kSliderCrank = R"(
units: {length: m, angle: deg}
points:
  O: [0, 0]
  X: [1, 0]
  S: [0.4, 0]
  A: [0.04330127018922194, 0.025]
  C: [0.2215567048889808, 0]
ground: [O, X, S]
gravity: [0, -9.81]
bodies:
  crank: {points: [O, A], mass: 0.5, inertia: 2e-4, cg: [0.021650635094610966, 0.0125]}
  rod: {points: [A, C], mass: 0.8, inertia: 2.5e-3, cg: [0.10694067233413754, 0.025162771734987946]}
  piston: {points: [C], mass: 0.6}
sliders:
  - {body: piston, point: C, along: [O, X]}
torques:
  - {body: crank, torque: 0.05}
springs:
  - {between: [C, S], stiffness: 40, free_length: 0.15, damping: 0.3}
drivers:
  - {angle: crank, free: true, initial_speed: 5 rad/s}
)";

SimulationOptions run_to(double t) {
  SimulationOptions options;
  options.end_time = t;
  options.output_step = t / 10;
  options.relative_tolerance = 1e-10;
  return options;
}

// Every row of Phi at q, the drivers at `values` (the free ones' rows are not among those kept).
Eigen::VectorXd residuals(const Mechanism& mech, const Eigen::VectorXd& q) {
  std::vector<DriverState> drivers;
  for (const Driver& d : mech.model().drivers) drivers.push_back(make_driver_state(Series(3, 0.0), d.is_angular()));
  Eigen::VectorXd phi;
  evaluate_residuals(mech, q, drivers, phi);
  return phi;
}

// Phi_q of the kept rows by central differences of Phi: exact but for rounding on rows that are
// at most quadratic in q.
void expect_jacobian_is_phis_derivative(const Mechanism& mech, const EquationsOfMotionAt& e) {
  const double h = 1e-6;
  for (Eigen::Index c = 0; c < e.q.size(); ++c) {
    Eigen::VectorXd plus = e.q, minus = e.q;
    plus(c) += h;
    minus(c) -= h;
    const Eigen::VectorXd derivative = (residuals(mech, plus) - residuals(mech, minus)) / (2 * h);
    for (std::size_t r = 0; r < e.rows.size(); ++r)
      EXPECT_NEAR(e.jacobian(static_cast<Eigen::Index>(r), c), derivative(e.rows[r]), 1e-8)
          << e.row_labels[r] << ", " << e.coordinates[c];
  }
}

// The printed system [M Phi_q^T; Phi_q 0] [q''; lambda] = [Q; gamma] solved here gives the
// accelerations of the simulation's row at T, from a run of its own to T.
void expect_system_gives_the_simulated_accelerations(const Mechanism& mech, const EquationsOfMotionAt& e,
                                                     const SimulationOptions& options) {
  const Eigen::Index n = e.q.size(), m = e.jacobian.rows();
  Eigen::MatrixXd system = Eigen::MatrixXd::Zero(n + m, n + m);
  system << e.mass, e.jacobian.transpose(), e.jacobian, Eigen::MatrixXd::Zero(m, m);
  Eigen::VectorXd rhs(n + m);
  rhs << e.gravity + e.applied + e.springs + e.friction, e.gamma;
  const Eigen::VectorXd solution = system.fullPivLu().solve(rhs);
  const Simulation run = simulate(mech, options);
  ASSERT_TRUE(run.complete) << run.stop_reason;
  ASSERT_DOUBLE_EQ(run.samples.back().time, e.time);
  const Eigen::VectorXd simulated = 2.0 * run.samples.back().taylor.col(2);
  const double scale = simulated.lpNorm<Eigen::Infinity>();
  EXPECT_LT((solution.head(n) - simulated).lpNorm<Eigen::Infinity>(), 1e-9 * scale);
  EXPECT_LT((e.acceleration - simulated).lpNorm<Eigen::Infinity>(), 1e-9 * scale);
  EXPECT_LT((solution.tail(m) - e.multipliers).lpNorm<Eigen::Infinity>(), 1e-9 * solution.tail(m).lpNorm<1>());
  EXPECT_LT(e.residual, 1e-12);
}

// q = (x_A, y_A); v_G = q'/2 and the bar turns at |q'|/L, so M = (m/4 + I/L^2) I = m/3 I. Phi is
// the bar's length; gravity's share of Q is m g / 2 on y_A.
TEST(EquationsOfMotion, PendulumMassMatrixJacobianAndAccelerations) {
  const Mechanism mech = mechanism_of(kPendulum);
  const double T = 0.35, m = 1.2;
  const EquationsOfMotionAt e = equations_of_motion_at(mech, T, run_to(T));
  ASSERT_EQ(e.q.size(), 2);
  EXPECT_EQ(e.coordinates, (std::vector<std::string>{"A.x", "A.y"}));
  EXPECT_LT((e.mass - m / 3 * Eigen::Matrix2d::Identity()).lpNorm<Eigen::Infinity>(), 1e-14);
  ASSERT_EQ(e.rows.size(), 1u);
  EXPECT_NEAR(e.gravity(0), 0.0, 1e-15);
  EXPECT_NEAR(e.gravity(1), -m * 9.81 / 2, 1e-13);
  EXPECT_EQ(e.applied.lpNorm<Eigen::Infinity>(), 0.0);
  expect_jacobian_is_phis_derivative(mech, e);
  expect_system_gives_the_simulated_accelerations(mech, e, run_to(T));
  // In the bar's angle: m L^2/3 th'' = -m g L/2 cos th, so |A''| tangential = L th''.
  const double L = 0.3, th = std::atan2(e.q(1), e.q(0));
  const double tangential = -e.acceleration(0) * std::sin(th) + e.acceleration(1) * std::cos(th);
  EXPECT_NEAR(tangential, L * (-1.5 * 9.81 / L * std::cos(th)), 1e-9);
}

// q = (x_A, y_A, x_C, y_C). The crank's centre of mass is A/2; the rod's r_G = A + B (C - A)
// with B = a I + b J (a, b its place along and across A-C); the piston's is C. So
// M = [(m1/4 + I1/r^2) I + m2 (I-B)^T (I-B) + I2/l^2 I,  m2 (I-B)^T B - I2/l^2 I;
//      (its transpose),  m2 B^T B + I2/l^2 I + mp I].
TEST(EquationsOfMotion, SliderCrankMassMatrixJacobianAndAccelerations) {
  const Mechanism mech = mechanism_of(kSliderCrank);
  const double T = 0.2;
  const EquationsOfMotionAt e = equations_of_motion_at(mech, T, run_to(T));
  ASSERT_EQ(e.q.size(), 4);
  EXPECT_EQ(e.coordinates, (std::vector<std::string>{"A.x", "A.y", "C.x", "C.y"}));
  const double r = 0.05, l = 0.18, m1 = 0.5, i1 = 2e-4, m2 = 0.8, i2 = 2.5e-3, mp = 0.6, a = 0.35, b = 0.05;
  const Eigen::Matrix2d I = Eigen::Matrix2d::Identity();
  Eigen::Matrix2d B;
  B << a, -b, b, a;
  Eigen::Matrix4d M;
  M.topLeftCorner<2, 2>() = (m1 / 4 + i1 / (r * r)) * I + m2 * (I - B).transpose() * (I - B) + i2 / (l * l) * I;
  M.topRightCorner<2, 2>() = m2 * (I - B).transpose() * B - i2 / (l * l) * I;
  M.bottomLeftCorner<2, 2>() = M.topRightCorner<2, 2>().transpose();
  M.bottomRightCorner<2, 2>() = m2 * B.transpose() * B + i2 / (l * l) * I + mp * I;
  EXPECT_LT((e.mass - M).lpNorm<Eigen::Infinity>(), 1e-12 * M.lpNorm<Eigen::Infinity>()) << e.mass;
  // Q by origin: the torque T on the crank is T perp(A)/|A|^2 on A; the spring's tension on C.
  const Eigen::Vector2d A = e.q.head<2>(), C = e.q.tail<2>();
  EXPECT_NEAR(e.applied(0), -0.05 * A.y() / A.squaredNorm(), 1e-12);
  EXPECT_NEAR(e.applied(1), 0.05 * A.x() / A.squaredNorm(), 1e-12);
  const Eigen::Vector2d to_s = Eigen::Vector2d(0.4, 0) - C;
  const double rate = -to_s.normalized().dot(e.velocity.tail<2>());
  const double tension = 40 * (to_s.norm() - 0.15) + 0.3 * rate;
  EXPECT_NEAR(e.springs(2), tension * to_s.normalized().x(), 1e-10);
  EXPECT_EQ(e.friction.lpNorm<Eigen::Infinity>(), 0.0);
  expect_jacobian_is_phis_derivative(mech, e);
  expect_system_gives_the_simulated_accelerations(mech, e, run_to(T));
}

TEST(EquationsOfMotion, AtTheStartTheStateIsTheModelsInitialConditions) {
  const Mechanism mech = mechanism_of(kPendulum);
  const EquationsOfMotionAt e = equations_of_motion_at(mech, 0.0, run_to(1.0));
  EXPECT_NEAR(e.q(0), 0.2819077862357725, 1e-15);
  // Released at 1 rad/s anticlockwise: A' = omega perp(A).
  EXPECT_NEAR(e.velocity(0), 0.10260604299770061, 1e-12);
  EXPECT_NEAR(e.velocity(1), 0.2819077862357725, 1e-12);
  EXPECT_EQ(e.accepted_steps, 0);
}

TEST(EquationsOfMotion, BadTimesAndModelsAreLocatedErrors) {
  const Mechanism mech = mechanism_of(kPendulum);
  for (double t : {-0.1, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    try {
      equations_of_motion_at(mech, t, run_to(1.0));
      ADD_FAILURE() << "no error at " << t;
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::BadInput) << e.message();
    }
  }
  const Mechanism driven = mechanism_of(R"(
units: {length: m}
points: {O: [0, 0], A: [0.3, 0]}
ground: [O]
bodies:
  bar: {points: [O, A], mass: 1}
drivers:
  - {angle: bar, speed: 60 rpm}
)");
  try {
    equations_of_motion_at(driven, 0.5, run_to(0.5));
    ADD_FAILURE() << "a model with nothing free";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::InvalidModel);
    EXPECT_EQ(e.where().kind, EntityRef::Kind::Driver);
    EXPECT_NE(e.message().find("free: true"), std::string::npos) << e.message();
  }
  SimulationOptions few = run_to(5.0);
  few.max_steps = 20;
  try {
    equations_of_motion_at(mech, 5.0, few);
    ADD_FAILURE() << "a run that stops before the time";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::StoppedAtLimit);
    EXPECT_NE(e.message().find("did not reach t = 5 s"), std::string::npos) << e.message();
  }
}

// The request's rules: `at` from 0 to 1e6 s, a number; only with `simulate`, which needs it.
TEST(EquationsOfMotion, TheRequestRefusesBadTimesByName) {
  const auto refused = [](request::Options options, const std::string& key) {
    try {
      request::ExplainRequest::read(options);
      ADD_FAILURE() << "accepted";
    } catch (const request::OptionError& e) {
      EXPECT_EQ(e.option(), key) << e.what();
    }
  };
  request::Options beyond;
  beyond.set("simulate", true);
  beyond.set("at", 2e6);
  refused(beyond, "at");
  request::Options negative;
  negative.set("simulate", true);
  negative.set("at", -1.0);
  refused(negative, "at");
  request::Options not_a_number;
  not_a_number.set("simulate", true);
  not_a_number.set("at", std::numeric_limits<double>::quiet_NaN());
  refused(not_a_number, "at");
  request::Options without_time;
  without_time.set("simulate", true);
  refused(without_time, "at");
  request::Options without_simulate;
  without_simulate.set("at", 0.5);
  refused(without_simulate, "at");
  request::Options markdown;
  markdown.set("simulate", true);
  markdown.set("at", 0.5);
  markdown.set("format", std::string("markdown"));
  refused(markdown, "format");
}

// Cancelled after 40 steps (the progress callback answers false), the run keeps its rows, each
// the same bit for bit as the uncancelled run's row of that time, and says where it stopped.
TEST(SimulationCancel, ACancelledRunKeepsItsRowsBitForBit) {
  const Mechanism mech = mechanism_of(kSliderCrank);
  SimulationOptions options = run_to(2.0);
  options.output_step = 0.005;
  const Simulation whole = simulate(mech, options);
  ASSERT_TRUE(whole.complete) << whole.stop_reason;
  RunControl control;
  int steps = 0;
  control.on_progress = [&steps](const Progress&) { return ++steps <= 40; };
  const Simulation cancelled = simulate(mech, options, control);
  EXPECT_FALSE(cancelled.complete);
  EXPECT_TRUE(cancelled.cancelled);
  EXPECT_EQ(steps, 41);
  EXPECT_EQ(cancelled.statistics.accepted_steps + cancelled.statistics.rejected_steps, 40);
  ASSERT_GT(cancelled.samples.size(), 2u);
  ASSERT_LT(cancelled.samples.size(), whole.samples.size());
  EXPECT_EQ(
      cancelled.stop_reason, "cancelled at t = " + [&] {
        std::ostringstream s;
        s.precision(9);
        s << cancelled.samples.back().time;
        return s.str();
      }() + " s");
  EXPECT_EQ(cancelled.time_reached(), cancelled.samples.back().time);
  for (std::size_t i = 0; i < cancelled.samples.size(); ++i) {
    EXPECT_EQ(cancelled.samples[i].time, whole.samples[i].time);
    EXPECT_TRUE(cancelled.samples[i].taylor == whole.samples[i].taylor) << "row " << i;
    EXPECT_EQ(cancelled.energies[i].balance, whole.energies[i].balance) << "row " << i;
  }
  // A token cancelled before the run: the start's row alone.
  RunControl before;
  before.token.cancel();
  const Simulation at_start = simulate(mech, options, before);
  EXPECT_TRUE(at_start.cancelled);
  ASSERT_EQ(at_start.samples.size(), 1u);
  EXPECT_TRUE(at_start.samples[0].taylor == whole.samples[0].taylor);
}

}  // namespace
}  // namespace nbar
