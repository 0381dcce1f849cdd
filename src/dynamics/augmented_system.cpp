#include "augmented_system.hpp"

#include "kinematics/sized.hpp"

#include <Eigen/OrderingMethods>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

namespace nbar {

namespace {

// alpha Phi_q^T Phi_q against M: large enough that the Schur complement's eigenvalues cluster
// (conjugate gradients converge in two or three iterations), small enough that K's rounding
// (about 1e-16 alpha of the answer) is taken out by one round of refinement. A free motion whose
// inertia is below 1e-12 of K's largest diagonal has none.
constexpr double kPenalty = 1e6;
constexpr double kNoInertia = 1e-12;
// Iterations of conjugate gradients (a few suffice away from a toggle) and rounds of refinement.
constexpr int kMostIterations = 200;
constexpr int kMostRounds = 6;
// What the iterations aim at, relative to the size of the terms.
constexpr double kConverged = 1e-15;
// A correction of x below this (relative) ends the rounds: each round leaves about alpha eps
// (1e-10) of the error before it, so after such a correction what is left is below 1e-18. A
// constraint residual left above kFallBack (relative), or rounds that do not settle, send the
// solve to the dense method.
constexpr double kSettled = 1e-8;
constexpr double kFallBack = 1e-10;
// A single round (a projection's correction) with S formed at other values leaves about their
// relative change (jacobian_moved_slightly: 1e-6 and below) of the residual: what the next
// Newton iteration takes out. An order-1 residual still tells the dependent rows.
constexpr double kStaleFallBack = 1e-5;
// A pivot of the dense Schur complement below this fraction of its largest diagonal: the rows
// nearly dependent (next to a toggle), where the iterations and their fallback take over.
constexpr double kSingularSchur = 1e-8;
// Above this ratio of its smallest to its largest squared pivot the Schur complement's condition
// number is below 1e4 and one direct round with M's factor is within about 1e-12 of x's size.
constexpr double kWellConditioned = 1e-4;

double largest(const Eigen::VectorXd& v) { return v.size() == 0 ? 0.0 : v.lpNorm<Eigen::Infinity>(); }

}  // namespace

AugmentedSystem::AugmentedSystem(int n, int m, const std::vector<Eigen::Triplet<double>>& mass,
                                 std::vector<Entry> entries)
    : n_(n), m_(m), entries_(std::move(entries)) {
  mass_.resize(n, n);
  mass_.setFromTriplets(mass.begin(), mass.end());
  mass_.makeCompressed();
  std::stable_sort(entries_.begin(), entries_.end(), [](const Entry& a, const Entry& b) { return a.row < b.row; });
  analyse(mass);
  for (Eigen::VectorXd* v : {&permuted_b_, &permuted_x_, &r1_, &g_, &dx_, &image_n_, &kx_}) v->setZero(n);
  for (Eigen::VectorXd* v : {&best_dx_, &mass_x_}) v->setZero(n);
  for (Eigen::VectorXd* v : {&r2_, &dlambda_, &best_dlambda_, &residual_, &direction_, &image_}) v->setZero(m);
}

// K's pattern (M's and Phi_q^T Phi_q's), its order (none when dense; else approximate minimum
// degree), where each term goes, and the symbolic factorisation.
void AugmentedSystem::analyse(const std::vector<Eigen::Triplet<double>>& mass) {
  std::vector<std::pair<int, int>> pattern;
  for (const auto& t : mass) pattern.emplace_back(t.row(), t.col());
  std::vector<std::pair<int, int>> pairs;  // (a, b): entries a and b share a row
  for (std::size_t first = 0; first < entries_.size();) {
    std::size_t last = first;
    while (last < entries_.size() && entries_[last].row == entries_[first].row) ++last;
    for (std::size_t a = first; a < last; ++a)
      for (std::size_t b = first; b < last; ++b) {
        pairs.emplace_back(static_cast<int>(a), static_cast<int>(b));
        pattern.emplace_back(entries_[a].col, entries_[b].col);
      }
    first = last;
  }
  for (int i = 0; i < n_; ++i) pattern.emplace_back(i, i);
  dense_ = n_ <= kDenseLimit;
  if (dense_)
    for (const Entry& e : entries_) dense_places_.push_back({e.value, e.row * n_ + e.col});
  new_index_.resize(n_);
  for (int i = 0; i < n_; ++i) new_index_[i] = i;
  std::map<std::pair<int, int>, int> slot;  // (i, j), i <= j in K's order -> where its value is
  if (dense_) {
    dense_k_.setZero(n_, n_);
    dense_mass_ = Eigen::MatrixXd(mass_);
    factor_mass();
    dense_jacobian_.setZero(n_, m_);
    schur_basis_.setZero(n_, m_);
    schur_factor_.setZero(m_, m_);
    schur_reciprocal_.setZero(m_);
    for (int j = 0; j < n_; ++j)
      for (int i = 0; i <= j; ++i) slot[{i, j}] = j * n_ + i;
    base_.assign(static_cast<std::size_t>(n_) * n_, 0.0);
  } else {
    std::vector<Eigen::Triplet<double>> ones;
    for (const auto& [i, j] : pattern) ones.emplace_back(i, j, 1.0);
    Eigen::SparseMatrix<double> symmetric(n_, n_);
    symmetric.setFromTriplets(ones.begin(), ones.end());
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> inverse;
    Eigen::AMDOrdering<int>()(symmetric, inverse);
    const Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> order = inverse.inverse();
    for (int i = 0; i < n_; ++i) new_index_[i] = order.indices()(i);
    std::vector<Eigen::Triplet<double>> upper;
    for (const auto& [i, j] : pattern) {
      const int a = new_index_[i], b = new_index_[j];
      upper.emplace_back(std::min(a, b), std::max(a, b), 0.0);
    }
    sparse_k_.resize(n_, n_);
    sparse_k_.setFromTriplets(upper.begin(), upper.end());
    sparse_k_.makeCompressed();
    for (int j = 0; j < n_; ++j)
      for (int p = sparse_k_.outerIndexPtr()[j]; p < sparse_k_.outerIndexPtr()[j + 1]; ++p)
        slot[{sparse_k_.innerIndexPtr()[p], j}] = p;
    base_.assign(static_cast<std::size_t>(sparse_k_.nonZeros()), 0.0);
    sparse_factor_.analyzePattern(sparse_k_);
  }
  const auto slot_of = [&](int i, int j) {
    const int a = new_index_[i], b = new_index_[j];
    return slot.at({std::min(a, b), std::max(a, b)});
  };
  for (const auto& t : mass)
    if (new_index_[t.row()] <= new_index_[t.col()]) base_[slot_of(t.row(), t.col())] += t.value();
  for (const auto& [a, b] : pairs)
    if (new_index_[entries_[a].col] <= new_index_[entries_[b].col])
      products_.push_back({slot_of(entries_[a].col, entries_[b].col), entries_[a].value, entries_[b].value});
}

// M = U^T U, where every coordinate has inertia (M's pivots above kNoInertia of its largest
// diagonal): then the small direct path solves with M's factor, formed here once, instead of K's,
// formed and factorised at every position (docs/dynamics.md, Formulation). A coordinate without
// inertia of its own (a riding point's, which only the constraints move) leaves M singular and
// the path with K.
void AugmentedSystem::factor_mass() {
  mass_factor_ = dense_mass_;
  const double most = n_ ? dense_mass_.diagonal().maxCoeff() : 0.0;
  mass_regular_ = n_ > 0 && cholesky_in_place<0>(mass_factor_.data()) &&
                  mass_factor_.diagonal().cwiseAbs2().minCoeff() > kNoInertia * most;
  mass_reciprocal_ = mass_factor_.diagonal().cwiseInverse();
}

void AugmentedSystem::choose_penalty(const std::vector<double>& values) {
  Eigen::VectorXd column_squares = Eigen::VectorXd::Zero(n_), row_sums = Eigen::VectorXd::Zero(m_);
  for (const Entry& e : entries_) {
    column_squares(e.col) += values[e.value] * values[e.value];
    row_sums(e.row) += std::abs(values[e.value]);
  }
  const double most_mass = n_ ? mass_.diagonal().maxCoeff() : 0.0;
  const double most_constraint = largest(column_squares);
  alpha_ = kPenalty * std::max(most_mass, 1e-300) / std::max(most_constraint, 1e-300);
  jacobian_scale_ = largest(row_sums);
}

bool AugmentedSystem::factorize(const std::vector<double>& values) {
  if (alpha_ == 0.0) choose_penalty(values);
  schur_ready_ = false;
  range_space_ = mass_regular_ && direct_ && with_coordinate_count(n_, [](auto size) { return size() > 0; });
  if (range_space_) {
    // M's factor serves every Jacobian and M is regular: no K to form, and no free motion without
    // inertia. K is formed only if the iterations are needed (next to a toggle).
    k_formed_ = false;
    return true;
  }
  return form_k(values);
}

bool AugmentedSystem::form_k(const std::vector<double>& values) {
  k_formed_ = true;
  double* k = dense_ ? dense_k_.data() : sparse_k_.valuePtr();
  std::copy(base_.begin(), base_.end(), k);
  // alpha and the values read once into locals: through k the compiler must assume they change.
  const double alpha = alpha_, *value = values.data();
  for (const Product& p : products_) k[p.slot] += alpha * value[p.a] * value[p.b];
  if (dense_) {
    largest_diagonal_ = dense_k_.diagonal().maxCoeff();
    const auto factorise_k = [&](auto size) { return cholesky_in_place<decltype(size)::value>(dense_k_.data()); };
    if (!with_coordinate_count(n_, factorise_k)) return false;
    k_reciprocal_ = dense_k_.diagonal().cwiseInverse();
    const double smallest_pivot = dense_k_.diagonal().cwiseAbs2().minCoeff();
    return smallest_pivot > kNoInertia * largest_diagonal_;
  }
  largest_diagonal_ = sparse_k_.diagonal().maxCoeff();
  sparse_factor_.factorize(sparse_k_);
  if (sparse_factor_.info() != Eigen::Success) return false;
  const double smallest_pivot = sparse_factor_.vectorD().minCoeff();
  return smallest_pivot > kNoInertia * largest_diagonal_;
}

void AugmentedSystem::solve_k(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  if (dense_) {
    x = b;
    forward_k<0>(dense_k_.data(), k_reciprocal_.data(), x.data());
    backward_k<0>(dense_k_.data(), k_reciprocal_.data(), x.data());
    return;
  }
  for (int i = 0; i < n_; ++i) permuted_b_(new_index_[i]) = b(i);
  permuted_x_ = sparse_factor_.solve(permuted_b_);
  for (int i = 0; i < n_; ++i) x(i) = permuted_x_(new_index_[i]);
}

void AugmentedSystem::apply(const std::vector<double>& values, const Eigen::VectorXd& x, Eigen::VectorXd& out) const {
  out.setZero(m_);
  for (const Entry& e : entries_) out(e.row) += values[e.value] * x(e.col);
}

void AugmentedSystem::apply_transposed(const std::vector<double>& values, const Eigen::VectorXd& y,
                                       Eigen::VectorXd& out) const {
  out.setZero(n_);
  for (const Entry& e : entries_) out(e.col) += values[e.value] * y(e.row);
}

// The correction (dx_, dlambda_) with M dx + Phi^T dlambda = r1, Phi dx = r2: with
// K dx + Phi^T dlambda = r1 + alpha Phi^T r2 =: g, dx = K^-1 (g - Phi^T dlambda) and
// S dlambda = Phi K^-1 g - r2, solved by conjugate gradients from dlambda = 0. Their residual
// is Phi dx - r2 for the current dx, updated as they go. They stop at `floor` (the rounding of the
// whole system's terms) or where the residual, having reached the rounding, grows again (along a
// dependent direction of the rows, S's null space); the best iterate is kept.
void AugmentedSystem::schur_cg(const std::vector<double>& values, const Eigen::VectorXd& r1, const Eigen::VectorXd& r2,
                               double floor) {
  apply_transposed(values, r2, image_n_);
  g_ = r1 + alpha_ * image_n_;
  solve_k(g_, dx_);
  dlambda_.setZero(m_);
  if (m_ == 0) return;
  apply(values, dx_, residual_);
  residual_ -= r2;
  const double target = std::max(floor, kConverged * (largest(r2) + jacobian_scale_ * largest(dx_)));
  direction_ = residual_;
  double squared = residual_.squaredNorm(), best = largest(residual_);
  int since_best = 0;
  best_dx_ = dx_;
  best_dlambda_ = dlambda_;
  for (int iteration = 0; iteration < kMostIterations && largest(residual_) > target; ++iteration) {
    // S p = Phi K^-1 Phi^T p; the residual falls by step S p when dlambda gains step p.
    apply_transposed(values, direction_, image_n_);
    solve_k(image_n_, kx_);
    apply(values, kx_, image_);
    const double curvature = direction_.dot(image_);
    if (!(curvature > 0.0)) break;
    const double step = squared / curvature;
    dlambda_ += step * direction_;
    dx_ -= step * kx_;
    residual_ -= step * image_;
    // At the rounding the residual stops falling (and along a dependent direction grows): three
    // iterations without a new best end them (CG's residual need not fall at every iteration).
    const double now = largest(residual_);
    if (now < best) {
      best = now;
      best_dx_ = dx_;
      best_dlambda_ = dlambda_;
      since_best = 0;
    } else if (++since_best >= 3 || now > 1e3 * best) {
      break;
    }
    const double next = residual_.squaredNorm();
    direction_ = residual_ + (next / squared) * direction_;
    squared = next;
  }
  dx_ = best_dx_;
  dlambda_ = best_dlambda_;
}

double AugmentedSystem::solve_iterative(const std::vector<double>& values, const Eigen::VectorXd& f,
                                        const Eigen::VectorXd& c, Eigen::VectorXd& x, Eigen::VectorXd& lambda,
                                        bool refine) {
  if (!k_formed_ && !form_k(values)) {  // with M regular K is too: not met
    lambda.setZero(m_);
    return solve_dense(values, f, c, x);
  }
  x.setZero(n_);
  if (lambda.size() != m_) lambda.setZero(m_);
  // Each round corrects (x, lambda) by the system's residuals, computed in working precision. The
  // force residual is no measure of x's accuracy: alpha Phi^T (rounding of Phi x - c) stays in it,
  // but lies in the range of Phi^T, which only moves lambda. The correction of x is: its size
  // after the first round is K's rounding, which the second takes out.
  bool converged = false;
  double constraint_left = 0.0;
  for (int round = 0; round < (refine ? kMostRounds : 1) && !converged; ++round) {
    apply_transposed(values, lambda, image_n_);
    mass_x_.noalias() = mass_ * x;
    r1_ = f - mass_x_ - image_n_;
    apply(values, x, r2_);
    r2_ = c - r2_;
    schur_cg(values, r1_, r2_, kConverged * (largest(c) + jacobian_scale_ * largest(x)));
    x += dx_;
    lambda += dlambda_;
    converged = !refine || (round > 0 && largest(dx_) <= kSettled * largest(x));
  }
  apply(values, x, r2_);
  r2_ = c - r2_;
  const double scale = largest(c) + jacobian_scale_ * largest(x);
  last_residual_ = largest(r2_);
  constraint_left = scale > 0 ? last_residual_ / scale : 0.0;
  if (converged && constraint_left <= kFallBack && x.allFinite()) return constraint_left;
  lambda.setZero(m_);  // no warm start from here
  return solve_dense(values, f, c, x);
}

// Written out rather than Eigen's LLT: at up to 16 coordinates its dispatch and copies cost more
// than the arithmetic, and the factor stays where K was formed.
template <int N>
bool AugmentedSystem::cholesky_in_place(double* u) const {
  const int n = N > 0 ? N : n_;  // U(i, j) = u[j * n + i], i <= j
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < j; ++i) {
      double sum = u[j * n + i];
      for (int k = 0; k < i; ++k) sum -= u[i * n + k] * u[j * n + k];
      u[j * n + i] = sum / u[i * n + i];
    }
    double diagonal = u[j * n + j];
    for (int k = 0; k < j; ++k) diagonal -= u[j * n + k] * u[j * n + k];
    if (!(diagonal > 0.0)) return false;
    u[j * n + j] = std::sqrt(diagonal);
  }
  return true;
}

