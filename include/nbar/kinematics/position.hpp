// The numbers that change while a mechanism moves (like Pinocchio's Data or MuJoCo's mjData),
// and the algorithms that fill them: Newton-Raphson on the constraints, then the Taylor
// coefficients of q along the path, from one factorisation of the Jacobian.
#pragma once

#include <Eigen/Core>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "nbar/kinematics/mechanism.hpp"
#include "nbar/model/series.hpp"

namespace nbar {

// A driver's value along the path as a Taylor series, with its sine and cosine for angles.
struct DriverState {
  Series value, cos, sin;
};

// Copyable: a copy is a snapshot that solves on its own exactly as its source would.
// Field by field (like MuJoCo's mjData): which call fills it, its units and its shape; n is
// mech.coordinate_count() (x, y of every moving point), d the number of drivers.
struct State {
  explicit State(const Mechanism& mech);

  // track() and the sweep: where along the path q is (s for a sweep in time).
  double parameter = 0.0;
  // solve_position() and track(): the natural coordinates, x then y of every moving point in
  // the model's order, m; n entries. The constructor sets the drawn pose.
  Eigen::VectorXd q;
  // set_drivers(): d entries, each driver's value (rad or m) with its sine and cosine for an
  // angle, as series in the parameter.
  std::vector<DriverState> drivers;
  // compute_series(): n x terms Taylor coefficients of q in the parameter (column k is
  // q^(k) / k!, m per unit parameter^k); column 0 is q.
  Eigen::MatrixXd series;
  // solve_position() and max_residual(): max |Phi| over every row at q, m.
  double residual = 0.0;
  // solve_position(): the Newton iterations of the last solve.
  int iterations = 0;

  // The solver's own, which no caller reads: the factorised Jacobian at q (and a spare, so that a
  // trial step can be rejected without losing the last accepted point's), the predictor's past
  // point and scratch space reused across steps, so that a step allocates nothing. Defined in
  // src/kinematics/workspace.hpp; copied with the State (a State moved from may only be assigned
  // to or destroyed).
  struct Workspace;
  Workspace& workspace() { return *workspace_; }
  const Workspace& workspace() const { return *workspace_; }

 private:
  // Owns the workspace, and copies it when the State is copied.
  class WorkspaceCopy {
   public:
    explicit WorkspaceCopy(const Mechanism& mech);
    WorkspaceCopy(const WorkspaceCopy& other);
    WorkspaceCopy& operator=(const WorkspaceCopy& other);
    WorkspaceCopy(WorkspaceCopy&& other) noexcept;
    WorkspaceCopy& operator=(WorkspaceCopy&& other) noexcept;
    ~WorkspaceCopy();
    Workspace& operator*() const { return *owned_; }

   private:
    std::unique_ptr<Workspace> owned_;
  };
  WorkspaceCopy workspace_;
};

// Sets the drivers from their values (series in the path parameter; terms >= 1).
void set_drivers(const Mechanism& mech, State& state, const std::vector<Series>& values);

// Factorises the Jacobian at state.q (kept in the state's workspace for the solves that follow).
// False when singular.
bool factorize_jacobian(const Mechanism& mech, State& state);

// Largest |residual| over all rows at state.q, and which row it is.
double max_residual(const Mechanism& mech, State& state, int* worst_row = nullptr);

struct NewtonReport {
  bool converged = false;
  int iterations = 0;
  double residual = 0.0;
  int worst_row = -1;
};

// What solve_position did, iteration by iteration, for people (nbar explain). Iterate 0 is the
// starting guess; each iterate's dq is the step taken from its q (after any damping), empty on
// the last one. SI units.
struct NewtonTrace {
  struct Iterate {
    Eigen::VectorXd q;
    double residual = 0.0;  // max |Phi| at q
    Eigen::VectorXd dq;
    double damping = 1.0;  // the fraction of the Newton step taken (1: the full step)
    bool nudged = false;   // the Jacobian was singular: dq is a small nudge off the singular set
  };
  std::vector<Iterate> iterates;
};

// Damped Newton-Raphson (Gauss-Newton for redundant systems) from state.q with the drivers
// as set. On success the Jacobian is factorised at the solution. With a trace, every iterate
// is recorded there (nothing is recorded, or allocated, without one).
NewtonReport solve_position(const Mechanism& mech, State& state, int max_iterations = 50, NewtonTrace* trace = nullptr);

// Taylor coefficients 1..terms-1 of q in the path parameter, with the Jacobian factorised at
// state.q: Phi_q q_k = -R_k. Writes state.series (or `out`).
void compute_series(const Mechanism& mech, State& state, int terms);
void compute_series(const Mechanism& mech, State& state, const std::vector<DriverState>& drivers, int terms,
                    Eigen::MatrixXd& out);

}  // namespace nbar
