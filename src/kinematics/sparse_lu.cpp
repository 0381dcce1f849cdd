#include "sparse_lu.hpp"

#include "sized.hpp"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace nbar {

namespace {

// The parity of a permutation given as the image of 0..n-1.
int permutation_sign(const std::vector<int>& image) {
  std::vector<char> seen(image.size(), 0);
  int sign = 1;
  for (std::size_t start = 0; start < image.size(); ++start) {
    if (seen[start]) continue;
    std::size_t length = 0;
    for (std::size_t i = start; !seen[i]; i = static_cast<std::size_t>(image[i])) {
      seen[i] = 1;
      ++length;
    }
    if (length % 2 == 0) sign = -sign;
  }
  return sign;
}

// COLAMD's column order of the pattern: the order that keeps the fill of L and U small.
std::vector<int> fill_reducing_order(int n, const std::vector<SparseLU::Entry>& entries) {
  std::vector<Eigen::Triplet<double, int>> triplets;
  triplets.reserve(entries.size());
  for (const auto& e : entries) triplets.emplace_back(e.row, e.col, 1.0);
  Eigen::SparseMatrix<double, Eigen::ColMajor, int> pattern(n, n);
  pattern.setFromTriplets(triplets.begin(), triplets.end());
  pattern.makeCompressed();
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> permutation;
  Eigen::COLAMDOrdering<int>()(pattern, permutation);
  std::vector<int> order(static_cast<std::size_t>(n));
  for (int col = 0; col < n; ++col) order[static_cast<std::size_t>(permutation.indices()(col))] = col;
  return order;
}

// Forward and back substitution with L and U dense and the size known at compile time, so that the
// right-hand side stays in registers. Not vectorised (this file is compiled with
// -fno-tree-vectorize, src/CMakeLists.txt): pairs of scalar results stored and then loaded as one
// vector stall the store forwarding, which costs more than the arithmetic at this size.
template <int N>
void dense_solve(const double* lu, const double* inverse_pivot, const int* pivot_row, const int* column_order,
                 const double* b, double* x) {
  double w[N];
  for (int i = 0; i < N; ++i) w[i] = b[pivot_row[i]];
  for (int k = 0; k < N; ++k)
    for (int i = k + 1; i < N; ++i) w[i] -= lu[k * N + i] * w[k];
  for (int k = N - 1; k >= 0; --k) {
    w[k] *= inverse_pivot[k];
    for (int i = 0; i < k; ++i) w[i] -= lu[k * N + i] * w[k];
  }
  for (int k = 0; k < N; ++k) x[column_order[k]] = w[k];
}

// The replay's elimination for N <= kDenseSolveLimit known when compiled, on the whole N x N
// array: the compiled list's loads of slots cost three times its arithmetic at these sizes. It
// does the list's multiply-subtracts in the list's order (each entry's in ascending pivot order),
// and besides them only ones whose product is an exact zero, which leave a nonzero entry as it
// was. Returns false when a pivot fails the threshold; sign, smallest and largest as replay's.
template <int N>
bool dense_eliminate(double* v, double* inverse_pivot, double threshold, int& sign, double& smallest, double& largest) {
  double least = smallest, most = largest;
#pragma GCC unroll 8
  for (int k = 0; k < N; ++k) {
    double* column = v + k * N;
#pragma GCC unroll 8
    for (int j = 0; j < k; ++j) {
      const double u = column[j];
      const double* l = v + j * N;
#pragma GCC unroll 8
      for (int r = j + 1; r < N; ++r) column[r] -= l[r] * u;
    }
    const double pivot = column[k];
    const double size = std::abs(pivot);
    // The threshold against each entry below rather than their largest: the same test, with a NaN
    // failing it.
#pragma GCC unroll 8
    for (int r = k + 1; r < N; ++r)
      if (!(size >= threshold * std::abs(column[r]))) return false;
    if (pivot == 0.0) return false;
    const double inverse = 1.0 / pivot;
    inverse_pivot[k] = inverse;
#pragma GCC unroll 8
    for (int r = k + 1; r < N; ++r) column[r] *= inverse;
    if (pivot < 0.0) sign = -sign;
    least = std::min(least, size);
    most = std::max(most, size);
  }
  smallest = least;
  largest = most;
  return true;
}

}  // namespace