template <int N>
void AugmentedSystem::forward_k(const double* u, const double* reciprocal, double* y) const {
  const int n = N > 0 ? N : n_;
  for (int j = 0; j < n; ++j) {
    double sum = y[j];
    for (int i = 0; i < j; ++i) sum -= u[j * n + i] * y[i];
    y[j] = sum * reciprocal[j];
  }
}

template <int N>
void AugmentedSystem::backward_k(const double* u, const double* reciprocal, double* x) const {
  const int n = N > 0 ? N : n_;
  for (int j = n - 1; j >= 0; --j) {
    const double value = x[j] * reciprocal[j];
    x[j] = value;
    for (int i = 0; i < j; ++i) x[i] -= u[j * n + i] * value;
  }
}

void AugmentedSystem::fill_dense_jacobian(const std::vector<double>& values) {
  jacobian_stale_ = false;
  double* j = dense_jacobian_.data();  // Phi_q(r, k) = j[r * n + k]
  std::fill(j, j + static_cast<std::ptrdiff_t>(n_) * m_, 0.0);
  const double* value = values.data();
  for (const DensePlace& e : dense_places_) j[e.place] += value[e.value];
}

template <int N, int M>
void AugmentedSystem::prepare_schur(const std::vector<double>& values) {
  schur_ready_ = true;
  schur_stale_ = false;
  const int n = N > 0 ? N : n_, m = M > 0 ? M : m_;
  fill_dense_jacobian(values);
  const double* j = dense_jacobian_.data();
  double* w = schur_basis_.data();  // W(k, r) = w[r * n + k]: row r of Phi_q, solved with U^T
  std::copy(j, j + static_cast<std::ptrdiff_t>(n) * m, w);
  const double *factor = small_factor(), *reciprocal = small_reciprocal();
  for (int r = 0; r < m; ++r) forward_k<N>(factor, reciprocal, w + r * n);
  double* l = schur_factor_.data();  // L(a, b) = l[b * m + a], a >= b
  double most = 0.0;
  for (int b = 0; b < m; ++b)
    for (int a = b; a < m; ++a) {
      double sum = 0.0;
      for (int k = 0; k < n; ++k) sum += w[a * n + k] * w[b * n + k];
      l[b * m + a] = sum;
      if (a == b) most = std::max(most, sum);
    }
  // S = L D L^T with L unit lower (no square roots, whose latency chained the columns), the
  // reciprocals of D kept. A small pivot: the rows nearly dependent there (next to a toggle).
  schur_usable_ = false;
  schur_conditioned_ = true;
  double* over_d = schur_reciprocal_.data();
  for (int b = 0; b < m; ++b) {
    double pivot = l[b * m + b];
    for (int k = 0; k < b; ++k) pivot -= l[k * m + b] * l[k * m + b] * l[k * m + k];
    if (!(pivot > kSingularSchur * most)) return;
    if (!(pivot > kWellConditioned * most)) schur_conditioned_ = false;
    l[b * m + b] = pivot;
    over_d[b] = 1.0 / pivot;
    for (int a = b + 1; a < m; ++a) {
      double sum = l[b * m + a];
      for (int k = 0; k < b; ++k) sum -= l[k * m + a] * l[k * m + b] * l[k * m + k];
      l[b * m + a] = sum * over_d[b];
    }
  }
  schur_usable_ = true;
}

