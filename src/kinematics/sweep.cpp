#include "nbar/kinematics/sweep.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace nbar {

namespace {

double factorial(int k) {
  double f = 1.0;
  for (int i = 2; i <= k; ++i) f *= i;
  return f;
}

// How the drivers move along the sweep, and where the samples are.
struct SweepPlan {
  DriverPath path;                 // driver series in the tracking parameter
  std::vector<double> parameters;  // tracking parameter of every sample
  std::vector<double> times;       // t column of every sample
  bool path_is_time = true;        // the tracking parameter is the time itself
  std::vector<double> from, speed, accel;  // for time derivatives when !path_is_time
};

SweepPlan plan_sweep(const Mechanism& mech, const SweepOptions& options) {
  const Model& m = mech.model();
  const int nd = static_cast<int>(m.drivers.size());
  const std::vector<double>& drawn = mech.drawn_driver_values();
  SweepPlan plan;
  plan.from.resize(nd);
  plan.speed.resize(nd);
  plan.accel.resize(nd);
  for (int d = 0; d < nd; ++d) {
    plan.from[d] = m.drivers[d].from.value_or(drawn[d]);
    plan.speed[d] = m.drivers[d].speed;
    plan.accel[d] = m.drivers[d].accel;
  }

  if (m.has_time_law()) {
    const double duration = m.sweep.duration;
    int samples = 0;
    if (options.steps) {
      samples = *options.steps;
    } else {
      const double dt = m.sweep.time_step.value_or(duration / 100.0);
      samples = static_cast<int>(std::floor(duration / dt + 1e-9)) + 1;
    }
    if (samples < 1) throw std::invalid_argument("a sweep needs at least one step");
    const double dt = m.sweep.time_step && !options.steps ? *m.sweep.time_step
                                                          : (samples > 1 ? duration / (samples - 1) : 0.0);
    for (int i = 0; i < samples; ++i) {
      plan.parameters.push_back(i * dt);
      plan.times.push_back(i * dt);
    }
    plan.path = [&m, from = plan.from](double t, int terms, std::vector<Series>& out) {
      out.resize(m.drivers.size());
      for (std::size_t d = 0; d < m.drivers.size(); ++d) {
        const Driver& drv = m.drivers[d];
        if (drv.law) {
          out[d] = drv.law->series(t, terms);
        } else {
          Series s = Series::variable(terms, t);
          out[d] = from[d] + drv.speed * s + 0.5 * drv.accel * (s * s);
        }
      }
    };
    return plan;
  }

  const int samples = options.steps.value_or(m.sweep.steps);
  if (samples < 1) throw std::invalid_argument("a sweep needs at least one step");
  std::vector<double> delta(nd);
  for (int d = 0; d < nd; ++d) delta[d] = m.drivers[d].to.value_or(plan.from[d]) - plan.from[d];

  // When every driver moves at constant speed in proportion to its range, the sweep is a
  // motion in time and one series serves both the predictor and the derivatives.
  bool proportional = nd > 0 && delta[0] != 0.0;
  for (int d = 0; d < nd && proportional; ++d) {
    proportional = plan.accel[d] == 0.0 &&
                   std::abs(plan.speed[d] * delta[0] - plan.speed[0] * delta[d]) <=
                       1e-12 * std::abs(plan.speed[0] * delta[0]) + 1e-300;
  }
  const double time_per_fraction = nd > 0 && delta[0] != 0.0 ? delta[0] / plan.speed[0] : 0.0;
  for (int i = 0; i < samples; ++i) {
    const double fraction = samples > 1 ? static_cast<double>(i) / (samples - 1) : 0.0;
    plan.times.push_back(fraction * time_per_fraction);
    plan.parameters.push_back(proportional ? fraction * time_per_fraction : fraction);
  }
  plan.path_is_time = proportional;
  if (proportional) {
    plan.path = [from = plan.from, speed = plan.speed](double t, int terms, std::vector<Series>& out) {
      out.resize(from.size());
      for (std::size_t d = 0; d < from.size(); ++d) out[d] = from[d] + speed[d] * Series::variable(terms, t);
    };
  } else {
    plan.path = [from = plan.from, delta](double f, int terms, std::vector<Series>& out) {
      out.resize(from.size());
      for (std::size_t d = 0; d < from.size(); ++d) out[d] = from[d] + delta[d] * Series::variable(terms, f);
    };
  }
  return plan;
}

std::string values_text(const Model& m, const std::vector<Series>& values) {
  std::ostringstream s;
  for (std::size_t d = 0; d < values.size(); ++d) {
    if (d) s << ", ";
    s << m.drivers[d].name << " = " << format_driver_value(m, static_cast<int>(d), values[d].value());
  }
  return s.str();
}

}  // namespace

