// Link stresses against beam theory, and the equilibrium of every section.
#include <gtest/gtest.h>

#include <cmath>

#include "../kinematics/helpers/kinematics_support.hpp"
#include "nbar/stress/link_stress.hpp"

namespace nbar::ktest {
namespace {

constexpr double kL = 0.3, kBarWidth = 0.02, kBarThickness = 0.005, kBarMargin = 0.015;

// A straight massless bar O-A held by a motor at O (a cantilever), at rest.
Model cantilever() {
  Model m;
  const int o = add_point(m, "O", {0, 0}, true);
  const int a = add_point(m, "A", {kL, 0});
  const int bar = add_body(m, "bar", {o, a});
  m.bodies[bar].shape = make_bar({0, 0}, {kL, 0}, kBarWidth, kBarMargin, 0.0, 0.0);
  m.bodies[bar].thickness = kBarThickness;
  m.bodies[bar].inertia = GivenInertia{0.0, {kL / 2, 0}, 0.0};
  m.bodies[bar].material = Material{"steel", 7850, 250e6, 200e9, 0.3};
  m.drivers.push_back(angle_driver("bar", bar, 0.0, 0.0, 1.0));
  m.sweep.steps = 2;
  return m;
}

struct SolvedSweep {
  std::shared_ptr<const InverseDynamics> dynamics;
  const Mechanism& mech;
  const InverseDynamics& dyn;
  SweepResult sweep;
  LinkStress stress;
  DynamicsResult forces;
  explicit SolvedSweep(Model m, int sections = 200)
      : dynamics(std::make_shared<const InverseDynamics>(std::make_shared<const Mechanism>(std::move(m)))),
        mech(dynamics->mechanism()),
        dyn(*dynamics),
        sweep(run_sweep(mech, sweep_options(2))),
        stress(dynamics, sections),
        forces(dyn.solve(sweep.samples.at(0))) {}
  std::vector<SectionStress> profile(int body = 0) const { return stress.profile(forces, body); }
};

bool between_joints(double s) { return s > 1e-9 && s < kL - 1e-9; }

TEST(LinkStress, AxialLoadGivesUniformTension) {
  const double F = 1200.0;
  Model m = cantilever();
  m.point_loads.push_back(PointLoad{1, 0, Law::parse(std::to_string(F)), Law::parse("0")});
  const SolvedSweep s(m);
  ASSERT_GE(s.stress.section_count(0), 100);
  const double area = kBarWidth * kBarThickness;
  int checked = 0;
  for (const SectionStress& sec : s.profile()) {
    EXPECT_NEAR(sec.area, area, 1e-15);
    if (between_joints(sec.position)) {
      ++checked;
      EXPECT_NEAR(sec.axial, F, 1e-9 * F);
      EXPECT_NEAR(sec.shear, 0.0, 1e-9 * F);
      EXPECT_NEAR(sec.moment, 0.0, 1e-9 * F * kL);
      EXPECT_NEAR(sec.sigma_low, F / area, 1e-9 * F / area);
      EXPECT_NEAR(sec.sigma_high, F / area, 1e-9 * F / area);
      EXPECT_NEAR(sec.von_mises, F / area, 1e-9 * F / area);
    } else {  // the margins beyond the joints carry nothing
      EXPECT_NEAR(sec.axial, 0.0, 1e-9 * F);
    }
  }
  EXPECT_GE(checked, 100);
}

TEST(LinkStress, EndMomentGivesPureBending) {
  // Two opposite transverse forces at A and at B, d before it: a couple P d, constant from O to B.
  const double P = 300.0, d = 0.05;
  Model m = cantilever();
  const int b = add_point(m, "B", {kL - d, 0});
  m.bodies[0].points.push_back(b);
  m.point_loads.push_back(PointLoad{1, 0, Law::parse("0"), Law::parse(std::to_string(P))});
  m.point_loads.push_back(PointLoad{b, 0, Law::parse("0"), Law::parse(std::to_string(-P))});
  const SolvedSweep s(m);
  const double I = kBarThickness * std::pow(kBarWidth, 3) / 12.0;
  const double sigma = P * d * (kBarWidth / 2) / I;
  for (const SectionStress& sec : s.profile()) {
    if (sec.position <= 1e-9 || sec.position >= kL - d - 1e-9) continue;
    EXPECT_NEAR(sec.inertia, I, 1e-12 * I);
    EXPECT_NEAR(sec.moment, P * d, 1e-9 * P * d);
    EXPECT_NEAR(sec.axial, 0.0, 1e-9 * P);
    EXPECT_NEAR(sec.shear, 0.0, 1e-9 * P);
    // Counter-clockwise moment on the part at O: the left (upper) fibre is compressed.
    EXPECT_NEAR(sec.sigma_high, -sigma, 1e-9 * sigma);
    EXPECT_NEAR(sec.sigma_low, sigma, 1e-9 * sigma);
    EXPECT_NEAR(sec.von_mises, sigma, 1e-9 * sigma);
  }
}

TEST(LinkStress, CantileverMatchesBeamTheory) {
  const double P = 250.0;
  Model m = cantilever();
  m.point_loads.push_back(PointLoad{1, 0, Law::parse("0"), Law::parse(std::to_string(P))});
  const SolvedSweep s(m);
  const double I = kBarThickness * std::pow(kBarWidth, 3) / 12.0;
  const double tau = 1.5 * P / (kBarWidth * kBarThickness);
  double peak = 0.0;
  for (const SectionStress& sec : s.profile()) {
    if (!between_joints(sec.position)) continue;
    const double M = P * (kL - sec.position);
    const double sigma = M * (kBarWidth / 2) / I;
    EXPECT_NEAR(sec.shear, P, 1e-9 * P);
    EXPECT_NEAR(sec.moment, M, 1e-9 * P * kL);
    EXPECT_NEAR(sec.tau_max, tau, 1e-9 * tau);
    EXPECT_NEAR(sec.sigma_high, -sigma, 1e-9 * P * kL * kBarWidth / I);
    EXPECT_NEAR(sec.von_mises, std::max(sigma, std::sqrt(3.0) * tau), 1e-9 * P * kL * kBarWidth / I);
    peak = std::max(peak, sec.von_mises);
  }
  // The peak over the sweep is at the root, on a fibre, with its safety factor.
  std::vector<DynamicsResult> per_sample;
  for (const Sample& sample : s.sweep.samples) per_sample.push_back(s.dyn.solve(sample));
  const auto peaks = stress_peaks(s.stress, s.sweep, per_sample);
  ASSERT_EQ(peaks.size(), 1u);
  EXPECT_DOUBLE_EQ(peaks[0].at.von_mises, peak);
  EXPECT_LT(peaks[0].at.position, 0.02 * kL);
  EXPECT_NEAR(std::abs(peaks[0].at.where.y()), kBarWidth / 2, 1e-12);
  ASSERT_TRUE(peaks[0].safety_factor.has_value());
  EXPECT_NEAR(*peaks[0].safety_factor, 250e6 / peak, 1e-9);
}

TEST(LinkStress, EverySectionOfAMovingFourBarIsInEquilibrium) {
  // Steel bars with pin holes, gravity, a force on the coupler point, at speed: the two parts
  // of every section, each with its share of the d'Alembert forces, balance.
  Model m;
  const double a = 0.05, b = 0.15, c = 0.12, d = 0.16;
  const NortonFourBar fb{a, b, c, d};
  const FourBarState st = fb.solve(0.4, 30.0, 0.0, true);
  const int o2 = add_point(m, "O2", {0, 0}, true), o4 = add_point(m, "O4", {d, 0}, true);
  const Eigen::Vector2d A = polar(a, st.theta2), B = Eigen::Vector2d(d, 0) + polar(c, st.theta4);
  const int pa = add_point(m, "A", A), pb = add_point(m, "B", B);
  const int crank = add_body(m, "crank", {o2, pa});
  const int coupler = add_body(m, "coupler", {pa, pb});
  const int rocker = add_body(m, "rocker", {o4, pb});
  const Material steel{"steel", 7850, 250e6, 200e9, 0.3};
  auto shape = [&](int body, Eigen::Vector2d p, Eigen::Vector2d q) {
    m.bodies[body].shape = make_bar(p, q, 0.015, 0.01, 0.004, 0.004);
    m.bodies[body].thickness = 0.006;
    m.bodies[body].material = steel;
  };
  shape(crank, {0, 0}, A);
  shape(coupler, A, B);
  shape(rocker, {d, 0}, B);
  m.gravity = {0, -9.81};
  m.point_loads.push_back(PointLoad{pb, coupler, Law::parse("40"), Law::parse("-25*cos(5*t)")});
  m.torques.push_back(BodyTorque{rocker, Law::parse("1.5"), std::nullopt});
  m.drivers.push_back(angle_driver("crank", crank, 0.4, 0.4 + 2 * kPi, 30.0, 20.0));
  m.sweep.steps = 13;
  const auto shared = std::make_shared<const InverseDynamics>(std::make_shared<const Mechanism>(m));
  const InverseDynamics& dyn = *shared;
  const SweepResult sweep = run_sweep(dyn.mechanism(), sweep_options(2));
  ASSERT_TRUE(sweep.complete);
  const LinkStress stress(shared, 120);
  double worst = 0.0;
  for (const Sample& sample : sweep.samples) {
    const DynamicsResult forces = dyn.solve(sample);
    double scale = 0.0;
    for (const auto& f : forces.pin_forces) scale = std::max(scale, f.norm());
    for (int body = 0; body < 3; ++body) {
      ASSERT_GE(stress.section_count(body), 100);
      for (int k = 0; k < stress.section_count(body); ++k) {
        const PartLoads near = stress.part_loads(forces, body, k, -1);
        const PartLoads far = stress.part_loads(forces, body, k, +1);
        const double err =
            std::max((near.force + far.force).norm() / scale, std::abs(near.moment + far.moment) / (scale * 0.2));
        worst = std::max(worst, err);
        ASSERT_LT(err, 1e-9) << "body " << body << " section " << k << " step " << sample.step;
      }
    }
  }
  std::printf("[ accuracy ] section equilibrium of a moving four-bar: max relative error %.1e\n", worst);
}

}  // namespace
}  // namespace nbar::ktest