template <int M>
void AugmentedSystem::solve_schur(double* y) const {
  const int m = M > 0 ? M : m_;
  // L(a, b) = l[b * m + a], a > b, unit diagonal; D(b) = l[b * m + b].
  const double *l = schur_factor_.data(), *over_d = schur_reciprocal_.data();
  for (int a = 0; a < m; ++a) {
    double sum = y[a];
    for (int k = 0; k < a; ++k) sum -= l[k * m + a] * y[k];
    y[a] = sum;
  }
  for (int a = 0; a < m; ++a) y[a] *= over_d[a];
  for (int a = m - 1; a >= 0; --a) {
    double sum = y[a];
    for (int k = a + 1; k < m; ++k) sum -= l[a * m + k] * y[k];
    y[a] = sum;
  }
}

// The rounds of solve_iterative, each correction (dx, dlambda) of the residuals (r1, r2) direct:
// with g = r1 + alpha Phi^T r2 and h = U^-T g, S dlambda = Phi K^-1 g - r2 = W^T h - r2 and
// dx = K^-1 (g - Phi^T dlambda) = U^-1 (h - W dlambda). N coordinates and M rows when compiled
// (M = 0: m_ read at run time); the vectors of a round are local, where the compiler keeps them.
template <int N, int M>
double AugmentedSystem::solve_small(const std::vector<double>& values, const Eigen::VectorXd& f,
                                    const Eigen::VectorXd& c, Eigen::VectorXd& x, Eigen::VectorXd& lambda,
                                    Rounds rounds) {
  if (!schur_ready_)
    prepare_schur<N, M>(values);
  else if (jacobian_stale_)
    fill_dense_jacobian(values);
  const bool one_round_suffices = range_space_ && !schur_stale_ && schur_conditioned_;
  const bool refine = rounds == Rounds::to_rounding || (rounds == Rounds::as_needed && !one_round_suffices);
  if (!schur_usable_) return solve_iterative(values, f, c, x, lambda, refine);
  constexpr int n = N;
  const int m = M > 0 ? M : m_;
  if (lambda.size() != m) lambda.setZero(m);
  const double *mass = dense_mass_.data(), *j = dense_jacobian_.data(), *w = schur_basis_.data(),
               *factor = small_factor(), *reciprocal = small_reciprocal();
  const bool range_space = range_space_;
  double xs[n] = {}, r1[n], h[n];
  double *r2 = r2_.data(), *y = dlambda_.data(), *ls = lambda.data();
  bool converged = false;
  for (int round = 0; round < (refine ? kMostRounds : 1) && !converged; ++round) {
    // The residuals (r1, r2) = (f - M x - Phi^T lambda, c - Phi x); x is zero in the first round,
    // the one round of most solves, whose products with it are spared.
    for (int i = 0; i < n; ++i) {
      double sum = f(i);
      if (round > 0)
        for (int k = 0; k < n; ++k) sum -= mass[i * n + k] * xs[k];
      r1[i] = sum;
      h[i] = 0.0;
    }
    for (int r = 0; r < m; ++r) {
      double sum = c(r);
      const double multiplier = ls[r];
      if (round > 0)
        for (int k = 0; k < n; ++k) sum -= j[r * n + k] * xs[k];
      for (int k = 0; k < n; ++k) r1[k] -= j[r * n + k] * multiplier;
      r2[r] = sum;
      if (!range_space)
        for (int k = 0; k < n; ++k) h[k] += j[r * n + k] * sum;
    }
    // With M's factor (range_space_) g is r1 itself: the penalty term is K's.
    for (int k = 0; k < n; ++k) h[k] = range_space ? r1[k] : r1[k] + alpha_ * h[k];
    forward_k<N>(factor, reciprocal, h);
    for (int r = 0; r < m; ++r) {
      double sum = 0.0;
      for (int k = 0; k < n; ++k) sum += w[r * n + k] * h[k];
      y[r] = sum - r2[r];
    }
    solve_schur<M>(y);
    for (int r = 0; r < m; ++r)
      for (int k = 0; k < n; ++k) h[k] -= w[r * n + k] * y[r];
    backward_k<N>(factor, reciprocal, h);
    double most_x = 0.0, most_dx = 0.0;
    for (int k = 0; k < n; ++k) {
      xs[k] += h[k];
      most_x = std::max(most_x, std::abs(xs[k]));
      most_dx = std::max(most_dx, std::abs(h[k]));
    }
    for (int r = 0; r < m; ++r) ls[r] += y[r];
    converged = !refine || (round > 0 && most_dx <= kSettled * most_x);
  }
  const double left = small_solution<N, M>(xs, c, x);
  const double allowed = schur_stale_ && !refine ? kStaleFallBack : kFallBack;
  if (converged && left <= allowed) return left;
  lambda.setZero(m_);  // no warm start from here
  return solve_dense(values, f, c, x);
}

