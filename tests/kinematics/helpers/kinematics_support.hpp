// Shared pieces of the kinematics verification tests: building models in code, the reference
// solutions they are checked against (Norton's closed-form four-bar, a Taylor "jet" written
// independently of nbar::Series), and positions solved to machine precision for finite
// differences.
#pragma once

#include "kinematics/workspace.hpp"
#include "nbar/kinematics/continuation.hpp"
#include "nbar/kinematics/mechanism.hpp"
#include "nbar/kinematics/position.hpp"
#include "nbar/kinematics/sweep.hpp"
#include "nbar/model/model.hpp"
#include "test_constants.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

namespace nbar::ktest {

using nbar::test_constants::kPi;

inline int add_point(Model& m, const std::string& name, Eigen::Vector2d p, bool ground = false) {
  m.points.push_back(Point{name, p, ground});
  return static_cast<int>(m.points.size()) - 1;
}

inline int add_body(Model& m, const std::string& name, std::vector<int> points,
                    std::optional<double> length = std::nullopt) {
  Body body;
  body.name = name;
  body.points = std::move(points);
  body.length = length;
  m.bodies.push_back(std::move(body));
  return static_cast<int>(m.bodies.size()) - 1;
}

inline Driver angle_driver(const std::string& name, int body, std::optional<double> from = std::nullopt,
                           std::optional<double> to = std::nullopt, double speed = 1.0, double accel = 0.0) {
  Driver d;
  d.name = name;
  d.kind = DriverKind::Angle;
  d.body = body;
  d.from = from;
  d.to = to;
  d.speed = speed;
  d.accel = accel;
  return d;
}

// Sweep options without designated initializers, which -Wextra flags when a field is left out.
inline SweepOptions sweep_options(int order, std::optional<int> steps = std::nullopt) {
  SweepOptions o;
  o.order = order;
  o.steps = steps;
  return o;
}

// a - b brought into [-pi, pi]: angles from atan2 and from a closed form agree only modulo 2 pi.
inline double angle_difference(double a, double b) { return std::remainder(a - b, 2.0 * kPi); }

inline Eigen::Vector2d polar(double length, double angle) {
  return {length * std::cos(angle), length * std::sin(angle)};
}

// ---------------------------------------------------------------------------------------------
// A truncated Taylor series in time, c[k] = f^(k)(t0) / k!. Deliberately not nbar::Series, so
// that a shared mistake in series arithmetic cannot make the solver and its reference agree.
template <int N>
struct Jet {
  std::array<double, N> c{};

  static Jet constant(double v) {
    Jet j;
    j.c[0] = v;
    return j;
  }
  // v0 + v1 t + v2 t^2 / 2: a driver moving at speed v1 with acceleration v2.
  static Jet motion(double v0, double v1, double v2) {
    Jet j;
    j.c[0] = v0;
    if (N > 1) j.c[1] = v1;
    if (N > 2) j.c[2] = 0.5 * v2;
    return j;
  }
  double derivative(int k) const {
    double f = 1.0;
    for (int i = 2; i <= k; ++i) f *= i;
    return f * c[k];
  }
};

template <int N>
Jet<N> operator+(Jet<N> a, const Jet<N>& b) {
  for (int k = 0; k < N; ++k) a.c[k] += b.c[k];
  return a;
}
template <int N>
Jet<N> operator-(Jet<N> a, const Jet<N>& b) {
  for (int k = 0; k < N; ++k) a.c[k] -= b.c[k];
  return a;
}
template <int N>
Jet<N> operator*(double s, Jet<N> a) {
  for (double& v : a.c) v *= s;
  return a;
}
template <int N>
Jet<N> operator+(Jet<N> a, double s) {
  a.c[0] += s;
  return a;
}
template <int N>
Jet<N> operator*(const Jet<N>& a, const Jet<N>& b) {
  Jet<N> r;
  for (int k = 0; k < N; ++k)
    for (int i = 0; i <= k; ++i) r.c[k] += a.c[i] * b.c[k - i];
  return r;
}
// r = sqrt(a): from r*r = a, r_k = (a_k - sum_{i=1}^{k-1} r_i r_{k-i}) / (2 r_0).
template <int N>
Jet<N> sqrt(const Jet<N>& a) {
  Jet<N> r;
  r.c[0] = std::sqrt(a.c[0]);
  for (int k = 1; k < N; ++k) {
    double s = a.c[k];
    for (int i = 1; i < k; ++i) s -= r.c[i] * r.c[k - i];
    r.c[k] = s / (2.0 * r.c[0]);
  }
  return r;
}
// s = sin a, c = cos a: s' = c a', c' = -s a', coefficient by coefficient.
template <int N>
void sincos(const Jet<N>& a, Jet<N>& s, Jet<N>& c) {
  s = Jet<N>{};
  c = Jet<N>{};
  s.c[0] = std::sin(a.c[0]);
  c.c[0] = std::cos(a.c[0]);
  for (int k = 1; k < N; ++k) {
    double ss = 0.0, cc = 0.0;
    for (int i = 1; i <= k; ++i) {
      ss += i * a.c[i] * c.c[k - i];
      cc -= i * a.c[i] * s.c[k - i];
    }
    s.c[k] = ss / k;
    c.c[k] = cc / k;
  }
}

// ---------------------------------------------------------------------------------------------
// Norton's closed-form four-bar (Design of Machinery, sections 4.5, 6.7, 7.3): crank a, coupler b,
// rocker c, ground d, angles measured in a frame whose x axis runs from O2 to O4.
struct FourBarState {
  double theta2 = 0, theta3 = 0, theta4 = 0;
  double omega2 = 0, omega3 = 0, omega4 = 0;
  double alpha2 = 0, alpha3 = 0, alpha4 = 0;
};

struct NortonFourBar {
  double a = 0, b = 0, c = 0, d = 0;

