// Properties of sweeps over random assemblable linkages: the constraints hold at every sample
// (checked from the point positions, not only from the solver's own residual), the branch never
// changes, the coupler angle moves no faster than its closed-form bound, and the motion does
// not depend on the size of the model or on its units.
#include "helpers/kinematics_support.hpp"
#include "nbar/kinematics/table.hpp"

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

namespace nbar::ktest {
namespace {

// A length in [lo, hi] on a grid of 1/1000: rapidcheck shrinks integers well.
double gen_length(double lo, double hi) {
  const int k = *rc::gen::inRange(0, 1001);
  return lo + (hi - lo) * k / 1000.0;
}

double gen_angle() { return gen_length(0, 2 * kPi); }

DrawingFrame gen_frame() {
  DrawingFrame f;
  f.origin = {gen_length(-2, 2), gen_length(-2, 2)};
  f.rotation = gen_angle();
  f.mirror = *rc::gen::element(1, -1);
  return f;
}

// A Grashof crank-rocker with the crank shortest and adjacent to the frame: a < p + q - l, with
// a margin so that it is never nearly a change point.
NortonFourBar gen_crank_rocker() {
  const double d = gen_length(0.5, 3), b = gen_length(0.5, 3), c = gen_length(0.5, 3);
  const double l = std::max({d, b, c});
  const double a_max = std::min(std::min({d, b, c}), d + b + c - 2 * l);
  RC_PRE(a_max > 0.1 * l);
  return NortonFourBar{a_max * gen_length(0.2, 0.85), b, c, d};
}

struct Built {
  Model m;
  int o2, o4, a, b, crank, coupler, rocker;
};

Built build_four_bar(const NortonFourBar& g, const DrawingFrame& frame, double drawn, bool open) {
  const FourBarState s = g.solve(drawn, 0, 0, open);
  Built r;
  r.o2 = add_point(r.m, "O2", frame.to_world({0, 0}), true);
  r.o4 = add_point(r.m, "O4", frame.to_world({g.d, 0}), true);
  r.a = add_point(r.m, "A", frame.to_world(polar(g.a, drawn)));
  r.b = add_point(r.m, "B", frame.to_world(Eigen::Vector2d(g.d, 0) + polar(g.c, s.theta4)));
  r.crank = add_body(r.m, "crank", {r.o2, r.a}, g.a);
  r.coupler = add_body(r.m, "coupler", {r.a, r.b}, g.b);
  r.rocker = add_body(r.m, "rocker", {r.o4, r.b}, g.c);
  return r;
}

// Smallest sin of the transmission angle of a crank-rocker: at theta2 = 0 or pi, where
// cos(mu) = (b^2 + c^2 - (d -+ a)^2) / (2 b c).
double min_sin_mu(const NortonFourBar& g) {
  double worst = 1;
  for (double diag : {g.d - g.a, g.d + g.a}) {
    const double cmu = (g.b * g.b + g.c * g.c - diag * diag) / (2 * g.b * g.c);
    worst = std::min(worst, std::sqrt(std::max(0.0, 1 - cmu * cmu)));
  }
  return worst;
}

RC_GTEST_PROP(SweepProperties, CrankRockerStaysClosedAndOnItsBranch, ()) {
  const NortonFourBar g = gen_crank_rocker();
  const DrawingFrame frame = gen_frame();
  const bool open = *rc::gen::arbitrary<bool>();
  const double drawn = gen_angle(), from = gen_angle();
  const int direction = *rc::gen::element(1, -1);
  const int steps = *rc::gen::inRange(37, 182);
  Built f = build_four_bar(g, frame, drawn, open);
  f.m.drivers.push_back(angle_driver("crank", f.crank, from, from + direction * 2 * kPi, direction * 3.0));
  f.m.sweep.steps = steps;
  const Mechanism mech(f.m);
  const SweepResult r = run_sweep(mech, sweep_options(1));
  RC_ASSERT(r.complete);
  RC_ASSERT(static_cast<int>(r.samples.size()) == steps);
  RC_ASSERT(r.warnings.empty());
  RC_ASSERT(mech.four_bar_loops().size() == 1u);

  const double size = mech.characteristic_length();
  const FourBarLoop& loop = mech.four_bar_loops()[0];
  const double dtheta2 = 2 * kPi / (steps - 1);
  const double ratio3 = g.a / (g.b * min_sin_mu(g)), ratio4 = g.a / (g.c * min_sin_mu(g));
  int sign0 = 0;
  double theta3_prev = 0, theta4_prev = 0;
  for (const Sample& s : r.samples) {
    RC_ASSERT(s.residual <= 1e-9 * size);
    const auto p = point_positions(mech, s.taylor.col(0));
    // The constraints, from the positions alone.
    RC_ASSERT(std::abs((p[f.a] - p[f.o2]).norm() - g.a) <= 1e-9 * size);
    RC_ASSERT(std::abs((p[f.b] - p[f.a]).norm() - g.b) <= 1e-9 * size);
    RC_ASSERT(std::abs((p[f.b] - p[f.o4]).norm() - g.c) <= 1e-9 * size);
    RC_ASSERT(std::abs(angle_difference(std::atan2((p[f.a] - p[f.o2]).y(), (p[f.a] - p[f.o2]).x()),
                                        s.driver_values[0])) <= 1e-9);
    // Velocities keep every link's length: (v_j - v_i) . (r_j - r_i) = 0.
    const Motion2 va = point_motion(mech, s, f.a), vb = point_motion(mech, s, f.b);
    const Eigen::Vector2d v_a(va.x[1], va.y[1]), v_b(vb.x[1], vb.y[1]);
    const double vscale = 3.0 * size * size * (1 + ratio3 + ratio4);
    RC_ASSERT(std::abs(v_a.dot(p[f.a] - p[f.o2])) <= 1e-9 * vscale);
    RC_ASSERT(std::abs((v_b - v_a).dot(p[f.b] - p[f.a])) <= 1e-9 * vscale);
    RC_ASSERT(std::abs(v_b.dot(p[f.b] - p[f.o4])) <= 1e-9 * vscale);

    const int sign = branch_sign(loop, p);
    const double theta3 = std::atan2((p[f.b] - p[f.a]).y(), (p[f.b] - p[f.a]).x());
    const double theta4 = std::atan2((p[f.b] - p[f.o4]).y(), (p[f.b] - p[f.o4]).x());
    if (s.step == 0) {
      sign0 = sign;
    } else {
      RC_ASSERT(sign == sign0);
      // Mean value theorem with |w3 / w2| <= a / (b sin(mu_min)): a jump to the other branch, or
      // a sample skipped around the cycle, would move the coupler much further.
      RC_ASSERT(std::abs(angle_difference(theta3, theta3_prev)) <= ratio3 * dtheta2 * (1 + 1e-6));
      RC_ASSERT(std::abs(angle_difference(theta4, theta4_prev)) <= ratio4 * dtheta2 * (1 + 1e-6));
    }
    theta3_prev = theta3;
    theta4_prev = theta4;
  }
}

// A non-Grashof linkage swept over a random part of its crank's feasible range.
RC_GTEST_PROP(SweepProperties, NonGrashofOverARandomFeasibleRange, ()) {
  const NortonFourBar g{gen_length(0.3, 3), gen_length(0.3, 3), gen_length(0.3, 3), gen_length(0.3, 3)};
  std::array<double, 4> len{g.a, g.b, g.c, g.d};
  std::sort(len.begin(), len.end());
  RC_PRE(len[0] + len[3] > (len[1] + len[2]) * 1.05);
  // The crank's feasible interval (it contains 0 or pi, or neither; see fourbar_closed_form_test).
  const double lo = g.cos_low(), hi = g.cos_high();
  RC_PRE(lo > -1 || hi < 1);
  double t_lo, t_hi;
  if (hi >= 1) {
    t_lo = -std::acos(lo);
    t_hi = std::acos(lo);
  } else if (lo <= -1) {
    t_lo = std::acos(hi);
    t_hi = 2 * kPi - std::acos(hi);
  } else {
    t_lo = std::acos(hi);
    t_hi = std::acos(lo);
  }
  const double span = t_hi - t_lo;
  RC_PRE(span > 0.05);
  // Sweep ends and drawing at least 2% of the range from the toggles.
  auto inside = [&] { return t_lo + span * gen_length(0.02, 0.98); };
  const double from = inside(), to = inside(), drawn = inside();
  RC_PRE(std::abs(to - from) > 0.01 * span);
  const bool open = *rc::gen::arbitrary<bool>();
  const DrawingFrame oriented = gen_frame();
  Built f = build_four_bar(g, oriented, drawn, open);
  const double world_from = oriented.angle_to_world(from), world_to = oriented.angle_to_world(to);
  // Time runs forward: the speed has the sign of the travel.
  f.m.drivers.push_back(
      angle_driver("crank", f.crank, world_from, world_to, std::copysign(2.0, world_to - world_from)));
  f.m.sweep.steps = 41;
  const Mechanism mech(f.m);
  const SweepResult r = run_sweep(mech, sweep_options(2));
  RC_ASSERT(r.complete);
  RC_ASSERT(r.warnings.empty());
  const double size = mech.characteristic_length();
  const FourBarLoop& loop = mech.four_bar_loops()[0];
  int sign0 = 0;
  for (const Sample& s : r.samples) {
    RC_ASSERT(s.residual <= 1e-9 * size);
    const auto p = point_positions(mech, s.taylor.col(0));
    RC_ASSERT(std::abs((p[f.b] - p[f.a]).norm() - g.b) <= 1e-9 * size);
    RC_ASSERT(std::abs((p[f.b] - p[f.o4]).norm() - g.c) <= 1e-9 * size);
    // Where the drawing's branch leads: the closed form on the same root.
    const double t2 = oriented.angle_to_local(s.driver_values[0]);
    const FourBarState ref = g.solve(t2, 0, 0, open);
    const double theta4 = oriented.angle_to_local(std::atan2((p[f.b] - p[f.o4]).y(), (p[f.b] - p[f.o4]).x()));
    RC_ASSERT(std::abs(angle_difference(theta4, ref.theta4)) <= 1e-7);
    const int sign = branch_sign(loop, p);
    if (s.step == 0) sign0 = sign;
    RC_ASSERT(sign == sign0);
  }
}

RC_GTEST_PROP(SweepProperties, SliderCrankFollowsItsClosedFormPosition, ()) {
  const double r = gen_length(0.5, 2), e = gen_length(-1, 1);
  const double L = r + std::abs(e) + gen_length(0.2, 3);
  const DrawingFrame frame = gen_frame();
  const double drawn = gen_angle(), from = gen_angle();
  auto piston = [&](double t) { return r * std::cos(t) + std::sqrt(L * L - std::pow(r * std::sin(t) - e, 2)); };
  Model m;
  const int o2 = add_point(m, "O2", frame.to_world({0, 0}), true);
  const int g1 = add_point(m, "G1", frame.to_world({-1, e}), true);
  const int g2 = add_point(m, "G2", frame.to_world({1, e}), true);
  const int a = add_point(m, "A", frame.to_world(polar(r, drawn)));
  const int c = add_point(m, "C", frame.to_world({piston(drawn), e}));
  const int crank = add_body(m, "crank", {o2, a}, r);
  add_body(m, "rod", {a, c}, L);
  const int block = add_body(m, "block", {c});
  m.sliders.push_back(Slider{block, c, {g1, g2}});
  m.drivers.push_back(angle_driver("crank", crank, frame.angle_to_world(from), frame.angle_to_world(from) + 2 * kPi));
  m.sweep.steps = 73;
  const Mechanism mech(m);
  const SweepResult res = run_sweep(mech, sweep_options(2));
  RC_ASSERT(res.complete);
  const double size = mech.characteristic_length();
  for (const Sample& s : res.samples) {
    RC_ASSERT(s.residual <= 1e-9 * size);
    const auto p = point_positions(mech, s.taylor.col(0));
    const double theta = frame.angle_to_local(s.driver_values[0]);
    const Eigen::Vector2d expected = frame.to_world({piston(theta), e});
    RC_ASSERT((p[c] - expected).norm() <= 1e-9 * size);
    RC_ASSERT(std::abs((p[c] - p[a]).norm() - L) <= 1e-9 * size);
  }
}

// The same four-bar at a random scale from 1 um to 1 km: positions and their derivatives scale,
// angles don't. A tolerance that is absolute somewhere in the solver shows up here.
RC_GTEST_PROP(SweepProperties, MotionScalesWithTheModel, ()) {
  const NortonFourBar g = gen_crank_rocker();
  const double scale = std::pow(10.0, gen_length(-6, 3));
  const double drawn = gen_angle();
  const bool open = *rc::gen::arbitrary<bool>();
  auto make = [&](double k) {
    Built f = build_four_bar(NortonFourBar{k * g.a, k * g.b, k * g.c, k * g.d}, DrawingFrame{}, drawn, open);
    f.m.drivers.push_back(angle_driver("crank", f.crank, drawn, drawn + 2 * kPi, 5.0, 3.0));
    f.m.sweep.steps = 37;
    return f;
  };
  const Built base = make(1.0), scaled = make(scale);
  const Mechanism mb(base.m), ms(scaled.m);
  const SweepResult rb = run_sweep(mb, sweep_options(3)), rs = run_sweep(ms, sweep_options(3));
  RC_ASSERT(rb.complete);
  RC_ASSERT(rs.complete);
  RC_ASSERT(rb.samples.size() == rs.samples.size());
  for (std::size_t i = 0; i < rb.samples.size(); ++i) {
    for (int pt : {base.a, base.b}) {
      const Motion2 mb_ = point_motion(mb, rb.samples[i], pt), ms_ = point_motion(ms, rs.samples[i], pt);
      for (int k = 0; k <= 3; ++k) {
        const double tol = 1e-9 * mb.characteristic_length() * std::pow(8.0 / min_sin_mu(g), k + 1);
        RC_ASSERT(std::abs(ms_.x[k] / scale - mb_.x[k]) <= tol);
        RC_ASSERT(std::abs(ms_.y[k] / scale - mb_.y[k]) <= tol);
      }
    }
    const auto ab = body_angle_motion(mb, rb.samples[i], base.coupler);
    const auto as = body_angle_motion(ms, rs.samples[i], scaled.coupler);
    RC_ASSERT(std::abs(angle_difference(ab[0], as[0])) <= 1e-9);
    for (int k = 1; k <= 3; ++k) RC_ASSERT(std::abs(ab[k] - as[k]) <= 1e-9 * std::pow(8.0 / min_sin_mu(g), k + 1));
  }
}

// Units only change how numbers are written: the table in mm is the table in m times 1000 for
// lengths, and identical for angles and times.
RC_GTEST_PROP(SweepProperties, TableUnitsOnlyScaleTheColumns, ()) {
  const NortonFourBar g = gen_crank_rocker();
  Built f = build_four_bar(NortonFourBar{0.1 * g.a, 0.1 * g.b, 0.1 * g.c, 0.1 * g.d}, gen_frame(), gen_angle(), true);
  f.m.drivers.push_back(angle_driver("crank", f.crank, 0.0, 2 * kPi, 2.0));
  f.m.sweep.steps = 19;
  f.m.units = *Units::make("m", "deg");
  Model mm = f.m;
  mm.units = *Units::make("mm", "deg");
  const Mechanism m_m(f.m), m_mm(mm);
  const ResultTable t_m = make_table(m_m, run_sweep(m_m, sweep_options(2)));
  const ResultTable t_mm = make_table(m_mm, run_sweep(m_mm, sweep_options(2)));
  RC_ASSERT(t_m.columns == t_mm.columns);
  RC_ASSERT(t_m.rows.size() == t_mm.rows.size());
  for (std::size_t c = 0; c < t_m.columns.size(); ++c) {
    const bool length = t_m.units[c].rfind("m", 0) == 0;  // m, m/s, m/s^2
    RC_ASSERT(t_mm.units[c] == (length ? "m" + t_m.units[c] : t_m.units[c]));
    for (std::size_t i = 0; i < t_m.rows.size(); ++i) {
      const double expected = (length ? 1000.0 : 1.0) * t_m.rows[i][c];
      RC_ASSERT(std::abs(t_mm.rows[i][c] - expected) <= 1e-12 * (1 + std::abs(expected)));
    }
  }
}

}  // namespace
}  // namespace nbar::ktest