template <int N, int M>
double AugmentedSystem::small_solution(const double* xs, const Eigen::VectorXd& c, Eigen::VectorXd& x) {
  constexpr int n = N;
  const int m = M > 0 ? M : m_;
  const double* j = dense_jacobian_.data();
  x.resize(n);
  double left = 0.0, most_x = 0.0, nan_if_not_finite = 0.0;  // x - x is NaN for an infinite or NaN x
  for (int k = 0; k < n; ++k) {
    x(k) = xs[k];
    most_x = std::max(most_x, std::abs(xs[k]));
    nan_if_not_finite += xs[k] - xs[k];
  }
  for (int r = 0; r < m; ++r) {
    double sum = c(r);
    for (int k = 0; k < n; ++k) sum -= j[r * n + k] * xs[k];
    left = std::max(left, std::abs(sum));
  }
  last_residual_ = left;
  if (nan_if_not_finite != 0.0) return std::numeric_limits<double>::infinity();
  const double scale = largest(c) + jacobian_scale_ * most_x;
  return scale > 0 ? left / scale : 0.0;
}

double AugmentedSystem::solve(const std::vector<double>& values, const Eigen::VectorXd& f, const Eigen::VectorXd& c,
                              Eigen::VectorXd& x, Eigen::VectorXd& lambda, Rounds rounds) {
  // The direct path for the sizes compiled for only: from 10 coordinates (Andrews' squeezer has 14)
  // forming S costs more than the few iterations it saves. With redundant rows S is singular
  // everywhere, its last pivot rounding that no threshold tells from a small one: iterations. One free degree of
  // freedom (m = n - 1) has its row count compiled too.
  return with_coordinate_count(dense_ && direct_ ? n_ : 0, [&](auto size) {
    constexpr int n = decltype(size)::value;
    if constexpr (n > 0) {
      if (m_ == n - 1) return solve_small<n, n - 1>(values, f, c, x, lambda, rounds);
      return solve_small<n, 0>(values, f, c, x, lambda, rounds);
    } else {
      return solve_iterative(values, f, c, x, lambda, rounds != Rounds::one);
    }
  });
}

