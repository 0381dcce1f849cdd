// The step-by-step explanation: every equation written from the solver's own rows
// (Mechanism::equations().rows, kinematics/constraints.cpp), Newton's iterations recorded by the solver itself
// (solve_position with a NewtonTrace), and the velocity and acceleration systems from the same
// Taylor recursion the sweep uses. Rendering is in explain_render.cpp.
#include "nbar/analysis/explain.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "explain_expr.hpp"
#include "kinematics/constraints.hpp"
#include "kinematics/rocking.hpp"
#include "model/plane_vectors.hpp"
#include "nbar/dynamics/inverse_dynamics.hpp"
#include "nbar/kinematics/position.hpp"
#include "nbar/kinematics/sweep.hpp"

namespace nbar {

namespace {

using explain_detail::call;
using explain_detail::E;
using explain_detail::latex_name;
using explain_detail::mul;
using explain_detail::num;
using explain_detail::plain_name;
using explain_detail::scale;
using explain_detail::sq;
using explain_detail::sum;
using explain_detail::sym;

// The equations of the rows, written with the model's names and numbers in its units.
class RowWriter {
 public:
  explicit RowWriter(const Mechanism& mech) : mech_(mech), m_(mech.model()), ls_(m_.units.length_scale) {}

  EquationRow write(int r) {
    const Constraint& c = mech_.equations().rows[r];
    EquationRow row;
    row.label = c.label;
    row.source = c.source;
    row.driver = c.is_driver();
    derivatives_.clear();
    const E f = equation(c, row);
    row.text = explain_detail::text(f) + " = 0";
    row.latex = explain_detail::latex(f) + " = 0";
    for (const auto& [column, parts] : derivatives_) {
      std::vector<std::pair<double, E>> terms;
      for (const E& e : parts) terms.push_back({1.0, e});
      const E d = sum(terms);
      if (explain_detail::is_zero(d)) continue;
      row.jacobian.push_back({column, explain_detail::text(d), explain_detail::latex(d)});
    }
    return row;
  }

  // The driver's symbol: th_<name> for angles, s_<name> for distances and slides.
  E driver_symbol(int d) const {
    const Driver& drv = m_.drivers[d];
    if (drv.is_angular()) return sym("th_" + plain_name(drv.name), "\\theta_{" + latex_name(drv.name) + "}");
    return sym("s_" + plain_name(drv.name), "s_{" + latex_name(drv.name) + "}");
  }

 private:
  // The equation of row `c` (= 0), its derivatives added by column; sets the row's kind and scale.
  E equation(const Constraint& c, EquationRow& row) {
    switch (c.type) {
      case ConstraintType::Distance:
      case ConstraintType::DriveDistance: return distance(c, row);
      case ConstraintType::RigidX: return rigid_x(c, row);
      case ConstraintType::RigidY: return rigid_y(c, row);
      case ConstraintType::PointOnLine: return point_on_line(c, row);
      case ConstraintType::Orientation:
      case ConstraintType::DriveRelativeAngle: return orientation(c, row);
      case ConstraintType::DriveAngle: return drive_angle(c, row);
      case ConstraintType::DriveSlide: return drive_slide(c, row);
    }
    return E{};
  }

  E distance(const Constraint& c, EquationRow& row) {
    const auto& p = c.p;
    const E length = c.type == ConstraintType::Distance ? num(c.a / ls_) : driver_symbol(c.driver);
    const E f = sum({{1, sq(dx(p[0], p[1]))}, {1, sq(dy(p[0], p[1]))}, {-1, sq(length)}});
    add(p[1], 0, scale(dx(p[0], p[1]), 2));
    add(p[1], 1, scale(dy(p[0], p[1]), 2));
    add(p[0], 0, scale(dx(p[0], p[1]), -2));
    add(p[0], 1, scale(dy(p[0], p[1]), -2));
    row.kind = c.type == ConstraintType::Distance ? "distance" : "driver";
    row.scale = c.scale * ls_;
    return f;
  }

  E rigid_x(const Constraint& c, EquationRow& row) {
    const auto& p = c.p;
    const E f = sum({{1, x(p[2])}, {-1, x(p[0])}, {-c.a, dx(p[0], p[1])}, {c.b, dy(p[0], p[1])}});
    add(p[2], 0, num(1));
    add(p[1], 0, num(-c.a));
    add(p[1], 1, num(c.b));
    add(p[0], 0, num(c.a - 1));
    add(p[0], 1, num(-c.b));
    row.kind = "rigid_x";
    row.scale = 1.0;
    return f;
  }

