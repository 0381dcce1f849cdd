// The velocities a simulation starts with: the kinematic drivers' speeds exactly, and the free
// drivers' `initial_speed` as nearly as the constraints allow.
#pragma once

#include <Eigen/Core>

#include <vector>

#include "nbar/kinematics/mechanism.hpp"
#include "nbar/model/diagnostics.hpp"

namespace nbar {

// q' with Phi_q q' = -Phi_t on every kept row (the joints and the kinematic drivers), and on the
// free drivers' rows in the least-squares sense within that: two free drivers whose initial
// speeds cannot both hold (or one the others already fix) get the nearest speeds that can. Each
// free driver whose speed had to change by more than 1e-9 of its size (per second) adds a
// warning "initial_speed_projected" saying by how much. `jacobian` and `phi_t` are over every
// row of the mechanism's equations.
Eigen::VectorXd consistent_initial_velocity(const Mechanism& mech, const Eigen::MatrixXd& jacobian,
                                            const Eigen::VectorXd& phi_t, std::vector<Warning>& warnings);

}  // namespace nbar
