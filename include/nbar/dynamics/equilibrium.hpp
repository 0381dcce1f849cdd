// Static equilibrium of the free drivers (`free: true`) under the model's loads at t = 0: gravity,
// springs with their preload, forces and torques at their values at t = 0 (a motor at its stall
// torque); the kinematic drivers held at their start. Dampers and joint friction give no force at
// rest (Coulomb friction would hold a range of positions; it is left out, as the docs say).
//
// Method (docs/dynamics.md, Equilibrium): the free drivers' values x are the coordinates of the
// constraint manifold there (every pose assembled from them, on the branch of the start). The
// generalised force on them is minus the effort each must give to hold the pose, from the
// inverse dynamics at rest; Newton's method zeroes it, with the stiffness K = d(effort)/dx by
// central differences. At the solution K is the Hessian of the potential in x: its
// eigenvalues' signs (Sylvester's law of inertia: the same in any coordinates) say whether the
// equilibrium is stable (all positive), unstable (one negative) or neutral (one zero).
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

#include "nbar/kinematics/mechanism.hpp"
#include "nbar/kinematics/sweep.hpp"
#include "nbar/kinematics/table.hpp"
#include "nbar/model/diagnostics.hpp"
#include "nbar/model/run_control.hpp"

namespace nbar {

enum class Stability { stable, unstable, neutral };
const char* to_string(Stability stability);

struct EquilibriumOptions {
  int max_iterations = 50;  // Newton iterations
};

struct Equilibrium {
  std::vector<int> free_drivers;  // driver indices
  Sample pose;                    // order 0: every driver's value and the positions q (SI)
  // Per free driver: the generalised force left on it (N m or N); the residual is the largest.
  std::vector<double> forces;
  double residual = 0.0;
  // The reduced stiffness K = d(effort)/dx (SI: N m/rad, N/rad, N m/m, N/m) and its eigenvalues,
  // smallest first. Their signs, not their sizes, are coordinate-free when the units are mixed.
  Eigen::MatrixXd stiffness;
  std::vector<double> eigenvalues;
  Stability stability = Stability::stable;
  int iterations = 0;
  // What the pose should be read with: `equilibrium_at_toggle` where the constraint Jacobian of
  // every row (the free drivers' at their values) is singular there to 1e-8 (a dead centre or
  // change point: the loads do not determine the motion there, and the stability is that of the
  // start's branch only); `equilibrium_past_toggle` where its determinant's sign differs from the
  // start's (the iteration passed a toggle: the pose may be on another branch than the drawn one).
  std::vector<Warning> warnings;
};

// Throws Error(InvalidModel) at the first free driver when there is nothing free, when there is
// no equilibrium (a load that nothing balances: the stiffness is zero where the force is not),
// or when Newton's method does not converge (the message gives the values and force reached);
// Error(CannotAssemble) when the start cannot be assembled; Error(Cancelled) from `control`.
Equilibrium find_equilibrium(const Mechanism& mechanism, const EquilibriumOptions& options = {},
                             const RunControl& control = {});

// The equilibrium's pose as a one-row table: step, t, every driver, every point's x and y, every
// body's angle (the positions columns of `nbar solve --order 0`), in the model's units.
ResultTable equilibrium_table(const Mechanism& mechanism, const Equilibrium& equilibrium);

}  // namespace nbar
