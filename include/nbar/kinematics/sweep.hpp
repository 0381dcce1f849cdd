// A sweep of the inputs: assemble at the start, follow the branch through every sample, and
// at each sample the exact time derivatives of every coordinate up to the requested order.
#pragma once

#include <Eigen/Core>

#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "nbar/kinematics/continuation.hpp"
#include "nbar/model/diagnostics.hpp"
#include "nbar/model/run_control.hpp"

namespace nbar {

// The most samples a sweep may have unless its caller raises the limit (`--max-steps` on the
// command line): every sample is kept, so the limit bounds the memory and the time of a run.
inline constexpr int kDefaultMaxSweepSamples = 10'000'000;

// The highest time derivative a sweep computes (jerk and two beyond).
inline constexpr int kMaxDerivativeOrder = 5;
// Throws Error(ErrorKind::BadInput) unless 0 <= order <= kMaxDerivativeOrder: every entry point
// that takes an order asks this first.
void check_derivative_order(int order);

struct SweepOptions {
  std::optional<int> steps;                 // overrides the model's sweep: number of samples, ends included
  int order = 2;                            // highest time derivative (0 = positions only), at most 5
  int max_steps = kDefaultMaxSweepSamples;  // more samples than this is an error
  bool condition = false;                   // estimate each sample's condition (Sample::reciprocal_condition)
};

struct Sample {
  int step = 0;
  double time = 0.0;                  // s
  std::vector<double> driver_values;  // SI
  // n x (order+1) Taylor coefficients of q in time: column k is q^(k) / k!, not the k-th
  // derivative (read derivatives with derivative()).
  Eigen::MatrixXd taylor;
  double residual = 0.0;  // max |Phi| over all rows, m
  // With SweepOptions::condition, an estimate of 1 / cond_1(Phi_q) at this pose from the
  // factorisation the series were solved with (LinearSolver::condition_estimate: no new
  // factorisation); 0 on a singular position. NaN when not asked for.
  double reciprocal_condition = std::numeric_limits<double>::quiet_NaN();
  // A rocking sweep (`at_limits: reverse`): how many times the input has turned back at a limit
  // since the start (SweepResult::reversals says where and when).
  int reversals = 0;
  // Each body's angle (rad) with its whole turns, where the sample's maker followed them through
  // its motion (a simulation, whose rows may be far apart); empty for a sweep, whose table
  // unwraps the angles from row to row.
  std::vector<double> body_angles;

