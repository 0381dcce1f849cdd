// Factorises the Jacobian once per step and solves with it for the Newton step and for every
// Taylor coefficient. Square regular systems use a sparse LU whose pivots are chosen once and
// kept while they stay good (SparseLU); systems with redundant constraints are overdetermined but
// consistent and use a rank-revealing least-squares factorisation.
#pragma once

#include <Eigen/Core>
#include <Eigen/Dense>

#include <vector>

#include "constraints.hpp"
#include "sparse_lu.hpp"

namespace nbar {

class LinearSolver {
 public:
  enum class Method { LU, LeastSquares };

  // Up to this many coordinates a Jacobian that may be near singular (its pivots differ by more
  // than a factor 1e6) gets its condition from a dense LU (Eigen's estimate); above, from
  // Hager's estimate on the sparse factors.
  static constexpr int kDenseConditionLimit = 40;

  explicit LinearSolver(const Mechanism& mech);

  Method method() const { return method_; }
  // Returns false when the matrix is singular to working precision.
  bool factorize(const std::vector<double>& jacobian_values);
  // x = J^-1 b (least squares for overdetermined systems); b and x must be different vectors.
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x);
  // The same with b (row_count() values) and x (coordinate_count() values) as arrays, which may
  // be the same for square systems.
  void solve(const double* b, double* x);
  // The same for a square system of N coordinates (N: coordinate_count(), at most
  // SparseLU::kDenseSolveLimit), without the dispatch on the method and the size.
  template <int N>
  void solve_dense(const double* b, double* x) const {
    lu_.solve_dense<N>(b, x);
  }
  // Sign of det(J) for square systems: constant along a regular branch. 0 when not available.
  int determinant_sign() const { return det_sign_; }
  // Estimate of 1/cond(J): while the pivots are within kRegularPivotRatio of each other, only
  // their ratio (what the solver needs to know: the matrix is regular).
  double reciprocal_condition() const { return rcond_; }
  // An estimate of 1/cond_1(J) of the last factorisation (`values` its entries) everywhere: the
  // one factorize() made when the pivots were far apart, else Hager's on the kept sparse factors
  // (a few solves, no new factorisation); the least-squares method's own ratio.
  double condition_estimate(const std::vector<double>& values) const;
  // How many times the LU chose its pivots (1 + the steps where the kept ones were no longer good).
  long pivot_analyses() const { return lu_.analyses(); }

 private:
  void dense_from(const std::vector<double>& values);
  double condition_near_singular(const std::vector<double>& values);

  Method method_;
  int rows_, cols_;
  std::vector<JacobianEntry> pattern_;  // a copy, so a State may outlive its Mechanism's storage
  SparseLU lu_;
  Eigen::MatrixXd dense_;
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod_;
  int det_sign_ = 0;
  double rcond_ = 0.0;
};

}  // namespace nbar
