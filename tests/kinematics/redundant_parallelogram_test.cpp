// A parallelogram with a redundant third crank: Gruebler counts 0 freedoms, the rank analysis
// finds 1 and one redundant constraint; the coupler translates without turning through a
// full revolution, and every coupler point moves exactly like the crank tip.
#include "helpers/kinematics_support.hpp"

#include <gtest/gtest.h>

namespace nbar::ktest {
namespace {

constexpr int kJetTerms = 6;
using J = Jet<kJetTerms>;

struct Parallelogram {
  Model m;
  int crank1 = -1, coupler = -1;
  std::vector<int> coupler_points;
  double crank = 0.05, drawn = kPi / 2;
};

// O3 off the line O1-O2, so that no two crank pairs reach their change points together.
Parallelogram parallelogram(double omega, double alpha) {
  Parallelogram p;
  Model& m = p.m;
  const int o1 = add_point(m, "O1", {0, 0}, true);
  const int o2 = add_point(m, "O2", {0.2, 0}, true);
  const int o3 = add_point(m, "O3", {0.1, 0.08}, true);
  const int a1 = add_point(m, "A1", {0, 0.05});
  const int a2 = add_point(m, "A2", {0.2, 0.05});
  const int a3 = add_point(m, "A3", {0.1, 0.13});
  p.crank1 = add_body(m, "crank1", {o1, a1});
  add_body(m, "crank2", {o2, a2});
  add_body(m, "crank3", {o3, a3});
  p.coupler = add_body(m, "coupler", {a1, a2, a3});
  p.coupler_points = {a1, a2, a3};
  // A full turn in the sense of omega: time runs forward from `from`.
  const double start = kPi / 2, end = kPi / 2 + 2 * kPi;
  m.drivers.push_back(angle_driver("crank1", p.crank1, omega > 0 ? start : end, omega > 0 ? end : start, omega, alpha));
  m.sweep.steps = 361;
  return p;
}

TEST(RedundantParallelogram, MobilityFindsOneFreedomAndOneRedundantConstraint) {
  const Parallelogram p = parallelogram(2 * kPi, 0);
  const Mechanism mech(p.m);
  const MobilityReport& r = mech.mobility();
  EXPECT_EQ(r.grubler, 0);
  EXPECT_EQ(r.coordinates, 6);
  EXPECT_EQ(r.constraint_rows, 6);
  EXPECT_EQ(r.rank, 5);
  EXPECT_EQ(r.dof, 1);
  EXPECT_EQ(r.redundant.size(), 1u);
  EXPECT_TRUE(mech.overdetermined());
}

void check_translation(double omega, double alpha) {
  const Parallelogram p = parallelogram(omega, alpha);
  const Mechanism mech(p.m);
  const SweepResult r = run_sweep(mech, sweep_options(5));
  ASSERT_TRUE(r.complete) << r.stop_reason;
  ASSERT_EQ(r.samples.size(), 361u);
  // The third crank carries each pair through its change points: nothing singular is crossed.
  EXPECT_TRUE(r.warnings.empty()) << r.warnings.front().message;

  double worst = 0;
  for (const Sample& s : r.samples) {
    SCOPED_TRACE("step " + std::to_string(s.step));
    EXPECT_LE(s.residual, 1e-12 * mech.characteristic_length());
    const std::vector<double> coupler = body_angle_motion(mech, s, p.coupler);
    EXPECT_NEAR(coupler[0], 0.0, 1e-12) << "the coupler turned";
    for (int k = 1; k < kJetTerms; ++k) EXPECT_NEAR(coupler[k], 0.0, 1e-9 * std::pow(std::abs(omega) + 1, k));

    // Every coupler point is its drawn position plus the crank tip's displacement.
    J c, sn;
    sincos(J::motion(s.driver_values[0], omega, alpha), sn, c);
    for (int point : p.coupler_points) {
      const Motion2 m = point_motion(mech, s, point);
      const Eigen::Vector2d drawn = p.m.points[point].position;
      const J x = p.crank * c + (drawn.x() - p.crank * std::cos(p.drawn));
      const J y = p.crank * sn + (drawn.y() - p.crank * std::sin(p.drawn));
      for (int k = 0; k < kJetTerms; ++k) {
        const double scale = p.crank * std::pow(std::sqrt(omega * omega + std::abs(alpha)), k);
        const double err = std::max(std::abs(m.x[k] - x.derivative(k)), std::abs(m.y[k] - y.derivative(k))) / scale;
        EXPECT_LE(err, 1e-9) << p.m.points[point].name << " derivative " << k;
        worst = std::max(worst, err);
      }
    }
  }
  std::printf("[ accuracy ] redundant parallelogram (w=%g, alpha=%g): max relative error %.1e over orders 0-5\n", omega,
              alpha, worst);
}

TEST(RedundantParallelogram, FullTurnCouplerTranslatesWithTheCrankTip) { check_translation(2 * kPi, 0); }

TEST(RedundantParallelogram, FullTurnWithAngularAcceleration) { check_translation(-3.0, 7.5); }

}  // namespace
}  // namespace nbar::ktest
