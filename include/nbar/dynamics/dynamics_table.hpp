// Inverse-dynamics columns for the result table. Forces in N, torques in N m and energies in J
// whatever the model's length unit.
#pragma once

#include <string>
#include <vector>

#include "nbar/dynamics/inverse_dynamics.hpp"
#include "nbar/kinematics/table.hpp"

namespace nbar {

struct DynamicsSummary {
  bool unique = true;          // false: redundant constraints, the minimum-norm forces are given
  double max_residual = 0.0;   // of the Newton-Euler equations, N or N m
  std::vector<std::string> warnings;
};

// Appends, for every joint, the force one link exerts on the other (`A.crank>coupler.Fx`,
// `.Fy`, and `.along` / `.across` the receiving link's axis from its first to its second
// point); where three or more links meet, the force the pin exerts on each
// (`A.pin>coupler.Fx`...); every slider's normal force and couple (`piston.slider.N`, `.M`),
// every slot's normal force (`D.slot.N`), every driver's effort (`crank.torque` or
// `.force`), and the kinetic and potential energy (`energy.kinetic`, `energy.potential`).
DynamicsSummary append_dynamics(const Mechanism& mech, const SweepResult& sweep, ResultTable& table);

}  // namespace nbar
