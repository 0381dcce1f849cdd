// Slider-crank sweeps against the piston's closed form x(theta) = r cos(theta) +
// sqrt(L^2 - (r sin(theta) - e)^2), differentiated in time through theta(t) with the test's own
// Taylor arithmetic (Jet), up to the fifth derivative; and the Myszka compressor's numbers.
#include "helpers/kinematics_support.hpp"
#include "nbar/kinematics/table.hpp"

#include <gtest/gtest.h>

#include <cstdio>

namespace nbar::ktest {
namespace {

constexpr int kTerms = 6;  // position and five derivatives
using J = Jet<kTerms>;

struct SliderCrank {
  double r = 0, L = 0, e = 0;  // crank, rod, offset of the line of stroke from the crank pivot

  // x along the line of stroke as a function of time, for a crank moving as theta.
  J piston(const J& theta) const {
    J s, c;
    sincos(theta, s, c);
    const J h = r * s + (-e);
    return r * c + sqrt(J::constant(L * L) - h * h);
  }
};

struct Case {
  std::string label;
  SliderCrank g;
  DrawingFrame frame;
  double drawn = 0.3;
  double from = 0, to = 2 * kPi, omega = 1, alpha = 0;
  int steps = 73;
};

struct Built {
  Model model;
  int a = -1, c = -1;
};

Built build(const Case& k) {
  const SliderCrank& g = k.g;
  Built b;
  Model& m = b.model;
  const int o2 = add_point(m, "O2", k.frame.to_world({0, 0}), true);
  const int g1 = add_point(m, "G1", k.frame.to_world({-2 * g.L, g.e}), true);
  const int g2 = add_point(m, "G2", k.frame.to_world({2 * g.L, g.e}), true);
  const double x0 = g.piston(J::constant(k.drawn)).c[0];
  b.a = add_point(m, "A", k.frame.to_world(polar(g.r, k.drawn)));
  b.c = add_point(m, "C", k.frame.to_world({x0, g.e}));
  const int crank = add_body(m, "crank", {o2, b.a}, g.r);
  add_body(m, "rod", {b.a, b.c}, g.L);
  const int piston = add_body(m, "piston", {b.c});
  m.sliders.push_back(Slider{piston, b.c, {g1, g2}});
  m.drivers.push_back(angle_driver("crank", crank, k.frame.angle_to_world(k.from), k.frame.angle_to_world(k.to),
                                   k.frame.rate_to_world(k.omega), k.frame.rate_to_world(k.alpha)));
  m.sweep.steps = k.steps;
  return b;
}

// Worst error over a test, per derivative order, relative to that order's scale.
struct Errors {
  std::array<double, kTerms> e{};
  void print(const char* what) const {
    std::printf("[ accuracy ] %s: max relative error x %.1e, v %.1e, a %.1e, jerk %.1e, d4 %.1e, d5 %.1e\n", what, e[0],
                e[1], e[2], e[3], e[4], e[5]);
  }
};

void check_case(const Case& k, Errors& worst) {
  SCOPED_TRACE(k.label);
  const Built b = build(k);
  const Mechanism mech(b.model);
  const SweepResult r = run_sweep(mech, sweep_options(5));
  ASSERT_TRUE(r.complete) << r.stop_reason;
  ASSERT_EQ(static_cast<int>(r.samples.size()), k.steps);
  EXPECT_TRUE(r.warnings.empty());

  const Eigen::Vector2d ex = k.frame.to_world({1, 0}) - k.frame.to_world({0, 0});
  const Eigen::Vector2d ey = k.frame.to_world({0, 1}) - k.frame.to_world({0, 0});
  const double rate = std::sqrt(k.omega * k.omega + std::abs(k.alpha));
  // Jerk and beyond at 1e-9 too: the solver's Taylor coefficients are exact up to rounding.
  const std::array<double, kTerms> tolerance{1e-9, 1e-9, 1e-9, 1e-9, 1e-9, 1e-9};
  for (const Sample& s : r.samples) {
    SCOPED_TRACE("step " + std::to_string(s.step));
    const double theta = k.frame.angle_to_local(s.driver_values[0]);
    ASSERT_NEAR(theta, k.from + (k.to - k.from) * s.step / (k.steps - 1), 1e-12 * (1 + std::abs(k.to)));
    // The t column: when the crank reaches this angle at its speed.
    EXPECT_NEAR(s.time, (theta - k.from) / k.omega, 1e-12 * std::abs((k.to - k.from) / k.omega));
    const J x = k.g.piston(J::motion(theta, k.omega, k.alpha));
    const Motion2 c = point_motion(mech, s, b.c);
    for (int d = 0; d < kTerms; ++d) {
      const Eigen::Vector2d got(c.x[d], c.y[d]);
      const double along = (d == 0 ? got - k.frame.to_world({0, 0}) : got).dot(ex);
      const double across = (d == 0 ? got - k.frame.to_world({0, 0}) : got).dot(ey);
      const double scale = std::max(std::abs(x.derivative(d)), k.g.r * std::pow(rate, d));
      const double err = std::abs(along - x.derivative(d)) / scale;
      EXPECT_LE(err, tolerance[d]) << "derivative " << d << ": " << along << " vs " << x.derivative(d);
      // The piston stays on its line of stroke, so every derivative across it vanishes.
      EXPECT_LE(std::abs(across - (d == 0 ? k.g.e : 0.0)), tolerance[d] * scale) << "derivative " << d;
      worst.e[d] = std::max(worst.e[d], err);
    }
  }
}

TEST(SliderCrank, CentredConstantSpeed) {
  Errors worst;
  Case k;
  k.label = "centred, constant speed";
  k.g = {0.05, 0.18, 0.0};
  k.omega = 100;
  k.steps = 181;
  check_case(k, worst);
  worst.print("centred slider-crank");
}

TEST(SliderCrank, CentredWithAngularAcceleration) {
  Errors worst;
  Case k;
  k.label = "centred, accelerating";
  k.g = {0.05, 0.18, 0.0};
  k.omega = 40;
  k.alpha = 900;
  check_case(k, worst);
  worst.print("centred slider-crank, accelerating");
}

TEST(SliderCrank, OffsetBothSidesRotatedAndMirrored) {
  Errors worst;
  for (const double e : {0.025, -0.04}) {
    for (const DrawingFrame& frame :
         {DrawingFrame{}, DrawingFrame{{0.1, 0.2}, 2.0, 1}, DrawingFrame{{0, 0}, -0.4, -1}}) {
      for (const double alpha : {0.0, -250.0}) {
        Case k;
        k.g = {0.05, 0.18, e};
        k.frame = frame;
        k.omega = -30;  // turning backwards, from 2 pi down to 0
        k.from = 2 * kPi + 0.1;
        k.to = 0.1;
        k.alpha = alpha;
        k.drawn = 2.5;
        k.label = "offset " + std::to_string(e) + ", rotation " + std::to_string(frame.rotation) +
                  (frame.mirror < 0 ? " mirrored" : "") + ", alpha " + std::to_string(alpha);
        check_case(k, worst);
      }
    }
  }
  worst.print("offset slider-cranks");
}

// Myszka, Machines and Mechanisms: compressor with crank 0.75 in, rod 2.00 in, 1750 rpm. At top
// dead centre (theta = 0) the piston's acceleration is exactly -r w^2 (1 + r/L), and at bottom
// dead centre +r w^2 (1 - r/L); the crank pin moves at r w. Read from the table, in inches.
TEST(SliderCrank, MyszkaCompressorInInches) {
  const double inch = 0.0254;
  Case k;
  k.label = "Myszka compressor";
  k.g = {0.75 * inch, 2.00 * inch, 0.0};
  k.omega = 1750 * 2 * kPi / 60;
  k.from = 0;
  k.to = 2 * kPi;
  k.steps = 361;
  k.drawn = 0;
  Built b = build(k);
  b.model.units = *Units::make("in", "deg");
  const Mechanism mech(b.model);
  const SweepResult r = run_sweep(mech, sweep_options(3));
  ASSERT_TRUE(r.complete) << r.stop_reason;
  const ResultTable t = make_table(mech, r);
  auto column = [&](const std::string& name) {
    const auto it = std::find(t.columns.begin(), t.columns.end(), name);
    EXPECT_NE(it, t.columns.end()) << name;
    return static_cast<std::size_t>(it - t.columns.begin());
  };
  const std::size_t cx = column("C.x"), cax = column("C.ax"), cvx = column("C.vx"), avx = column("A.vx"),
                    avy = column("A.vy"), crank = column("crank");
  EXPECT_EQ(t.units[cax], "in/s^2");
  const double w = k.omega, rr = 0.75, L = 2.0;
  ASSERT_EQ(t.rows.size(), 361u);
  const auto& tdc = t.rows[0];
  const auto& bdc = t.rows[180];
  EXPECT_NEAR(tdc[crank], 0.0, 1e-12);
  EXPECT_NEAR(bdc[crank], 180.0, 1e-9);
  EXPECT_NEAR(tdc[cx], rr + L, 1e-12);
  EXPECT_NEAR(bdc[cx], L - rr, 1e-12);
  const double a_tdc = -rr * w * w * (1 + rr / L);  // -34633.6 in/s^2
  const double a_bdc = rr * w * w * (1 - rr / L);
  EXPECT_NEAR(tdc[cax], a_tdc, 1e-9 * std::abs(a_tdc));
  EXPECT_NEAR(bdc[cax], a_bdc, 1e-9 * std::abs(a_tdc));
  EXPECT_NEAR(a_tdc, -34633.6, 0.1);
  EXPECT_NEAR(tdc[cvx], 0.0, 1e-9 * rr * w);
  for (const auto& row : t.rows) EXPECT_NEAR(std::hypot(row[avx], row[avy]), rr * w, 1e-9 * rr * w);  // 137.4 in/s
  EXPECT_NEAR(rr * w, 137.44, 0.01);
  // Peak piston speed (about 146.9 in/s near 71.6 deg): within the 1-degree sampling of the sweep.
  double peak = 0;
  for (const auto& row : t.rows) peak = std::max(peak, std::abs(row[cvx]));
  EXPECT_NEAR(peak, 146.9, 0.1);
}

}  // namespace
}  // namespace nbar::ktest