std::vector<double> sweep_start_values(const Mechanism& mech) {
  const SweepPlan plan = plan_sweep(mech, {});
  std::vector<Series> values;
  plan.path(plan.parameters.front(), 1, values);
  std::vector<double> start;
  for (const Series& s : values) start.push_back(s.value());
  return start;
}

SweepResult run_sweep(const Mechanism& mech, const SweepOptions& options) {
  if (options.order < 0 || options.order > 5)
    throw std::invalid_argument("the derivative order must be between 0 and 5");
  const Model& m = mech.model();
  const int nd = static_cast<int>(m.drivers.size());
  const SweepPlan plan = plan_sweep(mech, options);
  SweepResult result;
  result.order = options.order;
  const int terms_out = options.order + 1;
  TrackOptions track_options;
  track_options.terms = plan.path_is_time ? std::max(4, terms_out) : 4;

  std::vector<Series> values;
  plan.path(plan.parameters.front(), 1, values);
  std::vector<double> start(nd);
  for (int d = 0; d < nd; ++d) start[d] = values[d].value();

  State state(mech);
  result.assembly = assemble(mech, state, start);
  state.parameter = plan.parameters.front();
  plan.path(state.parameter, track_options.terms, values);
  set_drivers(mech, state, values);
  compute_series(mech, state, track_options.terms);

  // A loop's branch sign can only change through a singular position of the loop. A
  // change-point loop has such positions where it lies flat, and a mechanism that passes them
  // (a parallelogram held by a redundant crank) flips the sign without changing branch: only
  // the other loops are watched.
  std::vector<int> branch_signs;
  std::vector<bool> watched;
  {
    const auto points = point_positions(mech, state.q);
    for (const FourBarLoop& loop : mech.four_bar_loops()) {
      branch_signs.push_back(branch_sign(loop, points));
      result.branches.push_back(branch_name(branch_signs.back()));
      watched.push_back(classify_grashof(loop, points, mech.tolerance()).kind != GrashofClass::ChangePoint);
    }
  }

  std::vector<DriverState> time_drivers(nd);
  auto record = [&](int i) {
    Sample s;
    s.step = i;
    s.time = plan.times[i];
    for (int d = 0; d < nd; ++d) s.driver_values.push_back(state.drivers[d].value.value());
    if (plan.path_is_time) {
      s.series = state.series.leftCols(terms_out);
    } else {
      for (int d = 0; d < nd; ++d) {
        Series v(terms_out, s.driver_values[d]);
        if (terms_out > 1) v[1] = plan.speed[d];
        if (terms_out > 2) v[2] = 0.5 * plan.accel[d];
        time_drivers[d] = make_driver_state(v, m.drivers[d].is_angular());
      }
      compute_series(mech, state, time_drivers, terms_out, s.series);
    }
    s.residual = state.residual;
    result.max_residual = std::max(result.max_residual, s.residual);
    result.samples.push_back(std::move(s));
  };
  record(0);

  for (std::size_t i = 1; i < plan.parameters.size(); ++i) {
    const double p = plan.parameters[i];
    // Built only for a warning or a stop: formatting it every step costs a third of a step.
    auto where = [i] { return "between steps " + std::to_string(i - 1) + " and " + std::to_string(i); };
    try {
      plan.path(p, 1, values);
      for (int d = 0; d < nd; ++d) {
        // Zero relative to the model's size counts as zero: the row's Jacobian vanishes there.
        if (m.drivers[d].kind == DriverKind::Distance && !(values[d].value() > 1e-9 * mech.characteristic_length())) {
          result.complete = false;
          result.stop_reason = "sweep stopped " + where() + ": driver '" + m.drivers[d].name +
                               "' asks for a distance of " + format_driver_value(m, d, values[d].value()) +
                               ", which must be positive";
          return result;
        }
      }
      const TrackReport tr = track(mech, state, plan.path, p, track_options);
      if (tr.passed_singularity) {
        plan.path(tr.singular_parameter, 1, values);
        result.warnings.push_back("passed a singular (change-point) position " + where() + " near " +
                                  values_text(m, values) + ": the assembly branch may have changed there");
      }
      if (!tr.reached) {
        plan.path(tr.limit_parameter, 1, values);
        result.complete = false;
        result.stop_reason = "sweep stopped " + where() + " at " + values_text(m, values) + ": " + tr.reason;
        return result;
      }
    } catch (const std::domain_error& e) {
      result.complete = false;
      result.stop_reason = "sweep stopped " + where() + ": " + e.what();
      return result;
    }
    record(static_cast<int>(i));
    const auto points = point_positions(mech, state.q);
    const auto& loops = mech.four_bar_loops();
    for (std::size_t l = 0; l < loops.size(); ++l) {
      const int sign = branch_sign(loops[l], points);
      if (watched[l] && sign != branch_signs[l]) {
        result.warnings.push_back("four-bar loop " + loops[l].name + " changed branch " + where() + " (now " +
                                  branch_name(sign) + ")");
      }
      branch_signs[l] = sign;
    }
  }
  return result;
}