  // False when the loop cannot close at theta2.
  bool feasible(double theta2) const {
    const double k1 = d / a, k2 = d / c, k3 = (a * a - b * b + c * c + d * d) / (2 * a * c);
    const double ct = std::cos(theta2), st = std::sin(theta2);
    const double A = ct - k1 - k2 * ct + k3, B = -2 * st, C = k1 - (k2 + 1) * ct + k3;
    return B * B - 4 * A * C >= 0.0;
  }

  // open: Norton's minus root; crossed: the plus root.
  FourBarState solve(double theta2, double omega2, double alpha2, bool open) const {
    const double sgn = open ? -1.0 : 1.0;
    const double ct = std::cos(theta2), st = std::sin(theta2);
    const double k1 = d / a, k2 = d / c, k3 = (a * a - b * b + c * c + d * d) / (2 * a * c);
    const double A = ct - k1 - k2 * ct + k3, B = -2 * st, C = k1 - (k2 + 1) * ct + k3;
    const double k4 = d / b, k5 = (c * c - d * d - a * a - b * b) / (2 * a * b);
    const double D = ct - k1 + k4 * ct + k5, E = -2 * st, F = k1 + (k4 - 1) * ct + k5;
    FourBarState s;
    s.theta2 = theta2;
    s.theta4 = 2 * std::atan2(-B + sgn * std::sqrt(std::max(0.0, B * B - 4 * A * C)), 2 * A);
    s.theta3 = 2 * std::atan2(-E + sgn * std::sqrt(std::max(0.0, E * E - 4 * D * F)), 2 * D);
    const double t2 = s.theta2, t3 = s.theta3, t4 = s.theta4;
    s.omega2 = omega2;
    s.omega3 = (a * omega2 / b) * std::sin(t4 - t2) / std::sin(t3 - t4);
    s.omega4 = (a * omega2 / c) * std::sin(t2 - t3) / std::sin(t4 - t3);
    // Norton eq. 7.12.
    const double w2 = omega2, w3 = s.omega3, w4 = s.omega4;
    const double AA = c * std::sin(t4), BB = b * std::sin(t3);
    const double CC = a * alpha2 * std::sin(t2) + a * w2 * w2 * std::cos(t2) + b * w3 * w3 * std::cos(t3) -
                      c * w4 * w4 * std::cos(t4);
    const double DD = c * std::cos(t4), EE = b * std::cos(t3);
    const double FF = a * alpha2 * std::cos(t2) - a * w2 * w2 * std::sin(t2) - b * w3 * w3 * std::sin(t3) +
                      c * w4 * w4 * std::sin(t4);
    s.alpha2 = alpha2;
    s.alpha3 = (CC * DD - AA * FF) / (AA * EE - BB * DD);
    s.alpha4 = (CC * EE - BB * FF) / (AA * EE - BB * DD);
    return s;
  }

  // The crank angles where the loop can close: cos(theta2) between these bounds (from
  // |A - O4|^2 = a^2 + d^2 - 2 a d cos(theta2) lying between (b - c)^2 and (b + c)^2).
  double cos_low() const { return (a * a + d * d - (b + c) * (b + c)) / (2 * a * d); }
  double cos_high() const { return (a * a + d * d - (b - c) * (b - c)) / (2 * a * d); }
};

// The plane frame a four-bar is drawn in: origin at O2, x axis towards O4 at angle `rotation`,
// y axis turned +90 deg from it, or -90 deg for a mirrored drawing (mirror = -1).
struct DrawingFrame {
  Eigen::Vector2d origin{0, 0};
  double rotation = 0.0;
  int mirror = 1;

  Eigen::Vector2d to_world(const Eigen::Vector2d& local) const {
    const Eigen::Vector2d ex(std::cos(rotation), std::sin(rotation));
    const Eigen::Vector2d ey = mirror * Eigen::Vector2d(-ex.y(), ex.x());
    return origin + local.x() * ex + local.y() * ey;
  }
  double angle_to_world(double local) const { return rotation + mirror * local; }
  double angle_to_local(double world) const { return mirror * (world - rotation); }
  // Angular rates and their derivatives only change sign in a mirror.
  double rate_to_world(double local) const { return mirror * local; }
};

// ---------------------------------------------------------------------------------------------
// Positions at given driver values (SI), solved from a nearby pose `seed` and then polished with
// full Newton steps to machine precision: the solver stops as soon as the residual is below its
// tolerance (1e-12 of the model's size), which is too coarse for fifth finite differences.
// Returns the largest residual left in `residual`.
inline Eigen::VectorXd solve_near(const Mechanism& mech, const Eigen::VectorXd& seed, const std::vector<double>& values,
                                  double* residual = nullptr) {
  State state(mech);
  state.q = seed;
  std::vector<Series> series;
  for (double v : values) series.emplace_back(1, v);
  set_drivers(mech, state, series);
  solve_position(mech, state);
  for (int it = 0; it < 3; ++it) {
    max_residual(mech, state);
    if (!factorize_jacobian(mech, state)) break;
    State::Workspace& work = state.workspace();
    work.rhs = -work.phi;
    work.solver().solve(work.rhs, work.dq);
    state.q += work.dq;
  }
  if (residual) *residual = max_residual(mech, state);
  return state.q;
}

}  // namespace nbar::ktest