  E rigid_y(const Constraint& c, EquationRow& row) {
    const auto& p = c.p;
    const E f = sum({{1, y(p[2])}, {-1, y(p[0])}, {-c.a, dy(p[0], p[1])}, {-c.b, dx(p[0], p[1])}});
    add(p[2], 1, num(1));
    add(p[1], 1, num(-c.a));
    add(p[1], 0, num(-c.b));
    add(p[0], 1, num(c.a - 1));
    add(p[0], 0, num(c.b));
    row.kind = "rigid_y";
    row.scale = 1.0;
    return f;
  }

  E point_on_line(const Constraint& c, EquationRow& row) {
    const auto& p = c.p;
    // (rk - ri) x (rj - ri)
    const E ex = dx(p[0], p[2]), ey = dy(p[0], p[2]), wx = dx(p[0], p[1]), wy = dy(p[0], p[1]);
    const E f = sum({{1, mul(ex, wy)}, {-1, mul(ey, wx)}});
    add(p[2], 0, wy);
    add(p[2], 1, scale(wx, -1));
    add(p[1], 0, scale(ey, -1));
    add(p[1], 1, ex);
    add(p[0], 0, dy(p[1], p[2]));
    add(p[0], 1, dx(p[2], p[1]));
    row.kind = "point_on_line";
    row.scale = c.scale * ls_;
    return f;
  }

  E orientation(const Constraint& c, EquationRow& row) {
    const auto& p = c.p;
    // (rj - ri) x R (rn - rm), R the rotation by phi0 (constants a, b) or by the driver.
    E cs, sn;
    if (c.type == ConstraintType::Orientation) {
      cs = num(c.a);
      sn = num(c.b);
    } else {
      cs = call(false, driver_symbol(c.driver));
      sn = call(true, driver_symbol(c.driver));
    }
    const E vx = dx(p[0], p[1]), vy = dy(p[0], p[1]), wx = dx(p[2], p[3]), wy = dy(p[2], p[3]);
    const E zx = sum({{1, mul(cs, wx)}, {-1, mul(sn, wy)}});
    const E zy = sum({{1, mul(sn, wx)}, {1, mul(cs, wy)}});
    const E f = sum({{1, mul(vx, zy)}, {-1, mul(vy, zx)}});
    add(p[1], 0, zy);
    add(p[1], 1, scale(zx, -1));
    add(p[0], 0, scale(zy, -1));
    add(p[0], 1, zx);
    const E gx = sum({{1, mul(sn, vx)}, {-1, mul(cs, vy)}});
    const E gy = sum({{1, mul(cs, vx)}, {1, mul(sn, vy)}});
    add(p[3], 0, gx);
    add(p[3], 1, gy);
    add(p[2], 0, scale(gx, -1));
    add(p[2], 1, scale(gy, -1));
    row.kind = c.type == ConstraintType::Orientation ? "orientation" : "driver";
    row.scale = c.scale * ls_;
    return f;
  }

  E drive_angle(const Constraint& c, EquationRow& row) {
    const auto& p = c.p;
    const E th = driver_symbol(c.driver);
    const E cs = call(false, th), sn = call(true, th);
    const E f = sum({{1, mul(dx(p[0], p[1]), sn)}, {-1, mul(dy(p[0], p[1]), cs)}});
    add(p[1], 0, sn);
    add(p[1], 1, scale(cs, -1));
    add(p[0], 0, scale(sn, -1));
    add(p[0], 1, cs);
    row.kind = "driver";
    row.scale = c.scale;
    return f;
  }

  E drive_slide(const Constraint& c, EquationRow& row) {
    const auto& p = c.p;
    // (rk - ri).(rj - ri) / Lg - s
    const double k = ls_ / c.a;  // 1 / Lg in model units
    const E ex = dx(p[0], p[2]), ey = dy(p[0], p[2]), wx = dx(p[0], p[1]), wy = dy(p[0], p[1]);
    const E f = sum({{k, mul(ex, wx)}, {k, mul(ey, wy)}, {-1, driver_symbol(c.driver)}});
    add(p[2], 0, scale(wx, k));
    add(p[2], 1, scale(wy, k));
    add(p[1], 0, scale(ex, k));
    add(p[1], 1, scale(ey, k));
    add(p[0], 0, sum({{-k, wx}, {-k, ex}}));
    add(p[0], 1, sum({{-k, wy}, {-k, ey}}));
    row.kind = "driver";
    row.scale = 1.0;
    return f;
  }

