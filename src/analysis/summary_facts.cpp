// The facts a course asks of a slider-crank and of a quick-return, from the model's geometry:
// stroke, dead centres, swing and time ratio, by the closed forms of the textbooks.
#include "nbar/analysis/summary_facts.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <utility>
#include <vector>

#include "model/plane_vectors.hpp"
#include "nbar/kinematics/continuation.hpp"
#include "nbar/kinematics/loop_closure.hpp"
#include "nbar/kinematics/loops.hpp"

namespace nbar {

namespace {

constexpr double kTurn = 2 * std::numbers::pi;

double polar_angle(const Eigen::Vector2d& v) { return std::atan2(v.y(), v.x()); }

bool has_point(const Body& b, int p) { return std::find(b.points.begin(), b.points.end(), p) != b.points.end(); }

// How a crank's direction pivot -> pin maps to its input angle, and which way it turns.
struct CrankMeasure {
  double offset = 0;  // input = direction + offset
  double base = 0;    // angles are given in [base, base + 2 pi)
  double sense = 1;   // +1 counter-clockwise
  int driver = -1;
};

CrankMeasure crank_measure(const Model& m, int crank, int pivot, int pin) {
  CrankMeasure c;
  const Body& body = m.bodies[crank];
  const auto position = [&](int p) { return m.points[p].position; };
  c.offset = std::remainder(
      polar_angle(position(body.points[1]) - position(body.points[0])) - polar_angle(position(pin) - position(pivot)),
      kTurn);
  for (std::size_t d = 0; d < m.drivers.size(); ++d) {
    const Driver& drv = m.drivers[d];
    if (drv.kind != DriverKind::Angle || drv.body != crank || drv.relative_to >= 0) continue;
    c.driver = static_cast<int>(d);
    c.base = drv.from.value_or(0.0);
    const double direction = drv.to && drv.from && *drv.to != *drv.from ? *drv.to - *drv.from : drv.speed;
    c.sense = direction < 0 ? -1.0 : 1.0;
    break;
  }
  return c;
}

// The input angle of a crank direction, in [base, base + 2 pi).
double input_angle(const CrankMeasure& c, double direction) {
  const double a = direction + c.offset;
  return c.base + std::fmod(std::fmod(a - c.base, kTurn) + kTurn, kTurn);
}

// Crank turn from `from` to `to` in its sense of rotation, in [0, 2 pi).
double turn_between(const CrankMeasure& c, double from, double to) {
  return std::fmod(std::fmod(c.sense * (to - from), kTurn) + kTurn, kTurn);
}

std::string angle_text(const Model& m, const CrankMeasure& c, double si) {
  if (c.driver >= 0) return format_driver_value(m, c.driver, si);
  return fmt::format("{:.6g} {}", si / m.units.angle_scale, m.units.angle);
}

std::string length_text(const Model& m, double si) {
  return fmt::format("{:.6g} {}", si / m.units.length_scale, m.units.length);
}

// A crank on the ground whose pin is `pin`: {crank body, pivot point}, or {-1, -1}.
std::pair<int, int> crank_at(const Model& m, int pin, std::initializer_list<int> not_these) {
  for (std::size_t k = 0; k < m.bodies.size(); ++k) {
    const Body& b = m.bodies[k];
    if (std::find(not_these.begin(), not_these.end(), static_cast<int>(k)) != not_these.end()) continue;
    if (!has_point(b, pin)) continue;
    for (int o : b.points)
      if (o != pin && m.points[o].ground) return {static_cast<int>(k), o};
  }
  return {-1, -1};
}

void add_slider_crank(const Model& m, const Slider& s, std::vector<SliderCrankSummary>& out) {
  if (!m.points[s.along[0]].ground || !m.points[s.along[1]].ground) return;
  const int c_point = s.point;
  for (std::size_t r = 0; r < m.bodies.size(); ++r) {
    const Body& rod = m.bodies[r];
    if (static_cast<int>(r) == s.body || !has_point(rod, c_point)) continue;
    for (int pin : rod.points) {
      if (pin == c_point || m.points[pin].ground) continue;
      const auto [crank, pivot] = crank_at(m, pin, {static_cast<int>(r), s.body});
      if (crank < 0 || has_point(m.bodies[crank], c_point)) continue;
      SliderCrankSummary f;
      f.crank = m.bodies[crank].name;
      f.rod = rod.name;
      f.slider = m.bodies[s.body].name;
      const double cr = f.crank_length = link_length(m, crank, pivot, pin);
      const double l = f.rod_length = link_length(m, static_cast<int>(r), pin, c_point);
      const Eigen::Vector2d g0 = m.points[s.along[0]].position, o = m.points[pivot].position;
      const Eigen::Vector2d u = (m.points[s.along[1]].position - g0).normalized();
      const Eigen::Vector2d foot = g0 + u * (o - g0).dot(u);
      const double e = f.offset = (foot - o).norm();
      const double side = (m.points[c_point].position - foot).dot(u) < 0 ? -1.0 : 1.0;
      // Strictly: with rod - crank = offset the folded dead centre is a lock, not a turning point.
      f.crank_turns_fully = l - cr > e + 1e-9 * (l + cr);
      const CrankMeasure measure = crank_measure(m, crank, pivot, pin);
      if (!f.crank_turns_fully && measure.driver < 0) continue;  // a rocker driving a slider, not a crank
      if (!f.crank_turns_fully) {
        f.description = fmt::format(
            "slider-crank {}-{}-{}: crank {}, rod {}, offset {}: the crank cannot turn fully "
            "(rod - crank is not longer than the offset)",
            f.crank, f.rod, f.slider, length_text(m, cr), length_text(m, l), length_text(m, e));
        out.push_back(std::move(f));
        continue;
      }
      const double far = std::sqrt((l + cr) * (l + cr) - e * e), near = std::sqrt((l - cr) * (l - cr) - e * e);
      f.stroke = far - near;
      f.outer_dead_centre = input_angle(measure, polar_angle(foot + side * far * u - o));
      f.inner_dead_centre = input_angle(measure, polar_angle(o - (foot + side * near * u)));
      f.outstroke_turn = turn_between(measure, f.inner_dead_centre, f.outer_dead_centre);
      f.return_turn = kTurn - f.outstroke_turn;
      f.time_ratio = std::max(f.outstroke_turn, f.return_turn) / std::min(f.outstroke_turn, f.return_turn);
      const double unit = m.units.angle_scale;
      f.description = fmt::format(
          "slider-crank {}-{}-{}: crank {}, rod {}, offset {}; stroke {}; dead centres at {} {} (outer) and {} "
          "(inner); "
          "the outstroke takes {:.6g} {} of crank turn, the return {:.6g} {}: time ratio {:.4g}",
          f.crank, f.rod, f.slider, length_text(m, cr), length_text(m, l), length_text(m, e), length_text(m, f.stroke),
          measure.driver >= 0 ? m.drivers[measure.driver].name : f.crank, angle_text(m, measure, f.outer_dead_centre),
          angle_text(m, measure, f.inner_dead_centre), f.outstroke_turn / unit, m.units.angle, f.return_turn / unit,
          m.units.angle, f.time_ratio);
      out.push_back(std::move(f));
    }
  }
}

// A crank pin `pin` moving along the line through `along`, points of an arm pivoted on the ground.
void add_quick_return(const Model& m, int pin, std::array<int, 2> along, int block,
                      std::vector<QuickReturnSummary>& out) {
  for (std::size_t a = 0; a < m.bodies.size(); ++a) {
    const Body& arm = m.bodies[a];
    if (static_cast<int>(a) == block || !has_point(arm, along[0]) || !has_point(arm, along[1])) continue;
    int arm_pivot = -1;
    for (int p : arm.points)
      if (m.points[p].ground) arm_pivot = p;
    if (arm_pivot < 0) continue;
    const auto [crank, pivot] = crank_at(m, pin, {static_cast<int>(a), block});
    if (crank < 0 || pivot == arm_pivot) continue;
    const Eigen::Vector2d o2 = m.points[pivot].position, o4 = m.points[arm_pivot].position;
    const Eigen::Vector2d g0 = m.points[along[0]].position, g1 = m.points[along[1]].position;
    const double d = (o4 - o2).norm();
    // Only a slot through the arm's pivot has the textbook's closed form.
    if (std::abs(cross(g1 - g0, o4 - g0)) > 1e-9 * (g1 - g0).norm() * d) continue;
    QuickReturnSummary f;
    f.crank = m.bodies[crank].name;
    f.arm = arm.name;
    const double r = f.crank_length = link_length(m, crank, pivot, pin);
    f.pivot_distance = d;
    f.arm_turns_fully = r >= d;
    const CrankMeasure measure = crank_measure(m, crank, pivot, pin);
    if (f.arm_turns_fully) {
      f.description = fmt::format("quick-return {}-{}: crank {} >= pivot distance {}: the arm turns fully (Whitworth)",
                                  f.crank, f.arm, length_text(m, r), length_text(m, d));
      out.push_back(std::move(f));
      continue;
    }
    // Limits: the crank perpendicular to the arm, its pin at acos(r / d) either side of o2 -> o4.
    const double half = std::acos(r / d), towards = polar_angle(o4 - o2);
    f.swing = 2 * std::asin(r / d);
    f.limit_from = input_angle(measure, towards - half);
    f.limit_to = input_angle(measure, towards + half);
    f.fast_turn = 2 * half;  // the short arc, past the arm's pivot side
    f.slow_turn = kTurn - f.fast_turn;
    f.time_ratio = f.slow_turn / f.fast_turn;
    const double unit = m.units.angle_scale;
    f.description = fmt::format(
        "quick-return {}-{}: crank {}, pivots {} apart; the arm swings {:.6g} {}; its limits at {} {} and {}; one "
        "stroke "
        "takes {:.6g} {} of crank turn, the other {:.6g} {}: time ratio {:.4g}",
        f.crank, f.arm, length_text(m, r), length_text(m, d), f.swing / unit, m.units.angle,
        measure.driver >= 0 ? m.drivers[measure.driver].name : f.crank, angle_text(m, measure, f.limit_from),
        angle_text(m, measure, f.limit_to), f.slow_turn / unit, m.units.angle, f.fast_turn / unit, m.units.angle,
        f.time_ratio);
    out.push_back(std::move(f));
  }
}

// Where the coupler pin b lies when the crank (length a, about o2) and the coupler (length
// b_len) are in line, stretched (sign +1) or folded (-1), with the output (length c about o4) on
// the loop's branch `branch`: {crank pin, coupler pin}, or nothing when the loop cannot get there.
std::optional<std::pair<Eigen::Vector2d, Eigen::Vector2d>> in_line(const FourBarLoop& loop,
                                                                   std::vector<Eigen::Vector2d> p, double a,
                                                                   double b_len, double c, double sign, int branch) {
  const Eigen::Vector2d o2 = p[loop.o2], o4 = p[loop.o4];
  const double r = b_len + sign * a, d = (o4 - o2).norm();
  if (!(r > 0.0) || !(d > 0.0)) return std::nullopt;
  const double along = (r * r - c * c + d * d) / (2 * d), across2 = r * r - along * along;
  if (across2 < 0.0) return std::nullopt;
  const Eigen::Vector2d u = (o4 - o2) / d, n(-u.y(), u.x());
  for (double side : {1.0, -1.0}) {
    const Eigen::Vector2d pin = o2 + along * u + side * std::sqrt(across2) * n;
    p[loop.b] = pin;
    p[loop.a] = o2 + sign * a * (pin - o2) / r;
    if (branch_sign(loop, p) == branch) return std::make_pair(p[loop.a], pin);
  }
  return std::nullopt;
}

}  // namespace

void add_rocker_swing(const Mechanism& mech, const std::vector<Eigen::Vector2d>& p, LoopSummary& l) {
  const Model& m = mech.model();
  const FourBarLoop& loop = l.loop;
  const GrashofReport& g = l.grashof;
  if (loop.frame >= 0 || !g.input_turns_fully || g.output_turns_fully) return;
  const Body& output = m.bodies[loop.output];
  if (m.bodies[loop.input].points.size() < 2 || output.points.size() < 2) return;
  const int branch = branch_sign(loop, p);
  const auto stretched = in_line(loop, p, g.input, g.coupler, g.output, 1.0, branch);
  const auto folded = in_line(loop, p, g.input, g.coupler, g.output, -1.0, branch);
  if (!stretched || !folded) return;
  const CrankMeasure crank = crank_measure(m, loop.input, loop.o2, loop.a);
  // An input moved by the rest of a machine may swing instead of turning: its rocker's limits
  // would not be the motion's. Only a crank turned by its own driver has them.
  if (crank.driver < 0) return;
  // The rocker's angle as its column has it, on the start's side of the turn.
  const double rocker_now = polar_angle(p[output.points[1]] - p[output.points[0]]);
  const double offset = rocker_now - polar_angle(p[loop.b] - p[loop.o4]);
  const auto rocker_angle = [&](const Eigen::Vector2d& pin) {
    return rocker_now + std::remainder(polar_angle(pin - p[loop.o4]) + offset - rocker_now, kTurn);
  };
  RockerSwing r;
  r.crank_stretched = input_angle(crank, polar_angle(stretched->first - p[loop.o2]));
  r.crank_folded = input_angle(crank, polar_angle(folded->first - p[loop.o2]));
  r.rocker_stretched = rocker_angle(stretched->second);
  r.rocker_folded = rocker_angle(folded->second);
  r.swing = std::abs(r.rocker_stretched - r.rocker_folded);
  r.turn_to_stretched = turn_between(crank, r.crank_folded, r.crank_stretched);
  r.turn_to_folded = kTurn - r.turn_to_stretched;
  r.time_ratio = std::max(r.turn_to_stretched, r.turn_to_folded) / std::min(r.turn_to_stretched, r.turn_to_folded);
  const double unit = m.units.angle_scale;
  r.description = fmt::format(
      "the rocker {} swings {:.6g} {}, between {:.6g} {} (crank and coupler stretched in line, {} at {}) and "
      "{:.6g} {} (folded, at {}); the crank turns {:.6g} {} from folded to stretched and {:.6g} {} back: time "
      "ratio {:.4g}",
      output.name, r.swing / unit, m.units.angle, r.rocker_stretched / unit, m.units.angle,
      m.drivers[crank.driver].name, angle_text(m, crank, r.crank_stretched), r.rocker_folded / unit, m.units.angle,
      angle_text(m, crank, r.crank_folded), r.turn_to_stretched / unit, m.units.angle, r.turn_to_folded / unit,
      m.units.angle, r.time_ratio);
  l.rocker = std::move(r);
}

void summarize_crank_mechanisms(const Model& m, ModelSummary& out) {
  for (const Slider& s : m.sliders) {
    add_slider_crank(m, s, out.slider_cranks);
    if (m.bodies[s.body].points.size() == 1) add_quick_return(m, s.point, s.along, s.body, out.quick_returns);
  }
  for (const Slot& s : m.slots) add_quick_return(m, s.point, s.along, -1, out.quick_returns);
}

}  // namespace nbar
