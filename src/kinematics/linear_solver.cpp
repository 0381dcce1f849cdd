#include "nbar/kinematics/linear_solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace nbar {

namespace {
// Below this reciprocal condition the Jacobian is singular for our purposes: a position
// where the mechanism locks or changes branch.
constexpr double kSingularRcond = 1e-13;
}  // namespace

LinearSolver::LinearSolver(const Mechanism& mech)
    : rows_(mech.row_count()), cols_(mech.coordinate_count()), pattern_(mech.jacobian_pattern()) {
  if (mech.overdetermined())
    method_ = Method::LeastSquares;
  else if (cols_ <= kDenseLimit)
    method_ = Method::DenseLU;
  else
    method_ = Method::SparseLU;

  if (method_ == Method::SparseLU) {
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(pattern_.size());
    for (const auto& e : pattern_) t.emplace_back(e.row, e.col, 1.0);
    sparse_.resize(rows_, cols_);
    sparse_.setFromTriplets(t.begin(), t.end());
    sparse_.makeCompressed();
    value_slot_.resize(pattern_.size());
    for (std::size_t e = 0; e < pattern_.size(); ++e) {
      const int col = pattern_[e].col;
      const int* inner = sparse_.innerIndexPtr();
      for (int k = sparse_.outerIndexPtr()[col]; k < sparse_.outerIndexPtr()[col + 1]; ++k) {
        if (inner[k] == pattern_[e].row) {
          value_slot_[e] = k;
          break;
        }
      }
    }
  } else {
    dense_.resize(rows_, cols_);
  }
  small_ = method_ == Method::DenseLU && rows_ == cols_ && cols_ <= kSmallLimit;
}

LinearSolver::LinearSolver(const LinearSolver& other)
    : method_(other.method_),
      rows_(other.rows_),
      cols_(other.cols_),
      pattern_(other.pattern_),
      dense_(other.dense_),
      lu_(other.lu_),
      small_(other.small_),
      small_lu_(other.small_lu_),
      small_row_(other.small_row_),
      cod_(other.cod_),
      sparse_(other.sparse_),
      value_slot_(other.value_slot_),
      det_sign_(other.det_sign_),
      rcond_(other.rcond_) {
  if (other.sparse_factorized_) {
    sparse_lu_.analyzePattern(sparse_);
    sparse_lu_.factorize(sparse_);
    pattern_analysed_ = sparse_factorized_ = true;
  }
}

LinearSolver& LinearSolver::operator=(const LinearSolver& other) {
  if (this == &other) return *this;
  method_ = other.method_;
  rows_ = other.rows_;
  cols_ = other.cols_;
  pattern_ = other.pattern_;
  dense_ = other.dense_;
  lu_ = other.lu_;
  small_ = other.small_;
  small_lu_ = other.small_lu_;
  small_row_ = other.small_row_;
  cod_ = other.cod_;
  sparse_ = other.sparse_;
  value_slot_ = other.value_slot_;
  det_sign_ = other.det_sign_;
  rcond_ = other.rcond_;
  pattern_analysed_ = sparse_factorized_ = false;
  if (other.pattern_analysed_ && method_ == Method::SparseLU) {
    sparse_lu_.analyzePattern(sparse_);
    pattern_analysed_ = true;
  }
  if (other.sparse_factorized_) {
    sparse_lu_.factorize(sparse_);
    sparse_factorized_ = true;
  }
  return *this;
}

