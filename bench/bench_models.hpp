// Models shared by the benchmarks: a crank-rocker four-bar and chains of N four-bar loops.
#pragma once

#include <Eigen/Core>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "nbar/model/geometry.hpp"
#include "nbar/model/materials.hpp"
#include "nbar/model/model.hpp"

namespace nbar_bench {

inline constexpr double kPi = std::numbers::pi;
inline constexpr int kStepsPerTurn = 360;  // a 361-sample sweep of one turn
inline constexpr int kOrder = 2;           // position, velocity, acceleration

[[noreturn]] inline void die(const std::string& message) {
  std::fprintf(stderr, "bench: %s\n", message.c_str());
  std::fflush(stderr);
  std::abort();
}

// prefix + i, built by appending: GCC 12 warns falsely (-Wrestrict, PR 105651) on "G" + to_string(i).
inline std::string indexed(const char* prefix, int i) {
  std::string s(prefix);
  s += std::to_string(i);
  return s;
}

// Model entities by member rather than aggregate initialisation, so that fields added to them
// later keep their defaults without warnings.
inline nbar::Point point(std::string name, const Eigen::Vector2d& position, bool ground) {
  nbar::Point p;
  p.name = std::move(name);
  p.position = position;
  p.ground = ground;
  return p;
}

inline nbar::Body body(std::string name, std::vector<int> points, std::optional<double> length = std::nullopt) {
  nbar::Body b;
  b.name = std::move(name);
  b.points = std::move(points);
  b.length = length;
  return b;
}

inline Eigen::Vector2d unit(double angle) { return {std::cos(angle), std::sin(angle)}; }

// Where the coupler-output pin of a four-bar lies: the intersection of the circle of radius
// `coupler` about the crank pin `a` with the circle of radius `output` about the output pivot
// `o4`, on the left of the line from a to o4 when `left` (one assembly branch), else the right.
inline Eigen::Vector2d coupler_output_pin(const Eigen::Vector2d& a, const Eigen::Vector2d& o4, double coupler,
                                          double output, bool left) {
  const Eigen::Vector2d d = o4 - a;
  const double dist = d.norm();
  const double along = (coupler * coupler - output * output + dist * dist) / (2.0 * dist);
  const double h2 = coupler * coupler - along * along;
  if (!(h2 > 0.0)) die("four-bar cannot be assembled in the drawn pose");
  const Eigen::Vector2d e = d / dist, n(-e.y(), e.x());
  return a + along * e + (left ? 1.0 : -1.0) * std::sqrt(h2) * n;
}

// Crank-rocker four-bar without coupler point: ground 0.200, crank 0.080, coupler 0.180,
// rocker 0.150 m (Grashof: 0.080 + 0.200 < 0.180 + 0.150, shortest link next to the frame).
// The crank turns one full revolution at 120 rpm.
inline nbar::Model four_bar_model() {
  const double ground = 0.200, crank = 0.080, coupler = 0.180, rocker = 0.150;
  const Eigen::Vector2d o2(0.0, 0.0), o4(ground, 0.0), a(crank, 0.0);
  const Eigen::Vector2d b = coupler_output_pin(a, o4, coupler, rocker, true);
  nbar::Model m;
  m.name = "crank-rocker four-bar";
  m.points = {point("O2", o2, true), point("O4", o4, true), point("A", a, false), point("B", b, false)};
  m.bodies = {body("crank", {0, 2}, crank), body("coupler", {2, 3}, coupler), body("rocker", {1, 3}, rocker)};
  nbar::Driver d;
  d.name = "crank";
  d.kind = nbar::DriverKind::Angle;
  d.body = 0;
  d.from = 0.0;
  d.to = 2.0 * kPi;
  d.speed = 4.0 * kPi;  // 120 rpm
  m.drivers = {d};
  m.sweep.steps = kStepsPerTurn + 1;
  return m;
}

// A chain of N four-bar loops with one degree of freedom, every link turning fully.
//
// Ground pivots G0..GN lie on the x axis, one frame length (0.01 m) apart. Loop i has the frame Gi-G(i+1), the
// crank Gi-Ai, the coupler Ai-Bi and the output G(i+1)-Bi. The output of loop i is a ternary
// link G(i+1), Bi, A(i+1) whose third point, diametrically opposite Bi about G(i+1), is the
// crank pin of loop i+1.
//
// Every loop is the same Grashof double-crank (the frame is the shortest link: s + l = 1 + 2.5
// < p + q = 2 + 2.2, well away from a change point), with crank and output lengths swapped in
// odd loops. With the pin opposite Bi, loop i+1 is then loop i run backwards turned by half a
// turn: if loop i maps crank angle th to output angle ph, loop i+1 maps ph + pi to th + pi. The
// input-output relation of consecutive loops cancels, so every even loop's crank turns exactly
// with the input and every odd loop's crank with loop 0's output: velocity ratios stay bounded
// however long the chain, and no loop comes near a toggle.
inline nbar::Model chain_model(int loops) {
  if (loops < 1) die("a chain needs at least one loop");
  const double s = 0.01;  // m per unit of length
  const double frame = 1.0 * s, coupler = 2.5 * s;
  const double la = 2.0 * s, lc = 2.2 * s;  // crank and output of even loops; swapped in odd loops
  const double theta0 = 0.3;                // drawn input angle, rad

  nbar::Model m;
  m.name = "chain of " + std::to_string(loops) + " four-bars";
  m.points.reserve(3 * loops + 1);
  for (int i = 0; i <= loops; ++i) m.points.push_back(point(indexed("G", i), {i * frame, 0.0}, true));
  auto g = [](int i) { return i; };
  auto a = [loops](int i) { return loops + 1 + 2 * i; };
  auto b = [loops](int i) { return loops + 2 + 2 * i; };

  // Drawn pose: loop 0 at theta0 with B0 left of the line A0-G1 (above it); then the cancelling
  // relation gives every other loop in closed form.
  const Eigen::Vector2d a0 = unit(theta0) * la;
  const Eigen::Vector2d b0 = coupler_output_pin(a0, {frame, 0.0}, coupler, lc, true);
  const double phi0 = std::atan2(b0.y(), b0.x() - frame);
  for (int i = 0; i < loops; ++i) {
    const Eigen::Vector2d gi(i * frame, 0.0), gn((i + 1) * frame, 0.0);
    Eigen::Vector2d pa, pb;
    if (i % 2 == 0) {
      pa = gi + la * unit(theta0);
      pb = gn + lc * unit(phi0);
    } else {
      pa = gi + lc * unit(phi0 + kPi);
      pb = gn + la * unit(theta0 + kPi);
    }
    m.points.push_back(point(indexed("A", i), pa, false));
    m.points.push_back(point(indexed("B", i), pb, false));
  }

  m.bodies.reserve(2 * loops + 1);
  m.bodies.push_back(body("crank0", {g(0), a(0)}, la));
  for (int i = 0; i < loops; ++i) {
    m.bodies.push_back(body(indexed("coupler", i), {a(i), b(i)}, coupler));
    const double out = i % 2 == 0 ? lc : la;
    if (i + 1 < loops)
      m.bodies.push_back(body(indexed("output", i), {g(i + 1), b(i), a(i + 1)}));  // lengths: 2-point bodies only
    else
      m.bodies.push_back(body(indexed("output", i), {g(i + 1), b(i)}, out));
  }

  nbar::Driver d;
  d.name = "input";
  d.kind = nbar::DriverKind::Angle;
  d.body = 0;
  d.from = theta0;
  d.to = theta0 + 2.0 * kPi;
  d.speed = 2.0 * kPi;  // 60 rpm
  m.drivers = {d};
  m.sweep.steps = kStepsPerTurn + 1;
  return m;
}

// The chain of `loops` four-bars with every link cut from 4 x 3 mm steel bar, under gravity:
// 2 * loops + 1 bodies with mass, for the dynamics, FE and simulation benchmarks.
inline nbar::Model steel_chain(int loops) {
  nbar::Model m = chain_model(loops);
  const nbar::Material steel = *nbar::builtin_material("steel");
  for (nbar::Body& b : m.bodies) {
    const Eigen::Vector2d p = m.points[b.points[0]].position, q = m.points[b.points[1]].position;
    b.shape = nbar::make_bar(p, q, 0.004, 0.003, 0.001, 0.001);
    b.thickness = 0.003;
    b.material = steel;
  }
  m.gravity = {0.0, -9.81};
  return m;
}

}  // namespace nbar_bench