// The first version's solve, for where the iterations above do not converge (the rows nearly or
// exactly dependent: at or next to a toggle): a rank-revealing QR of Phi_q^T gives the
// minimum-norm x_p with Phi_q x_p = c and an orthonormal basis N of the null space, and
// x = x_p + N z with (N^T M N) z = N^T (f - M x_p). Dense and cubic in the size, but only met
// near a toggle.
double AugmentedSystem::solve_dense(const std::vector<double>& values, const Eigen::VectorXd& f,
                                    const Eigen::VectorXd& c, Eigen::VectorXd& x) {
  Eigen::MatrixXd jacobian = Eigen::MatrixXd::Zero(m_, n_);
  for (const Entry& e : entries_) jacobian(e.row, e.col) += values[e.value];
  const Eigen::MatrixXd mass = Eigen::MatrixXd(mass_);
  Eigen::MatrixXd basis = Eigen::MatrixXd::Identity(n_, n_);
  Eigen::VectorXd particular = Eigen::VectorXd::Zero(n_);
  int rank = 0;
  if (m_ > 0) {
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr;
    qr.setThreshold(1e-10);
    qr.compute(jacobian.transpose());
    rank = static_cast<int>(qr.rank());
    basis = qr.householderQ();
    const Eigen::VectorXd permuted = qr.colsPermutation().transpose() * c;
    const Eigen::VectorXd y =
        qr.matrixR().topLeftCorner(rank, rank).transpose().triangularView<Eigen::Lower>().solve(permuted.head(rank));
    particular = basis.leftCols(rank) * y;
  }
  x = particular;
  if (rank < n_) {
    const auto null = basis.rightCols(n_ - rank);
    const Eigen::MatrixXd reduced = null.transpose() * mass * null;
    const Eigen::VectorXd z = reduced.ldlt().solve(null.transpose() * (f - mass * particular));
    x += null * z;
  }
  const double scale = largest(c) + jacobian_scale_ * largest(x);
  last_residual_ = largest(Eigen::VectorXd(c - jacobian * x));
  return scale > 0 ? last_residual_ / scale : 0.0;
}

}  // namespace nbar
