// Factorises the Jacobian once per step and solves with it for the Newton step and for every
// Taylor coefficient. Square regular systems use LU (dense when small, sparse when large);
// systems with redundant constraints are overdetermined but consistent and use a
// rank-revealing least-squares factorisation.
#pragma once

#include <Eigen/Core>
#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include <array>
#include <memory>
#include <vector>

#include "nbar/kinematics/mechanism.hpp"

namespace nbar {

class LinearSolver {
 public:
  enum class Method { DenseLU, SparseLU, LeastSquares };

  // Dense LU up to this many coordinates; above, sparse LU (measured crossover: about 40).
  static constexpr int kDenseLimit = 40;
  // Up to this many coordinates the dense LU is factorised and solved by the loops below rather
  // than by Eigen's general routines, whose set-up costs more than the arithmetic at this size.
  // The loops do Eigen's operations in Eigen's order (unblocked partial-pivoting LU, and the
  // triangular solves within one panel of EIGEN_TUNE_TRIANGULAR_PANEL_WIDTH = 8), so that the
  // numbers are the same bit for bit.
  static constexpr int kSmallLimit = 8;

  explicit LinearSolver(const Mechanism& mech);
  // A copy solves exactly as its source: it holds its own pattern, and a factorised sparse LU
  // (which Eigen cannot copy) is factorised again from the copied matrix.
  LinearSolver(const LinearSolver& other);
  LinearSolver& operator=(const LinearSolver& other);

  Method method() const { return method_; }
  // Returns false when the matrix is singular to working precision.
  bool factorize(const std::vector<double>& jacobian_values);
  // x = J^-1 b (least squares for overdetermined systems); b and x must be different vectors.
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x);
  // Sign of det(J) for square systems: constant along a regular branch. 0 when not available.
  int determinant_sign() const { return det_sign_; }
  // Estimate of 1/cond(J) (1 for sparse systems, where it is not estimated).
  double reciprocal_condition() const { return rcond_; }

 private:
  Method method_;
  int rows_, cols_;
  std::vector<JacobianEntry> pattern_;  // a copy, so a State may outlive its Mechanism's storage
  Eigen::MatrixXd dense_;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;
  bool small_ = false;                                   // the loops' LU, not lu_
  std::array<double, kSmallLimit * kSmallLimit> small_lu_{};  // column-major, unit lower L and U
  std::array<int, kSmallLimit> small_row_{};             // row i of P b is b[small_row_[i]]
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod_;
  Eigen::SparseMatrix<double> sparse_;
  std::vector<int> value_slot_;  // pattern entry -> index into sparse_.valuePtr()
  Eigen::SparseLU<Eigen::SparseMatrix<double>> sparse_lu_;
  bool factorize_small_from(const std::vector<double>& values);
  void solve_small(const Eigen::VectorXd& b, Eigen::VectorXd& x) const;

  bool pattern_analysed_ = false;
  bool sparse_factorized_ = false;
  int det_sign_ = 0;
  double rcond_ = 0.0;
};

}  // namespace nbar
