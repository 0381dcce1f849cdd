// What the core does with mechanisms and requests it cannot satisfy: wrong driver counts,
// dependent drivers, linkages that cannot close, drivers pushed past their limits, distance
// drivers reaching zero, laws leaving their domain, and change points. Every failure must say
// why, and a sweep that stops keeps what it computed.
#include "helpers/kinematics_support.hpp"
#include "test_constants.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <regex>

namespace nbar::ktest {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

using nbar::test_constants::kDeg;

struct FourBar {
  Model m;
  int o2 = -1, o4 = -1, a = -1, b = -1;
  int crank = -1, coupler = -1, rocker = -1;
};

// Frame O2-O4 along +x, crank O2-A of length a at theta2, rocker O4-B; B on the side given by
// `up` of the diagonal A-O4.
FourBar four_bar(double a, double b, double c, double d, double theta2, bool up = true) {
  FourBar f;
  const Eigen::Vector2d pa = polar(a, theta2), po4(d, 0);
  const Eigen::Vector2d diag = po4 - pa;
  const double l = diag.norm();
  const double along = (b * b - c * c + l * l) / (2 * l);
  const double h = std::sqrt(std::max(0.0, b * b - along * along));
  const Eigen::Vector2d n(-diag.y() / l, diag.x() / l);
  const Eigen::Vector2d pb = pa + along * diag / l + (up ? 1 : -1) * h * n;
  f.o2 = add_point(f.m, "O2", {0, 0}, true);
  f.o4 = add_point(f.m, "O4", po4, true);
  f.a = add_point(f.m, "A", pa);
  f.b = add_point(f.m, "B", pb);
  f.crank = add_body(f.m, "crank", {f.o2, f.a});
  f.coupler = add_body(f.m, "coupler", {f.a, f.b});
  f.rocker = add_body(f.m, "rocker", {f.o4, f.b});
  return f;
}

// The first number after `prefix` in `text`.
double number_after(const std::string& text, const std::string& prefix) {
  const std::size_t at = text.find(prefix);
  if (at == std::string::npos) return std::nan("");
  return std::strtod(text.c_str() + at + prefix.size(), nullptr);
}

TEST(BadInput, NoDriverForAOneDofLinkage) {
  FourBar f = four_bar(0.08, 0.18, 0.14, 0.2, 1.0);
  try {
    Mechanism mech(f.m);
    FAIL() << "a four-bar without drivers was accepted";
  } catch (const ModelError& e) {
    EXPECT_THAT(e.what(),
                AllOf(HasSubstr("1 degree of freedom"), HasSubstr("0 drivers are given"), HasSubstr("add one driver")));
    EXPECT_EQ(e.where().kind, EntityRef::Kind::Model);
  }
}

TEST(BadInput, TwoDriversForAOneDofLinkage) {
  FourBar f = four_bar(0.08, 0.18, 0.14, 0.2, 1.0);
  f.m.drivers.push_back(angle_driver("crank", f.crank));
  f.m.drivers.push_back(angle_driver("rocker", f.rocker));
  try {
    Mechanism mech(f.m);
    FAIL() << "a four-bar with two drivers was accepted";
  } catch (const ModelError& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr("1 degree of freedom"), HasSubstr("2 drivers are given"),
                                HasSubstr("driver 'rocker' moves what the joints and the drivers before it "
                                          "already fix: remove it")));
    EXPECT_EQ(e.where().kind, EntityRef::Kind::Driver);
    EXPECT_EQ(e.where().index, 1);
  }
}

// A parallelogram with a redundant third crank, driven twice: the second driver is named, not
// the redundant crank (a redundancy of the joints themselves is no mistake).
TEST(BadInput, SecondDriverOfARedundantParallelogramIsNamed) {
  Model m;
  const int o1 = add_point(m, "O1", {0, 0}, true);
  const int o2 = add_point(m, "O2", {0.2, 0}, true);
  const int o3 = add_point(m, "O3", {0.1, 0.08}, true);
  const int a1 = add_point(m, "A1", {0, 0.05});
  const int a2 = add_point(m, "A2", {0.2, 0.05});
  const int a3 = add_point(m, "A3", {0.1, 0.13});
  const int crank1 = add_body(m, "crank1", {o1, a1});
  const int crank2 = add_body(m, "crank2", {o2, a2});
  add_body(m, "crank3", {o3, a3});
  add_body(m, "coupler", {a1, a2, a3});
  m.drivers.push_back(angle_driver("first", crank1));
  m.drivers.push_back(angle_driver("second", crank2));
  try {
    Mechanism mech(m);
    FAIL() << "a parallelogram with two drivers was accepted";
  } catch (const ModelError& e) {
    EXPECT_THAT(e.what(), HasSubstr("driver 'second' moves what the joints and the drivers before it already fix"));
    EXPECT_EQ(e.where().kind, EntityRef::Kind::Driver);
    EXPECT_EQ(e.where().index, 1);
  }
}