  int order() const { return static_cast<int>(taylor.cols()) - 1; }
  // The k-th time derivative of q (k! times column k), and of one coordinate.
  Eigen::VectorXd derivative(int k) const;
  double derivative(int coordinate, int k) const;
  Eigen::VectorXd positions() const { return taylor.col(0); }
};

// Where a rocking sweep's input turned back: at a limit of the mechanism, between two samples or
// on one. The speed keeps its size and changes sign there; the mechanism's other velocities grow
// without bound as the limit nears (the constraint Jacobian is singular at it).
struct Reversal {
  int after_step = 0;         // between this sample and the next
  double time = 0.0;          // s
  double driver_value = 0.0;  // SI: the limit, as find_path_limits locates it
  std::string involved;       // what is in line there ("coupler and output in line at B")
  // The sample `after_step` lies on the turn (its derivatives are then not numbers: the linkage is
  // at its limit while the input moves at full speed); else the turn is between it and the next.
  bool at_sample = false;
};

struct SweepResult {
  int order = 2;
  std::vector<Sample> samples;
  bool complete = true;
  std::string stop_reason;        // when !complete
  std::vector<Warning> warnings;  // branch changes ("branch_changed"), singular crossings ("change_point_passed")
  AssemblyReport assembly;
  std::vector<std::string> branches;  // each four-bar loop's branch at the start: open | crossed
  double max_residual = 0.0;
  std::size_t solved = 0;           // samples solved: samples.size(), or those handed to a sink
  std::vector<Reversal> reversals;  // a rocking sweep's turns, in order
};

// Receives every sample as the sweep solves it, in order. The sample is the sweep's scratch
// space, valid only during the call: a sweep with a sink keeps no sample, so its memory does not
// grow with the number of samples.
using SampleSink = std::function<void(const Sample&)>;

// Runs the whole sweep. Throws Error: CannotAssemble (an AssemblyError) when the start cannot be
// assembled, BadInput for bad options, UndefinedLaw (at the driver) for a driver law undefined
// where the sweep goes, Cancelled when `control` says so (checked between samples). A sweep
// that cannot go on stops early and says why (complete is false).
SweepResult run_sweep(const Mechanism& mech, const SweepOptions& options = {}, const RunControl& control = {});
// The same with every sample handed to `sink` instead of kept (result.samples stays empty).
SweepResult run_sweep(const Mechanism& mech, const SweepOptions& options, const RunControl& control,
                      const SampleSink& sink);

// Each driver's value at the start of the sweep (SI).
// Throws Error(InvalidModel) at the model's sweep when it has more than `max_steps` samples.
std::vector<double> sweep_start_values(const Mechanism& mech, int max_steps = kDefaultMaxSweepSamples);

// The path the sweep follows: the drivers as series in a tracking parameter, the parameter and
// the time of every sample. Tracking from the start along `drivers` (assemble, then track)
// stays on the branch the sweep takes.
struct SweepPath {
  DriverPath drivers;
  std::vector<double> parameters;  // of every sample (empty when planned untabulated)
  std::vector<double> times;       // s, of every sample (empty when planned untabulated)
  std::size_t samples = 0;         // how many
  // The parameter and the time of sample i, the same numbers as parameters[i] and times[i].
  double sample_parameter(std::size_t i) const;
  double sample_time(std::size_t i) const;
  bool parameter_is_time = true;
  bool time_law = false;                          // some driver follows a law in t: the parameter is the time
  std::vector<double> from, delta, speed, accel;  // per driver (SI), for from/to sweeps
  // The parameter at which the first driver has `value` (SI), or, for time laws, the time
  // `value` (s). Throws Error(BadInput) for a model without drivers or a first driver that
  // does not move.
  double parameter_of(double value) const;
  // The time at parameter p.
  double time_at(double p) const;
  double fraction_time = 0.0;  // from/to sweeps: the time the first driver takes over its range
  double time_step = 0.0;      // time-law sweeps
};
// The number of samples sweep_path plans (`steps`, or the model's sweep: its steps, or for time
// laws its duration over its time step, plus one). A double, so that a front-end can refuse an
// absurd sweep before anything is allocated.
double sweep_sample_count(const Model& model, std::optional<int> steps = std::nullopt);
// Throws Error(BadInput) for `steps` below one or above `max_steps`, and
// Error(InvalidModel) about the model's sweep (EntityRef::Kind::Sweep) when the model's own
// sweep has more than `max_steps` samples.
// With `tabulate` false, parameters and times are left empty (sample_parameter and sample_time
// give them): run_sweep's memory then does not grow with the number of samples.
SweepPath sweep_path(const Mechanism& mech, std::optional<int> steps = std::nullopt,
                     int max_steps = kDefaultMaxSweepSamples, bool tabulate = true);
// The check sweep_path makes of the number of samples, alone (nothing is allocated).
void check_sample_count(const Model& model, std::optional<int> steps, int max_steps = kDefaultMaxSweepSamples);

// One pose, like MuJoCo's mj_forward at a state: Newton from state.q with the drivers at
// `driver_values` (SI; moving at each driver's `speed` and `accel`), then the Taylor
// coefficients in time to `order`. The pose found is the one nearest state.q, so small moves
// stay on its branch. Throws AssemblyError when Newton does not converge, and Error(BadInput)
// for a model with a time-law driver (use solve_at_time).
Sample solve_at(const Mechanism& mech, State& state, const std::vector<double>& driver_values, int order);
// The same for models driven by laws in time (and any model: drivers without a law move from
// their start at their speed), at time t.
Sample solve_at_time(const Mechanism& mech, State& state, double t, int order);
// The pose at time t reached from the drawing as a sweep reaches its start: Newton at the drawn
// driver values, then continuation of the drivers to their values at t on the drawn branch
// (assemble), then solve_at_time there. For a fresh State: Newton straight from the drawing would
// find the pose nearest it, which for a driver far from its drawn angle can be the other branch
// of the driver's own row (the body turned half a turn).
Sample assemble_at_time(const Mechanism& mech, State& state, double t, int order);

// Derived motion of a sample: positions and derivatives 0..order of a point, and of a body's
// angle (the angle of the line from its first to its second point).
struct Motion2 {
  std::vector<double> x, y;  // x[k] = k-th time derivative
};
Motion2 point_motion(const Mechanism& mech, const Sample& sample, int point);
std::vector<double> body_angle_motion(const Mechanism& mech, const Sample& sample, int body);
// The same without allocating, for tables: order + 1 values written to each of x, y (out).
void point_derivatives(const Mechanism& mech, const Sample& sample, int point, double* x, double* y);
void body_angle_derivatives(const Mechanism& mech, const Sample& sample, int body, double* out);
std::vector<Eigen::Vector2d> point_positions(const Mechanism& mech, const Eigen::VectorXd& q);

}  // namespace nbar