bool LinearSolver::factorize(const std::vector<double>& values) {
  switch (method_) {
    case Method::DenseLU: {
      if (small_) return factorize_small_from(values);
      dense_.setZero();
      for (std::size_t e = 0; e < pattern_.size(); ++e) dense_(pattern_[e].row, pattern_[e].col) += values[e];
      lu_.compute(dense_);
      const auto& lu = lu_.matrixLU();
      int sign = lu_.permutationP().determinant();
      double smallest = std::numeric_limits<double>::infinity(), largest = 0.0;
      for (int i = 0; i < cols_; ++i) {
        sign *= lu(i, i) < 0 ? -1 : 1;
        smallest = std::min(smallest, std::abs(lu(i, i)));
        largest = std::max(largest, std::abs(lu(i, i)));
      }
      det_sign_ = sign;
      // Eigen's condition estimate costs several triangular solves, a quarter of a four-bar
      // step: the pivot ratio is enough to tell a regular matrix, the estimate is made only
      // when the pivots say the matrix may be near singular.
      const double pivot_ratio = largest > 0.0 ? smallest / largest : 0.0;
      rcond_ = pivot_ratio > 1e-6 ? pivot_ratio : lu_.rcond();
      return std::isfinite(rcond_) && rcond_ > kSingularRcond;
    }
    case Method::SparseLU: {
      double* v = sparse_.valuePtr();
      std::fill(v, v + sparse_.nonZeros(), 0.0);
      for (std::size_t e = 0; e < pattern_.size(); ++e) v[value_slot_[e]] += values[e];
      if (!pattern_analysed_) {
        sparse_lu_.analyzePattern(sparse_);
        pattern_analysed_ = true;
      }
      sparse_lu_.factorize(sparse_);
      sparse_factorized_ = sparse_lu_.info() == Eigen::Success;
      if (!sparse_factorized_) return false;
      det_sign_ = static_cast<int>(sparse_lu_.signDeterminant());
      rcond_ = 1.0;
      return std::isfinite(sparse_lu_.logAbsDeterminant());
    }
    case Method::LeastSquares: {
      dense_.setZero();
      for (std::size_t e = 0; e < pattern_.size(); ++e) dense_(pattern_[e].row, pattern_[e].col) += values[e];
      cod_.setThreshold(1e-10);
      cod_.compute(dense_);
      det_sign_ = 0;
      const auto& r = cod_.matrixQTZ();
      const double big = std::abs(r(0, 0));
      const double small = std::abs(r(cols_ - 1, cols_ - 1));
      rcond_ = big > 0 ? small / big : 0.0;
      return cod_.rank() == cols_ && rcond_ > kSingularRcond;
    }
  }
  return false;
}

void LinearSolver::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  switch (method_) {
    case Method::DenseLU:
      if (small_) {
        solve_small(b, x);
        return;
      }
      // In place: Eigen's solve() allocates temporaries, and this runs several times a step.
      x.resize(b.size());
      x.noalias() = lu_.permutationP() * b;
      lu_.matrixLU().triangularView<Eigen::UnitLower>().solveInPlace(x);
      lu_.matrixLU().triangularView<Eigen::Upper>().solveInPlace(x);
      return;
    case Method::SparseLU:
      x = sparse_lu_.solve(b);
      return;
    case Method::LeastSquares:
      x = cod_.solve(b);
      return;
  }
}

namespace {

// Eigen's unblocked_lu with the size known at compile time (a, column-major, N x N): pivot on
// the first largest |a| of the column, swap whole rows, divide the column below the pivot by it,
// subtract the outer product from the corner. Returns the number of row swaps.
template <int N>
__attribute__((optimize("no-tree-vectorize"))) int eliminate(double* __restrict a, int* __restrict transposition, bool& zero_pivot) {
  int swaps = 0;
  for (int k = 0; k < N; ++k) {
    int pivot = k;
    double biggest = std::abs(a[k * N + k]);
    for (int i = k + 1; i < N; ++i)
      if (std::abs(a[k * N + i]) > biggest) {
        biggest = std::abs(a[k * N + i]);
        pivot = i;
      }
    transposition[k] = pivot;
    if (biggest != 0.0) {
      if (pivot != k) {
        for (int j = 0; j < N; ++j) std::swap(a[j * N + k], a[j * N + pivot]);
        ++swaps;
      }
      const double diagonal = a[k * N + k];
      for (int i = k + 1; i < N; ++i) a[k * N + i] /= diagonal;
    } else {
      zero_pivot = true;
    }
    for (int j = k + 1; j < N; ++j) {
      const double u = a[j * N + k];
      for (int i = k + 1; i < N; ++i) a[j * N + i] -= a[k * N + i] * u;
    }
  }
  return swaps;
}

// Forward and back substitution with the size known at compile time, fully unrolled, in place
// in x: Eigen's triangular_solve_vector within one panel, column by column, skipping zeros.
// Not vectorised: pairs of scalar results stored and then loaded as one vector stall the store
// forwarding, which cost more than the arithmetic (measured: 7 % of a four-bar step).
template <int N>
__attribute__((optimize("no-tree-vectorize"))) void substitute(const double* __restrict lu,
                                                                const int* __restrict row,
                                                                const double* __restrict b,
                                                                double* __restrict x) {
  for (int i = 0; i < N; ++i) x[i] = b[row[i]];
  for (int i = 0; i < N; ++i) {
    if (x[i] == 0.0) continue;
    for (int j = i + 1; j < N; ++j) x[j] -= x[i] * lu[i * N + j];
  }
  for (int i = N - 1; i >= 0; --i) {
    if (x[i] == 0.0) continue;
    x[i] /= lu[i * N + i];
    for (int j = 0; j < i; ++j) x[j] -= x[i] * lu[i * N + j];
  }
}

}  // namespace