void SparseLU::set_pattern(int n, const std::vector<Entry>& entries) {
  n_ = n;
  entries_ = entries;
  column_order_ = n > 0 ? fill_reducing_order(n, entries) : std::vector<int>{};
  work_.assign(static_cast<std::size_t>(n), 0.0);
  kept_.clear();
  current_ = -1;
  det_sign_ = 0;
  pivot_ratio_ = 0.0;
}

bool SparseLU::factorize(const double* values) {
  if (n_ == 0) {
    det_sign_ = 1;
    pivot_ratio_ = 1.0;
    return true;
  }
  // A number that is not finite anywhere in the matrix makes it unusable, whether or not the
  // elimination would carry it into a pivot: the replay finds one as it reads the values in, and
  // the analysis scans for one first.
  for (std::size_t i = 0; i < kept_.size(); ++i) {
    const Replay replayed = replay(kept_[i], values, true);
    if (replayed == Replay::NotFinite) return fail();
    if (replayed == Replay::Refused) continue;
    // Most recently used first: the next step most likely needs this one again.
    std::rotate(kept_.begin(), kept_.begin() + static_cast<std::ptrdiff_t>(i),
                kept_.begin() + static_cast<std::ptrdiff_t>(i) + 1);
    current_ = 0;
    return true;
  }
  for (std::size_t e = 0; e < entries_.size(); ++e)
    if (!std::isfinite(values[e])) return fail();
  Elimination chosen;
  if (!analyse(values, chosen)) return fail();
  if (static_cast<int>(kept_.size()) == kKeptEliminations) kept_.pop_back();
  kept_.insert(kept_.begin(), std::move(chosen));
  current_ = 0;
  // The replay of the elimination just chosen: the pivots are the largest of their columns, so
  // only a pivot that rounds to exactly zero can stop it.
  return replay(kept_.front(), values, false) == Replay::Done || fail();
}

bool SparseLU::fail() {
  det_sign_ = 0;
  pivot_ratio_ = 0.0;
  current_ = -1;
  return false;
}

int SparseLU::factor_nonzeros() const {
  if (current_ < 0) return 0;
  return static_cast<int>(current().u_slot.size() + current().l_slot.size()) + n_;
}

namespace {

// The work of one analysis, column by column: the rows a column reaches and its values, by the
// matrix's row; the columns of L and U found so far, by pivot position.
struct ColumnElimination {
  explicit ColumnElimination(std::size_t n)
      : position_of_row(n, -1),
        u_rows(n),
        l_rows(n),
        l_values(n),
        x(n, 0.0),
        in_pattern(n, 0),
        visited(n, 0),
        next_child(n, 0) {}

  std::vector<int> position_of_row;
  std::vector<std::vector<int>> u_rows, l_rows;  // u: positions; l: the matrix's rows until compiled
  std::vector<std::vector<double>> l_values;
  std::vector<double> x;         // by the matrix's row
  std::vector<char> in_pattern;  // by the matrix's row
  std::vector<char> visited;     // by position
  std::vector<int> pattern, finished, stack, next_child;

  void add_row(int r) {
    if (!in_pattern[static_cast<std::size_t>(r)]) {
      in_pattern[static_cast<std::size_t>(r)] = 1;
      pattern.push_back(r);
    }
  }

