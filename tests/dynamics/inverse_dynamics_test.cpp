// Inverse dynamics against independent references: Norton's 9x9 Newton-Euler system for the
// four-bar (kinematics from the closed form, solved here), virtual work for static mechanical
// advantage, and the power balance at every step.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>

#include "../kinematics/helpers/kinematics_support.hpp"
#include "bench_models.hpp"
#include "nbar/analysis/analysis.hpp"
#include "nbar/dynamics/dynamics_table.hpp"
#include "nbar/dynamics/inverse_dynamics.hpp"
#include "nbar/io/model_file.hpp"

namespace nbar::ktest {
namespace {

Eigen::Vector2d perp(const Eigen::Vector2d& v) { return {-v.y(), v.x()}; }
double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }
Eigen::Vector2d rotate(const Eigen::Vector2d& v, double angle) {
  return {std::cos(angle) * v.x() - std::sin(angle) * v.y(), std::sin(angle) * v.x() + std::cos(angle) * v.y()};
}

// Acceleration of a point at offset r from a point with acceleration a0, on a body turning at w, alpha.
Eigen::Vector2d rigid_acceleration(const Eigen::Vector2d& a0, const Eigen::Vector2d& r, double w, double alpha) {
  return a0 + alpha * perp(r) - w * w * r;
}

Law constant_law(double v) { return Law::parse(std::to_string(v)); }

int find_link(const InverseDynamics& dyn, int point, int link) {
  const auto& links = dyn.joint_links();
  for (std::size_t i = 0; i < links.size(); ++i)
    if (links[i].point == point && links[i].link == link) return static_cast<int>(i);
  return -1;
}

// A crank-rocker with masses, offset centres of mass, gravity, a force on the coupler point
// and a torque on the rocker.
struct LoadedFourBar {
  NortonFourBar fb{0.05, 0.15, 0.12, 0.16};
  double theta0 = 0.3, omega2 = 20.0, alpha2 = 5.0;
  double m2 = 0.4, m3 = 1.1, m4 = 0.8;
  double i2 = 2e-4, i3 = 3e-3, i4 = 1.5e-3;
  Eigen::Vector2d g2_local{0.02, 0.005}, g3_local{0.06, 0.02}, g4_local{0.07, -0.01};  // along, across each link
  Eigen::Vector2d p_local{0.075, 0.04};                                                // the coupler point
  Eigen::Vector2d force_p{30.0, -50.0};
  double torque4 = -2.0;
  Eigen::Vector2d gravity{0.0, -9.81};

  // The model drawn at theta0 on the open branch.
  Model model(int steps) const {
    const FourBarState s = fb.solve(theta0, omega2, alpha2, true);
    const Eigen::Vector2d O2(0, 0), O4(fb.d, 0);
    const Eigen::Vector2d A = polar(fb.a, s.theta2), B = O4 + polar(fb.c, s.theta4);
    Model m;
    const int o2 = add_point(m, "O2", O2, true), o4 = add_point(m, "O4", O4, true);
    const int a = add_point(m, "A", A), b = add_point(m, "B", B);
    const int p = add_point(m, "P", A + rotate(p_local, s.theta3));
    const int crank = add_body(m, "crank", {o2, a});
    const int coupler = add_body(m, "coupler", {a, b, p});
    const int rocker = add_body(m, "rocker", {o4, b});
    m.bodies[crank].inertia = GivenInertia{m2, O2 + rotate(g2_local, s.theta2), i2};
    m.bodies[coupler].inertia = GivenInertia{m3, A + rotate(g3_local, s.theta3), i3};
    m.bodies[rocker].inertia = GivenInertia{m4, O4 + rotate(g4_local, s.theta4), i4};
    m.drivers.push_back(angle_driver("crank", crank, theta0, theta0 + 2 * kPi, omega2, alpha2));
    m.sweep.steps = steps;
    m.gravity = gravity;
    m.point_loads.push_back(PointLoad{p, coupler, constant_law(force_p.x()), constant_law(force_p.y())});
    m.torques.push_back(BodyTorque{rocker, constant_law(torque4), std::nullopt});
    return m;
  }

