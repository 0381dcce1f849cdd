#include "nbar/kinematics/limits.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <sstream>

#include "constraints.hpp"
#include "path_follower.hpp"

namespace nbar {

namespace {

// A search that takes more steps than this each way gives up and says so.
constexpr int kMaxAccepted = 20000;

// The first driver that moves along the path: its rate in p decides how far a full turn is.
int moving_driver(const DriverPath& path, double p, std::size_t drivers) {
  std::vector<Series> values;
  path(p, 2, values);
  for (std::size_t d = 0; d < drivers; ++d)
    if (values[d][1] != 0.0) return static_cast<int>(d);
  return -1;
}

std::string body_list(const Model& m, const std::vector<int>& bodies) {
  std::string s;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (i) s += i + 1 == bodies.size() ? " and " : ", ";
    s += m.bodies[bodies[i]].name;
  }
  return s;
}

// The point two bodies share, or -1.
int shared_point(const Model& m, int a, int b) {
  for (int p : m.bodies[a].points)
    for (int q : m.bodies[b].points)
      if (p == q) return p;
  return -1;
}

// Follows the path from the start in `direction` until a limit, the window's end or a full turn.
PathReach reach(PathFollower& follower, const Eigen::VectorXd& start, int direction, double p_window, bool full_turn) {
  PathReach out;
  PathFollower::Step step = follower.begin(start, direction);
  const double p0 = follower.parameter(start);
  const auto undecided = [&](std::string why) {
    out.undecided = std::move(why);
    out.undecided_at = follower.singularity(step.y, PathSingularityKind::Limit);
    return out;
  };
  for (int steps = 0;; ++steps) {
    if (steps == kMaxAccepted) return undecided("the path takes too many steps to follow");
    const PathFollower::Advance advance = follower.advance(step);
    if (!advance.ok) return undecided(advance.reason);
    if (advance.change_point) out.singularities.push_back(*advance.change_point);
    if (advance.limit) {
      out.singularities.push_back(*advance.limit);
      return out;
    }
    const double moved = direction * (follower.parameter(step.y) - p0);
    if (moved >= p_window) {
      out.window_end = true;
      out.turns_fully = full_turn;
      return out;
    }
  }
}

// Where an undecided search stopped, told as a found limit is: the input's value there and the
// bodies of the Jacobian's weakest combination (those nearest a singular position: what makes the
// path hard to follow there, or, for a search stopped by its budget, what it was creeping toward).
void say_where_undecided(const Mechanism& mech, int driver, PathReach& reach) {
  PathSingularity& at = *reach.undecided_at;
  describe_singularity(mech, at);
  const Model& m = mech.model();
  reach.undecided += ", at " + m.drivers[driver].name + " = " +
                     format_driver_value(m, driver, at.driver_values[driver]) +
                     " (nearest a singular position there: " + at.involved + ")";
}

}  // namespace

const PathSingularity* PathReach::limit() const {
  for (const PathSingularity& s : singularities)
    if (s.kind == PathSingularityKind::Limit) return &s;
  return nullptr;
}