  // The pivots this column reaches through L, in depth-first post-order (`finished`).
  void reach() {
    const std::size_t first_rows = pattern.size();
    for (std::size_t i = 0; i < first_rows; ++i) {
      const int root = position_of_row[static_cast<std::size_t>(pattern[i])];
      if (root < 0 || visited[static_cast<std::size_t>(root)]) continue;
      stack.assign(1, root);
      visited[static_cast<std::size_t>(root)] = 1;
      next_child[static_cast<std::size_t>(root)] = 0;
      while (!stack.empty()) {
        const auto j = static_cast<std::size_t>(stack.back());
        const std::vector<int>& children = l_rows[j];
        bool descended = false;
        while (next_child[j] < static_cast<int>(children.size())) {
          const int r = children[static_cast<std::size_t>(next_child[j]++)];
          add_row(r);
          const int child = position_of_row[static_cast<std::size_t>(r)];
          if (child >= 0 && !visited[static_cast<std::size_t>(child)]) {
            visited[static_cast<std::size_t>(child)] = 1;
            next_child[static_cast<std::size_t>(child)] = 0;
            stack.push_back(child);
            descended = true;
            break;
          }
        }
        if (!descended) {
          finished.push_back(static_cast<int>(j));
          stack.pop_back();
        }
      }
    }
  }

  // x = L \ A(:, k), the columns in topological order.
  void solve(const std::vector<int>& pivot_row) {
    for (auto it = finished.rbegin(); it != finished.rend(); ++it) {
      const auto j = static_cast<std::size_t>(*it);
      const double xj = x[static_cast<std::size_t>(pivot_row[j])];
      for (std::size_t i = 0; i < l_rows[j].size(); ++i)
        x[static_cast<std::size_t>(l_rows[j][i])] -= l_values[j][i] * xj;
    }
  }

  // The largest entry of x in a row not yet a pivot's; -1 when there is none.
  int largest_free_entry() const {
    int pivot = -1;
    double biggest = 0.0;
    for (int r : pattern) {
      const double size = std::abs(x[static_cast<std::size_t>(r)]);
      if (position_of_row[static_cast<std::size_t>(r)] < 0 && size > biggest) {
        biggest = size;
        pivot = r;
      }
    }
    return pivot;
  }

  // Column k of U (the pivots above) and of L (x below the pivot over the pivot).
  void take_pivot(std::size_t k, int pivot, std::vector<int>& pivot_row) {
    pivot_row[k] = pivot;
    position_of_row[static_cast<std::size_t>(pivot)] = static_cast<int>(k);
    const double diagonal = x[static_cast<std::size_t>(pivot)];
    for (int r : pattern) {
      const int j = position_of_row[static_cast<std::size_t>(r)];
      if (r == pivot) continue;
      if (j >= 0) {
        u_rows[k].push_back(j);
      } else {
        l_rows[k].push_back(r);
        l_values[k].push_back(x[static_cast<std::size_t>(r)] / diagonal);
      }
    }
    std::sort(u_rows[k].begin(), u_rows[k].end());
  }

  // Ready for the next column.
  void clear_column() {
    for (int r : pattern) {
      x[static_cast<std::size_t>(r)] = 0.0;
      in_pattern[static_cast<std::size_t>(r)] = 0;
    }
    for (int j : finished) visited[static_cast<std::size_t>(j)] = 0;
  }
};

}  // namespace

