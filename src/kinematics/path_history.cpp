#include "path_history.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "nbar/model/series.hpp"
#include "sized.hpp"

namespace nbar {

namespace {

// The predictor reaches at most this many times the last step beyond the current point: further
// out a polynomial through the past point is no better a guess than the current series.
constexpr double kMaxReach = 2.0;
// Steps of a uniform sweep differ in their last bits (t_k = k dt, so h / h_prev is off by about
// k x 2.2e-16 at step k): a reach within this fraction of the one the weights are for keeps them.
// The prediction then moves by about as little of the step's motion (1e-9 of a degree's step is
// far below the tolerance, and the correction removes it); at 1e-12 a sweep past about 4 500
// steps recomputed them at every step, work that changed nothing.
constexpr double kSameReach = 1e-9;

double binomial(int n, int k) {
  double b = 1.0;
  for (int i = 1; i <= k; ++i) b = b * (n - k + i) / i;
  return b;
}

// q = sum over k of now[k] a_k + before[k] b_k, coordinate by coordinate, with Terms coefficients
// (0: as many as a has) of N coordinates (0: as many as a has).
template <int Terms, int N>
void weigh(const double* now, const double* before, const Eigen::MatrixXd& a, const Eigen::MatrixXd& b,
           Eigen::VectorXd& q) {
  const Eigen::Index n = N > 0 ? N : a.rows();
  const int terms = Terms > 0 ? Terms : static_cast<int>(a.cols());
  const double* x = a.data();
  const double* y = b.data();
  for (Eigen::Index i = 0; i < n; ++i) {
    double sum = 0.0;
#pragma GCC unroll 4
    for (int k = 0; k < terms; ++k) sum += now[k] * x[k * n + i] + before[k] * y[k * n + i];
    q[i] = sum;
  }
}

// The common sizes unrolled: a sweep of order 2 or 3, the coordinates a step is compiled for
// (N > 0, or with N = 0 the sizes of kinematics/sized.hpp found at run time).
template <int Terms, int N>
void weigh_sized(const double* now, const double* before, const Eigen::MatrixXd& a, const Eigen::MatrixXd& b,
                 Eigen::VectorXd& q) {
  if constexpr (N > 0) {
    weigh<Terms, N>(now, before, a, b, q);
  } else {
    with_coordinate_count(static_cast<int>(a.rows()),
                          [&](auto n) { weigh<Terms, decltype(n)::value>(now, before, a, b, q); });
  }
}

// Whether n numbers are the same bits, N of them when N > 0: the differences' bits gathered, with
// no branch per number (a few numbers, which two calls of memcmp cost more than); many with
// memcmp, which compares 32 bytes at once.
template <int N>
bool same_bits(const double* a, const double* b, Eigen::Index n) {
  if constexpr (N == 0) {
    if (n > 8) return std::memcmp(a, b, static_cast<std::size_t>(n) * sizeof(double)) == 0;
  }
  std::uint64_t differ = 0;
  for (Eigen::Index i = 0; i < (N > 0 ? N : n); ++i) {
    std::uint64_t x, y;
    std::memcpy(&x, a + i, sizeof x);
    std::memcpy(&y, b + i, sizeof y);
    differ |= x ^ y;
  }
  return differ == 0;
}

// to = the n numbers at from (N when N > 0), resized to them.
template <int N>
void copy_sized(const double* from, Eigen::Index n, Eigen::VectorXd& to) {
  if (to.size() != (N > 0 ? N : n)) to.resize(N > 0 ? N : n);
  copy_numbers<N>(from, n, to.data());
}

}  // namespace

void PathHistory::push(double parameter, const Eigen::MatrixXd& series) {
  // The same size every step: no allocation once sized.
  if (past_.rows() != series.rows() || past_.cols() != series.cols()) past_.resize(series.rows(), series.cols());
  std::copy_n(series.data(), series.size(), past_.data());
  past_parameter_ = parameter;
  has_past_ = true;
}

void PathHistory::take(double parameter, Eigen::MatrixXd& series) {
  past_.swap(series);
  past_parameter_ = parameter;
  has_past_ = true;
}

template <int N>
void PathHistory::mark_current(double parameter, const Eigen::MatrixXd& series) {
  if constexpr (N > 0) {
    if (series.rows() != N) return mark_current<0>(parameter, series);  // not the size compiled for
  }
  current_parameter_ = parameter;
  const Eigen::Index n = N > 0 ? N : series.rows();
  copy_sized<N>(series.data(), n, current_q_);
  if (series.cols() > 1) {
    copy_sized<N>(series.data() + n, n, current_rate_);
  } else {
    current_rate_.resize(0);
  }
}

// The state must be the point the last accepted step reached, with the same path through it (its
// rate along the path), bit for bit: anything else (a restart, a pose solved on its own, another
// path through the same pose) has no usable past.
template <int N>
bool PathHistory::continues_from(double parameter, const Eigen::MatrixXd& series) const {
  if (!has_past_ || parameter != current_parameter_ || series.cols() < 2 || past_.cols() < series.cols()) return false;
  const Eigen::Index n = series.rows();
  if ((N > 0 && n != N) || current_q_.size() != n || current_rate_.size() != n) return false;
  // Compared as bits: what was copied is what must still be there.
  return same_bits<N>(series.data(), current_q_.data(), n) && same_bits<N>(series.data() + n, current_rate_.data(), n);
}

// With the past point at -1, the current one at 0 and the target at r, the polynomial's
// coefficients a solve M a = c from the points' Taylor coefficients c (row (point, k):
// sum_j a_j C(j, k) z^(j - k)), and its value at r is v . a with v_j = r^j: the weights are
// M^-T v. M depends only on the number of terms, so its inverse is kept; a step then costs one
// small product.
bool PathHistory::weights_fit(double reach, int terms) const {
  return terms == weight_terms_ && std::abs(reach - weight_reach_) <= kSameReach * std::abs(reach);
}

void PathHistory::update_weights(double reach, int terms) {
  const int n = 2 * terms;
  if (terms != weight_terms_) {
    weight_terms_ = terms;
    const double node[2] = {0.0, -1.0};
    Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < 2; ++i)
      for (int k = 0; k < terms; ++k)
        for (int j = k; j < n; ++j) m(i * terms + k, j) = binomial(j, k) * std::pow(node[i], j - k);
    inverse_transpose_ = m.transpose().partialPivLu().inverse();
  }
  // w = M^-T v, column by column of M^-T (stored column-major): n multiply-adds of a column.
  const double* m = inverse_transpose_.data();
  for (int i = 0; i < n; ++i) weight_[i] = m[i];
  double p = reach;
  for (int j = 1; j < n; ++j, p *= reach)
    for (int i = 0; i < n; ++i) weight_[i] += m[j * n + i] * p;
  weight_reach_ = reach;
}

