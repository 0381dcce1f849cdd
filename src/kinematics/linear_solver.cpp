#include "linear_solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "model/linear_algebra.hpp"

namespace nbar {

namespace {
// Below this reciprocal condition the Jacobian is singular for our purposes: a position
// where the mechanism locks or changes branch.
constexpr double kSingularRcond = 1e-13;
// Pivots within this ratio of each other say the matrix is regular: the ratio serves as its
// reciprocal condition. Beyond it the condition is estimated properly, so that every threshold
// the continuation compares it with near a singular position (1e-4 and below) meets an estimate.
constexpr double kRegularPivotRatio = 1e-3;
}  // namespace

LinearSolver::LinearSolver(const Mechanism& mech)
    : method_(mech.overdetermined() ? Method::LeastSquares : Method::LU),
      rows_(mech.row_count()),
      cols_(mech.coordinate_count()),
      pattern_(mech.equations().pattern) {
  if (method_ == Method::LU) {
    std::vector<SparseLU::Entry> entries;
    entries.reserve(pattern_.size());
    for (const auto& e : pattern_) entries.push_back({e.row, e.col});
    lu_.set_pattern(cols_, entries);
  }
}

void LinearSolver::dense_from(const std::vector<double>& values) {
  dense_.setZero(rows_, cols_);
  for (std::size_t e = 0; e < pattern_.size(); ++e) dense_(pattern_[e].row, pattern_[e].col) += values[e];
}

double LinearSolver::condition_near_singular(const std::vector<double>& values) {
  if (cols_ > kDenseConditionLimit) return lu_.reciprocal_condition_estimate(values.data());
  dense_from(values);
  return Eigen::PartialPivLU<Eigen::MatrixXd>(dense_).rcond();
}

bool LinearSolver::factorize(const std::vector<double>& values) {
  if (method_ == Method::LU) {
    if (!lu_.factorize(values.data())) {
      det_sign_ = 0;
      rcond_ = 0.0;
      return false;
    }
    det_sign_ = lu_.determinant_sign();
    const double ratio = lu_.pivot_ratio();
    rcond_ = ratio > kRegularPivotRatio ? ratio : condition_near_singular(values);
    return std::isfinite(rcond_) && rcond_ > kSingularRcond;
  }
  dense_from(values);
  cod_.setThreshold(1e-10);
  cod_.compute(dense_);
  det_sign_ = 0;
  const auto& r = cod_.matrixQTZ();
  const double big = std::abs(r(0, 0));
  const double small = std::abs(r(cols_ - 1, cols_ - 1));
  rcond_ = big > 0 ? small / big : 0.0;
  return cod_.rank() == cols_ && rcond_ > kSingularRcond;
}

double LinearSolver::condition_estimate(const std::vector<double>& values) const {
  if (method_ != Method::LU || rcond_ <= kRegularPivotRatio) return rcond_;
  return lu_.reciprocal_condition_estimate(values.data());
}

void LinearSolver::solve(const double* b, double* x) {
  if (method_ == Method::LU) {
    lu_.solve(b, x);
    return;
  }
  Eigen::VectorXd::Map(x, cols_) = cod_.solve(Eigen::VectorXd::Map(b, rows_));
}

void LinearSolver::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  if (method_ == Method::LU) {
    x.resize(cols_);
    lu_.solve(b.data(), x.data());
    return;
  }
  x = cod_.solve(b);
}

}  // namespace nbar