// Left-looking LU with partial pivoting (Gilbert and Peierls): column k of L and U from the
// solve L x = A(:, k) over the rows that the columns before it reach, then the largest remaining
// entry of x as the pivot. It records the pivots and the patterns; the numbers come from the
// replay that follows.
bool SparseLU::analyse(const double* values, Elimination& chosen) {
  ++analyses_;
  const auto n = static_cast<std::size_t>(n_);
  std::vector<std::vector<int>> entries_of_column(n);
  for (std::size_t e = 0; e < entries_.size(); ++e)
    entries_of_column[static_cast<std::size_t>(entries_[e].col)].push_back(static_cast<int>(e));

  std::vector<int>& pivot_row = chosen.pivot_row;
  pivot_row.assign(n, -1);
  ColumnElimination w(n);
  for (std::size_t k = 0; k < n; ++k) {
    w.pattern.clear();
    w.finished.clear();
    for (int e : entries_of_column[static_cast<std::size_t>(column_order_[k])]) {
      w.add_row(entries_[static_cast<std::size_t>(e)].row);
      w.x[static_cast<std::size_t>(entries_[static_cast<std::size_t>(e)].row)] += values[e];
    }
    w.reach();
    w.solve(pivot_row);
    const int pivot = w.largest_free_entry();
    if (pivot >= 0) w.take_pivot(k, pivot, pivot_row);
    w.clear_column();
    if (pivot < 0) return false;  // nothing nonzero left in this column: singular
  }
  for (auto& rows : w.l_rows)
    for (int& r : rows) r = w.position_of_row[static_cast<std::size_t>(r)];
  compile(w.u_rows, w.l_rows, chosen);
  return true;
}

// Lays L and U out and writes the replay's multiply-adds. Large systems keep only the nonzeros,
// column by column; small ones keep the whole n x n array (column-major), whose zeros the
// unrolled solves read.
void SparseLU::compile(const std::vector<std::vector<int>>& u_rows, const std::vector<std::vector<int>>& l_rows,
                       Elimination& e) const {
  const auto n = static_cast<std::size_t>(n_);
  const bool dense = n_ <= kDenseSolveLimit;
  std::size_t next = 0;
  const auto slot = [&](std::size_t row, std::size_t col) { return static_cast<int>(dense ? col * n + row : next++); };
  e.u_start.assign(n + 1, 0);
  e.l_start.assign(n + 1, 0);
  e.diagonal.assign(n, 0);
  e.u_slot.clear();
  e.u_row.clear();
  e.l_slot.clear();
  e.l_row.clear();
  // column[k]: (position, slot) of each entry of column k while compiling.
  std::vector<std::vector<std::pair<int, int>>> column(n);
  for (std::size_t k = 0; k < n; ++k) {
    e.u_start[k] = static_cast<int>(e.u_slot.size());
    e.l_start[k] = static_cast<int>(e.l_slot.size());
    for (int r : u_rows[k]) {
      e.u_row.push_back(r);
      e.u_slot.push_back(slot(static_cast<std::size_t>(r), k));
      column[k].emplace_back(r, e.u_slot.back());
    }
    e.diagonal[k] = slot(k, k);
    column[k].emplace_back(static_cast<int>(k), e.diagonal[k]);
    std::vector<int> below = l_rows[k];
    std::sort(below.begin(), below.end());
    for (int r : below) {
      e.l_row.push_back(r);
      e.l_slot.push_back(slot(static_cast<std::size_t>(r), k));
      column[k].emplace_back(r, e.l_slot.back());
    }
  }
  e.u_start[n] = static_cast<int>(e.u_slot.size());
  e.l_start[n] = static_cast<int>(e.l_slot.size());
  e.values = dense ? n * n : next;

  std::vector<int> slot_of(n, -1);  // within the column being compiled, by position
  e.update.clear();
  e.update_start.assign(n + 1, 0);
  for (std::size_t k = 0; k < n; ++k) {
    e.update_start[k] = static_cast<int>(e.update.size());
    for (const auto& [r, s] : column[k]) slot_of[static_cast<std::size_t>(r)] = s;
    for (int i = e.u_start[k]; i < e.u_start[k + 1]; ++i) {
      const auto j = static_cast<std::size_t>(e.u_row[static_cast<std::size_t>(i)]);
      for (int l = e.l_start[j]; l < e.l_start[j + 1]; ++l)
        e.update.push_back({slot_of[static_cast<std::size_t>(e.l_row[static_cast<std::size_t>(l)])],
                            e.l_slot[static_cast<std::size_t>(l)], e.u_slot[static_cast<std::size_t>(i)]});
    }
    for (const auto& [r, s] : column[k]) slot_of[static_cast<std::size_t>(r)] = -1;
  }
  e.update_start[n] = static_cast<int>(e.update.size());

  std::vector<int> position_of_row(n), position_of_column(n);
  for (std::size_t k = 0; k < n; ++k) {
    position_of_row[static_cast<std::size_t>(e.pivot_row[k])] = static_cast<int>(k);
    position_of_column[static_cast<std::size_t>(column_order_[k])] = static_cast<int>(k);
  }
  e.entry_slot.resize(entries_.size());
  for (std::size_t i = 0; i < entries_.size(); ++i) {
    const auto k = static_cast<std::size_t>(position_of_column[static_cast<std::size_t>(entries_[i].col)]);
    const int row = position_of_row[static_cast<std::size_t>(entries_[i].row)];
    for (const auto& [r, s] : column[k])
      if (r == row) e.entry_slot[i] = s;
  }
  e.permutation_sign = permutation_sign(e.pivot_row) * permutation_sign(column_order_);
}

