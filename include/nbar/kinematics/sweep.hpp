// A sweep of the inputs: assemble at the start, follow the branch through every sample, and
// at each sample the exact time derivatives of every coordinate up to the requested order.
#pragma once

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

#include "nbar/kinematics/continuation.hpp"

namespace nbar {

struct SweepOptions {
  std::optional<int> steps;  // overrides the model's sweep: number of samples, ends included
  int order = 2;             // highest time derivative (0 = positions only), at most 5
};

struct Sample {
  int step = 0;
  double time = 0.0;                  // s
  std::vector<double> driver_values;  // SI
  Eigen::MatrixXd series;             // n x (order+1) Taylor coefficients of q in time
  double residual = 0.0;              // max |Phi| over all rows, m
};

struct SweepResult {
  int order = 2;
  std::vector<Sample> samples;
  bool complete = true;
  std::string stop_reason;             // when !complete
  std::vector<std::string> warnings;   // branch changes, singular crossings
  AssemblyReport assembly;
  std::vector<std::string> branches;   // each four-bar loop's branch at the start: open | crossed
  double max_residual = 0.0;
};

// Runs the whole sweep. Throws AssemblyError when the start cannot be assembled and
// std::invalid_argument for bad options; a sweep that cannot go on stops early and says why.
SweepResult run_sweep(const Mechanism& mech, const SweepOptions& options = {});

// Each driver's value at the start of the sweep (SI).
std::vector<double> sweep_start_values(const Mechanism& mech);

// Derived motion of a sample: positions and derivatives 0..order of a point, and of a body's
// angle (the angle of the line from its first to its second point).
struct Motion2 {
  std::vector<double> x, y;  // x[k] = k-th time derivative
};
Motion2 point_motion(const Mechanism& mech, const Sample& sample, int point);
std::vector<double> body_angle_motion(const Mechanism& mech, const Sample& sample, int body);
std::vector<Eigen::Vector2d> point_positions(const Mechanism& mech, const Eigen::VectorXd& q);

}  // namespace nbar