// A slider-crank whose slider was put on the rod instead of the piston: the joints alone lock
// it, and the slider's constraint is the one named, at the slider.
TEST(BadInput, SliderOnTheWrongBodyIsNamed) {
  Model m;
  const int o2 = add_point(m, "O2", {0, 0}, true);
  const int x = add_point(m, "X", {0.4, 0}, true);
  const int a = add_point(m, "A", {0.05, 0.02});
  const int c = add_point(m, "C", {0.23, 0});
  const int crank = add_body(m, "crank", {o2, a});
  const int rod = add_body(m, "rod", {a, c});
  m.sliders.push_back(Slider{rod, c, {o2, x}});
  m.drivers.push_back(angle_driver("crank", crank));
  try {
    Mechanism mech(m);
    FAIL() << "a slider-crank locked by its slider was accepted";
  } catch (const ModelError& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr("0 degrees of freedom"), HasSubstr("is the slider on the right body?")));
    EXPECT_EQ(e.where().kind, EntityRef::Kind::Slider);
    EXPECT_EQ(e.where().index, 0);
  }
}

// A slider-crank whose piston has two points but no slider: the piston is free, and named.
TEST(BadInput, ForgottenSliderNamesTheFreeBody) {
  Model m;
  const int o2 = add_point(m, "O2", {0, 0}, true);
  const int a = add_point(m, "A", {0.05, 0.02});
  const int c = add_point(m, "C", {0.23, 0});
  const int d = add_point(m, "D", {0.26, 0});
  const int crank = add_body(m, "crank", {o2, a});
  add_body(m, "rod", {a, c});
  const int piston = add_body(m, "piston", {c, d});
  m.drivers.push_back(angle_driver("crank", crank));
  try {
    Mechanism mech(m);
    FAIL() << "a slider-crank without its slider was accepted";
  } catch (const ModelError& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr("3 degrees of freedom"),
                                HasSubstr("body 'piston' can still move with the drivers held (it is joined to the "
                                          "rest only at C)")));
    EXPECT_EQ(e.where().kind, EntityRef::Kind::Body);
    EXPECT_EQ(e.where().index, piston);
  }
}

// A five-bar has two freedoms, but two drivers on the same crank move only one of them.
TEST(BadInput, DependentDriverIsNamed) {
  Model m;
  const int o1 = add_point(m, "O1", {0, 0}, true);
  const int o5 = add_point(m, "O5", {0.1, 0}, true);
  const int a = add_point(m, "A", {0.06, 0});
  const int b = add_point(m, "B", {0.13, 0.052});
  const int p = add_point(m, "P", {0.028, 0.116});
  const int left = add_body(m, "left", {o1, a});
  add_body(m, "right", {o5, b});
  add_body(m, "distal_left", {a, p});
  add_body(m, "distal_right", {b, p});
  m.drivers.push_back(angle_driver("first", left));
  m.drivers.push_back(angle_driver("second", left));
  try {
    Mechanism mech(m);
    FAIL() << "two drivers of the same angle were accepted";
  } catch (const ModelError& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr("'second'"), HasSubstr("does not move the mechanism independently")));
    EXPECT_EQ(e.where().kind, EntityRef::Kind::Driver);
    EXPECT_EQ(e.where().index, 1);
  }
}