std::vector<Eigen::Vector2d> point_positions(const Mechanism& mech, const Eigen::VectorXd& q) {
  std::vector<Eigen::Vector2d> out;
  out.reserve(mech.model().points.size());
  for (std::size_t i = 0; i < mech.model().points.size(); ++i) out.push_back(mech.point_position(static_cast<int>(i), q));
  return out;
}

Motion2 point_motion(const Mechanism& mech, const Sample& sample, int point) {
  const int terms = static_cast<int>(sample.series.cols());
  Motion2 m;
  m.x.assign(terms, 0.0);
  m.y.assign(terms, 0.0);
  const int col = mech.column_of(point);
  if (col < 0) {
    m.x[0] = mech.model().points[point].position.x();
    m.y[0] = mech.model().points[point].position.y();
    return m;
  }
  for (int k = 0; k < terms; ++k) {
    m.x[k] = factorial(k) * sample.series(col, k);
    m.y[k] = factorial(k) * sample.series(col + 1, k);
  }
  return m;
}

std::vector<double> body_angle_motion(const Mechanism& mech, const Sample& sample, int body) {
  const int terms = static_cast<int>(sample.series.cols());
  const Body& b = mech.model().bodies[body];
  auto coordinate = [&](int point, int axis) {
    Series s(terms);
    const int col = mech.column_of(point);
    if (col < 0) {
      s[0] = mech.model().points[point].position[axis];
    } else {
      for (int k = 0; k < terms; ++k) s[k] = sample.series(col + axis, k);
    }
    return s;
  };
  const Series ux = coordinate(b.points[1], 0) - coordinate(b.points[0], 0);
  const Series uy = coordinate(b.points[1], 1) - coordinate(b.points[0], 1);
  const Series angle = atan2(uy, ux);
  std::vector<double> out(terms);
  for (int k = 0; k < terms; ++k) out[k] = factorial(k) * angle[k];
  return out;
}

}  // namespace nbar
