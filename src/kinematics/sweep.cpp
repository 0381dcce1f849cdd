#include "nbar/kinematics/sweep.hpp"

#include "constraints.hpp"
#include "rocking.hpp"
#include "workspace.hpp"

#include <cmath>
#include <exception>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

namespace nbar {

namespace {

double factorial(int k) {
  double f = 1.0;
  for (int i = 2; i <= k; ++i) f *= i;
  return f;
}

SweepPath plan_from_to(const Mechanism& mech, int samples, SweepPath plan, bool tabulate) {
  const Model& m = mech.model();
  const int nd = static_cast<int>(m.drivers.size());
  plan.delta.resize(nd);
  for (int d = 0; d < nd; ++d) plan.delta[d] = m.drivers[d].to.value_or(plan.from[d]) - plan.from[d];
  const std::vector<double>& delta = plan.delta;

  // When every driver moves at constant speed in proportion to its range, the sweep is a
  // motion in time and one series serves both the predictor and the derivatives.
  bool proportional = nd > 0 && delta[0] != 0.0;
  for (int d = 0; d < nd && proportional; ++d) {
    proportional = plan.accel[d] == 0.0 && std::abs(plan.speed[d] * delta[0] - plan.speed[0] * delta[d]) <=
                                               1e-12 * std::abs(plan.speed[0] * delta[0]) + 1e-300;
  }
  plan.fraction_time = nd > 0 && delta[0] != 0.0 ? delta[0] / plan.speed[0] : 0.0;
  plan.samples = static_cast<std::size_t>(samples);
  plan.parameter_is_time = proportional;
  if (tabulate) {
    plan.times.reserve(plan.samples);
    plan.parameters.reserve(plan.samples);
    for (std::size_t i = 0; i < plan.samples; ++i) {
      plan.times.push_back(plan.sample_time(i));
      plan.parameters.push_back(plan.sample_parameter(i));
    }
  }
  if (proportional) {
    plan.drivers = [from = plan.from, speed = plan.speed](double t, int terms, std::vector<Series>& out) {
      out.resize(from.size());
      for (std::size_t d = 0; d < from.size(); ++d) out[d].set_line(terms, from[d], speed[d], t);
    };
  } else {
    plan.drivers = [from = plan.from, delta](double f, int terms, std::vector<Series>& out) {
      out.resize(from.size());
      for (std::size_t d = 0; d < from.size(); ++d) out[d].set_line(terms, from[d], delta[d], f);
    };
  }
  return plan;
}

// Every driver in time: its law, or from its start at its speed and acceleration.
DriverPath motion_in_time(const Model& m, std::vector<double> from) {
  return [&m, from = std::move(from)](double t, int terms, std::vector<Series>& out) {
    out.resize(m.drivers.size());
    for (std::size_t d = 0; d < m.drivers.size(); ++d) {
      const Driver& drv = m.drivers[d];
      if (drv.law) {
        try {
          out[d] = drv.law->series(t, terms);
        } catch (const Error& e) {  // said at the driver whose law it is
          throw Error(e.kind(), e.message(), EntityRef{EntityRef::Kind::Driver, static_cast<int>(d), 0});
        }
      } else {
        Series s = Series::variable(terms, t);
        out[d] = from[d] + drv.speed * s + 0.5 * drv.accel * (s * s);
      }
    }
  };
}

SweepPath plan_time_law(const Mechanism& mech, std::optional<int> steps, SweepPath plan, bool tabulate) {
  const Model& m = mech.model();
  const double duration = m.sweep.duration;
  // check_sample_count (in sweep_path) has bounded the count.
  const int samples = static_cast<int>(sweep_sample_count(m, steps));
  plan.time_step = m.sweep.time_step && !steps ? *m.sweep.time_step : (samples > 1 ? duration / (samples - 1) : 0.0);
  plan.samples = static_cast<std::size_t>(samples);
  if (tabulate) {
    plan.times.reserve(plan.samples);
    plan.parameters.reserve(plan.samples);
    for (std::size_t i = 0; i < plan.samples; ++i) {
      plan.parameters.push_back(plan.sample_parameter(i));
      plan.times.push_back(plan.sample_time(i));
    }
  }
  plan.drivers = motion_in_time(m, plan.from);
  return plan;
}

// Each driver moving at its speed and acceleration through `values`, as series in time.
void time_drivers(const Mechanism& mech, const std::vector<double>& values, const std::vector<double>& speed,
                  const std::vector<double>& accel, int terms, std::vector<DriverState>& out) {
  const Model& m = mech.model();
  out.resize(values.size());
  for (std::size_t d = 0; d < values.size(); ++d) {
    Series v(terms, values[d]);
    if (terms > 1) v[1] = speed[d];
    if (terms > 2) v[2] = 0.5 * accel[d];
    out[d] = make_driver_state(v, m.drivers[d].is_angular());
  }
}

}  // namespace

double sample_condition(State& state) {
  State::Workspace& work = state.workspace();
  return work.solver().condition_estimate(work.jacobian);
}

namespace {

// A Sample of the pose in `state` (solved, its Jacobian factorised), with the Taylor
// coefficients in time for the drivers moving as `drivers` says.
void fill_sample(const Mechanism& mech, State& state, int step, double time, const std::vector<DriverState>& drivers,
                 int terms, Sample& s) {
  s.step = step;
  s.time = time;
  s.driver_values.resize(state.drivers.size());
  for (std::size_t d = 0; d < state.drivers.size(); ++d) s.driver_values[d] = state.drivers[d].value.value();
  compute_series(mech, state, drivers, terms, s.taylor);
  s.residual = state.residual;
}

Sample make_sample(const Mechanism& mech, State& state, int step, double time, const std::vector<DriverState>& drivers,
                   int terms) {
  Sample s;
  fill_sample(mech, state, step, time, drivers, terms, s);
  return s;
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

// A whole number of samples, as "1000000000" (not "1e+09").
static std::string fmt_count(double count) {
  std::ostringstream s;
  s.precision(0);
  s << std::fixed << count;
  return s.str();
}

double sweep_sample_count(const Model& m, std::optional<int> steps) {
  if (steps) return *steps;
  if (!m.has_time_law()) return m.sweep.steps;
  // `steps: 1` in a time sweep leaves no time step to sample by: the one pose at t = 0.
  if (!m.sweep.time_step && m.sweep.steps == 1) return 1;
  const double dt = m.sweep.time_step.value_or(m.sweep.duration / 100.0);
  return std::floor(m.sweep.duration / dt + 1e-9) + 1;
}

SweepPath sweep_path(const Mechanism& mech, std::optional<int> steps, int max_steps, bool tabulate) {
  const Model& m = mech.model();
  check_sample_count(m, steps, max_steps);
  const int nd = static_cast<int>(m.drivers.size());
  const std::vector<double>& drawn = mech.drawn_driver_values();
  SweepPath plan;
  plan.from.resize(nd);
  plan.speed.resize(nd);
  plan.accel.resize(nd);
  for (int d = 0; d < nd; ++d) {
    plan.from[d] = m.drivers[d].from.value_or(drawn[d]);
    plan.speed[d] = m.drivers[d].speed;
    plan.accel[d] = m.drivers[d].accel;
  }
  plan.time_law = m.has_time_law();
  if (plan.time_law) return plan_time_law(mech, steps, std::move(plan), tabulate);
  return plan_from_to(mech, steps.value_or(m.sweep.steps), std::move(plan), tabulate);
}

void check_sample_count(const Model& m, std::optional<int> steps, int max_steps) {
  const double count = sweep_sample_count(m, steps);
  const std::string limit = std::to_string(max_steps);
  if (steps) {
    if (*steps < 1)
      throw Error(ErrorKind::BadInput, "a sweep needs at least one step (got " + std::to_string(*steps) + ")");
    if (*steps > max_steps)
      throw Error(ErrorKind::BadInput, "the sweep asks for " + std::to_string(*steps) +
                                           " steps, more than the limit of " + limit + " (raise it with --max-steps)");
    return;
  }
  // The model's own sweep: validate() has made sure that the count is finite and at least 1.
  if (!(count >= 1.0 && count <= max_steps)) {
    const std::string asked = std::isfinite(count) ? fmt_count(count) : "too many";
    throw Error(ErrorKind::InvalidModel,
                "the sweep asks for " + asked + " steps, more than the limit of " + limit +
                    (m.has_time_law() ? " (its duration over its time step)" : "") +
                    ": ask for fewer, or raise the limit with --max-steps",
                EntityRef{EntityRef::Kind::Sweep, -1});
  }
}

double SweepPath::parameter_of(double value) const {
  if (time_law) return value;
  if (from.empty()) throw Error(ErrorKind::BadInput, "the model has no driver to pose it by");
  if (delta[0] == 0.0) throw Error(ErrorKind::BadInput, "the first driver does not move over the sweep");
  const double fraction = (value - from[0]) / delta[0];
  return parameter_is_time ? fraction * (delta[0] / speed[0]) : fraction;
}

double SweepPath::sample_time(std::size_t i) const {
  if (time_law) return static_cast<double>(static_cast<int>(i)) * time_step;
  const double fraction = samples > 1 ? static_cast<double>(static_cast<int>(i)) / static_cast<int>(samples - 1) : 0.0;
  return fraction * fraction_time;
}

double SweepPath::sample_parameter(std::size_t i) const {
  if (time_law || parameter_is_time) return sample_time(i);
  return samples > 1 ? static_cast<double>(static_cast<int>(i)) / static_cast<int>(samples - 1) : 0.0;
}

double SweepPath::time_at(double p) const {
  if (time_law || parameter_is_time) return p;
  return !from.empty() && delta[0] != 0.0 ? p * (delta[0] / speed[0]) : 0.0;
}

std::vector<double> sweep_start_values(const Mechanism& mech, int max_steps) {
  // The start is the same whatever the number of samples: plan one, after checking the
  // model's own count, so that an oversized sweep is reported here too.
  check_sample_count(mech.model(), std::nullopt, max_steps);
  const SweepPath plan = sweep_path(mech, 1);
  std::vector<Series> values;
  plan.drivers(plan.parameters.front(), 1, values);
  std::vector<double> start;
  for (const Series& s : values) start.push_back(s.value());
  return start;
}

namespace {

// Watches every four-bar loop's branch sign along the sweep. A sign can only change through a
// singular position of the loop. A change-point loop has such positions where it lies flat,
// and a mechanism that passes them (a parallelogram held by a redundant crank) flips the sign
// without changing branch: only the other loops are watched.
class BranchWatch {
 public:
  BranchWatch(const Mechanism& mech, const Eigen::VectorXd& q, SweepResult& result) : mech_(mech) {
    const auto points = point_positions(mech, q);
    for (const FourBarLoop& loop : mech.four_bar_loops()) {
      signs_.push_back(branch_sign(loop, points));
      result.branches.push_back(branch_name(signs_.back()));
      watched_.push_back(classify_grashof(loop, points, mech.tolerance()).kind != GrashofClass::ChangePoint);
    }
  }
  // `where` is called only for a warning.
  template <class Where>
  void check(const Eigen::VectorXd& q, int step, const Where& where, SweepResult& result) {
    const auto& loops = mech_.four_bar_loops();
    if (loops.empty()) return;
    points_.resize(mech_.model().points.size());
    for (std::size_t i = 0; i < points_.size(); ++i) points_[i] = mech_.point_position(static_cast<int>(i), q);
    const auto& points = points_;
    for (std::size_t l = 0; l < loops.size(); ++l) {
      const int sign = branch_sign(loops[l], points);
      if (watched_[l] && sign != signs_[l])
        result.warnings.push_back(
            {"branch_changed", step,
             "four-bar loop " + loops[l].name + " changed branch " + where() + " (now " + branch_name(sign) + ")"});
      signs_[l] = sign;
    }
  }

 private:
  const Mechanism& mech_;
  std::vector<int> signs_;
  std::vector<bool> watched_;
  std::vector<Eigen::Vector2d> points_;  // reused from sample to sample
};

// A driver distance that reaches zero (relative to the model's size) stops the sweep: the
// row's Jacobian vanishes there. Returns the stop reason, or empty.
std::string nonpositive_distance(const Mechanism& mech, const std::vector<Series>& values) {
  const Model& m = mech.model();
  for (std::size_t d = 0; d < values.size(); ++d)
    if (m.drivers[d].kind == DriverKind::Distance && !(values[d].value() > 1e-9 * mech.characteristic_length()))
      return "driver '" + m.drivers[d].name + "' asks for a distance of " +
             format_driver_value(m, static_cast<int>(d), values[d].value()) + ", which must be positive";
  return {};
}

// The driver whose motion is largest at a sample, in the size of its Taylor coefficients
// (speed, acceleration and beyond): what makes the derivatives of the mechanism overflow.
int largest_driver(const std::vector<DriverState>& drivers) {
  int best = -1;
  double largest = -1.0;
  for (std::size_t d = 0; d < drivers.size(); ++d) {
    double size = 0.0;
    for (int k = 1; k < drivers[d].value.terms(); ++k) {
      const double c = std::abs(drivers[d].value[k]);
      size = std::isfinite(c) ? std::max(size, c) : std::numeric_limits<double>::infinity();
    }
    if (size > largest) {
      largest = size;
      best = static_cast<int>(d);
    }
  }
  return best;
}

// A sample whose positions or derivatives are not finite numbers came from inputs too large to
// compute with (a driver's acceleration of 1e300 makes the fifth derivative overflow): an error
// about the driver that moves fastest, never a row of nan.
void check_finite(const Mechanism& mech, const Sample& s, const std::vector<DriverState>& drivers) {
  if (s.taylor.allFinite()) [[likely]]
    return;
  int order = 0;
  while (order + 1 < s.taylor.cols() && s.taylor.col(order).allFinite()) ++order;
  const char* names[] = {"positions", "velocities", "accelerations", "jerks", "4th derivatives", "5th derivatives"};
  const int d = largest_driver(drivers);
  const std::string what = "at step " + std::to_string(s.step) + " the " + names[order] +
                           " of the mechanism overflow (are not finite numbers)";
  if (d < 0) throw Error(ErrorKind::InvalidModel, what + ": the model's numbers are too large to compute with");
  throw Error(ErrorKind::InvalidModel,
              what + ": driver '" + mech.model().drivers[d].name +
                  "' moves too fast for them (check its speed, acceleration or law, or ask for a lower order)",
              EntityRef{EntityRef::Kind::Driver, d});
}

// A from/to sweep whose parameter is the fraction of the sweep (drivers with an acceleration)
// still moves every driver along its range in time, as s(t) = speed t + accel t^2 / 2 over the
// range, when their speeds and accelerations are in proportion to their ranges.
struct FractionRate {
  double speed = 0.0;  // d(fraction)/dt
  double accel = 0.0;  // d2(fraction)/dt2
};

std::optional<FractionRate> fraction_rate(const SweepPath& plan) {
  if (plan.time_law || plan.delta.empty() || plan.delta[0] == 0.0) return std::nullopt;
  const double d0 = plan.delta[0];
  for (std::size_t d = 1; d < plan.delta.size(); ++d) {
    const double scale = 1e-12 * std::abs(d0) * (std::abs(plan.speed[0]) + std::abs(plan.accel[0]));
    if (std::abs(plan.speed[d] * d0 - plan.speed[0] * plan.delta[d]) > scale + 1e-300 ||
        std::abs(plan.accel[d] * d0 - plan.accel[0] * plan.delta[d]) > scale + 1e-300)
      return std::nullopt;
  }
  return FractionRate{plan.speed[0] / d0, plan.accel[0] / d0};
}

// The Taylor series in time from those in the sweep fraction: q(t) = Q(s(t)), s(t) as above.
void series_in_time(const Eigen::MatrixXd& in_fraction, const FractionRate& rate, int terms, Eigen::MatrixXd& out) {
  out.setZero(in_fraction.rows(), terms);
  std::vector<double> power(terms, 0.0), next(terms);
  power[0] = 1.0;  // s(t)^k, k = 0
  for (Eigen::Index k = 0; k < in_fraction.cols(); ++k) {
    for (int j = 0; j < terms; ++j) out.col(j) += power[j] * in_fraction.col(k);
    std::fill(next.begin(), next.end(), 0.0);
    for (int j = 0; j < terms; ++j) {
      if (j + 1 < terms) next[j + 1] += rate.speed * power[j];
      if (j + 2 < terms) next[j + 2] += 0.5 * rate.accel * power[j];
    }
    power.swap(next);
  }
}

// How well a sample on a singular position is known, for its warning.
std::string coasted_accuracy(double relative_error, int terms) {
  std::ostringstream s;
  s.precision(1);
  s << "positions, velocities and accelerations there to about " << std::max(relative_error, 1e-15) << " relative";
  if (terms > 3) s << "; higher derivatives there are only estimates";
  return s.str();
}

// Checking the control costs a clock read: every few samples is often enough.
constexpr std::size_t kControlInterval = 16;

}  // namespace

void check_derivative_order(int order) {
  if (order < 0 || order > kMaxDerivativeOrder)
    throw Error(ErrorKind::BadInput, "the derivative order must be between 0 and " +
                                         std::to_string(kMaxDerivativeOrder) + ", not " + std::to_string(order));
}

SweepResult run_sweep(const Mechanism& mech, const SweepOptions& options, const RunControl& control) {
  return run_sweep(mech, options, control, nullptr);
}

namespace {
SweepResult run_steady_sweep(const Mechanism& mech, const SweepOptions& options, const RunControl& control,
                             const SampleSink& sink);
}  // namespace

SweepResult run_sweep(const Mechanism& mech, const SweepOptions& options, const RunControl& control,
                      const SampleSink& sink) {
  check_derivative_order(options.order);
  if (!sweep_rocks(mech.model())) return run_steady_sweep(mech, options, control, sink);
  const RockingPlan plan = plan_rocking(mech);
  if (plan.reverses) {
    SweepResult result = run_rocking_sweep(mech, plan, options, control, sink);
    BranchWatch start(mech, plan.start_pose, result);  // each four-bar loop's branch at the start
    return result;
  }
  SweepResult result = run_steady_sweep(mech, options, control, sink);
  result.warnings.insert(result.warnings.begin(),
                         {"never_reverses", -1,
                          "driver '" + mech.model().drivers[0].name + "' never reverses (`at_limits: reverse`): " +
                              plan.never_reverses + ", so the sweep runs from its start to its end as usual"});
  return result;
}

namespace {

// Left long (109 lines) on purpose: the start (assembly, the first series) and the loop over the
// samples share the plan, the tracker's state, the reused sample and whether the sample being
// recorded lies on a singular position with `record`; the loop runs once a sample, and the
// warnings it gives read the tracker's report of that sample's track where it is made.
SweepResult run_steady_sweep(const Mechanism& mech, const SweepOptions& options, const RunControl& control,
                             const SampleSink& sink) {
  const Model& m = mech.model();
  const int nd = static_cast<int>(m.drivers.size());
  const SweepPath plan = sweep_path(mech, options.steps, options.max_steps, false);
  const std::size_t samples = plan.samples;
  control.checkpoint("sweep", 0, static_cast<long>(samples));
  SweepResult result;
  result.order = options.order;
  const int terms_out = options.order + 1;
  TrackOptions track_options;
  track_options.terms = std::max(3, terms_out);
  const std::optional<FractionRate> rate = plan.parameter_is_time ? std::nullopt : fraction_rate(plan);
  if (plan.parameter_is_time || rate) track_options.coast_terms = terms_out;

  std::vector<Series> values;
  plan.drivers(plan.sample_parameter(0), 1, values);
  std::vector<double> start(nd);
  for (int d = 0; d < nd; ++d) start[d] = values[d].value();

  State state(mech);
  result.assembly = assemble(mech, state, start);
  state.parameter = plan.sample_parameter(0);
  plan.drivers(state.parameter, track_options.terms, values);
  set_drivers(mech, state, values);
  compute_series(mech, state, track_options.terms);
  BranchWatch branches(mech, state.q, result);

  std::vector<DriverState> drivers_in_time(nd);
  std::vector<double> now(nd);
  Sample streamed;                    // a sink's sample, reused: its buffers are allocated once
  bool on_singular_position = false;  // the sample being recorded, as the tracker found it
  auto record = [&](int i) {
    Sample& s = sink ? streamed : result.samples.emplace_back();
    if (plan.parameter_is_time || on_singular_position) {
      // The tracker's series: already in time, or (on a singular position, whose Jacobian
      // cannot give them in time) in the sweep fraction, re-centred from a regular point beside it.
      s.step = i;
      s.time = plan.sample_time(i);
      s.driver_values.resize(nd);
      for (int d = 0; d < nd; ++d) s.driver_values[d] = state.drivers[d].value.value();
      if (plan.parameter_is_time)
        s.taylor = state.series.leftCols(terms_out);
      else
        series_in_time(state.series, *rate, terms_out, s.taylor);
      s.residual = state.residual;
    } else {
      for (int d = 0; d < nd; ++d) now[d] = state.drivers[d].value.value();
      time_drivers(mech, now, plan.speed, plan.accel, terms_out, drivers_in_time);
      fill_sample(mech, state, i, plan.sample_time(i), drivers_in_time, terms_out, s);
    }
    if (options.condition) s.reciprocal_condition = on_singular_position ? 0.0 : sample_condition(state);
    check_finite(mech, s, plan.parameter_is_time ? state.drivers : drivers_in_time);
    result.max_residual = std::max(result.max_residual, s.residual);
    ++result.solved;
    if (sink) sink(s);
  };
  record(0);

  for (std::size_t i = 1; i < samples; ++i) {
    if (i % kControlInterval == 0) control.checkpoint("sweep", static_cast<long>(i), static_cast<long>(samples));
    const double p = plan.sample_parameter(i);
    // Built only for a warning or a stop: formatting it every step costs a third of a step.
    auto where = [i] { return "between steps " + std::to_string(i - 1) + " and " + std::to_string(i); };
    try {
      plan.drivers(p, 1, values);
      if (const std::string reason = nonpositive_distance(mech, values); !reason.empty()) {
        result.complete = false;
        result.stop_reason = "sweep stopped " + where() + ": " + reason;
        return result;
      }
      const TrackReport tr = track(mech, state, plan.drivers, p, track_options);
      // Leaving a sample that lies on a change point crosses it again: said once, at the sample.
      const bool leaving_singular_sample = on_singular_position && tr.passed_singularity &&
                                           std::abs(tr.singular_parameter - plan.sample_parameter(i - 1)) <=
                                               0.5 * std::abs(p - plan.sample_parameter(i - 1));
      on_singular_position = tr.reached && tr.singular_end;
      if (on_singular_position) {
        plan.drivers(p, 1, values);
        result.warnings.push_back({"change_point_at_sample", static_cast<int>(i),
                                   "step " + std::to_string(i) + " lies on a singular (change-point) position at " +
                                       values_text(m, values) +
                                       ", where the constraints do not fix the velocities: they are those of the "
                                       "branch the sweep came along, which it follows on (" +
                                       coasted_accuracy(tr.singular_end_accuracy, terms_out) + ")"});
      }
      if (tr.passed_singularity && !leaving_singular_sample) {
        plan.drivers(tr.singular_parameter, 1, values);
        result.warnings.push_back({"change_point_passed", static_cast<int>(i),
                                   "passed a singular (change-point) position " + where() + " near " +
                                       values_text(m, values) + ": the assembly branch may have changed there"});
      }
      if (!tr.reached) {
        plan.drivers(tr.limit_parameter, 1, values);
        result.complete = false;
        result.stop_reason = "sweep stopped " + where() + " at " + values_text(m, values) + ": " + tr.reason;
        return result;
      }
    } catch (const Error& e) {
      // A law with no value where the sweep goes is the model's error, as at a sample (exit 1 on
      // the command line), placed at the law's text: not a limit position of the linkage.
      if (e.kind() != ErrorKind::UndefinedLaw) throw;
      throw Error(e.kind(), e.message() + ", which the sweep passes " + where(), e.where(), e.file(), e.mark());
    }
    record(static_cast<int>(i));
    branches.check(state.q, static_cast<int>(i), where, result);
  }
  return result;
}

}  // namespace

namespace {

// Newton from state.q; throws AssemblyError naming the constraint that cannot be met.
void converge(const Mechanism& mech, State& state, const std::string& what) {
  const NewtonReport newton = solve_position(mech, state);
  if (newton.converged) return;
  const Model& m = mech.model();
  std::ostringstream s;
  s << what << ": " << mech.equations().rows[std::max(newton.worst_row, 0)].label << " is off by "
    << newton.residual / m.units.length_scale << " " << m.units.length;
  throw AssemblyError(s.str(), newton.worst_row,
                      newton.worst_row >= 0 ? mech.equations().rows[newton.worst_row].source : EntityRef{});
}

}  // namespace

Sample solve_at(const Mechanism& mech, State& state, const std::vector<double>& driver_values, int order) {
  const Model& m = mech.model();
  if (m.has_time_law())
    throw Error(ErrorKind::BadInput,
                "the model has a driver that follows a law in time: pose it by time (solve_at_time)");
  if (driver_values.size() != m.drivers.size())
    throw Error(ErrorKind::BadInput, "expected " + std::to_string(m.drivers.size()) + " driver values, got " +
                                         std::to_string(driver_values.size()));
  check_derivative_order(order);
  std::vector<double> speed, accel;
  for (const Driver& d : m.drivers) {
    speed.push_back(d.speed);
    accel.push_back(d.accel);
  }
  std::vector<DriverState> drivers;
  time_drivers(mech, driver_values, speed, accel, order + 1, drivers);
  state.drivers = drivers;
  std::vector<Series> values;
  for (double v : driver_values) values.push_back(Series(1, v));
  converge(mech, state, "no pose with " + values_text(m, values) + " near the given one");
  return make_sample(mech, state, 0, 0.0, drivers, order + 1);
}

Sample solve_at_time(const Mechanism& mech, State& state, double t, int order) {
  check_derivative_order(order);
  // Drivers without a law move from their start at their speed and acceleration.
  const SweepPath plan = sweep_path(mech, 2);
  const int terms = order + 1;
  std::vector<Series> values;
  motion_in_time(mech.model(), plan.from)(t, terms, values);
  set_drivers(mech, state, values);
  std::ostringstream at;
  at << "no pose at t = " << t << " s near the given one";
  converge(mech, state, at.str());
  return make_sample(mech, state, 0, t, state.drivers, terms);
}

Sample assemble_at_time(const Mechanism& mech, State& state, double t, int order) {
  const SweepPath plan = sweep_path(mech, 2);
  std::vector<Series> values;
  motion_in_time(mech.model(), plan.from)(t, 1, values);
  std::vector<double> at;
  for (const Series& v : values) at.push_back(v.value());
  try {
    assemble(mech, state, at);
  } catch (const AssemblyError&) {
    // The continuation stops at a limit of the drivers' travel, the pose left there. A start on
    // that limit (a dead centre, its value the limit's to rounding) is reached by Newton from
    // there; a start beyond it keeps the continuation's message, which says where it stops.
    const std::exception_ptr unreached = std::current_exception();
    try {
      return solve_at_time(mech, state, t, order);
    } catch (const AssemblyError&) {
      std::rethrow_exception(unreached);
    }
  }
  return solve_at_time(mech, state, t, order);
}

Eigen::VectorXd Sample::derivative(int k) const { return factorial(k) * taylor.col(k); }

double Sample::derivative(int coordinate, int k) const { return factorial(k) * taylor(coordinate, k); }

std::vector<Eigen::Vector2d> point_positions(const Mechanism& mech, const Eigen::VectorXd& q) {
  std::vector<Eigen::Vector2d> out;
  out.reserve(mech.model().points.size());
  for (std::size_t i = 0; i < mech.model().points.size(); ++i)
    out.push_back(mech.point_position(static_cast<int>(i), q));
  return out;
}

void point_derivatives(const Mechanism& mech, const Sample& sample, int point, double* x, double* y) {
  const int terms = static_cast<int>(sample.taylor.cols());
  const int col = mech.column_of(point);
  if (col < 0) {
    x[0] = mech.model().points[point].position.x();
    y[0] = mech.model().points[point].position.y();
    for (int k = 1; k < terms; ++k) x[k] = y[k] = 0.0;
    return;
  }
  for (int k = 0; k < terms; ++k) {
    x[k] = factorial(k) * sample.taylor(col, k);
    y[k] = factorial(k) * sample.taylor(col + 1, k);
  }
}

Motion2 point_motion(const Mechanism& mech, const Sample& sample, int point) {
  const int terms = static_cast<int>(sample.taylor.cols());
  Motion2 m;
  m.x.assign(terms, 0.0);
  m.y.assign(terms, 0.0);
  point_derivatives(mech, sample, point, m.x.data(), m.y.data());
  return m;
}

void body_angle_derivatives(const Mechanism& mech, const Sample& sample, int body, double* out) {
  const int terms = static_cast<int>(sample.taylor.cols());
  const Body& b = mech.model().bodies[body];
  auto coordinate = [&](int point, int axis) {
    Series s(terms);
    const int col = mech.column_of(point);
    if (col < 0) {
      s[0] = mech.model().points[point].position[axis];
    } else {
      for (int k = 0; k < terms; ++k) s[k] = sample.taylor(col + axis, k);
    }
    return s;
  };
  const Series ux = coordinate(b.points[1], 0) - coordinate(b.points[0], 0);
  const Series uy = coordinate(b.points[1], 1) - coordinate(b.points[0], 1);
  const Series angle = atan2(uy, ux);
  for (int k = 0; k < terms; ++k) out[k] = factorial(k) * angle[k];
}

std::vector<double> body_angle_motion(const Mechanism& mech, const Sample& sample, int body) {
  std::vector<double> out(sample.taylor.cols());
  body_angle_derivatives(mech, sample, body, out.data());
  return out;
}

}  // namespace nbar