// Coupler and rocker together shorter than the diagonal they must span: nothing closes.
TEST(BadInput, BarsTooShortToCloseNameAConstraint) {
  FourBar f = four_bar(0.08, 0.18, 0.14, 0.2, 1.0);
  f.m.bodies[f.coupler].length = 0.02;
  f.m.drivers.push_back(angle_driver("crank", f.crank, 0.0, 2 * kPi));
  const Mechanism mech(f.m);
  try {
    run_sweep(mech);
    FAIL() << "assembled a four-bar whose coupler is too short to close";
  } catch (const AssemblyError& e) {
    ASSERT_GE(e.row(), 0) << e.what();
    ASSERT_LT(e.row(), mech.row_count());
    const std::string label = mech.row_label(e.row());
    EXPECT_THAT(e.what(), AllOf(HasSubstr("constraint '" + label + "'"), HasSubstr("cannot be met")));
    EXPECT_THAT(label, HasSubstr("length of"));
  }
}

// A non-Grashof linkage (s + l > p + q) driven by its rocker, asked for an angle the rocker
// cannot reach. The rocker's limits are where crank and coupler line up:
// |O2 B|^2 = c^2 + d^2 + 2 c d cos(theta4) = (a + b)^2 or (a - b)^2.
TEST(BadInput, RockerAskedForAnUnreachableAngle) {
  const double a = 0.3, b = 0.5, c = 0.45, d = 0.9;
  const double limit = std::acos(((a + b) * (a + b) - c * c - d * d) / (2 * c * d));  // 117.38 deg
  // Drawn with the rocker at 160 deg, well inside its range [117.38, 242.62] deg: A where the
  // circles about O2 (radius a) and B (radius b) meet.
  FourBar f = four_bar(a, b, c, d, 0.0);
  const Eigen::Vector2d pb = Eigen::Vector2d(d, 0) + polar(c, 160 * kDeg);
  const double l = pb.norm(), along = (a * a - b * b + l * l) / (2 * l);
  const Eigen::Vector2d pa = along * pb / l + std::sqrt(a * a - along * along) * Eigen::Vector2d(-pb.y(), pb.x()) / l;
  f.m.points[f.a].position = pa;
  f.m.points[f.b].position = pb;
  f.m.drivers.push_back(angle_driver("rocker", f.rocker, 100 * kDeg, 130 * kDeg));
  const Mechanism mech(f.m);
  try {
    run_sweep(mech);
    FAIL() << "assembled the rocker at 100 deg, beyond its limit at " << limit / kDeg << " deg";
  } catch (const AssemblyError& e) {
    const std::string what = e.what();
    EXPECT_THAT(what, AllOf(HasSubstr("driver 'rocker' stops at"), HasSubstr("wanted 100 deg")));
    // No pose exists at 100 deg, so the error names the constraint that the closest one misses.
    ASSERT_GE(e.row(), 0) << what;
    EXPECT_THAT(what, HasSubstr("'" + mech.row_label(e.row()) + "'"));
    const double stopped = number_after(what, "stops at ") * kDeg;
    EXPECT_NEAR(stopped, limit, 0.05 * kDeg) << what;
    std::printf("[ accuracy ] rocker limit: reported %.6f deg, closed form %.6f deg\n", stopped / kDeg, limit / kDeg);
  }
}

// The same linkage driven by its input link asked to turn fully: its range is |theta2| <= 90.26
// deg (|A O4| = b + c). The sweep stops there, keeps the samples before the limit and says where.
TEST(BadInput, NonGrashofCrankAskedToTurnFullyStopsAtItsLimit) {
  const double a = 0.3, b = 0.5, c = 0.45, d = 0.9;
  const double limit = std::acos((a * a + d * d - (b + c) * (b + c)) / (2 * a * d));
  FourBar f = four_bar(a, b, c, d, 30 * kDeg);
  f.m.drivers.push_back(angle_driver("crank", f.crank, 0.0, 2 * kPi, 10.0));
  f.m.sweep.steps = 361;
  const Mechanism mech(f.m);
  const SweepResult r = run_sweep(mech, sweep_options(2));
  EXPECT_FALSE(r.complete);
  EXPECT_THAT(r.stop_reason, AllOf(HasSubstr("between steps 90 and 91"), HasSubstr("toggle")));
  ASSERT_EQ(r.samples.size(), 91u) << "every sample before the limit is kept";
  const double last = r.samples.back().driver_values[0];
  EXPECT_NEAR(last, 90 * kDeg, 1e-12);
  EXPECT_LE(last, limit);
  EXPECT_LT(limit - last, 1 * kDeg);
  const double reported = number_after(r.stop_reason, "crank = ") * kDeg;
  EXPECT_NEAR(reported, limit, 0.05 * kDeg) << r.stop_reason;
  std::printf("[ accuracy ] crank limit: reported %.6f deg, closed form %.6f deg\n", reported / kDeg, limit / kDeg);
  for (const Sample& s : r.samples) EXPECT_LE(s.residual, 1e-12 * mech.characteristic_length());
}