SparseLU::Replay SparseLU::replay(const Elimination& e, const double* values, bool check) {
  if (value_.size() != e.values) value_.resize(e.values);
  inverse_pivot_.resize(static_cast<std::size_t>(n_));
  double* v = value_.data();
  std::fill_n(v, e.values, 0.0);
  const int* entry_slot = e.entry_slot.data();
  // probe is NaN when any value is infinite or NaN (0 times it is NaN), and 0 otherwise.
  double probe = 0.0;
  const std::size_t entries = e.entry_slot.size();
#pragma GCC unroll 4
  for (std::size_t i = 0; i < entries; ++i) {
    v[entry_slot[i]] += values[i];
    probe += 0.0 * values[i];
  }
  if (probe != 0.0) return Replay::NotFinite;
  const double threshold = check ? kPivotThreshold : 0.0;
  int sign = e.permutation_sign;
  double smallest = HUGE_VAL, largest = 0.0;
  const bool done = with_coordinate_count(n_, [&](auto size) {
    if constexpr (decltype(size)::value > 0) {
      return dense_eliminate<decltype(size)::value>(v, inverse_pivot_.data(), threshold, sign, smallest, largest);
    } else {
      return sparse_eliminate(e, v, threshold, sign, smallest, largest);
    }
  });
  if (!done) return Replay::Refused;
  det_sign_ = sign;
  pivot_ratio_ = largest > 0.0 ? smallest / largest : 0.0;
  return Replay::Done;
}

bool SparseLU::sparse_eliminate(const Elimination& e, double* v, double threshold, int& sign, double& smallest,
                                double& largest) {
  const Update* update = e.update.data();
  const int* update_start = e.update_start.data();
  const int* l_start = e.l_start.data();
  const int* l_slot = e.l_slot.data();
  const int* diagonal = e.diagonal.data();
  for (int k = 0; k < n_; ++k) {
    for (int u = update_start[k]; u < update_start[k + 1]; ++u) v[update[u].target] -= v[update[u].l] * v[update[u].u];
    const double pivot = v[diagonal[k]];
    double biggest = 0.0;
    for (int i = l_start[k]; i < l_start[k + 1]; ++i) {
      const double size = std::abs(v[l_slot[i]]);
      if (!(size <= biggest) && !std::isnan(biggest)) biggest = size;  // a NaN stays
    }
    // Written so that a NaN fails it.
    if (!(std::abs(pivot) >= threshold * biggest) || pivot == 0.0) return false;
    const double inverse = 1.0 / pivot;
    inverse_pivot_[static_cast<std::size_t>(k)] = inverse;
    for (int i = l_start[k]; i < l_start[k + 1]; ++i) v[l_slot[i]] *= inverse;
    if (pivot < 0.0) sign = -sign;
    smallest = std::min(smallest, std::abs(pivot));
    largest = std::max(largest, std::abs(pivot));
  }
  return true;
}