template <int N>
bool PathHistory::predict(double parameter, const Eigen::MatrixXd& series, double h, Eigen::VectorXd& q) {
  if (!continues_from<N>(parameter, series)) return false;
  const double back = parameter - past_parameter_;  // the last step, signed as h is
  if (!(back * h > 0.0 && std::abs(h) <= kMaxReach * std::abs(back))) return false;
  const int terms = static_cast<int>(series.cols());
  if (terms > Series::kCapacity) return false;  // the weights' storage holds 2 x kCapacity
  if (!weights_fit(h / back, terms)) update_weights(h / back, terms);
  // Coefficient k in the scaled variable is coefficient k in the parameter times back^k.
  double now[Series::kCapacity], before[Series::kCapacity];
  double power = 1.0;
  for (int k = 0; k < terms; ++k, power *= back) {
    now[k] = weight_[k] * power;
    before[k] = weight_[terms + k] * power;
  }
  if (q.size() != series.rows()) q.resize(series.rows());
  switch (terms) {  // the common sizes unrolled (a sweep of order 2 or 3)
    case 3: weigh_sized<3, N>(now, before, series, past_, q); break;
    case 4: weigh_sized<4, N>(now, before, series, past_, q); break;
    default: weigh_sized<0, N>(now, before, series, past_, q); break;
  }
  return true;
}

// The sizes of kinematics/sized.hpp, and any (N = 0).
#define NBAR_PATH_HISTORY_SIZED(N)                                                             \
  template void PathHistory::mark_current<N>(double parameter, const Eigen::MatrixXd& series); \
  template bool PathHistory::predict<N>(double parameter, const Eigen::MatrixXd& series, double h, Eigen::VectorXd& q);
NBAR_PATH_HISTORY_SIZED(0)
NBAR_PATH_HISTORY_SIZED(2)
NBAR_PATH_HISTORY_SIZED(4)
NBAR_PATH_HISTORY_SIZED(6)
NBAR_PATH_HISTORY_SIZED(8)
#undef NBAR_PATH_HISTORY_SIZED

}  // namespace nbar