// A linear actuator whose commanded length passes through zero: the sweep stops before the
// first sample that is not positive, keeping the ones before.
TEST(BadInput, DistanceDriverReachingZero) {
  Model m;
  const int o = add_point(m, "O", {0, 0}, true);
  const int x = add_point(m, "X", {1, 0}, true);
  const int c = add_point(m, "C", {0.5, 0});
  const int block = add_body(m, "block", {c});
  m.sliders.push_back(Slider{block, c, {o, x}});
  Driver d;
  d.name = "actuator";
  d.kind = DriverKind::Distance;
  d.points = {o, c};
  d.from = 0.5;
  d.to = -0.1;
  d.speed = -0.1;
  m.drivers.push_back(d);
  m.sweep.steps = 5;  // 0.5, 0.35, 0.2, 0.05, -0.1
  const Mechanism mech(m);
  const SweepResult r = run_sweep(mech);
  EXPECT_FALSE(r.complete);
  EXPECT_THAT(r.stop_reason,
              AllOf(HasSubstr("'actuator'"), HasSubstr("must be positive"), HasSubstr("between steps 3 and 4")));
  ASSERT_EQ(r.samples.size(), 4u);
  for (const Sample& s : r.samples) {
    const Motion2 mc = point_motion(mech, s, c);
    EXPECT_NEAR(mc.x[0], s.driver_values[0], 1e-12);
    EXPECT_NEAR(mc.x[1], -0.1, 1e-12);
  }
}

// The same actuator swept in 7 steps: the sixth value, 0.5 - 0.6 * 5/6, is 5.6e-17 m, zero up to
// rounding, where the distance row's Jacobian vanishes. An exact `> 0` test once let it through
// and recorded x = 5.3e-14 m, vx = -1.0e-4 m/s (true -0.1) and ax = 1.9e11 m/s^2 (true 0), with
// a residual of 2.8e-27 m: the sweep must stop before it instead.
TEST(BadInput, DistanceDriverSweptToZeroUpToRounding) {
  Model m;
  const int o = add_point(m, "O", {0, 0}, true);
  const int x = add_point(m, "X", {1, 0}, true);
  const int c = add_point(m, "C", {0.5, 0});
  const int block = add_body(m, "block", {c});
  m.sliders.push_back(Slider{block, c, {o, x}});
  Driver d;
  d.name = "actuator";
  d.kind = DriverKind::Distance;
  d.points = {o, c};
  d.from = 0.5;
  d.to = -0.1;
  d.speed = -0.1;
  m.drivers.push_back(d);
  m.sweep.steps = 7;  // 0.5, 0.4, 0.3, 0.2, 0.1, ~0, -0.1
  const Mechanism mech(m);
  const SweepResult r = run_sweep(mech, sweep_options(2));
  EXPECT_FALSE(r.complete);
  EXPECT_THAT(r.stop_reason, AllOf(HasSubstr("must be positive"), HasSubstr("between steps 4 and 5")));
  EXPECT_EQ(r.samples.size(), 5u);
  for (const Sample& s : r.samples) {
    SCOPED_TRACE("step " + std::to_string(s.step));
    const Motion2 mc = point_motion(mech, s, c);
    EXPECT_NEAR(mc.x[0], s.driver_values[0], 1e-12);
    EXPECT_NEAR(mc.x[1], -0.1, 1e-9);
    EXPECT_NEAR(mc.x[2], 0.0, 1e-9);
  }
}

