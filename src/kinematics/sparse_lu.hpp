// A sparse LU for the square constraint Jacobians of kinematics, which keep one sparsity pattern
// for a whole sweep and change a little from one step to the next.
//
// The pivots are chosen once and then kept, as KLU does for circuit simulation: `factorize`
// first orders the columns to limit fill (COLAMD), then factorises left-looking (Gilbert and
// Peierls) with partial pivoting, which fixes the row order and the patterns of L and U. It
// compiles that elimination into a flat list of multiply-adds. Every later `factorize` replays
// the list on the new values, checking each pivot against the largest entry below it in its
// column; a pivot that has become smaller than kPivotThreshold times that entry (the linkage has
// turned so that another row should lead) makes it choose the pivots again, at these values.
// So the multipliers stay below 1 / kPivotThreshold, the replay does no search and no
// allocation, and its cost follows the nonzeros of L and U, not n^3. As a linkage turns, its
// pivots move between a few rows and back (a crank's x and y components take turns to lead), so
// the last few eliminations are kept and tried before a new one is chosen.
#pragma once

#include <vector>

namespace nbar {

class SparseLU {
 public:
  // A replayed pivot must be at least this fraction of the largest entry of its column.
  static constexpr double kPivotThreshold = 0.1;
  // Up to this size the factors are also kept as a dense array and the solves are unrolled: at
  // a four-bar's size the index arithmetic of the sparse loops costs more than the zeros.
  static constexpr int kDenseSolveLimit = 8;
  // Eliminations kept for reuse.
  static constexpr int kKeptEliminations = 4;

  struct Entry {
    int row = 0;
    int col = 0;
  };

  // An n x n pattern; entries may repeat (their values are summed).
  void set_pattern(int n, const std::vector<Entry>& entries);

  // Factorises the matrix whose entries, in the pattern's order, are `values`. False when it is
  // singular (a column with no nonzero pivot left) or holds a number that is not finite; solves
  // then give NaN.
  bool factorize(const double* values);

  // x = A^-1 b, and x = A^-T b. b and x may be the same array.
  void solve(const double* b, double* x) const;
  void solve_transposed(const double* b, double* x) const;
  // solve() for N = size() <= kDenseSolveLimit known when compiled (instantiated for 1 to 8).
  template <int N>
  void solve_dense(const double* b, double* x) const;

  int size() const { return n_; }
  // The sign of det(A) (0 when the last factorisation failed).
  int determinant_sign() const { return det_sign_; }
  // Smallest over largest |pivot|: a cheap sign of how near singular A is.
  double pivot_ratio() const { return pivot_ratio_; }
  // Hager and Higham's estimate of 1 / (|A|_1 |A^-1|_1), from a few solves with the factors.
  double reciprocal_condition_estimate(const double* values) const;

  // How many times the pivots were chosen afresh (every kept elimination refused by the
  // threshold, or none kept yet), singular attempts included.
  long analyses() const { return analyses_; }
  // Nonzeros of L and U, the diagonal included.
  int factor_nonzeros() const;

 private:
  struct Update {
    int target, l, u;  // value[target] -= value[l] * value[u]
  };
  // One choice of pivots, compiled. L and U live in one array of `values` numbers (n x n
  // column-major when n <= kDenseSolveLimit, else the nonzeros only), in pivot positions. Column
  // k's U entries above the diagonal are u_start[k] .. u_start[k+1]-1 (their rows in u_row,
  // ascending, and where their values are in u_slot); L's likewise.
  struct Elimination {
    std::vector<int> pivot_row;  // position k -> the matrix's row chosen as k-th pivot
    int permutation_sign = 1;    // parity of the row and column orders together
    std::size_t values = 0;
    std::vector<int> u_start, u_row, u_slot;
    std::vector<int> l_start, l_row, l_slot;
    std::vector<int> diagonal;    // where each pivot is
    std::vector<int> entry_slot;  // pattern entry -> where its value is added
    std::vector<Update> update;   // column k's: update_start[k] .. update_start[k + 1] - 1
    std::vector<int> update_start;
  };

  bool analyse(const double* values, Elimination& e);
  void compile(const std::vector<std::vector<int>>& u_rows, const std::vector<std::vector<int>>& l_rows,
               Elimination& e) const;
  // Done; Refused when a pivot fails the threshold (or is zero); NotFinite when a value is not a
  // finite number (then no factors).
  enum class Replay { Done, Refused, NotFinite };
  Replay replay(const Elimination& e, const double* values, bool check);
  // replay's elimination from the compiled list, for any size. False when a pivot is refused.
  bool sparse_eliminate(const Elimination& e, double* v, double threshold, int& sign, double& smallest,
                        double& largest);
  bool fail();  // the state of a failed factorisation; returns false
  bool unfactorised(double* x) const;
  const Elimination& current() const { return kept_[static_cast<std::size_t>(current_)]; }

  int n_ = 0;
  std::vector<Entry> entries_;
  std::vector<int> column_order_;  // position k -> the matrix's column
  std::vector<Elimination> kept_;  // most recently used first
  int current_ = -1;               // the one the factors come from

  std::vector<double> value_;
  std::vector<double> inverse_pivot_;
  mutable std::vector<double> work_;
  // reciprocal_condition_estimate's vectors, sized once.
  struct ConditionWork {
    std::vector<double> element, column_sum, x, y, z;
  };
  mutable ConditionWork condition_work_;
  int det_sign_ = 0;
  double pivot_ratio_ = 0.0;
  long analyses_ = 0;
};

}  // namespace nbar
