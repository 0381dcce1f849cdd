// The time derivatives (orders 1 to 5) of every coordinate and every body angle against
// Richardson-extrapolated central differences of positions solved at neighbouring times, for
// mechanisms covering every joint and driver kind. The differences use only position solutions, so they check the
// Taylor-series machinery (and the driver's speed/accel semantics) from the outside.
#include "helpers/kinematics_support.hpp"
#include "kinematics/constraints.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <map>

namespace nbar::ktest {
namespace {

struct FdCase {
  std::string label;
  Model model;
  double h = 0.05;  // step of the differences for orders 4 and 5 (h/2 below), s
  int steps = 9;    // samples of the sweep
  std::vector<int> samples{2, 4, 6};
  // Per order, relative to the largest derivative of that order: 10 to 25 times what the
  // differences themselves reach (worst measured: d1 4e-11, d2 1e-10, d3 1e-8, d4 5e-7, d5 1e-5).
  std::array<double, 6> tolerance{0, 1e-9, 1e-9, 1e-7, 1e-5, 1e-4};
};

using Stencil = std::vector<std::pair<int, double>>;  // offset in steps, weight

// Second-order central differences: the error is a series in h^2, which Richardson removes.
const std::array<Stencil, 6> kCentral = {
    Stencil{},
    Stencil{{1, 0.5}, {-1, -0.5}},
    Stencil{{1, 1}, {0, -2}, {-1, 1}},
    Stencil{{2, 0.5}, {1, -1}, {-1, 1}, {-2, -0.5}},
    Stencil{{2, 1}, {1, -4}, {0, 6}, {-1, -4}, {-2, 1}},
    Stencil{{3, 0.5}, {2, -2}, {1, 2.5}, {-1, -2.5}, {-2, 2}, {-3, -0.5}},
};

// Each driver's value (SI) at time offset tau from a sample, as the sweep defines the motion:
// a law at t + tau; in a time sweep other drivers move as from + speed t + accel t^2 / 2; in a
// from/to sweep every driver moves from its sampled value at its speed with its accel.
std::vector<double> driver_values(const Mechanism& mech, const Sample& s, double tau) {
  const Model& m = mech.model();
  std::vector<double> v;
  for (std::size_t d = 0; d < m.drivers.size(); ++d) {
    const Driver& drv = m.drivers[d];
    if (drv.law) {
      v.push_back(drv.law->value(s.time + tau));
    } else if (m.has_time_law()) {
      const double t = s.time + tau;
      v.push_back(drv.from.value_or(mech.drawn_driver_values()[d]) + drv.speed * t + 0.5 * drv.accel * t * t);
    } else {
      v.push_back(s.driver_values[d] + drv.speed * tau + 0.5 * drv.accel * tau * tau);
    }
  }
  return v;
}

void check_case(const FdCase& c) {
  SCOPED_TRACE(c.label);
  const Mechanism mech(c.model);
  const SweepResult r = run_sweep(mech, sweep_options(5, c.steps));
  ASSERT_TRUE(r.complete) << r.stop_reason;
  const double size = mech.characteristic_length();
  std::array<double, 6> worst{}, worst_angle{};

  for (int i : c.samples) {
    SCOPED_TRACE("sample " + std::to_string(i));
    const Sample& s = r.samples.at(i);
    // Positions on a grid of h/8 out to 3h (the widest stencil at the coarsest step), each solved
    // from its neighbour nearer the sample so that Newton stays on the sample's branch.
    const double g = c.h / 8;
    std::map<int, Eigen::VectorXd> f;
    double residual = 0;
    f[0] = solve_near(mech, s.taylor.col(0), driver_values(mech, s, 0.0), &residual);
    ASSERT_LE((f[0] - s.taylor.col(0)).lpNorm<Eigen::Infinity>(), 1e-11 * size) << "the sweep's own position";
    for (int dir : {1, -1}) {
      for (int j = 1; j <= 24; ++j) {
        f[dir * j] = solve_near(mech, f[dir * (j - 1)], driver_values(mech, s, dir * j * g), &residual);
        ASSERT_LE(residual, 1e-14 * size) << "offset " << dir * j;
      }
    }
    // The angle of every body with two points, unwrapped around the sample's: differentiated
    // like the coordinates, it checks body_angle_motion's series of atan2.
    std::vector<int> angled;
    for (std::size_t b = 0; b < c.model.bodies.size(); ++b)
      if (c.model.bodies[b].points.size() >= 2) angled.push_back(static_cast<int>(b));
    auto angles = [&](const Eigen::VectorXd& q) {
      Eigen::VectorXd a(angled.size());
      for (std::size_t i = 0; i < angled.size(); ++i) {
        const auto& pts = c.model.bodies[angled[i]].points;
        const Eigen::Vector2d u = mech.point_position(pts[1], q) - mech.point_position(pts[0], q);
        a[i] = std::atan2(u.y(), u.x());
      }
      return a;
    };
    std::map<int, Eigen::VectorXd> theta;
    const Eigen::VectorXd theta0 = angles(f[0]);
    for (const auto& [j, q] : f) {
      theta[j] = angles(q);
      for (Eigen::Index i = 0; i < theta0.size(); ++i)
        theta[j][i] = theta0[i] + angle_difference(theta[j][i], theta0[i]);
    }

    auto central = [&](std::map<int, Eigen::VectorXd>& values, int k, int spacing) {
      Eigen::VectorXd d = Eigen::VectorXd::Zero(values[0].size());
      for (const auto& [offset, weight] : kCentral[k]) d += weight * values[offset * spacing];
      return Eigen::VectorXd(d / std::pow(spacing * g, k));
    };
    // Truncation falls like h^6 after two extrapolations, rounding grows like h^-k: the low
    // orders are most accurate at h/2 (spacings 1, 2, 4 grid steps), the high ones at h.
    auto richardson = [&](std::map<int, Eigen::VectorXd>& values, int k) {
      const int unit = k <= 3 ? 1 : 2;
      const Eigen::VectorXd r1_fine = (4 * central(values, k, unit) - central(values, k, 2 * unit)) / 3;
      const Eigen::VectorXd r1_coarse = (4 * central(values, k, 2 * unit) - central(values, k, 4 * unit)) / 3;
      return Eigen::VectorXd((16 * r1_fine - r1_coarse) / 15);
    };
    // Where a derivative happens to vanish (a constant-speed arm, a symmetric pose), its error is
    // judged against the size of a nonzero one: size * rate^k, with the bodies' fastest rate.
    double rate = 0;
    for (int b : angled) rate = std::max(rate, std::abs(body_angle_motion(mech, s, b)[1]));
    double factorial = 1;
    for (int k = 1; k <= 5; ++k) {
      factorial *= k;
      const Eigen::VectorXd fd = richardson(f, k);
      const Eigen::VectorXd exact = factorial * s.taylor.col(k);
      const double scale = std::max(exact.lpNorm<Eigen::Infinity>(), 0.1 * size * std::pow(rate, k));
      const double err = (fd - exact).lpNorm<Eigen::Infinity>() / scale;
      EXPECT_LE(err, c.tolerance[k]) << "derivative " << k << "\nexact " << exact.transpose() << "\nfd    "
                                     << fd.transpose();
      worst[k] = std::max(worst[k], err);

      const Eigen::VectorXd fd_angle = richardson(theta, k);
      Eigen::VectorXd exact_angle(angled.size());
      for (std::size_t b = 0; b < angled.size(); ++b) exact_angle[b] = body_angle_motion(mech, s, angled[b])[k];
      const double angle_scale = std::max(exact_angle.lpNorm<Eigen::Infinity>(), std::pow(rate, k));
      const double angle_err = (fd_angle - exact_angle).lpNorm<Eigen::Infinity>() / angle_scale;
      EXPECT_LE(angle_err, c.tolerance[k])
          << "angle derivative " << k << "\nexact " << exact_angle.transpose() << "\nfd    " << fd_angle.transpose();
      worst_angle[k] = std::max(worst_angle[k], angle_err);
    }
  }
  std::printf(
      "[ accuracy ] %-40s FD relative error, points d1-d5: %.0e %.0e %.0e %.0e %.0e; angles %.0e %.0e %.0e %.0e %.0e\n",
      c.label.c_str(), worst[1], worst[2], worst[3], worst[4], worst[5], worst_angle[1], worst_angle[2], worst_angle[3],
      worst_angle[4], worst_angle[5]);
}

// ---------------------------------------------------------------------------------------------
// The mechanisms, in metres.

Model four_bar_with_coupler_point() {
  Model m;
  const int o2 = add_point(m, "O2", {0, 0}, true);
  const int o4 = add_point(m, "O4", {0.2, 0}, true);
  const int a = add_point(m, "A", {0.04, 0.07});
  const int b = add_point(m, "B", {0.21, 0.14});
  const int p = add_point(m, "P", {0.14, 0.19});
  const int crank = add_body(m, "crank", {o2, a});
  add_body(m, "coupler", {a, b, p});
  add_body(m, "rocker", {o4, b});
  // Accelerating: positions at evenly spaced angles, derivatives of theta + w t + alpha t^2/2.
  m.drivers.push_back(angle_driver("crank", crank, 0.0, 2 * kPi, 1.3, 0.7));
  return m;
}

Model offset_slider_crank() {
  Model m;
  const int o2 = add_point(m, "O2", {0, 0}, true);
  const int y1 = add_point(m, "Y1", {-0.1, 0.025}, true);
  const int y2 = add_point(m, "Y2", {0.4, 0.025}, true);
  const int a = add_point(m, "A", {0.05, 0});
  const int c = add_point(m, "C", {0.228255435, 0.025});
  const int crank = add_body(m, "crank", {o2, a});
  add_body(m, "rod", {a, c});
  const int slider = add_body(m, "slider", {c});
  m.sliders.push_back(Slider{slider, c, {y1, y2}});
  m.drivers.push_back(angle_driver("crank", crank, 2 * kPi, 0.0, -2.0));
  return m;
}

// Piston-driven: a Slide driver, kept away from the dead centres where the crank would toggle.
Model piston_driven_slider_crank() {
  Model m = offset_slider_crank();
  m.drivers.clear();
  Driver d;
  d.name = "piston";
  d.kind = DriverKind::Slide;
  d.slider = 0;
  d.from = 0.32;  // from Y1, along the guide: x = 0.22
  d.to = 0.25;    // x = 0.15
  d.speed = -0.05;
  d.accel = 0.02;
  m.drivers.push_back(d);
  return m;
}

Model watt_six_bar() {
  Model m;
  const int o2 = add_point(m, "O2", {0, 0}, true);
  const int o4 = add_point(m, "O4", {0.2, 0}, true);
  const int a = add_point(m, "A", {0.08, 0});
  const int b = add_point(m, "B", {0.18125, 0.148823511});
  const int c = add_point(m, "C", {0.031070272, 0.105857837});
  const int d = add_point(m, "D", {0.13531373, 0.193431348});
  const int e = add_point(m, "E", {0.120625808, 0.114791251});
  const int crank = add_body(m, "crank", {o2, a});
  add_body(m, "coupler", {a, b, c});
  add_body(m, "rocker", {o4, b, d});
  add_body(m, "link5", {c, e});
  add_body(m, "link6", {e, d});
  m.drivers.push_back(angle_driver("crank", crank, 0.0, 2 * kPi, 1.0));
  return m;
}

struct FiveBar {
  Model m;
  int left = -1, right = -1, distal_left = -1;
};

FiveBar five_bar() {
  FiveBar f;
  Model& m = f.m;
  const int o1 = add_point(m, "O1", {0, 0}, true);
  const int o5 = add_point(m, "O5", {0.1, 0}, true);
  const int a = add_point(m, "A", {0.06, 0});
  const int b = add_point(m, "B", {0.13, 0.051961524});
  const int p = add_point(m, "P", {0.028360751, 0.115753868});
  f.left = add_body(m, "left", {o1, a});
  f.right = add_body(m, "right", {o5, b});
  f.distal_left = add_body(m, "distal_left", {a, p});
  add_body(m, "distal_right", {b, p});
  return f;
}

Model five_bar_two_drivers() {
  FiveBar f = five_bar();
  // Different speeds over equal ranges: the sweep is not one motion in time.
  f.m.drivers.push_back(angle_driver("theta_left", f.left, 0.0, kPi, 1.0));
  f.m.drivers.push_back(angle_driver("theta_right", f.right, kPi / 3, 4 * kPi / 3, 0.6, -0.3));
  return f.m;
}

// Equal speeds over equal ranges: the sweep is one motion in time, and the same series serves
// the predictor and the derivatives.
Model five_bar_proportional_drivers() {
  FiveBar f = five_bar();
  f.m.drivers.push_back(angle_driver("theta_left", f.left, 0.0, kPi, 1.5));
  f.m.drivers.push_back(angle_driver("theta_right", f.right, kPi / 3, 4 * kPi / 3, 1.5));
  return f.m;
}

// A time sweep where one driver follows a law and the other moves as from + speed t + accel t^2/2.
Model five_bar_law_and_speed_drivers() {
  FiveBar f = five_bar();
  Driver left = angle_driver("theta_left", f.left);
  left.law = Law::parse("0.3*sin(2*t) + 0.5*t");
  f.m.drivers.push_back(left);
  f.m.drivers.push_back(angle_driver("theta_right", f.right, kPi / 3, std::nullopt, 0.5, 0.1));
  f.m.sweep.duration = 2.0;
  return f.m;
}

Model five_bar_relative_driver() {
  FiveBar f = five_bar();
  // The left crank turns back while the distal link opens relative to it (drawn at about
  // 105 deg): P stays between 60 and 180 mm from O5, so the right dyad never straightens.
  f.m.drivers.push_back(angle_driver("theta_left", f.left, 0.0, -0.6, -1.0));
  Driver rel = angle_driver("elbow", f.distal_left, std::nullopt, 2.2, 0.7, 0.4);
  rel.relative_to = f.left;
  f.m.drivers.push_back(rel);
  return f.m;
}

Model two_link_arm() {
  Model m;
  const int o = add_point(m, "O", {0, 0}, true);
  const int e = add_point(m, "E", {0.259807621, 0.15});
  const int h = add_point(m, "H", {0.420504524, 0.341511111});
  const int upper = add_body(m, "upper", {o, e});
  const int fore = add_body(m, "fore", {e, h});
  m.drivers.push_back(angle_driver("shoulder", upper, kPi / 6, kPi / 2, kPi / 6));
  Driver elbow = angle_driver("elbow", fore, kPi / 9, 5 * kPi / 9, 2 * kPi / 9);
  elbow.relative_to = upper;
  m.drivers.push_back(elbow);
  return m;
}

// Inverted slider-crank (crank shaper): the crank pin's block slides on the swinging arm, a
// guide that itself moves; the ram slides on the ground.
Model crank_shaper() {
  Model m;
  const int o4 = add_point(m, "O4", {0, 0}, true);
  const int o2 = add_point(m, "O2", {0, 0.25}, true);
  const int g1 = add_point(m, "G1", {-0.6, 0.49}, true);
  const int g2 = add_point(m, "G2", {0.6, 0.49}, true);
  const int a = add_point(m, "A", {0.1, 0.25});
  const int t = add_point(m, "T", {0.185695338, 0.464238345});
  const int r = add_point(m, "R", {0.333466571, 0.49});
  const int crank = add_body(m, "crank", {o2, a});
  const int block = add_body(m, "block", {a});
  add_body(m, "arm", {o4, t});
  add_body(m, "link", {t, r});
  const int ram = add_body(m, "ram", {r});
  m.sliders.push_back(Slider{block, a, {o4, t}});
  m.sliders.push_back(Slider{ram, r, {g1, g2}});
  m.drivers.push_back(angle_driver("crank", crank, 0.0, 2 * kPi, kPi));
  return m;
}

// Dump-truck tipper: a distance driver (the cylinder length), whose rod slides in a barrel
// that swings about its own pivot.
Model tipper() {
  Model m;
  const int h = add_point(m, "H", {4.0, 1.15}, true);
  const int c0 = add_point(m, "C0", {1.5, 0.8}, true);
  const int f = add_point(m, "F", {-0.2, 1.15});
  const int t = add_point(m, "T", {-0.2, 2.3});
  const int e = add_point(m, "E", {2.329156198, 1.15});
  const int d = add_point(m, "D", {2.144899265, 1.072222222});
  const int g = add_point(m, "G", {1.776385399, 0.916666667});
  add_body(m, "bed", {h, f, t, e});
  add_body(m, "barrel", {c0, d});
  const int rod = add_body(m, "rod", {e, g});
  m.sliders.push_back(Slider{rod, e, {c0, d}});
  Driver cyl;
  cyl.name = "cylinder";
  cyl.kind = DriverKind::Distance;
  cyl.points = {c0, e};
  cyl.from = 0.9;
  cyl.to = 2.1;
  cyl.speed = 0.05;
  cyl.accel = 0.01;
  m.drivers.push_back(cyl);
  return m;
}

// A pin in a slot: the crank pin runs along the slotted lever.
Model slotted_lever() {
  Model m;
  const int o = add_point(m, "O", {0, 0}, true);
  const int a = add_point(m, "A", {0.04, 0});
  const int q = add_point(m, "Q", {0, -0.12}, true);
  const int e = add_point(m, "E", {0.09, 0.15});
  const int crank = add_body(m, "crank", {o, a});
  add_body(m, "lever", {q, e});
  m.slots.push_back(Slot{a, {q, e}});
  m.drivers.push_back(angle_driver("crank", crank, 0.0, 2 * kPi, 1.0));
  return m;
}

// A crank following a law in time (radians): 0.5 sin(3t) + 0.2 t^2.
Model four_bar_time_law() {
  Model m = four_bar_with_coupler_point();
  m.drivers[0].from.reset();
  m.drivers[0].to.reset();
  m.drivers[0].law = Law::parse("0.5*sin(3*t)+0.2*t^2");
  m.sweep.duration = 2.0;
  return m;
}

TEST(FiniteDifferences, FourBarWithCouplerPointAccelerating) {
  check_case({"four-bar + coupler point, accel", four_bar_with_coupler_point(), 0.05});
}
TEST(FiniteDifferences, OffsetSliderCrank) { check_case({"offset slider-crank", offset_slider_crank(), 0.025}); }
TEST(FiniteDifferences, PistonDrivenSliderCrank) {
  check_case({"slider-crank, slide driver", piston_driven_slider_crank(), 0.05});
}
TEST(FiniteDifferences, WattSixBar) { check_case({"Watt six-bar", watt_six_bar(), 0.05}); }
TEST(FiniteDifferences, FiveBarTwoDrivers) { check_case({"five-bar, two drivers", five_bar_two_drivers(), 0.05}); }
TEST(FiniteDifferences, FiveBarProportionalDrivers) {
  check_case({"five-bar, proportional drivers", five_bar_proportional_drivers(), 0.035});
}
TEST(FiniteDifferences, FiveBarLawAndSpeedDriversInATimeSweep) {
  check_case({"five-bar, law + speed/accel drivers", five_bar_law_and_speed_drivers(), 0.05});
}
TEST(FiniteDifferences, FiveBarRelativeAngleDriver) {
  check_case({"five-bar, relative-angle driver", five_bar_relative_driver(), 0.05});
}
TEST(FiniteDifferences, TwoLinkArmRelativeAngleDriver) {
  check_case({"two-link arm, relative elbow", two_link_arm(), 0.1});
}
TEST(FiniteDifferences, InvertedSliderCrankOnMovingGuide) { check_case({"crank shaper", crank_shaper(), 0.015}); }
TEST(FiniteDifferences, DistanceDriverWithSliderBetweenMovingBodies) {
  check_case({"tipper, distance driver", tipper(), 0.5});
}
TEST(FiniteDifferences, PinInSlot) { check_case({"slotted lever", slotted_lever(), 0.05}); }
TEST(FiniteDifferences, TimeLawDriver) {
  check_case({"four-bar, law 0.5 sin 3t + 0.2 t^2", four_bar_time_law(), 0.02});
}

// The corrections take a point's Jacobian from the pass that evaluates its residuals: the same
// numbers, bit for bit, as the two evaluations apart, for every kind of row these models hold (at
// poses off the constraints, where no row is zero).
TEST(ResidualsAndJacobian, OnePassGivesWhatTheTwoEvaluationsGive) {
  const std::vector<std::pair<std::string, Model>> models = {
      {"four-bar + coupler point", four_bar_with_coupler_point()},
      {"offset slider-crank", offset_slider_crank()},
      {"slider-crank, slide driver", piston_driven_slider_crank()},
      {"Watt six-bar", watt_six_bar()},
      {"five-bar, relative-angle driver", five_bar_relative_driver()},
      {"two-link arm", two_link_arm()},
      {"crank shaper", crank_shaper()},
      {"tipper", tipper()},
      {"slotted lever", slotted_lever()}};
  for (const auto& [label, model] : models) {
    SCOPED_TRACE(label);
    const Mechanism mech(model);
    State state(mech);
    std::vector<Series> values;
    for (double v : mech.drawn_driver_values()) values.emplace_back(1, v + 0.1);
    set_drivers(mech, state, values);
    for (Eigen::Index i = 0; i < state.q.size(); ++i) state.q[i] += 1e-3 * std::sin(3.0 + 5.0 * static_cast<double>(i));
    Eigen::VectorXd phi_apart, phi_together;
    std::vector<double> jacobian_apart, jacobian_together;
    const double largest_apart = evaluate_residuals(mech, state.q, state.drivers, phi_apart);
    evaluate_jacobian(mech, state.q, state.drivers, jacobian_apart);
    const double largest_together =
        evaluate_residuals_and_jacobian(mech, state.q, state.drivers, phi_together, jacobian_together);
    EXPECT_GT(largest_apart, 0.0);
    EXPECT_EQ(largest_together, largest_apart);
    ASSERT_EQ(phi_together.size(), phi_apart.size());
    for (Eigen::Index r = 0; r < phi_apart.size(); ++r) EXPECT_EQ(phi_together[r], phi_apart[r]) << "row " << r;
    ASSERT_EQ(jacobian_together.size(), jacobian_apart.size());
    for (std::size_t e = 0; e < jacobian_apart.size(); ++e)
      EXPECT_EQ(jacobian_together[e], jacobian_apart[e]) << "entry " << e;
  }
}

// A body's length and a crank's angle are evaluated in loops compiled for which of the row's two
// points are fixed (RowGroup::fixed). Checked here against the rows' formulas written out, with
// the fixed point first and second: residuals, Jacobian entries (none for a fixed point) and the
// second series remainder.
TEST(ResidualsAndJacobian, RowsWithTheFixedPointFirstOrSecond) {
  const auto four_bar = [](bool fixed_second) {
    Model m;
    const int o2 = add_point(m, "O2", {0, 0}, true);
    const int o4 = add_point(m, "O4", {0.2, 0}, true);
    const int a = add_point(m, "A", {0.04, 0.07});
    const int b = add_point(m, "B", {0.21, 0.14});
    const int crank = fixed_second ? add_body(m, "crank", {a, o2}) : add_body(m, "crank", {o2, a});
    add_body(m, "coupler", fixed_second ? std::vector<int>{b, a} : std::vector<int>{a, b});
    add_body(m, "rocker", fixed_second ? std::vector<int>{b, o4} : std::vector<int>{o4, b});
    m.drivers.push_back(angle_driver("crank", crank));
    return m;
  };
  for (const bool fixed_second : {false, true}) {
    SCOPED_TRACE(fixed_second ? "fixed points second" : "fixed points first");
    const Mechanism mech(four_bar(fixed_second));
    State state(mech);
    Series theta(3, mech.drawn_driver_values()[0] + 0.1);
    theta[1] = 1.7;
    theta[2] = -0.4;
    set_drivers(mech, state, {theta});
    for (Eigen::Index i = 0; i < state.q.size(); ++i) state.q[i] += 1e-3 * std::sin(3.0 + 5.0 * static_cast<double>(i));
    // The second coefficient's remainder reads the first coefficients (column 1) and the positions.
    Eigen::MatrixXd coefficients(state.q.size(), 3);
    coefficients.col(0) = state.q;
    for (Eigen::Index i = 0; i < state.q.size(); ++i) coefficients(i, 1) = std::cos(1.0 + 2.0 * static_cast<double>(i));
    coefficients.col(2).setZero();
    Eigen::VectorXd phi, rhs;
    std::vector<double> jacobian;
    evaluate_residuals_and_jacobian(mech, state.q, state.drivers, phi, jacobian);
    evaluate_series_remainder(mech, coefficients, 2, state.drivers, rhs);
    const DriverState& d = state.drivers[0];
    int rows_checked = 0;
    for (int r = 0; r < mech.row_count(); ++r) {
      const Constraint& c = mech.equations().rows[static_cast<std::size_t>(r)];
      SCOPED_TRACE(c.label);
      const Eigen::Vector2d u = mech.point_position(c.p[1], state.q) - mech.point_position(c.p[0], state.q);
      const auto rate = [&](int point) {
        const int col = mech.column_of(point);
        return col < 0 ? Eigen::Vector2d(0.0, 0.0) : Eigen::Vector2d(coefficients(col, 1), coefficients(col + 1, 1));
      };
      const Eigen::Vector2d u1 = rate(c.p[1]) - rate(c.p[0]);
      Eigen::Vector2d gradient;  // at the second point; minus it at the first
      if (c.type == ConstraintType::Distance) {
        EXPECT_DOUBLE_EQ(phi[r], (u.squaredNorm() - c.a * c.a) * c.scale);
        EXPECT_DOUBLE_EQ(rhs[r], u1.squaredNorm() * c.scale);
        gradient = 2.0 * c.scale * u;
      } else if (c.type == ConstraintType::DriveAngle) {
        EXPECT_DOUBLE_EQ(phi[r], (u.x() * d.sin[0] - u.y() * d.cos[0]) * c.scale);
        EXPECT_NEAR(rhs[r], (u.x() * d.sin[2] - u.y() * d.cos[2] + u1.x() * d.sin[1] - u1.y() * d.cos[1]) * c.scale,
                    1e-15);
        gradient = c.scale * Eigen::Vector2d(d.sin[0], -d.cos[0]);
      } else {
        ADD_FAILURE() << "a four-bar has lengths and a crank angle only";
        continue;
      }
      for (int slot = 0; slot < 2; ++slot) {
        const int e = mech.equations().entry_index(r, slot);
        const bool fixed = mech.model().points[static_cast<std::size_t>(c.p[slot])].ground;
        ASSERT_EQ(e < 0, fixed) << "slot " << slot;
        if (fixed) continue;
        const double sign = slot == 0 ? -1.0 : 1.0;
        EXPECT_DOUBLE_EQ(jacobian[static_cast<std::size_t>(e)], sign * gradient.x()) << "slot " << slot;
        EXPECT_DOUBLE_EQ(jacobian[static_cast<std::size_t>(e) + 1], sign * gradient.y()) << "slot " << slot;
      }
      ++rows_checked;
    }
    EXPECT_EQ(rows_checked, 4);
    // The loops ran for both orders: the groups know the fixed points where they are.
    bool first_fixed = false, second_fixed = false;
    for (const RowGroup& g : mech.equations().groups) {
      first_fixed |= g.fixed == 1;
      second_fixed |= g.fixed == 2;
    }
    EXPECT_EQ(first_fixed, !fixed_second);
    EXPECT_EQ(second_fixed, fixed_second);
  }
}

}  // namespace
}  // namespace nbar::ktest