// sqrt(1.05 - t) has no value after t = 1.05: the sweep stops with the law's own reason at the
// first sample past it and keeps the samples before.
TEST(BadInput, LawWithADomainErrorMidSweep) {
  FourBar f = four_bar(0.08, 0.18, 0.14, 0.2, 1.0);
  Driver d = angle_driver("crank", f.crank);
  d.law = Law::parse("1 + sqrt(1.05 - t)");
  f.m.drivers.push_back(d);
  f.m.sweep.duration = 2.0;
  const Mechanism mech(f.m);
  // The model's error, as a law undefined at the start is (exit 1 on the command line), at the
  // driver whose law it is: not a stop at a limit position of the linkage.
  try {
    run_sweep(mech, sweep_options(2, 21));
    ADD_FAILURE() << "the sweep went through t = 1.1";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::UndefinedLaw);
    EXPECT_EQ(e.where().kind, EntityRef::Kind::Driver);
    EXPECT_EQ(e.where().index, 0);
    EXPECT_THAT(e.message(),
                AllOf(HasSubstr("sqrt(1.05 - t)"), HasSubstr("t = 1.1"), HasSubstr("between steps 10 and 11")));
  }
}

TEST(BadInput, DerivativeOrderOutOfRange) {
  FourBar f = four_bar(0.08, 0.18, 0.14, 0.2, 1.0);
  f.m.drivers.push_back(angle_driver("crank", f.crank, 0.0, 1.0));
  const Mechanism mech(f.m);
  for (const SweepOptions& bad : {sweep_options(6), sweep_options(-1), sweep_options(2, 0)}) {
    try {
      run_sweep(mech, bad);
      ADD_FAILURE() << "order " << bad.order << " accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::BadInput) << e.what();
    }
  }
  EXPECT_NO_THROW(run_sweep(mech, sweep_options(5, 3)));
}

// A parallelogram (crank = rocker, coupler = ground) without a redundant third crank has change
// points at crank angles 0 and 180 deg, where it may continue as an antiparallelogram. The sweep
// (whose step 120 lands on the change point at 180 deg) goes through them as the parallelogram
// it was drawn as, saying where it passed them (tests/kinematics/change_point_test.cpp checks
// the numbers at many step counts).
TEST(BadInput, ChangePointParallelogramNeverSwitchesSilently) {
  const double a = 0.05, d = 0.2;
  Model m;
  const int o2 = add_point(m, "O2", {0, 0}, true);
  const int o4 = add_point(m, "O4", {d, 0}, true);
  const int pa = add_point(m, "A", polar(a, 60 * kDeg));
  const int pb = add_point(m, "B", Eigen::Vector2d(d, 0) + polar(a, 60 * kDeg));
  const int crank = add_body(m, "crank", {o2, pa});
  const int coupler = add_body(m, "coupler", {pa, pb});
  add_body(m, "rocker", {o4, pb});
  m.drivers.push_back(angle_driver("crank", crank, 60 * kDeg, 420 * kDeg, 5.0));
  m.sweep.steps = 361;
  const Mechanism mech(m);
  const SweepResult r = run_sweep(mech, sweep_options(1));

  // The step each warning names: "between steps i and j" (passed between samples) or "step i
  // lies on" (a sample on the change point).
  const std::regex between("between steps [0-9]+ and ([0-9]+)"), on("^step ([0-9]+) lies on");
  std::vector<int> warned;
  for (const Warning& warning : r.warnings) {
    const std::string& w = warning.message;
    std::smatch match;
    const bool passed = std::regex_search(w, match, between);
    ASSERT_TRUE(passed || std::regex_search(w, match, on)) << w;
    EXPECT_EQ(warning.step, std::stoi(match[1])) << "the structured step is the one the message names";
    EXPECT_EQ(warning.code, passed ? "change_point_passed" : "change_point_at_sample");
    EXPECT_THAT(w, HasSubstr("singular")) << w;
    warned.push_back(warning.step);
  }
  EXPECT_TRUE(r.complete) << r.stop_reason;
  EXPECT_THAT(warned, ::testing::Contains(120)) << "step 120 lies on the change point at 180 deg";
  int first_bad = -1;
  for (const Sample& s : r.samples) {
    const double angle = body_angle_motion(mech, s, coupler)[0];
    if (std::abs(std::sin(angle)) > 1e-6 || std::cos(angle) < 0) {
      first_bad = s.step;
      break;
    }
  }
  EXPECT_EQ(first_bad, -1) << "the coupler stopped being parallel to the ground at step " << first_bad;
}

}  // namespace
}  // namespace nbar::ktest
