#include "nbar/analysis/pose.hpp"

#include <sstream>

#include "nbar/kinematics/continuation.hpp"

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

}  // namespace

Sample pose_at(const Mechanism& mech, double value, int order, const RunControl& control) {
  const Model& m = mech.model();
  if (m.drivers.empty()) throw Error(ErrorKind::BadInput, "a pose along the sweep needs a driver");
  const SweepPath path = sweep_path(mech);
  const double target =
      path.time_law ? value : value * (m.drivers[0].is_angular() ? m.units.angle_scale : m.units.length_scale);
  const double end = path.parameter_of(target);
  control.checkpoint("pose", 0, 1);

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