  // Norton's 9x9 (Design of Machinery, section 11.5) with the closed-form kinematics:
  // unknowns F12x F12y F32x F32y F43x F43y F14x F14y T12 (F_ij: force of link i on link j).
  Eigen::VectorXd norton(double theta2) const {
    const FourBarState s = fb.solve(theta2, omega2, alpha2, true);
    const Eigen::Vector2d O2(0, 0), O4(fb.d, 0);
    const Eigen::Vector2d A = polar(fb.a, s.theta2), B = O4 + polar(fb.c, s.theta4);
    const Eigen::Vector2d G2 = rotate(g2_local, s.theta2), G3 = A + rotate(g3_local, s.theta3),
                          G4 = O4 + rotate(g4_local, s.theta4), P = A + rotate(p_local, s.theta3);
    const Eigen::Vector2d aA = rigid_acceleration({0, 0}, A, s.omega2, s.alpha2);
    const Eigen::Vector2d aG2 = rigid_acceleration({0, 0}, G2, s.omega2, s.alpha2);
    const Eigen::Vector2d aG3 = rigid_acceleration(aA, G3 - A, s.omega3, s.alpha3);
    const Eigen::Vector2d aG4 = rigid_acceleration({0, 0}, G4 - O4, s.omega4, s.alpha4);

    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(9, 9);
    Eigen::VectorXd rhs(9);
    // Link 2: F12 + F32 = m2 aG2 - m2 g; T12 + R12 x F12 + R32 x F32 = I2 alpha2.
    M(0, 0) = 1;
    M(0, 2) = 1;
    M(1, 1) = 1;
    M(1, 3) = 1;
    const Eigen::Vector2d R12 = O2 - G2, R32 = A - G2;
    M(2, 0) = -R12.y();
    M(2, 1) = R12.x();
    M(2, 2) = -R32.y();
    M(2, 3) = R32.x();
    M(2, 8) = 1;
    rhs.segment<2>(0) = m2 * (aG2 - gravity);
    rhs(2) = i2 * s.alpha2;
    // Link 3: F23 + F43 + Fp = m3 aG3 - m3 g, with F23 = -F32.
    M(3, 2) = -1;
    M(3, 4) = 1;
    M(4, 3) = -1;
    M(4, 5) = 1;
    const Eigen::Vector2d R23 = A - G3, R43 = B - G3;
    M(5, 2) = R23.y();
    M(5, 3) = -R23.x();
    M(5, 4) = -R43.y();
    M(5, 5) = R43.x();
    rhs.segment<2>(3) = m3 * (aG3 - gravity) - force_p;
    rhs(5) = i3 * s.alpha3 - cross(P - G3, force_p);
    // Link 4: F34 + F14 = m4 aG4 - m4 g, with F34 = -F43.
    M(6, 4) = -1;
    M(6, 6) = 1;
    M(7, 5) = -1;
    M(7, 7) = 1;
    const Eigen::Vector2d R34 = B - G4, R14 = O4 - G4;
    M(8, 4) = R34.y();
    M(8, 5) = -R34.x();
    M(8, 6) = -R14.y();
    M(8, 7) = R14.x();
    rhs.segment<2>(6) = m4 * (aG4 - gravity);
    rhs(8) = i4 * s.alpha4 - torque4;
    return M.fullPivLu().solve(rhs);
  }
};

TEST(InverseDynamics, FourBarMatchesNortonsNewtonEulerSystem) {
  const LoadedFourBar case_;
  const Mechanism mech(case_.model(73));
  const SweepResult sweep = run_sweep(mech, sweep_options(2));
  ASSERT_TRUE(sweep.complete) << sweep.stop_reason;
  const InverseDynamics dyn(std::make_shared<const Mechanism>(mech));
  const int o2 = 0, o4 = 1, a = 2, b = 3;
  const int crank = 0, coupler = 1, rocker = 2;
  double worst = 0.0;
  for (const Sample& s : sweep.samples) {
    const Eigen::VectorXd ref = case_.norton(s.driver_values[0]);
    const DynamicsResult r = dyn.solve(s);
    EXPECT_TRUE(r.unique);
    const double scale = ref.lpNorm<Eigen::Infinity>();
    auto check = [&](const Eigen::Vector2d& got, const Eigen::Vector2d& want) {
      const double err = (got - want).lpNorm<Eigen::Infinity>() / scale;
      worst = std::max(worst, err);
      EXPECT_LT(err, 1e-9) << "got " << got.transpose() << " want " << want.transpose() << " at step " << s.step;
    };
    check(r.pin_forces[find_link(dyn, o2, crank)], ref.segment<2>(0));    // F12
    check(r.pin_forces[find_link(dyn, a, coupler)], -ref.segment<2>(2));  // F23 = -F32
    check(r.pin_forces[find_link(dyn, a, crank)], ref.segment<2>(2));     // F32
    check(r.pin_forces[find_link(dyn, b, rocker)], -ref.segment<2>(4));   // F34 = -F43
    check(r.pin_forces[find_link(dyn, o4, rocker)], ref.segment<2>(6));   // F14
    EXPECT_NEAR(r.driver_effort[0], ref(8), 1e-9 * scale) << "step " << s.step;
  }
  std::printf("[ accuracy ] four-bar joint forces vs Norton's 9x9: max relative error %.1e\n", worst);
}

// Power balance: driver power + power of the applied loads = d(kinetic + potential)/dt.
void expect_power_balance(const Mechanism& mech, const SweepResult& sweep) {
  const Model& m = mech.model();
  const InverseDynamics dyn(std::make_shared<const Mechanism>(mech));
  double worst = 0.0;
  for (const Sample& s : sweep.samples) {
    const DynamicsResult r = dyn.solve(s);
    auto velocity = [&](int p) {
      const Motion2 mo = point_motion(mech, s, p);
      return Eigen::Vector2d(mo.x[1], mo.y[1]);
    };
    auto position = [&](int p) {
      const Motion2 mo = point_motion(mech, s, p);
      return Eigen::Vector2d(mo.x[0], mo.y[0]);
    };
    double d_energy = 0.0, scale = 0.0;
    for (std::size_t b = 0; b < m.bodies.size(); ++b) {
      const BodyMotion bm = body_motion(mech, s, static_cast<int>(b));
      const MassProperties& mp = dyn.masses()[b];
      const Eigen::Vector2d vg = bm.point(mp.cg, 1), ag = bm.point(mp.cg, 2);
      const double kinetic = mp.mass * vg.dot(ag) + mp.inertia * bm.omega * bm.alpha;
      const double gravity = -mp.mass * m.gravity.dot(vg);
      d_energy += kinetic + gravity;
      // Magnitudes, not the terms: a term that vanishes (a velocity normal to gravity) would
      // otherwise leave nothing to compare rounding errors with.
      scale += mp.mass * vg.norm() * (ag.norm() + m.gravity.norm()) + mp.inertia * std::abs(bm.omega * bm.alpha);
    }
    double load_power = 0.0;
    for (const PointLoad& l : m.point_loads) {
      const double p = Eigen::Vector2d(l.fx.value(s.time), l.fy.value(s.time)).dot(velocity(l.point));
      load_power += p;
      scale += std::abs(p);
    }
    for (const BodyTorque& t : m.torques) {
      const double p = t.torque.value(s.time) * body_angle_motion(mech, s, t.body)[1];
      load_power += p;
      scale += std::abs(p);
    }
    for (const Spring& sp : m.springs) {
      const Eigen::Vector2d d = position(sp.points[1]) - position(sp.points[0]);
      const double rate = d.normalized().dot(velocity(sp.points[1]) - velocity(sp.points[0]));
      const double elastic = sp.stiffness * (d.norm() - sp.free_length) * rate;
      const double damper = sp.damping * rate * rate;
      d_energy += elastic;
      load_power -= damper;
      scale += std::abs(elastic) + damper;
    }
    double driver_power = 0.0;
    for (std::size_t d = 0; d < m.drivers.size(); ++d) {
      const Driver& drv = m.drivers[d];
      double rate = 0.0;
      if (drv.kind == DriverKind::Angle) {
        rate = body_angle_motion(mech, s, drv.body)[1];
        if (drv.relative_to >= 0) rate -= body_angle_motion(mech, s, drv.relative_to)[1];
      } else if (drv.kind == DriverKind::Distance) {
        const Eigen::Vector2d d = position(drv.points[1]) - position(drv.points[0]);
        rate = d.normalized().dot(velocity(drv.points[1]) - velocity(drv.points[0]));
      } else {
        const Slider& sl = m.sliders[drv.slider];
        const Eigen::Vector2d w = (position(sl.along[1]) - position(sl.along[0])).normalized();
        rate = w.dot(velocity(sl.point) - velocity(sl.along[0]));
      }
      driver_power += r.driver_effort[d] * rate;
      scale += std::abs(r.driver_effort[d] * rate);
    }
    const double err = std::abs(driver_power + load_power - d_energy) / scale;
    worst = std::max(worst, err);
    EXPECT_LT(err, 1e-9) << "step " << s.step << ": driver " << driver_power << " loads " << load_power << " dE/dt "
                         << d_energy;
  }
  std::printf("[ accuracy ] %s: power balance max relative error %.1e\n", m.name.c_str(), worst);
}

TEST(InverseDynamics, PowerBalanceOfALoadedFourBarWithSpringAndDamper) {
  const LoadedFourBar case_;
  Model m = case_.model(91);
  m.name = "four-bar with spring";
  m.springs.push_back(Spring{"s", {4, 0}, 800.0, 0.05, 3.0, 0.0});  // P to O2
  m.point_loads[0].fx = Law::parse("30*sin(7*t)");
  const Mechanism mech(m);
  const SweepResult sweep = run_sweep(mech, sweep_options(2));
  ASSERT_TRUE(sweep.complete) << sweep.stop_reason;
  expect_power_balance(mech, sweep);
}

TEST(InverseDynamics, PowerBalanceWithATimeLawDriver) {
  const LoadedFourBar case_;
  Model m = case_.model(2);
  m.name = "four-bar on a time law";
  m.drivers[0].from.reset();
  m.drivers[0].to.reset();
  m.drivers[0].law = Law::parse("0.3 + 0.8*sin(3*t) + 2*t");
  m.sweep.duration = 1.5;
  m.sweep.time_step = 0.01;
  const Mechanism mech(m);
  const SweepResult sweep = run_sweep(mech, sweep_options(2));
  ASSERT_TRUE(sweep.complete) << sweep.stop_reason;
  expect_power_balance(mech, sweep);
}

// Offset slider-crank with a heavy piston, a gas force on it and gravity.
Model loaded_slider_crank() {
  Model m;
  m.name = "slider-crank with gas force";
  const double r = 0.04, l = 0.14, e = 0.01;
  const int o2 = add_point(m, "O2", {0, 0}, true);
  const int x = add_point(m, "X", {1, e}, true);
  const int x0 = add_point(m, "X0", {0, e}, true);
  const int a = add_point(m, "A", {0, r});
  const double cx = std::sqrt(l * l - (r - e) * (r - e));
  const int c = add_point(m, "C", {cx, e});
  const int crank = add_body(m, "crank", {o2, a});
  const int rod = add_body(m, "rod", {a, c});
  const int piston = add_body(m, "piston", {c});
  m.sliders.push_back(Slider{piston, c, {x0, x}});
  m.bodies[crank].inertia = GivenInertia{0.5, {0, 0.005}, 1e-4};
  m.bodies[rod].inertia = GivenInertia{0.3, {0.4 * cx, 0.4 * r + 0.6 * e}, 6e-4};
  m.bodies[piston].inertia = GivenInertia{0.45, {cx, e}, 2e-4};
  m.gravity = {0, -9.81};
  m.point_loads.push_back(PointLoad{c, piston, Law::parse("-200 - 150*cos(3*t)"), Law::parse("0")});
  m.drivers.push_back(angle_driver("crank", crank, kPi / 2, kPi / 2 + 2 * kPi, 150.0, 40.0));
  m.sweep.steps = 121;
  return m;
}

TEST(InverseDynamics, PowerBalanceOfASliderCrank) {
  const Mechanism mech(loaded_slider_crank());
  const SweepResult sweep = run_sweep(mech, sweep_options(2));
  ASSERT_TRUE(sweep.complete) << sweep.stop_reason;
  expect_power_balance(mech, sweep);
}

TEST(InverseDynamics, StaticMechanicalAdvantageOfAFourBar) {
  // Massless links, a torque on the rocker: virtual work gives T2 w2 + T4 w4 = 0, with
  // w4 / w2 from the closed form.
  LoadedFourBar case_;
  Model m = case_.model(37);
  for (Body& b : m.bodies) b.inertia.reset();
  m.point_loads.clear();
  m.gravity = {0, 0};
  const Mechanism mech(m);
  const SweepResult sweep = run_sweep(mech, sweep_options(2));
  ASSERT_TRUE(sweep.complete);
  const InverseDynamics dyn(std::make_shared<const Mechanism>(mech));
  for (const Sample& s : sweep.samples) {
    const FourBarState ref = case_.fb.solve(s.driver_values[0], 1.0, 0.0, true);
    const double expected = -case_.torque4 * ref.omega4 / ref.omega2;
    EXPECT_NEAR(dyn.solve(s).driver_effort[0], expected, 1e-9 * std::abs(case_.torque4)) << "step " << s.step;
  }
}

TEST(InverseDynamics, SliderNormalForceOfAStaticCentredSliderCrank) {
  // A force F pushing the piston towards the crank: the rod carries F / cos(phi), the guide
  // pushes back with F tan(phi), and the crank needs T = F v_piston / w (virtual work).
  Model m;
  const double r = 0.05, l = 0.2, F = 1000.0;
  const int o2 = add_point(m, "O2", {0, 0}, true), x = add_point(m, "X", {1, 0}, true);
  const double theta = 1.0;
  const Eigen::Vector2d A = polar(r, theta);
  const Eigen::Vector2d C(A.x() + std::sqrt(l * l - A.y() * A.y()), 0);
  const int a = add_point(m, "A", A), c = add_point(m, "C", C);
  const int crank = add_body(m, "crank", {o2, a});
  add_body(m, "rod", {a, c});
  const int piston = add_body(m, "piston", {c});
  m.sliders.push_back(Slider{piston, c, {o2, x}});
  m.point_loads.push_back(PointLoad{c, piston, Law::parse(std::to_string(-F)), Law::parse("0")});
  m.drivers.push_back(angle_driver("crank", crank, theta, theta, 1.0));
  m.sweep.steps = 2;
  const Mechanism mech(m);
  const SweepResult sweep = run_sweep(mech, sweep_options(2));
  const DynamicsResult res = InverseDynamics(std::make_shared<const Mechanism>(mech)).solve(sweep.samples[0]);
  const double phi = std::asin(A.y() / l);  // rod angle below the axis, seen from the piston
  EXPECT_NEAR(std::abs(res.slider_normal[0]), F * std::tan(phi), 1e-9 * F);
  const double piston_speed =
      -r * std::sin(theta) - r * r * std::sin(theta) * std::cos(theta) / std::sqrt(l * l - A.y() * A.y());
  EXPECT_NEAR(res.driver_effort[0], -(-F) * piston_speed, 1e-9 * F * r);
}

// A four-bar drawn at picometres and at ten thousand kilometres, with 1 kg at the crank's pivot:
// the ground carries its weight and the driver no torque, at every size. The moment rows hold
// lengths where the force rows hold ones, so at these sizes the plain LU's condition looked
// singular; the least squares dropped the moment rows and gave O2 7.355 N, O4 2.452 N and a
// torque of 25% of weight x size, with a warning of redundant constraints there are none of.
TEST(InverseDynamics, AWeightAtThePivotIsCarriedThereAtEverySize) {
  for (const double size : {1e-12, 1e-9, 1.0, 1e7, 1e10}) {
    SCOPED_TRACE(size);
    Model m;
    const int o2 = add_point(m, "O2", {0, 0}, true), o4 = add_point(m, "O4", {0.2 * size, 0}, true);
    const int a = add_point(m, "A", {0.08 * size, 0}), b = add_point(m, "B", {0.18125 * size, 0.148823511 * size});
    const int crank = add_body(m, "crank", {o2, a});
    add_body(m, "coupler", {a, b});
    add_body(m, "rocker", {o4, b});
    m.bodies[crank].inertia = GivenInertia{1.0, {0, 0}, 0.0};
    m.gravity = {0, -9.80665};
    m.drivers.push_back(angle_driver("crank", crank, 0.0, 2 * kPi, 4 * kPi));
    m.sweep.steps = 5;
    AnalysisOptions options;
    options.dynamics = true;
    const Analysis analysis = analyse(std::make_shared<const Mechanism>(m), options);
    ASSERT_TRUE(analysis.sweep.complete) << analysis.sweep.stop_reason;
    EXPECT_TRUE(analysis.dynamics->unique);
    EXPECT_TRUE(analysis.dynamics->warnings.empty());
    std::size_t on_crank = 0, on_rocker = 0;  // the ground's forces on them, at O2 and O4
    for (const JointForceColumn& c : joint_force_columns(*analysis.dynamics->solver)) {
      if (c.name == "O2.ground>crank") on_crank = c.joint_link;
      if (c.name == "O4.ground>rocker") on_rocker = c.joint_link;
    }
    ASSERT_NE(on_crank, on_rocker);
    for (const DynamicsResult& r : analysis.dynamics->samples) {
      EXPECT_LE(std::abs(r.driver_effort[0]), 1e-12 * 9.80665 * size);
      EXPECT_NEAR(r.pin_forces[on_crank].y(), 9.80665, 1e-9);
      EXPECT_NEAR(r.pin_forces[on_crank].x(), 0.0, 1e-9);
      EXPECT_NEAR(r.pin_forces[on_rocker].norm(), 0.0, 1e-9);
    }
  }
}

TEST(InverseDynamics, RedundantParallelogramGivesTheMinimumNormForcesAndSaysSo) {
  Model m;
  const int o1 = add_point(m, "O1", {0, 0}, true), o2 = add_point(m, "O2", {0.2, 0}, true),
            o3 = add_point(m, "O3", {0.1, 0.03}, true);
  const int a1 = add_point(m, "A1", {0, 0.05}), a2 = add_point(m, "A2", {0.2, 0.05}),
            a3 = add_point(m, "A3", {0.1, 0.08});
  const int c1 = add_body(m, "crank1", {o1, a1});
  add_body(m, "crank2", {o2, a2});
  add_body(m, "crank3", {o3, a3});
  const int coupler = add_body(m, "coupler", {a1, a2, a3});
  m.bodies[coupler].inertia = GivenInertia{2.0, {0.1, 0.06}, 0.01};
  m.gravity = {0, -9.81};
  m.drivers.push_back(angle_driver("crank1", c1, kPi / 2, kPi / 2 + 2 * kPi, 10.0));
  m.sweep.steps = 37;
  const Mechanism mech(m);
  AnalysisOptions options;
  options.dynamics = true;
  const Analysis analysis = analyse(std::make_shared<const Mechanism>(m), options);
  const SweepResult& sweep = analysis.sweep;
  ASSERT_TRUE(sweep.complete) << sweep.stop_reason;
  EXPECT_FALSE(analysis.dynamics->unique);
  ASSERT_EQ(analysis.dynamics->warnings.size(), 1u);
  EXPECT_EQ(analysis.dynamics->warnings[0].code, "forces_not_unique");
  EXPECT_NE(analysis.dynamics->warnings[0].message.find("not unique"), std::string::npos);
  EXPECT_LT(analysis.dynamics->max_residual, 1e-9);
  // The coupler translates on a circle of radius 0.05 at 10 rad/s: the driver torque is still
  // unique (power balance) even though the bar forces are not.
  expect_power_balance(mech, sweep);
}

}  // namespace
}  // namespace nbar::ktest

