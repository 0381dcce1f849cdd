// Four-bar sweeps against Norton's closed form (positions, velocities, accelerations), on both
// assembly branches, for random Grashof and non-Grashof linkages, in rotated and mirrored
// drawings. The closed form shares nothing with the solver but the geometry.
#include "helpers/kinematics_support.hpp"

#include <gtest/gtest.h>

#include <complex>
#include <cstdio>
#include <random>

namespace nbar::ktest {
namespace {

enum class Kind { CrankRocker, DoubleCrank, GrashofDoubleRocker, NonGrashof };

const char* kind_name(Kind k) {
  switch (k) {
    case Kind::CrankRocker: return "crank-rocker";
    case Kind::DoubleCrank: return "double-crank";
    case Kind::GrashofDoubleRocker: return "Grashof double-rocker";
    case Kind::NonGrashof: return "non-Grashof";
  }
  return "";
}

// Our own Grashof classification, with a margin so that no linkage is nearly a change point.
std::optional<Kind> classify(const NortonFourBar& g, double margin) {
  std::array<double, 4> len{g.d, g.a, g.b, g.c};  // frame, crank, coupler, rocker
  const auto sorted = [&] {
    auto s = len;
    std::sort(s.begin(), s.end());
    return s;
  }();
  const double grashof = (sorted[1] + sorted[2]) - (sorted[0] + sorted[3]);
  if (std::abs(grashof) < margin * sorted[3]) return std::nullopt;
  if (grashof < 0) return Kind::NonGrashof;
  const int shortest = static_cast<int>(std::min_element(len.begin(), len.end()) - len.begin());
  switch (shortest) {
    case 0: return Kind::DoubleCrank;
    case 1: return Kind::CrankRocker;
    case 2: return Kind::GrashofDoubleRocker;
    default: return std::nullopt;  // rocker shortest: the input would be a rocker of a crank-rocker
  }
}

// A crank interval where the loop closes, shrunk away from the toggles at its ends.
struct CrankRange {
  double from = 0, to = 0;
  bool full_turn = false;
};

CrankRange crank_range(const NortonFourBar& g, double shrink) {
  const double lo = g.cos_low(), hi = g.cos_high();
  CrankRange r;
  if (lo <= -1 && hi >= 1) {
    r.full_turn = true;
    r.from = 0;
    r.to = 2 * kPi;
    return r;
  }
  if (hi >= 1) {
    r.from = -std::acos(lo);
    r.to = std::acos(lo);
  } else if (lo <= -1) {
    r.from = std::acos(hi);
    r.to = 2 * kPi - std::acos(hi);
  } else {
    r.from = std::acos(hi);
    r.to = std::acos(lo);
  }
  const double cut = shrink * (r.to - r.from);
  r.from += cut;
  r.to -= cut;
  return r;
}

struct Case {
  std::string label;
  NortonFourBar g;
  bool open = true;
  DrawingFrame frame;
  double theta_drawn = 0;         // local crank angle of the drawing
  double from = 0, to = 0;        // local crank angles of the sweep
  double omega2 = 1, alpha2 = 0;  // local
  int steps = 73;
};

struct Built {
  Model model;
  int crank = -1, coupler = -1, rocker = -1;
};

Built build(const Case& c) {
  const NortonFourBar& g = c.g;
  const FourBarState s = g.solve(c.theta_drawn, 0, 0, c.open);
  Built b;
  Model& m = b.model;
  const int o2 = add_point(m, "O2", c.frame.to_world({0, 0}), true);
  const int o4 = add_point(m, "O4", c.frame.to_world({g.d, 0}), true);
  const int pa = add_point(m, "A", c.frame.to_world(polar(g.a, s.theta2)));
  const int pb = add_point(m, "B", c.frame.to_world(Eigen::Vector2d(g.d, 0) + polar(g.c, s.theta4)));
  // Exact lengths, so that rounding in the drawing cannot move the geometry off the closed form.
  b.crank = add_body(m, "crank", {o2, pa}, g.a);
  b.coupler = add_body(m, "coupler", {pa, pb}, g.b);
  b.rocker = add_body(m, "rocker", {o4, pb}, g.c);
  m.drivers.push_back(angle_driver("crank", b.crank, c.frame.angle_to_world(c.from), c.frame.angle_to_world(c.to),
                                   c.frame.rate_to_world(c.omega2), c.frame.rate_to_world(c.alpha2)));
  m.sweep.steps = c.steps;
  return b;
}

// The largest error seen, relative to the scale of each quantity, over every case of a test.
struct Errors {
  double angle = 0, omega = 0, alpha = 0;
  void print(const char* what) const {
    std::printf("[ accuracy ] %s: max error angle %.2e rad, omega %.2e, alpha %.2e (relative)\n", what, angle, omega,
                alpha);
  }
};

// nbar names branches after Norton's roots read in the world frame (counter-clockwise angles,
// x axis from O2 to O4), so a mirrored drawing of the open branch reads as crossed.
std::string expected_branch_name(const Case& c) { return (c.frame.mirror > 0) == c.open ? "open" : "crossed"; }

void check_case(const Case& c, Errors& worst, double tolerance = 1e-9) {
  SCOPED_TRACE(c.label);
  const Built b = build(c);
  const Mechanism mech(b.model);
  SweepResult r;
  try {
    r = run_sweep(mech, sweep_options(2, std::nullopt));
  } catch (const std::exception& e) {
    FAIL() << e.what();
  }
  ASSERT_TRUE(r.complete) << r.stop_reason;
  ASSERT_EQ(static_cast<int>(r.samples.size()), c.steps);
  EXPECT_TRUE(r.warnings.empty()) << r.warnings.front().message;
  ASSERT_EQ(r.branches.size(), 1u);
  EXPECT_EQ(r.branches[0], expected_branch_name(c));

  const double w2 = std::abs(c.omega2);
  for (const Sample& s : r.samples) {
    SCOPED_TRACE("step " + std::to_string(s.step));
    const double expected_input = c.from + (c.to - c.from) * s.step / (c.steps - 1);
    const double t2 = c.frame.angle_to_local(s.driver_values[0]);
    ASSERT_NEAR(t2, expected_input, 1e-12 * (1 + std::abs(expected_input)));

    const FourBarState ref = c.g.solve(t2, c.omega2, c.alpha2, c.open);
    // The reference must itself close the loop, and so must its first two derivatives.
    {
      using C = std::complex<double>;
      const C i(0, 1);
      auto e = [&](double t) { return std::exp(i * t); };
      const C pos = c.g.a * e(ref.theta2) + c.g.b * e(ref.theta3) - c.g.c * e(ref.theta4) - c.g.d;
      const C vel = i * (c.g.a * ref.omega2 * e(ref.theta2) + c.g.b * ref.omega3 * e(ref.theta3) -
                         c.g.c * ref.omega4 * e(ref.theta4));
      auto acc_term = [&](double len, double t, double w, double al) { return len * (i * al - w * w) * e(t); };
      const C acc = acc_term(c.g.a, ref.theta2, ref.omega2, ref.alpha2) +
                    acc_term(c.g.b, ref.theta3, ref.omega3, ref.alpha3) -
                    acc_term(c.g.c, ref.theta4, ref.omega4, ref.alpha4);
      const double size = c.g.a + c.g.b + c.g.c + c.g.d;
      ASSERT_LT(std::abs(pos), 1e-12 * size);
      ASSERT_LT(std::abs(vel), 1e-12 * size * w2);
      ASSERT_LT(std::abs(acc), 1e-11 * size * (w2 * w2 + std::abs(c.alpha2) + 1e-300));
      // Norton's minus root puts B to the left of the line from A to O4 at every crank angle, the
      // side nbar calls open.
      const C ab = c.g.b * e(ref.theta3), ao4 = c.g.d - c.g.a * e(ref.theta2);
      ASSERT_EQ(std::imag(std::conj(ao4) * ab) > 0, c.open);
    }

    const std::vector<double> m3 = body_angle_motion(mech, s, b.coupler);
    const std::vector<double> m4 = body_angle_motion(mech, s, b.rocker);
    const std::vector<double> m2 = body_angle_motion(mech, s, b.crank);
    // The input itself: the driver's speed and acceleration at every sample.
    EXPECT_NEAR(angle_difference(c.frame.angle_to_local(m2[0]), ref.theta2), 0.0, 1e-11);
    EXPECT_NEAR(c.frame.rate_to_world(m2[1]), c.omega2, 1e-12 * w2);
    EXPECT_NEAR(c.frame.rate_to_world(m2[2]), c.alpha2, 1e-12 * (w2 * w2 + std::abs(c.alpha2)));

    const double omega_scale = std::max({w2, std::abs(ref.omega3), std::abs(ref.omega4)});
    const double alpha_scale = std::max({w2 * w2 + std::abs(c.alpha2), std::abs(ref.alpha3), std::abs(ref.alpha4)});
    const double e3 = std::abs(angle_difference(c.frame.angle_to_local(m3[0]), ref.theta3));
    const double e4 = std::abs(angle_difference(c.frame.angle_to_local(m4[0]), ref.theta4));
    const double ew3 = std::abs(c.frame.rate_to_world(m3[1]) - ref.omega3) / omega_scale;
    const double ew4 = std::abs(c.frame.rate_to_world(m4[1]) - ref.omega4) / omega_scale;
    const double ea3 = std::abs(c.frame.rate_to_world(m3[2]) - ref.alpha3) / alpha_scale;
    const double ea4 = std::abs(c.frame.rate_to_world(m4[2]) - ref.alpha4) / alpha_scale;
    EXPECT_LE(e3, tolerance) << "theta3 " << m3[0] << " vs " << ref.theta3;
    EXPECT_LE(e4, tolerance) << "theta4 " << m4[0] << " vs " << ref.theta4;
    EXPECT_LE(ew3, tolerance) << "omega3 " << m3[1] << " vs " << ref.omega3;
    EXPECT_LE(ew4, tolerance) << "omega4 " << m4[1] << " vs " << ref.omega4;
    EXPECT_LE(ea3, tolerance) << "alpha3 " << m3[2] << " vs " << ref.alpha3;
    EXPECT_LE(ea4, tolerance) << "alpha4 " << m4[2] << " vs " << ref.alpha4;
    worst.angle = std::max({worst.angle, e3, e4});
    worst.omega = std::max({worst.omega, ew3, ew4});
    worst.alpha = std::max({worst.alpha, ea3, ea4});
  }
}

// Smallest |sin| of the transmission angle over the sampled crank angles: the closed form and
// the solver both lose accuracy like 1/sin(mu), so the random linkages keep away from mu = 0.
double worst_transmission(const NortonFourBar& g, double from, double to, bool open, int samples) {
  double worst = 1.0;
  for (int i = 0; i < samples; ++i) {
    const FourBarState s = g.solve(from + (to - from) * i / (samples - 1), 0, 0, open);
    worst = std::min(worst, std::abs(std::sin(s.theta3 - s.theta4)));
  }
  return worst;
}

// Random linkages of one Grashof class, each swept on both branches from a random drawing.
std::vector<Case> random_cases(Kind kind, unsigned seed, int count) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> length(0.2, 3.0), unit(0.0, 1.0);
  std::vector<Case> cases;
  int attempts = 0;
  while (static_cast<int>(cases.size()) < 2 * count) {
    if (++attempts > 200000) throw std::runtime_error("could not generate the random four-bars");
    NortonFourBar g{length(rng), length(rng), length(rng), length(rng)};
    if (classify(g, 0.05) != kind) continue;
    const CrankRange range = crank_range(g, 0.08);
    if ((kind == Kind::CrankRocker || kind == Kind::DoubleCrank) != range.full_turn) continue;
    double from = range.from, to = range.to;
    if (range.full_turn) {
      from = 2 * kPi * unit(rng);
      to = from + 2 * kPi;
    }
    const bool reversed = unit(rng) < 0.3;
    if (reversed) std::swap(from, to);
    const double omega = (reversed ? -1 : 1) * (0.5 + 30 * unit(rng));
    // Half the cases at constant speed (the sweep is then one motion in time), half with an
    // angular acceleration (positions and derivatives are then computed separately).
    const double alpha = unit(rng) < 0.5 ? 0.0 : (unit(rng) - 0.5) * 400;
    const double drawn = range.full_turn ? 2 * kPi * unit(rng) : range.from + (range.to - range.from) * unit(rng);
    bool ok = true;
    for (bool open : {true, false}) ok = ok && worst_transmission(g, from, to, open, 200) > 0.2 && g.feasible(drawn);
    if (!ok) continue;
    for (bool open : {true, false}) {
      Case c;
      char label[200];
      std::snprintf(label, sizeof label, "%s #%zu: a=%.6g b=%.6g c=%.6g d=%.6g, %s, %.6g..%.6g rad, w2=%.4g, a2=%.4g",
                    kind_name(kind), cases.size() / 2, g.a, g.b, g.c, g.d, open ? "open" : "crossed", from, to, omega,
                    alpha);
      c.label = label;
      c.g = g;
      c.open = open;
      c.theta_drawn = drawn;
      c.from = from;
      c.to = to;
      c.omega2 = omega;
      c.alpha2 = alpha;
      c.steps = 91;
      cases.push_back(c);
    }
  }
  return cases;
}

TEST(FourBarClosedForm, RandomCrankRockers) {
  Errors worst;
  for (const Case& c : random_cases(Kind::CrankRocker, 20240601u, 12)) check_case(c, worst);
  worst.print("crank-rockers");
}

TEST(FourBarClosedForm, RandomDoubleCranks) {
  Errors worst;
  for (const Case& c : random_cases(Kind::DoubleCrank, 777u, 10)) check_case(c, worst);
  worst.print("double-cranks");
}

TEST(FourBarClosedForm, RandomNonGrashofOverTheirFeasibleRange) {
  Errors worst;
  for (const Case& c : random_cases(Kind::NonGrashof, 4242u, 12)) check_case(c, worst);
  worst.print("non-Grashof");
}

TEST(FourBarClosedForm, RandomGrashofDoubleRockersOverTheirFeasibleRange) {
  Errors worst;
  for (const Case& c : random_cases(Kind::GrashofDoubleRocker, 99u, 8)) check_case(c, worst);
  worst.print("Grashof double-rockers");
}

// Norton's example 4-1 linkage (a=40, b=120, c=80, d=100 mm) drawn in frames that are not
// the plane's own: the frame line O2-O4 at 37 deg, away from the origin, and mirrored.
TEST(FourBarClosedForm, FrameNotHorizontalAndMirroredDrawings) {
  Errors worst;
  const NortonFourBar g{0.040, 0.120, 0.080, 0.100};
  for (const double rotation : {0.0, 37.0 * kPi / 180, -2.5}) {
    for (const int mirror : {1, -1}) {
      for (const bool open : {true, false}) {
        Case c;
        c.g = g;
        c.open = open;
        c.frame = DrawingFrame{Eigen::Vector2d(0.3, -0.7), rotation, mirror};
        c.theta_drawn = 40.0 * kPi / 180;
        c.from = 40.0 * kPi / 180;
        c.to = c.from + 2 * kPi;
        c.omega2 = 25.0;
        c.alpha2 = -15.0;
        c.steps = 145;
        c.label =
            "rotation " + std::to_string(rotation) + (mirror < 0 ? ", mirrored" : "") + (open ? ", open" : ", crossed");
        check_case(c, worst);
      }
    }
  }
  worst.print("rotated/mirrored");
}

// A non-Grashof linkage whose crank can only move in [20.59, 339.41] deg, drawn at 278.1 deg and
// swept from 60 to 300 deg. The start is on the drawn branch, reachable by turning the crank back
// through 180 deg; the shorter arc, forward through 0 deg, leaves the range at 339.41 deg.
// Assembly once took only the shorter arc and gave up at its limit ("cannot reach the drivers'
// starting values ... stops at -20.5911 deg"), although the start is on the drawn branch.
TEST(FourBarClosedForm, AssemblyReachesTheStartTheLongWayRound) {
  Errors worst;
  const NortonFourBar g{0.882163, 1.70145, 2.19325, 1.2074};
  ASSERT_NEAR(std::acos(g.cos_high()) * 180 / kPi, 20.59, 0.01);
  for (const bool open : {true, false}) {
    Case c;
    c.g = g;
    c.open = open;
    c.theta_drawn = 278.1 * kPi / 180;
    c.from = 60 * kPi / 180;
    c.to = 300 * kPi / 180;
    c.omega2 = 2;
    c.label = std::string("long way round, ") + (open ? "open" : "crossed");
    check_case(c, worst);
  }
}

// The reference itself against printed solutions: Norton's example 4-1 (a=40, b=120, c=80, d=100,
// theta2=40 deg: open theta3=20.298, theta4=57.325 deg) and a published exercise with a double-crank
// (a=35, b=25, c=15, d=10, theta2=30 deg: open 254.1745/334.0983, crossed 187.3223/107.3985 deg).
TEST(FourBarClosedForm, ReferenceMatchesPrintedExamples) {
  auto deg = [](double r) {
    const double d = std::fmod(r * 180 / kPi, 360.0);
    return d < 0 ? d + 360 : d;
  };
  const FourBarState n_open = NortonFourBar{40, 120, 80, 100}.solve(40.0 * kPi / 180, 1, 0, true);
  EXPECT_NEAR(deg(n_open.theta3), 20.298, 5e-4);
  EXPECT_NEAR(deg(n_open.theta4), 57.325, 5e-4);
  const NortonFourBar g{35, 25, 15, 10};
  const FourBarState open = g.solve(30.0 * kPi / 180, 1, 0, true);
  const FourBarState crossed = g.solve(30.0 * kPi / 180, 1, 0, false);
  EXPECT_NEAR(deg(open.theta3), 254.1745, 5e-5);
  EXPECT_NEAR(deg(open.theta4), 334.0983, 5e-5);
  EXPECT_NEAR(deg(crossed.theta3), 187.3223, 5e-5);
  EXPECT_NEAR(deg(crossed.theta4), 107.3985, 5e-5);
}

}  // namespace
}  // namespace nbar::ktest
