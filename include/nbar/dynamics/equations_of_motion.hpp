// The equations of motion of a simulation at one time, written out for teaching (`nbar explain
// --simulate --at T`, Python's Model.explain(simulate=True, at=T), POST /api/explain): the system
// the forward dynamics solves at every evaluation (docs/dynamics.md, Formulation),
//
//   [ M     Phi_q^T ] [ q''    ]   [ Q     ]
//   [ Phi_q 0       ] [ lambda ] = [ gamma ]
//
// at the state the simulation reaches at T, with Q split by origin and the system's solution.
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

#include "nbar/dynamics/forward_dynamics.hpp"
#include "nbar/kinematics/mechanism.hpp"
#include "nbar/model/run_control.hpp"

namespace nbar {

// Everything in SI: q in m, M in kg, Q in N, gamma in m/s^2, lambda in N. Each row of Phi is
// scaled as the solver scales it (its residual a length), so Phi_q is dimensionless.
struct EquationsOfMotionAt {
  double time = 0.0;                     // s, T
  Eigen::VectorXd q, velocity;           // the simulation's row at T: m, m/s
  std::vector<std::string> coordinates;  // q's names: "A.x", "A.y", ...
  std::vector<int> rows;                 // the rows of Phi kept (joints and kinematic drivers), as the mechanism's rows
  std::vector<std::string> row_labels;   // as the solver names them
  std::vector<std::string> free_drivers;  // the drivers whose rows are dropped
  Eigen::MatrixXd mass;                   // M (n x n), constant
  Eigen::MatrixXd jacobian;               // Phi_q of the kept rows at q
  // Q's parts by origin: gravity; the given forces and torques (laws of time, motors' torque-speed
  // lines); springs and dampers; joint friction. `forces` is their sum.
  Eigen::VectorXd gravity, applied, springs, friction, forces;
  Eigen::VectorXd gamma;  // Phi_q q'' = gamma
  // The solution of the system written out (a dense complete orthogonal decomposition: the
  // least-norm multipliers where the rows are redundant), and how well it satisfies the system:
  // max |residual| / max |right-hand side|.
  Eigen::VectorXd acceleration, multipliers;
  double residual = 0.0;
  // q'' of the simulation's own row at T (its sparse augmented solve), for comparison.
  Eigen::VectorXd simulated_acceleration;
  long accepted_steps = 0;  // of the run to T
};

// The equations of motion at `time` (s, >= 0 and finite) of the simulation run with `options`
// (as `simulate`, its end_time replaced by `time`: the state is the last row of that run; at 0,
// the start). Throws Error: BadInput for a time that is negative or not a number, InvalidModel at
// the first driver when nothing is free, StoppedAtLimit at the entity concerned when the run ends
// before `time` (a toggle, a stop condition, its step limit), Cancelled from `control`.
EquationsOfMotionAt equations_of_motion_at(const Mechanism& mechanism, double time, SimulationOptions options,
                                           const RunControl& control = {});

// As text: the system, its blocks, Q by origin and the solution, numbers in SI.
std::string render_equations_of_motion(const Mechanism& mechanism, const EquationsOfMotionAt& equations);

}  // namespace nbar