namespace nbar::ktest {
namespace {

TEST(InverseDynamics, OutlivesTheCallersMechanism) {
  auto mech = std::make_shared<const Mechanism>(
      io::load_model_file(std::string(NBAR_EXAMPLES_DIR) + "/fourbar-steel-bars.yaml").model);
  const SweepResult sweep = run_sweep(*mech, sweep_options(2, 7));
  const std::weak_ptr<const Mechanism> watch = mech;
  const InverseDynamics dynamics(mech);
  const DynamicsResult expected = dynamics.solve(sweep.samples[3]);
  mech.reset();  // the caller lets go: the solver keeps the mechanism alive
  EXPECT_FALSE(watch.expired());
  DynamicsWorkspace workspace;
  const DynamicsResult again = dynamics.solve(sweep.samples[3], workspace);
  EXPECT_EQ(again.driver_effort, expected.driver_effort);
  ASSERT_EQ(again.pin_forces.size(), expected.pin_forces.size());
  for (std::size_t i = 0; i < again.pin_forces.size(); ++i) EXPECT_EQ(again.pin_forces[i], expected.pin_forces[i]);
}

}  // namespace
}  // namespace nbar::ktest

namespace nbar::ktest {
namespace {

// A machine of 40 loaded four-bars in a chain: 120 bodies, 240 unknowns, solved by sparse LU.
// Its forces balance the power: what the driver gives is what the bodies' energy gains.
TEST(InverseDynamics, LargeMachinesUseSparseLUAndBalancePower) {
  Model m = nbar_bench::chain_model(40);
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const Eigen::Vector2d p = m.points[m.bodies[b].points[0]].position, q = m.points[m.bodies[b].points[1]].position;
    m.bodies[b].inertia = GivenInertia{0.2 + 0.01 * static_cast<double>(b % 7), 0.5 * (p + q), 1e-4};
  }
  m.gravity = {0, -9.81};
  m.sweep.steps = 7;
  const Mechanism mech(m);
  const InverseDynamics dyn(std::make_shared<const Mechanism>(mech));
  ASSERT_GT(dyn.unknown_count(), InverseDynamics::kDenseLimit);
  ASSERT_EQ(dyn.unknown_count(), dyn.equation_count());
  const SweepResult sweep = run_sweep(mech, sweep_options(2));
  ASSERT_TRUE(sweep.complete) << sweep.stop_reason;
  for (const Sample& s : sweep.samples) EXPECT_LT(dyn.solve(s).residual, 1e-9) << s.step;
  expect_power_balance(mech, sweep);
}

}  // namespace
}  // namespace nbar::ktest
