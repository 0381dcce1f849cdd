// What a State keeps for the solver alone (State::Workspace): the factorisations, the predictor's
// past point and the scratch space of a step. The kinematics engine's own, not installed: the
// public State names it only, so its header shows no solver internals.
#pragma once

#include <Eigen/Core>

#include <array>
#include <vector>

#include "linear_solver.hpp"
#include "nbar/kinematics/position.hpp"
#include "path_history.hpp"

namespace nbar {

struct State::Workspace {
  explicit Workspace(const Mechanism& mech);

  // The factorised Jacobian at the state's q. Two slots, so a trial step can be rejected without
  // losing the factorisation of the last accepted point.
  LinearSolver& solver() { return solvers_[current_]; }
  const LinearSolver& solver() const { return solvers_[current_]; }
  LinearSolver& spare_solver() { return solvers_[1 - current_]; }
  void swap_solvers() { current_ = 1 - current_; }

  // Scratch space reused across steps: no allocation in the hot loop.
  Eigen::VectorXd phi, dq, rhs, q_accepted, q_predicted, q_track_start;
  std::vector<double> jacobian;
  std::vector<Series> driver_values;
  // The points track() accepted last, for its predictor.
  PathHistory history;

 private:
  std::array<LinearSolver, 2> solvers_;
  int current_ = 0;
};

// Factorises the Jacobian at state.q into `solver` (the state's own or its spare). False when
// singular.
bool factorize_jacobian(const Mechanism& mech, State& state, LinearSolver& solver);

}  // namespace nbar
