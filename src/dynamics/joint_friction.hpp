// Friction in joints (Model::frictions) as generalised forces in the natural coordinates, for the
// forward dynamics. Each friction resists one relative coordinate s(q) of its joint: the angle of
// one link relative to the other at a pin, or the position of a slider's or slot's point along
// its guide. Its force f(s') = -viscous s' - coulomb tanh(s' / creep_speed) does the virtual work
// f ds = f grad(s) . dq, so it enters Q as f grad(s); the power it takes, -f s', is >= 0.
#pragma once

#include <Eigen/Core>

#include "nbar/kinematics/mechanism.hpp"

namespace nbar {

// Adds every joint friction's generalised force at (q, q') to `loads`; returns the power the
// friction dissipates there (W, >= 0).
double add_joint_friction(const Mechanism& mech, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                          Eigen::VectorXd& loads);

// The friction force or torque of one joint friction at the relative speed `speed` (rad/s or m/s).
double friction_force(const JointFriction& friction, double speed);

}  // namespace nbar
