#include "nbar/analysis/pose.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

#include "nbar/kinematics/continuation.hpp"
#include "nbar/kinematics/limits.hpp"

namespace nbar {

namespace {

std::string driver_values_text(const Model& m, const std::vector<Series>& values) {
  std::string s;
  for (std::size_t d = 0; d < values.size(); ++d)
    s += (d ? ", " : "") + m.drivers[d].name + " = " + format_driver_value(m, static_cast<int>(d), values[d].value());
  return s;
}

std::string target_text(const Model& m, const SweepPath& path, double target) {
  if (path.time_law) {
    std::ostringstream s;
    s << "t = " << target << " s";
    return s.str();
  }
  return m.drivers[0].name + " = " + format_driver_value(m, 0, target);
}

// The pose is tracked from the sweep's start, so its work grows with the distance from there: as
// far as a sweep may go (1000 turns of an angle driver), or 1000 sweeps' ranges or durations.
void check_pose_value(const Model& m, const SweepPath& path, double value, double target) {
  if (!std::isfinite(value)) {
    std::ostringstream s;
    s << "the pose's value must be a finite number, not " << value;
    throw Error(ErrorKind::BadInput, s.str());
  }
  constexpr double kMaxTurns = kMaxDriverTurns, kMaxRanges = 1000.0;
  std::ostringstream s;
  s.precision(3);
  if (path.time_law) {
    const double duration = m.sweep.duration;
    if (!(std::abs(target) > kMaxRanges * duration)) return;
    s << target_text(m, path, target) << " is " << std::abs(target) / duration
      << " times the sweep's duration; a pose is limited to " << static_cast<int>(kMaxRanges) << " times it";
  } else if (path.from.empty()) {
    return;  // parameter_of says why
  } else if (m.drivers[0].is_angular()) {
    const double turns = std::abs(target - path.from[0]) / (2 * std::numbers::pi);
    if (!(turns > kMaxTurns)) return;
    s << target_text(m, path, target) << " is " << turns << " turns from the sweep's start; a pose is limited to "
      << static_cast<int>(kMaxTurns) << " turns from it";
  } else {
    const double ranges = path.delta[0] != 0.0 ? std::abs((target - path.from[0]) / path.delta[0]) : 0.0;
    if (!(ranges > kMaxRanges)) return;
    s << target_text(m, path, target) << " is " << ranges
      << " times the sweep's range from its start; a pose is limited to " << static_cast<int>(kMaxRanges) << " times";
  }
  s << " (the work grows with the distance): check the value and its units";
  throw Error(ErrorKind::BadInput, s.str());
}

}  // namespace

Sample pose_at(const Mechanism& mech, double value, int order, const RunControl& control) {
  const Model& m = mech.model();
  if (m.drivers.empty()) throw Error(ErrorKind::BadInput, "a pose along the sweep needs a driver");
  const SweepPath path = sweep_path(mech);
  const double target =
      path.time_law ? value : value * (m.drivers[0].is_angular() ? m.units.angle_scale : m.units.length_scale);
  check_pose_value(m, path, value, target);
  control.checkpoint("pose", 0, 1);
  // A rocking driver takes most values more than once, on different branches: the pose is where
  // its motion first has the value, after the turns it passes on the way.
  if (m.drivers.size() == 1 && m.drivers[0].at_limits == AtLimits::Reverse && !path.time_law)
    if (const RockingPlan plan = plan_rocking(mech); plan.reverses) return rocking_sample_at(mech, plan, target, order);
  const double end = path.parameter_of(target);

  // From the sweep's start, along the sweep's own path: the branch the sweep takes.
  State state(mech);
  std::vector<Series> values;
  path.drivers(path.parameters.front(), 1, values);
  std::vector<double> start;
  for (const Series& v : values) start.push_back(v.value());
  assemble(mech, state, start);
  TrackOptions options;
  state.parameter = path.parameters.front();
  path.drivers(state.parameter, options.terms, values);
  set_drivers(mech, state, values);
  compute_series(mech, state, options.terms);
  const TrackReport tracked = track(mech, state, path.drivers, end, options);
  if (!tracked.reached) {
    path.drivers(tracked.limit_parameter, 1, values);
    throw Error(ErrorKind::StoppedAtLimit, "cannot reach " + target_text(m, path, target) + ": it stops at " +
                                               driver_values_text(m, values) + ": " + tracked.reason);
  }
  if (path.time_law) return solve_at_time(mech, state, target, order);
  path.drivers(end, 1, values);
  std::vector<double> at;
  for (const Series& v : values) at.push_back(v.value());
  Sample sample = solve_at(mech, state, at, order);
  sample.time = path.time_at(end);
  return sample;
}

}  // namespace nbar