  E coordinate(int point, int axis) const {
    if (mech_.column_of(point) < 0) return num(m_.points[point].position[axis] / ls_);
    const std::string& n = m_.points[point].name;
    const char* a = axis == 0 ? "x" : "y";
    return sym(std::string(a) + "_" + plain_name(n), std::string(a) + "_{" + latex_name(n) + "}");
  }
  E x(int point) const { return coordinate(point, 0); }
  E y(int point) const { return coordinate(point, 1); }
  E dx(int from, int to) const { return sum({{1, x(to)}, {-1, x(from)}}); }
  E dy(int from, int to) const { return sum({{1, y(to)}, {-1, y(from)}}); }
  void add(int point, int axis, E e) {
    const int col = mech_.column_of(point);
    if (col < 0) return;
    derivatives_[col + axis].push_back(std::move(e));
  }

  const Mechanism& mech_;
  const Model& m_;
  double ls_;
  std::map<int, std::vector<E>> derivatives_;  // of the row being written, by column
};

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// A point's position and velocity in model units, from q and qdot (ground points: drawn, at rest).
Eigen::Vector2d position_at(const Mechanism& mech, const Eigen::VectorXd& q, int p) {
  const Model& m = mech.model();
  const int col = mech.column_of(p);
  return col < 0 ? Eigen::Vector2d(m.points[p].position / m.units.length_scale) : Eigen::Vector2d(q.segment<2>(col));
}

Eigen::Vector2d velocity_at(const Mechanism& mech, const Eigen::VectorXd& qdot, int p) {
  const int col = mech.column_of(p);
  return col < 0 ? Eigen::Vector2d::Zero() : Eigen::Vector2d(qdot.segment<2>(col));
}

// A link's velocity field: v at r, turning at omega.
struct Link {
  int body;
  std::string name;
  Eigen::Vector2d r{0, 0}, v{0, 0};
  double omega = 0.0;
  std::vector<int> points;
};

// The ground and every link with an angle; `speed` the largest speed of the field (a point's,
// or omega times the mechanism's size `lc`).
std::vector<Link> moving_links(const Mechanism& mech, const Eigen::VectorXd& q, const Eigen::VectorXd& qdot, double lc,
                               double& speed, std::vector<std::string>& notes) {
  const Model& m = mech.model();
  std::vector<Link> links;
  Link ground{-1, "ground", {0, 0}, {0, 0}, 0.0, {}};
  for (std::size_t p = 0; p < m.points.size(); ++p)
    if (m.points[p].ground) ground.points.push_back(static_cast<int>(p));
  links.push_back(ground);
  speed = 0.0;
  std::vector<std::string> skipped;
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const BodyFrame f = body_frame(m, static_cast<int>(b));
    if (f.from < 0) {
      skipped.push_back(m.bodies[b].name);
      continue;
    }
    Link l;
    l.body = static_cast<int>(b);
    l.name = m.bodies[b].name;
    l.points = m.bodies[b].points;
    l.r = position_at(mech, q, f.origin);
    l.v = velocity_at(mech, qdot, f.origin);
    const Eigen::Vector2d u = position_at(mech, q, f.to) - position_at(mech, q, f.from),
                          du = velocity_at(mech, qdot, f.to) - velocity_at(mech, qdot, f.from);
    l.omega = cross2(u, du) / u.squaredNorm();
    speed = std::max({speed, l.v.norm(), std::abs(l.omega) * lc});
    links.push_back(l);
  }
  if (!skipped.empty()) {
    std::string names;
    for (const auto& s : skipped) names += (names.empty() ? "" : ", ") + s;
    notes.push_back("no instant centres for " + names +
                    ": a link of one point with no guide has no angle, so its rotation is not defined");
  }
  if (speed == 0.0) notes.push_back("the mechanism is at rest at this instant: its instant centres are not defined");
  return links;
}

// The instant centre of links a and b: at their shared joint, where their velocity fields agree,
// or at infinity when they turn alike.
InstantCentre instant_centre(const Mechanism& mech, const Eigen::VectorXd& q, const Link& a, const Link& b, double lc,
                             double speed) {
  InstantCentre c;
  c.body_a = a.body;
  c.body_b = b.body;
  c.name = "I(" + a.name + "," + b.name + ")";
  int shared = -1;
  for (int p : a.points)
    if (std::find(b.points.begin(), b.points.end(), p) != b.points.end()) {
      shared = p;
      break;
    }
  const double dw = a.omega - b.omega;
  // Relative velocity of a's field minus b's at b's reference point.
  const Eigen::Vector2d dv = a.v + a.omega * perp(b.r - a.r) - b.v;
  if (shared >= 0) {
    c.at_joint = true;
    c.position = position_at(mech, q, shared);
  } else if (speed == 0.0) {
    c.indeterminate = true;
  } else if (std::abs(dw) * lc <= 1e-9 * speed) {
    if (dv.norm() <= 1e-9 * speed) {
      c.indeterminate = true;
    } else {
      c.at_infinity = true;
      // One of the two opposite directions, x positive; y positive when x is zero but for
      // rounding (a vertical direction must not turn over with the last bit of x).
      Eigen::Vector2d d = perp(dv).normalized();
      if (std::abs(d.x()) <= 1e-9) d.x() = 0.0;
      if (d.x() < 0 || (d.x() == 0 && d.y() < 0)) d = -d;
      c.direction = d;
    }
  } else {
    // a's field minus b's vanishes at p: dv + dw k x (p - b.r) = 0.
    const Eigen::Vector2d k = -dv / dw;  // = k x (p - b.r) = (-(p - b.r).y, (p - b.r).x)
    c.position = b.r + Eigen::Vector2d(k.y(), -k.x());
  }
  return c;
}

// The instant centres of every pair of links, from the velocity field of each.
std::vector<InstantCentre> instant_centres(const Mechanism& mech, const Eigen::VectorXd& q, const Eigen::VectorXd& qdot,
                                           std::vector<std::string>& notes) {
  const Model& m = mech.model();
  const double lc = mech.characteristic_length() / m.units.length_scale;
  double speed = 0.0;
  const std::vector<Link> links = moving_links(mech, q, qdot, lc, speed, notes);
  std::vector<InstantCentre> out;
  for (std::size_t i = 0; i < links.size(); ++i)
    for (std::size_t j = i + 1; j < links.size(); ++j)
      out.push_back(instant_centre(mech, q, links[i], links[j], lc, speed));
  return out;
}

double max_abs(const Eigen::VectorXd& v) { return v.size() ? v.cwiseAbs().maxCoeff() : 0.0; }

// The coordinates, two per moving point: columns are given to the moving points in their order,
// so q's order is theirs.
std::vector<Coordinate> coordinates_of(const Mechanism& mech) {
  const Model& m = mech.model();
  std::vector<Coordinate> coordinates;
  for (std::size_t p = 0; p < m.points.size(); ++p) {
    const int col = mech.column_of(static_cast<int>(p));
    if (col < 0) continue;
    for (int axis = 0; axis < 2; ++axis) {
      Coordinate c;
      c.name = m.points[p].name + (axis == 0 ? ".x" : ".y");
      c.symbol = std::string(axis == 0 ? "x_" : "y_") + explain_detail::plain_name(m.points[p].name);
      c.point = static_cast<int>(p);
      c.axis = axis;
      coordinates.push_back(c);
    }
  }
  return coordinates;
}

// Newton-Raphson, by the sweep's own solver, from the drawn pose (step 0) or from the sweep's
// previous sample, with the drivers at this sample's values. Leaves `state` at the sweep's
// solution (its Jacobian factorised) and `values` the drivers' values.
void explain_newton(const Mechanism& mech, const SweepResult& sweep, const ExplainOptions& options, State& state,
                    std::vector<Series>& values, Explanation& ex) {
  const Model& m = mech.model();
  const double ls = m.units.length_scale;
  const int nd = static_cast<int>(m.drivers.size());
  const Sample& sample = sweep.samples[options.step];
  if (options.step == 0) {
    state.q = mech.drawn_coordinates();
    ex.start = "the drawn pose";
  } else {
    state.q = sweep.samples[options.step - 1].positions();
    ex.start = "step " + std::to_string(options.step - 1) + "'s pose";
  }
  for (int d = 0; d < nd; ++d) values.push_back(Series(1, sample.driver_values[d]));
  set_drivers(mech, state, values);
  NewtonTrace trace;
  const NewtonReport newton = solve_position(mech, state, options.max_iterations, &trace);
  for (std::size_t i = 0; i < trace.iterates.size(); ++i) {
    const auto& it = trace.iterates[i];
    ex.newton.push_back({static_cast<int>(i), it.q / ls, it.residual / ls,
                         it.dq.size() ? Eigen::VectorXd(it.dq / ls) : Eigen::VectorXd()});
    if (it.nudged)
      ex.notes.push_back("at iteration " + std::to_string(i) +
                         " Phi_q was singular: the solver nudged q off the singular position instead of a step");
  }
  ex.converged = newton.converged;
  const Eigen::VectorXd q_sweep = sample.positions();
  ex.sweep_difference = max_abs(state.q - q_sweep) / ls;
  ex.matches_sweep = newton.converged && ex.sweep_difference <= 1e-8 * mech.characteristic_length() / ls;
  if (!newton.converged) {
    ex.notes.push_back("Newton-Raphson from " + ex.start + " did not converge in " +
                       std::to_string(options.max_iterations) +
                       " iterations; what follows is the sweep's solution, which continuation reached");
  } else if (!ex.matches_sweep) {
    std::ostringstream s;
    s << "Newton-Raphson from " << ex.start << " converged to another solution than the sweep's (they differ by up to "
      << ex.sweep_difference << " " << m.units.length
      << ": another assembly branch); what follows is the sweep's solution, which continuation reached on the drawn "
         "branch";
    ex.notes.push_back(s.str());
  }
  if (!ex.matches_sweep) {
    state.q = q_sweep;
    set_drivers(mech, state, values);
    max_residual(mech, state);
    factorize_jacobian(mech, state);
  }
  ex.q = state.q / ls;
  ex.residual = max_residual(mech, state) / ls;
}

// The drivers as series in time, as the sweep's samples take them. A rocking input (`at_limits:
// reverse`, one driver at a constant speed) moves at its speed's size, against it after an odd
// number of turns: its own plan's law holds only up to the first turn.
std::vector<DriverState> drivers_in_time(const Model& m, const SweepPath& plan, const Sample& sample, int step) {
  const int nd = static_cast<int>(m.drivers.size());
  std::vector<DriverState> in_time(nd);
  if (sweep_rocks(m)) {
    Series s(3, sample.driver_values[0]);
    s[1] = (sample.reversals % 2 == 0 ? 1.0 : -1.0) * plan.speed[0];
    in_time[0] = make_driver_state(s, m.drivers[0].is_angular());
  } else if (plan.time_law || plan.parameter_is_time) {
    std::vector<Series> series;
    plan.drivers(plan.parameters[step], 3, series);
    for (int d = 0; d < nd; ++d) in_time[d] = make_driver_state(series[d], m.drivers[d].is_angular());
  } else {
    for (int d = 0; d < nd; ++d) {
      Series s(3, sample.driver_values[d]);
      s[1] = plan.speed[d];
      s[2] = 0.5 * plan.accel[d];
      in_time[d] = make_driver_state(s, m.drivers[d].is_angular());
    }
  }
  return in_time;
}

// Phi_q and the velocity and acceleration systems at `state`, checked against the sweep's sample.
void explain_rates(const Mechanism& mech, State& state, const std::vector<DriverState>& in_time, const Sample& sample,
                   Explanation& ex) {
  const double ls = mech.model().units.length_scale;
  const int n = mech.coordinate_count();
  std::vector<double> values_j;
  evaluate_jacobian(mech, state.q, in_time, values_j);
  ex.jacobian = Eigen::MatrixXd::Zero(mech.row_count(), n);
  const auto& pattern = mech.equations().pattern;
  for (std::size_t e = 0; e < pattern.size(); ++e) ex.jacobian(pattern[e].row, pattern[e].col) += values_j[e];

  Eigen::MatrixXd coefficients;
  compute_series(mech, state, in_time, 3, coefficients);
  Eigen::VectorXd r1, r2;
  evaluate_series_remainder(mech, coefficients, 1, in_time, r1);
  evaluate_series_remainder(mech, coefficients, 2, in_time, r2);
  ex.velocity = {ex.jacobian, -r1 / ls, coefficients.col(1) / ls};
  ex.acceleration = {ex.jacobian, -2.0 * r2 / ls, 2.0 * coefficients.col(2) / ls};
  if (mech.row_count() > n)
    ex.notes.push_back("Phi_q has " + std::to_string(mech.row_count()) + " rows for " + std::to_string(n) +
                       " coordinates (redundant constraints): every system is solved by least squares, and is "
                       "consistent");
  if (sample.order() >= 2) {
    const double vs = std::max(1.0, max_abs(sample.derivative(1))) / ls;
    const double as = std::max(1.0, max_abs(sample.derivative(2))) / ls;
    if (max_abs(ex.velocity.solution - sample.derivative(1) / ls) > 1e-6 * vs ||
        max_abs(ex.acceleration.solution - sample.derivative(2) / ls) > 1e-6 * as)
      ex.notes.push_back("the velocities or accelerations differ from the sweep's at this step");
  }
}

// Each shaped link's largest von Mises stress at one sample, from that sample's inverse dynamics,
// as the stress stage finds its peaks over a sweep (stress_peaks), here over this one sample.
std::vector<StressPeak> stresses_at(const std::shared_ptr<const Mechanism>& mechanism, const Sample& sample,
                                    const ExplainOptions& options) {
  const Model& m = mechanism->model();
  const bool shaped = std::any_of(m.bodies.begin(), m.bodies.end(),
                                  [](const Body& b) { return b.shape && b.thickness > 0.0 && b.points.size() >= 2; });
  if (!shaped) return {};
  const auto dynamics = std::make_shared<const InverseDynamics>(mechanism);
  const LinkStress links(dynamics, options.sections);
  SweepResult one;
  one.samples.push_back(sample);
  return stress_peaks(links, one, {dynamics->solve(sample)}, options.control);
}

}  // namespace