bool LinearSolver::factorize_small_from(const std::vector<double>& values) {
  const int n = cols_;
  double* a = small_lu_.data();  // column-major, leading dimension n
  std::fill(a, a + n * n, 0.0);
  for (std::size_t e = 0; e < pattern_.size(); ++e) a[pattern_[e].col * n + pattern_[e].row] += values[e];
  std::array<int, kSmallLimit> transposition{};
  bool zero_pivot = false;
  int swaps = 0;
  switch (n) {
    case 1: swaps = eliminate<1>(a, transposition.data(), zero_pivot); break;
    case 2: swaps = eliminate<2>(a, transposition.data(), zero_pivot); break;
    case 3: swaps = eliminate<3>(a, transposition.data(), zero_pivot); break;
    case 4: swaps = eliminate<4>(a, transposition.data(), zero_pivot); break;
    case 5: swaps = eliminate<5>(a, transposition.data(), zero_pivot); break;
    case 6: swaps = eliminate<6>(a, transposition.data(), zero_pivot); break;
    case 7: swaps = eliminate<7>(a, transposition.data(), zero_pivot); break;
    case 8: swaps = eliminate<8>(a, transposition.data(), zero_pivot); break;
  }
  // The permutation the transpositions make: row i of P b is b[small_row_[i]].
  for (int i = 0; i < n; ++i) small_row_[i] = i;
  for (int k = 0; k < n; ++k) std::swap(small_row_[k], small_row_[transposition[k]]);
  int sign = swaps % 2 == 0 ? 1 : -1;
  double smallest = std::numeric_limits<double>::infinity(), largest = 0.0;
  for (int i = 0; i < n; ++i) {
    const double d = a[i * n + i];
    sign *= d < 0 ? -1 : 1;
    smallest = std::min(smallest, std::abs(d));
    largest = std::max(largest, std::abs(d));
  }
  det_sign_ = sign;
  const double pivot_ratio = largest > 0.0 ? smallest / largest : 0.0;
  if (pivot_ratio > 1e-6 && !zero_pivot) {
    rcond_ = pivot_ratio;
  } else {
    // Near singular: Eigen's condition estimate, as the general path makes it.
    dense_.setZero();
    for (std::size_t e = 0; e < pattern_.size(); ++e) dense_(pattern_[e].row, pattern_[e].col) += values[e];
    lu_.compute(dense_);
    rcond_ = lu_.rcond();
  }
  return std::isfinite(rcond_) && rcond_ > kSingularRcond;
}

void LinearSolver::solve_small(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  x.resize(cols_);
  const double* lu = small_lu_.data();
  const int* row = small_row_.data();
  switch (cols_) {
    case 1: return substitute<1>(lu, row, b.data(), x.data());
    case 2: return substitute<2>(lu, row, b.data(), x.data());
    case 3: return substitute<3>(lu, row, b.data(), x.data());
    case 4: return substitute<4>(lu, row, b.data(), x.data());
    case 5: return substitute<5>(lu, row, b.data(), x.data());
    case 6: return substitute<6>(lu, row, b.data(), x.data());
    case 7: return substitute<7>(lu, row, b.data(), x.data());
    case 8: return substitute<8>(lu, row, b.data(), x.data());
  }
}

}  // namespace nbar