// The bodies that make the Jacobian singular are those both loaded by its self-stress (the left
// null vector w: constraint forces in balance with no load, which pass through every body between
// the culprit and the ground) and moved by its free motion (the right null vector v: with the
// drivers held, what can still move, which is everything the culprit carries). A dyad in line is
// in both; the bodies that only carry its force, or only ride along, are in one.
void describe_singularity(const Mechanism& mech, PathSingularity& s) {
  const Model& m = mech.model();
  const Eigen::MatrixXd jacobian = dense_jacobian(mech, s.q, s.driver_values);
  const Eigen::Index n = jacobian.cols();
  if (n == 0) return;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(jacobian, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::VectorXd w = svd.matrixU().col(n - 1);
  const Eigen::VectorXd v = svd.matrixV().col(n - 1);
  const double w_largest = w.cwiseAbs().maxCoeff(), v_largest = v.cwiseAbs().maxCoeff();
  std::set<int> loaded;
  s.rows.clear();
  for (Eigen::Index r = 0; r < w.size(); ++r) {
    if (!(std::abs(w[r]) > 1e-3 * w_largest)) continue;
    s.rows.push_back(static_cast<int>(r));
    const EntityRef& source = mech.equations().rows[r].source;
    if (source.kind == EntityRef::Kind::Body && source.index >= 0) loaded.insert(source.index);
    if (source.kind == EntityRef::Kind::Slider && source.index >= 0) loaded.insert(m.sliders[source.index].body);
  }
  const auto moves = [&](int point) {
    const int column = mech.column_of(point);
    return column >= 0 && std::max(std::abs(v[column]), std::abs(v[column + 1])) > 1e-3 * v_largest;
  };
  s.bodies.clear();
  for (int b : loaded)
    if (std::any_of(m.bodies[b].points.begin(), m.bodies[b].points.end(), moves)) s.bodies.push_back(b);
  if (s.bodies.empty()) s.bodies.assign(loaded.begin(), loaded.end());
  std::ostringstream text;
  if (s.bodies.size() == 2 && shared_point(m, s.bodies[0], s.bodies[1]) >= 0)
    text << body_list(m, s.bodies) << " in line at " << m.points[shared_point(m, s.bodies[0], s.bodies[1])].name;
  else if (!s.bodies.empty())
    text << "bodies " << body_list(m, s.bodies);
  else
    text << "rows " << s.rows.size();
  s.loop = -1;
  const auto& loops = mech.four_bar_loops();
  for (std::size_t l = 0; l < loops.size() && s.loop < 0; ++l) {
    const std::set<int> members{loops[l].frame, loops[l].input, loops[l].coupler, loops[l].output};
    if (!s.bodies.empty() && std::all_of(s.bodies.begin(), s.bodies.end(), [&](int b) { return members.count(b); })) {
      text << " (four-bar loop " << loops[l].name << ")";
      s.loop = static_cast<int>(l);
    }
  }
  s.involved = text.str();
}

PathLimits find_path_limits(const Mechanism& mech, const LimitSearchOptions& options) {
  PathLimits out;
  const Model& m = mech.model();
  if (m.drivers.empty()) {
    out.not_searched = "the model has no driver";
    return out;
  }
  const SweepPath plan = sweep_path(mech, std::nullopt, kDefaultMaxSweepSamples, false);
  const double p0 = plan.sample_parameter(0);
  const double p_end = plan.samples > 1 ? plan.sample_parameter(plan.samples - 1) : p0;
  out.start_parameter = p0;
  out.end_parameter = p_end;
  const int driver = moving_driver(plan.drivers, p0, m.drivers.size());
  if (driver < 0 || p_end == p0) {
    out.not_searched = "the sweep does not move its drivers";
    return out;
  }
  out.driver = driver;
  std::vector<Series> values;
  plan.drivers(p0, 2, values);
  std::vector<double> start(values.size());
  for (std::size_t d = 0; d < values.size(); ++d) start[d] = values[d].value();
  State state(mech);
  assemble(mech, state, start);

  const double span = std::abs(p_end - p0);
  const int ahead = p_end > p0 ? 1 : -1;
  const double rate = std::abs(values[driver][1]);
  const bool angular = m.drivers[driver].is_angular() && !plan.time_law;
  const double turn = angular ? 2.0 * std::numbers::pi / rate : 0.0;
  const double window = std::max(span * (1.0 + options.window_spans), options.full_turn ? turn * 1.0000001 : 0.0);
  PathFollower follower(mech, plan.drivers, span);
  follower.set_work_budget(options.work_budget);
  Eigen::VectorXd y0(state.q.size() + 1);
  y0 << state.q, follower.scaled(p0);
  out.ahead = reach(follower, y0, ahead, window, angular && options.full_turn && window >= turn);
  out.behind = reach(follower, y0, -ahead, std::max(span * options.window_spans, options.full_turn ? turn : 0.0),
                     angular && options.full_turn && window >= turn);
  out.searched = true;
  out.work = follower.work();
  for (PathReach* r : {&out.ahead, &out.behind}) {
    for (PathSingularity& s : r->singularities) describe_singularity(mech, s);
    if (r->undecided_at) say_where_undecided(mech, driver, *r);
  }
  if (const PathSingularity* limit = out.ahead.limit(); limit && ahead * (limit->parameter - p_end) < 0.0)
    out.stop = *limit;
  return out;
}

}  // namespace nbar
