// Constraint equations in natural coordinates. Every equation is at most quadratic in the
// coordinates q (driver laws enter through known functions of the parameter), and every row is
// scaled so that its residual is a length: one tolerance, relative to the model's size, fits all.
// The kinematics engine's own (not installed): a Mechanism keeps its rows here
// (Mechanism::Equations), and the library's sources read them through Mechanism::equations().
#pragma once

#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

#include "nbar/kinematics/mechanism.hpp"
#include "nbar/kinematics/position.hpp"
#include "nbar/model/model.hpp"
#include "nbar/model/series.hpp"

namespace nbar {

enum class ConstraintType {
  Distance,            // |rj - ri|^2 - L^2 = 0                       (p: i, j; a = L)
  RigidX,              // rk = ri + a u + b u_perp, u = rj - ri: x row (p: i, j, k)
  RigidY,              //                                      y row
  PointOnLine,         // (rk - ri) x (rj - ri) = 0                   (p: i, j, k)
  Orientation,         // (rj - ri) x R(phi0) (rn - rm) = 0            (p: i, j, m, n; a, b = cos, sin phi0)
  DriveAngle,          // (rj - ri) x (cos th, sin th) = 0             (p: i, j)
  DriveRelativeAngle,  // (rj - ri) x R(th) (rn - rm) = 0         (p: i, j, m, n)
  DriveDistance,       // |rj - ri|^2 - s^2 = 0                        (p: i, j)
  DriveSlide,          // (rk - ri).(rj - ri) / Lg - s = 0             (p: i, j, k; a = Lg)
};

struct Constraint {
  ConstraintType type = ConstraintType::Distance;
  std::array<int, 4> p{-1, -1, -1, -1};  // point indices into Model::points
  double a = 0.0, b = 0.0;               // constants, see ConstraintType
  double scale = 1.0;                    // makes the residual a length
  int driver = -1;                       // index into Model::drivers for Drive* rows
  std::string label;                     // for people: "length of crank (O2-A)"
  EntityRef source;                      // the model entity the row comes from

  bool is_driver() const { return driver >= 0; }
};

struct JacobianEntry {
  int row = 0;
  int col = 0;
};

// A row as the evaluation loops read it (Mechanism::Equations::compiled, grouped as RowGroup says
// so that each loop runs over rows of one kind): the constants, and for each of its points where
// its coordinates are: a column of q (>= 0), or ~i for the fixed coordinates at
// Mechanism::Equations::fixed_coordinates[i] (unused slots: ~0 too, never read); and where the
// row's Jacobian entries for each point start in the pattern (-1 for fixed points and unused
// slots).
struct CompiledRow {
  ConstraintType type = ConstraintType::Distance;
  int row = 0;  // its place in Mechanism::Equations::rows and in the residual vector
  int driver = -1;
  double a = 0.0, b = 0.0, scale = 1.0;
  std::array<int, 4> at{~0, ~0, ~0, ~0};
  std::array<int, 4> entry{-1, -1, -1, -1};
};

// A run of compiled rows of one type: Mechanism::Equations::compiled[first, last). Rows of a
// body's length and of a crank's angle are grouped besides by which of their two points are fixed
// (bit 0 of `fixed` for the first, bit 1 for the second; 0 for the other types), so that their
// loops know it when compiled.
struct RowGroup {
  ConstraintType type = ConstraintType::Distance;
  int fixed = 0;
  int first = 0, last = 0;
};

// The rows of a Mechanism, built once with it.
struct Mechanism::Equations {
  // Every row, in the order of the residual vector: the constraints, then one row per driver.
  std::vector<Constraint> rows;
  // Where the Jacobian's values go, in the order evaluate_jacobian gives them (entries may repeat
  // a (row, col) pair; they add up).
  std::vector<JacobianEntry> pattern;
  // The rows as the evaluation loops read them, grouped (RowGroup), and the coordinates of the
  // points fixed to the frame (x, y of every point, in the model's order) that CompiledRow::at
  // points into.
  std::vector<CompiledRow> compiled;
  std::vector<RowGroup> groups;
  std::vector<double> fixed_coordinates;
  // For each row and point slot, the index of its first pattern entry (x, then y at +1); -1 when
  // that point is fixed.
  std::vector<std::array<int, 4>> entry;

  int entry_index(int row, int slot) const { return entry[row][slot]; }
};

// Makes `state` the driver's at `value` (with its sine and cosine for an angle), in place; in line,
// as it runs for every driver at every step of a sweep.
inline void set_driver_state(DriverState& state, const Series& value, bool angular) {
  // Term by term: the path has just stored them as scalars, and a copy of the whole series would
  // read them back as vectors (a store-forwarding stall every step of a sweep).
  state.value.reset(value.terms(), value[0]);
  for (int k = 1; k < value.terms(); ++k) state.value[k] = value[k];
  if (angular) {
    sincos(value, state.sin, state.cos);
  } else {
    state.sin = Series(value.terms());
    state.cos = Series(value.terms());
  }
}
// The same, as a new state.
inline DriverState make_driver_state(const Series& value, bool angular) {
  DriverState s;
  set_driver_state(s, value, angular);
  return s;
}

// Residuals of every row at q (length units). Returns the largest |residual|, infinite when one
// is NaN.
double evaluate_residuals(const Mechanism& mech, const Eigen::VectorXd& q, const std::vector<DriverState>& drivers,
                          Eigen::VectorXd& phi);
// The same, and the Jacobian's values as evaluate_jacobian gives them, in one pass over the rows.
double evaluate_residuals_and_jacobian(const Mechanism& mech, const Eigen::VectorXd& q,
                                       const std::vector<DriverState>& drivers, Eigen::VectorXd& phi,
                                       std::vector<double>& values);
// Jacobian values in the order of Mechanism::Equations::pattern (entries may repeat a
// (row, col) pair; they add up).
void evaluate_jacobian(const Mechanism& mech, const Eigen::VectorXd& q, const std::vector<DriverState>& drivers,
                       std::vector<double>& values);
// The k-th Taylor coefficient (k >= 1) of every row evaluated with q's coefficients 0..k-1 from
// `coefficients` (n x terms, column j = coefficient j) and coefficient k taken as zero.
// Then Phi_q * q_k = -rhs gives q_k.
void evaluate_series_remainder(const Mechanism& mech, const Eigen::MatrixXd& coefficients, int k,
                               const std::vector<DriverState>& drivers, Eigen::VectorXd& rhs);

}  // namespace nbar