Explanation explain(std::shared_ptr<const Mechanism> mechanism, const ExplainOptions& options) {
  if (!mechanism) throw Error(ErrorKind::BadInput, "no mechanism to explain");
  const Mechanism& mech = *mechanism;
  const Model& m = mech.model();
  const double ls = m.units.length_scale;
  const int nd = static_cast<int>(m.drivers.size());
  if (options.max_iterations < 1) throw Error(ErrorKind::BadInput, "at least one Newton iteration is needed");
  const SweepPath plan = sweep_path(mech, options.steps, options.max_steps);
  const int samples = static_cast<int>(plan.parameters.size());
  if (options.step < 0 || options.step >= samples)
    throw Error(ErrorKind::BadInput, "step " + std::to_string(options.step) + " is not a step of the sweep (0 to " +
                                         std::to_string(samples - 1) + ")");
  SweepOptions sweep_options;
  sweep_options.steps = options.steps;
  sweep_options.order = 2;
  const SweepResult sweep = run_sweep(mech, sweep_options, options.control);
  options.control.checkpoint("explain", 0, 3);
  if (options.step >= static_cast<int>(sweep.samples.size()))
    throw Error(ErrorKind::StoppedAtLimit,
                sweep.stop_reason + ": step " + std::to_string(options.step) + " is not reached");
  const Sample& sample = sweep.samples[options.step];

  Explanation ex;
  ex.mechanism = mechanism;
  ex.step = options.step;
  ex.time = sample.time;
  for (int d = 0; d < nd; ++d)
    ex.driver_values.push_back(sample.driver_values[d] / (m.drivers[d].is_angular() ? m.units.angle_scale : ls));

  const PairCount pairs = count_pairs(m);
  ex.count = {pairs.links, pairs.lower_pairs, pairs.higher_pairs, pairs.dof, mech.mobility().dof};
  ex.coordinates = coordinates_of(mech);

  RowWriter writer(mech);
  for (int r = 0; r < mech.row_count(); ++r) {
    options.control.checkpoint("explain", 1, 3);
    ex.equations.push_back(writer.write(r));
  }

  State state(mech);
  std::vector<Series> values;
  explain_newton(mech, sweep, options, state, values, ex);
  explain_rates(mech, state, drivers_in_time(m, plan, sample, options.step), sample, ex);

  options.control.checkpoint("explain", 2, 3);
  ex.centres = instant_centres(mech, ex.q, ex.velocity.solution, ex.notes);
  ex.stresses = stresses_at(mechanism, sample, options);
  return ex;
}

}  // namespace nbar