// No factors to solve with (none yet, the last factorisation failed, or an empty system): x is
// all NaN, and the solves return at once.
bool SparseLU::unfactorised(double* x) const {
  if (current_ >= 0) return false;
  std::fill(x, x + n_, std::numeric_limits<double>::quiet_NaN());
  return true;
}

template <int N>
void SparseLU::solve_dense(const double* b, double* x) const {
  if (current_ < 0 && unfactorised(x)) return;
  dense_solve<N>(value_.data(), inverse_pivot_.data(), current().pivot_row.data(), column_order_.data(), b, x);
}
template void SparseLU::solve_dense<1>(const double*, double*) const;
template void SparseLU::solve_dense<2>(const double*, double*) const;
template void SparseLU::solve_dense<3>(const double*, double*) const;
template void SparseLU::solve_dense<4>(const double*, double*) const;
template void SparseLU::solve_dense<5>(const double*, double*) const;
template void SparseLU::solve_dense<6>(const double*, double*) const;
template void SparseLU::solve_dense<7>(const double*, double*) const;
template void SparseLU::solve_dense<8>(const double*, double*) const;

void SparseLU::solve(const double* b, double* x) const {
  switch (n_) {  // the dense factors' sizes
    case 1: return solve_dense<1>(b, x);
    case 2: return solve_dense<2>(b, x);
    case 3: return solve_dense<3>(b, x);
    case 4: return solve_dense<4>(b, x);
    case 5: return solve_dense<5>(b, x);
    case 6: return solve_dense<6>(b, x);
    case 7: return solve_dense<7>(b, x);
    case 8: return solve_dense<8>(b, x);
    default: break;
  }
  if (unfactorised(x)) return;
  const Elimination& e = current();
  double* w = work_.data();
  const double* v = value_.data();
  for (int k = 0; k < n_; ++k) w[k] = b[e.pivot_row[static_cast<std::size_t>(k)]];
  for (int k = 0; k < n_; ++k) {
    const double wk = w[k];
    for (int i = e.l_start[static_cast<std::size_t>(k)]; i < e.l_start[static_cast<std::size_t>(k) + 1]; ++i)
      w[e.l_row[static_cast<std::size_t>(i)]] -= v[e.l_slot[static_cast<std::size_t>(i)]] * wk;
  }
  for (int k = n_ - 1; k >= 0; --k) {
    const double wk = w[k] * inverse_pivot_[static_cast<std::size_t>(k)];
    w[k] = wk;
    for (int i = e.u_start[static_cast<std::size_t>(k)]; i < e.u_start[static_cast<std::size_t>(k) + 1]; ++i)
      w[e.u_row[static_cast<std::size_t>(i)]] -= v[e.u_slot[static_cast<std::size_t>(i)]] * wk;
  }
  for (int k = 0; k < n_; ++k) x[column_order_[static_cast<std::size_t>(k)]] = w[k];
}

// A = P^T L U Q^T, so A^T y = c is U^T L^T (P y) = Q^T c: U^T forward, L^T backward.
void SparseLU::solve_transposed(const double* b, double* x) const {
  if (unfactorised(x)) return;
  const Elimination& e = current();
  double* w = work_.data();
  const double* v = value_.data();
  for (int k = 0; k < n_; ++k) w[k] = b[column_order_[static_cast<std::size_t>(k)]];
  for (int k = 0; k < n_; ++k) {
    double sum = w[k];
    for (int i = e.u_start[static_cast<std::size_t>(k)]; i < e.u_start[static_cast<std::size_t>(k) + 1]; ++i)
      sum -= v[e.u_slot[static_cast<std::size_t>(i)]] * w[e.u_row[static_cast<std::size_t>(i)]];
    w[k] = sum * inverse_pivot_[static_cast<std::size_t>(k)];
  }
  for (int k = n_ - 1; k >= 0; --k) {
    double sum = w[k];
    for (int i = e.l_start[static_cast<std::size_t>(k)]; i < e.l_start[static_cast<std::size_t>(k) + 1]; ++i)
      sum -= v[e.l_slot[static_cast<std::size_t>(i)]] * w[e.l_row[static_cast<std::size_t>(i)]];
    w[k] = sum;
  }
  for (int k = 0; k < n_; ++k) x[e.pivot_row[static_cast<std::size_t>(k)]] = w[k];
}

// Hager's method as LAPACK's dlacon runs it: a few solves with A and A^T climb to the column of
// A^-1 with the largest 1-norm.
double SparseLU::reciprocal_condition_estimate(const double* values) const {
  if (n_ == 0) return 1.0;
  if (det_sign_ == 0 || current_ < 0) return 0.0;
  const Elimination& e = current();
  const auto n = static_cast<std::size_t>(n_);
  // In storage kept: the gate of a simulation asks at every step.
  std::vector<double>& element = condition_work_.element;
  std::vector<double>& column_sum = condition_work_.column_sum;
  std::vector<double>& x = condition_work_.x;
  std::vector<double>& y = condition_work_.y;
  std::vector<double>& z = condition_work_.z;
  // |A|_1 from the entries, repeated ones summed first.
  element.assign(value_.size(), 0.0);
  for (std::size_t i = 0; i < e.entry_slot.size(); ++i) element[static_cast<std::size_t>(e.entry_slot[i])] += values[i];
  column_sum.assign(n, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    column_sum[k] = std::abs(element[static_cast<std::size_t>(e.diagonal[k])]);
    for (int i = e.u_start[k]; i < e.u_start[k + 1]; ++i)
      column_sum[k] += std::abs(element[static_cast<std::size_t>(e.u_slot[static_cast<std::size_t>(i)])]);
    for (int i = e.l_start[k]; i < e.l_start[k + 1]; ++i)
      column_sum[k] += std::abs(element[static_cast<std::size_t>(e.l_slot[static_cast<std::size_t>(i)])]);
  }
  const double norm = *std::max_element(column_sum.begin(), column_sum.end());
  if (!(norm > 0.0)) return 0.0;

  x.assign(n, 1.0 / static_cast<double>(n));
  y.resize(n);
  z.resize(n);
  double estimate = 0.0;
  std::size_t last = n;
  for (int iteration = 0; iteration < 5; ++iteration) {
    solve(x.data(), y.data());
    estimate = 0.0;
    for (double value : y) estimate += std::abs(value);
    for (std::size_t i = 0; i < n; ++i) y[i] = y[i] >= 0.0 ? 1.0 : -1.0;
    solve_transposed(y.data(), z.data());
    std::size_t j = 0;
    for (std::size_t i = 1; i < n; ++i)
      if (std::abs(z[i]) > std::abs(z[j])) j = i;
    double zx = 0.0;
    for (std::size_t i = 0; i < n; ++i) zx += z[i] * x[i];
    if (!std::isfinite(estimate)) return 0.0;
    if (iteration > 0 && (std::abs(z[j]) <= zx || j == last)) break;
    std::fill(x.begin(), x.end(), 0.0);
    x[j] = 1.0;
    last = j;
  }
  // Higham's second guess, alternating signs, guards against Hager's worst cases.
  for (std::size_t i = 0; i < n; ++i)
    x[i] = (i % 2 == 0 ? 1.0 : -1.0) * (1.0 + static_cast<double>(i) / static_cast<double>(n > 1 ? n - 1 : 1));
  solve(x.data(), y.data());
  double alternative = 0.0;
  for (double value : y) alternative += std::abs(value);
  estimate = std::max(estimate, 2.0 * alternative / (3.0 * static_cast<double>(n)));
  if (!(estimate > 0.0) || !std::isfinite(estimate)) return 0.0;
  return 1.0 / (norm * estimate);
}

}  // namespace nbar
