// The linear systems of forward dynamics, sparse, in storage sized once at set-up:
//
//   M x + Phi_q^T lambda = f,   Phi_q x = c
//
// with M the constant mass matrix on the natural coordinates and Phi_q the Jacobian of the rows
// kept (constraints and kinematic drivers). The same system gives the accelerations (f = Q, c =
// gamma) and the mass-orthogonal projections of the positions and velocities (f = 0, c = the
// residual). It is solved through the augmented matrix K = M + alpha Phi_q^T Phi_q, symmetric
// positive definite wherever every free motion has inertia (even where Phi_q loses rank: redundant
// constraints, a toggle), whose pattern is fixed and analysed once (a fill-reducing order, then an
// LDL^T with its elimination tree; a dense Cholesky up to kDenseLimit coordinates, where the index
// arithmetic costs more than the zeros). Eliminating x leaves S lambda = b with the Schur
// complement S = Phi_q K^-1 Phi_q^T, whose eigenvalues are s / (1 + alpha s) for the eigenvalues s
// of Phi_q M^-1 Phi_q^T: all near 1 / alpha but for the few directions where the constraints are
// nearly dependent (near a toggle). Conjugate gradients on S therefore converge in a few
// iterations, each one solve with K, and a round of iterative refinement on the whole system
// takes out the rounding that the large alpha brings into K. The cost of everything is linear in
// the nonzeros of K and its factor: for a chain of loops, linear in the number of loops.
//
// Up to kDenseLimit coordinates everything is dense and S itself is formed (m solves with K's
// factor, once per Jacobian) and factorised, so that each round of a solve is two triangular
// solves with K's factor and two with S's: no iterations, nothing allocated, and for 2 to 8
// coordinates the loops compiled for their size (kinematics/sized.hpp). Where S is singular to
// rounding (redundant rows) the iterations take over.
//
// docs/dynamics.md (Formulation) says why this and not the null-space basis of the first version.
#pragma once

#include <Eigen/Core>
#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <vector>

namespace nbar {

class AugmentedSystem {
 public:
  // Up to this many coordinates K is factorised dense.
  static constexpr int kDenseLimit = 16;

  // One nonzero of the kept Jacobian: its value is values[value] of the array the calls pass (the
  // kinematics' Jacobian values, every row), at (row, col) of Phi_q (row among the kept rows).
  struct Entry {
    int value = 0, row = 0, col = 0;
  };

  // n coordinates, m kept rows, the mass matrix as (row, col, value) triplets (repeats add up; both
  // triangles), the kept Jacobian's entries. Analyses K's pattern and orders it.
  AugmentedSystem(int n, int m, const std::vector<Eigen::Triplet<double>>& mass, std::vector<Entry> entries);

  int coordinates() const { return n_; }
  int rows() const { return m_; }
  const Eigen::SparseMatrix<double>& mass() const { return mass_; }

  // Some kept rows depend on the others everywhere (redundant constraints): S is singular, and the
  // solves keep to the iterations, which need no regular S.
  void rows_redundant() { direct_ = false; }

  // The Jacobian values have changed since the last factorize (K stays): the dense Schur
  // complement is formed again at the next solve.
  void jacobian_changed() { schur_ready_ = false; }
  // The Jacobian values have moved by a small projection's correction (relative to the drawing,
  // 1e-6 and below): with M's factor, S from before stays, as the preconditioner of the
  // refinement, whose residuals take the present values (the dense Phi_q is refreshed at the next
  // solve); each round then takes out all but about that relative change of the error. Without
  // M's factor, as jacobian_changed. Forming S costs more than the rounds it saves.
  void jacobian_moved_slightly() {
    if (range_space_ && schur_ready_)
      jacobian_stale_ = schur_stale_ = true;
    else
      schur_ready_ = false;
  }

  // Forms K from the Jacobian values and factorises it. The penalty alpha is fixed at the first
  // call: 1e4 times the mass matrix's largest diagonal over the largest of Phi_q^T Phi_q. False
  // when K is singular: a motion that the kept rows allow moves no mass.
  bool factorize(const std::vector<double>& values);

  // The penalty alpha and the Jacobian's scale that the first factorize chose. A system given
  // another's (before its first factorize) solves as that one does, whatever Jacobian it meets
  // first: the output rows made by either of two systems are the same.
  struct Scales {
    double penalty = 0.0, jacobian = 0.0;
  };
  Scales scales() const { return {alpha_, jacobian_scale_}; }
  void take_scales(const Scales& scales) {
    alpha_ = scales.penalty;
    jacobian_scale_ = scales.jacobian;
  }

  // How far a solve goes: one round (a projection's correction); rounds of iterative refinement
  // until x is at rounding (an output row's accelerations); or, as_needed, one round where M's
  // factor and a Schur complement formed at these values and well conditioned (its pivots' ratio
  // above kWellConditioned) leave an error within about eps / kWellConditioned (1e-12) of x's
  // size, and rounds to rounding elsewhere (the integrator's stages, whose own error is the
  // tolerance's, 1e-8 by default).
  enum class Rounds { one, to_rounding, as_needed };

  // Solves the system with the Jacobian `values` (exact; K from the last factorize, which may be
  // at a nearby point: it only preconditions). `lambda` starts the iteration (a warm start) and
  // returns the multipliers. Rounds of iterative refinement take x to rounding (`rounds`);
  // one round leaves a relative error of about alpha eps (1e-10) in the part of x that
  // the constraints leave free, which is nothing for a projection's small correction. Returns the
  // largest |Phi_q x - c| left, relative to |c| + |Phi_q||x|: about 1e-15 where the system is
  // consistent, of order 1 where the rows have become dependent and c asks the impossible
  // (exactly at a toggle). Where the iterations do not settle (next to a toggle) it falls back to
  // the dense null-space solve of the first version.
  double solve(const std::vector<double>& values, const Eigen::VectorXd& f, const Eigen::VectorXd& c,
               Eigen::VectorXd& x, Eigen::VectorXd& lambda, Rounds rounds);

  // The largest |Phi_q x - c| the last solve left, absolute (solve returns it relative): a row's
  // drift on the acceleration level, without another product with Phi_q.
  double last_residual() const { return last_residual_; }

  // out = Phi_q x, and out = Phi_q^T y.
  void apply(const std::vector<double>& values, const Eigen::VectorXd& x, Eigen::VectorXd& out) const;
  void apply_transposed(const std::vector<double>& values, const Eigen::VectorXd& y, Eigen::VectorXd& out) const;

 private:
  // One product alpha J_a J_b added to K's stored value at `slot`.
  struct Product {
    int slot = 0, a = 0, b = 0;
  };
  // solve() through conjugate gradients on S: the general path, for the sparse K and a singular S.
  double solve_iterative(const std::vector<double>& values, const Eigen::VectorXd& f, const Eigen::VectorXd& c,
                         Eigen::VectorXd& x, Eigen::VectorXd& lambda, bool refine);
  // solve() through the dense S (dense K only), N coordinates and M rows (M = 0: m_, read at run
  // time).
  template <int N, int M>
  double solve_small(const std::vector<double>& values, const Eigen::VectorXd& f, const Eigen::VectorXd& c,
                     Eigen::VectorXd& x, Eigen::VectorXd& lambda, Rounds rounds);
  // x from the round's solution xs, and what is left of the constraints, relative (infinite where x
  // is not finite): |c - Phi_q x| / (|c| + |Phi_q| |x|), the absolute kept in last_residual_.
  template <int N, int M>
  double small_solution(const double* xs, const Eigen::VectorXd& c, Eigen::VectorXd& x);
  // Phi_q dense, W = U^-T Phi_q^T and S = W^T W = Phi_q K^-1 Phi_q^T, factorised (S = L D L^T);
  // schur_usable_ false where S is singular to rounding, schur_conditioned_ where its pivots'
  // ratio is above kWellConditioned.
  template <int N, int M>
  void prepare_schur(const std::vector<double>& values);
  // The dense Phi_q from the present values (prepare_schur's first part).
  void fill_dense_jacobian(const std::vector<double>& values);
  // A = U^T U factorised in place in u's upper triangle (n x n, column-major); false where a pivot
  // is not positive.
  template <int N>
  bool cholesky_in_place(double* u) const;
  // y = U^-T y and x = U^-1 x, in place (A = U^T U, dense, U in u's upper triangle, the
  // reciprocals of its diagonal in `reciprocal`: a multiplication where a division's latency
  // chained the sweeps).
  template <int N>
  void forward_k(const double* u, const double* reciprocal, double* y) const;
  template <int N>
  void backward_k(const double* u, const double* reciprocal, double* x) const;
  // y = S^-1 y, in place, with S = L D L^T as prepare_schur left it (M rows when compiled, M = 0:
  // m_ read at run time).
  template <int M>
  void solve_schur(double* y) const;
  // K formed from the Jacobian values and factorised (factorize without the shortcut of M's factor).
  bool form_k(const std::vector<double>& values);
  void factor_mass();
  // The small direct path's factor: M's where range_space_, else K's.
  const double* small_factor() const { return range_space_ ? mass_factor_.data() : dense_k_.data(); }
  const double* small_reciprocal() const { return range_space_ ? mass_reciprocal_.data() : k_reciprocal_.data(); }
  double solve_dense(const std::vector<double>& values, const Eigen::VectorXd& f, const Eigen::VectorXd& c,
                     Eigen::VectorXd& x);
  void analyse(const std::vector<Eigen::Triplet<double>>& mass);
  void choose_penalty(const std::vector<double>& values);
  // x = K^-1 b (through the permutation).
  void solve_k(const Eigen::VectorXd& b, Eigen::VectorXd& x);
  // Conjugate gradients on the Schur complement for the correction (dx_, dlambda_) of the
  // residuals (r1, r2), until Phi_q dx - r2 is down to `floor` or to its rounding.
  void schur_cg(const std::vector<double>& values, const Eigen::VectorXd& r1, const Eigen::VectorXd& r2, double floor);

  int n_ = 0, m_ = 0;
  std::vector<Entry> entries_;
  // The dense path's: each entry's value and its place in the dense Phi_q (row * n + col), the
  // index arithmetic done once.
  struct DensePlace {
    int value = 0, place = 0;
  };
  std::vector<DensePlace> dense_places_;
  Eigen::SparseMatrix<double> mass_;  // both triangles
  double alpha_ = 0.0;
  double jacobian_scale_ = 0.0;  // the largest |row of Phi_q|_1, for the residual's scale

  bool dense_ = true;
  std::vector<int> new_index_;     // coordinate -> its place in K (the fill-reducing order)
  std::vector<double> base_;       // K's stored values from M alone
  std::vector<Product> products_;  // the alpha Phi_q^T Phi_q part
  Eigen::MatrixXd dense_k_;        // upper triangle used (dense_): K, then its factor U
  // The dense path's (dense_): M, Phi_q (row r at r * n), W (column r at r * n), L and D (S's
  // factor L D L^T, column-major lower, D on the diagonal), whether they are formed for the present Jacobian and S was
  // regular there.
  Eigen::MatrixXd dense_mass_, dense_jacobian_, schur_basis_, schur_factor_;
  // The reciprocals of the diagonals of M's and K's factors, and of S's D.
  Eigen::VectorXd mass_reciprocal_, k_reciprocal_, schur_reciprocal_;
  // After jacobian_moved_slightly: the dense Phi_q not yet refreshed (jacobian_stale_), S formed
  // at other values than the present (schur_stale_, until S is formed again).
  bool schur_ready_ = false, schur_usable_ = false, direct_ = true, jacobian_stale_ = false, schur_stale_ = false,
       schur_conditioned_ = false;
  // M's factor (mass_factor_, upper) where M is regular (mass_regular_); range_space_ while the
  // small direct path solves with it (S = Phi_q M^-1 Phi_q^T, no penalty), K then formed only for
  // the iterations (k_formed_ says whether dense_k_ holds K's factor for the present Jacobian).
  Eigen::MatrixXd mass_factor_;
  bool mass_regular_ = false, range_space_ = false, k_formed_ = false;
  Eigen::SparseMatrix<double> sparse_k_;  // upper triangle, in the fill-reducing order
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Upper, Eigen::NaturalOrdering<int>> sparse_factor_;
  double largest_diagonal_ = 0.0;
  double last_residual_ = 0.0;  // last_residual()

  // Work vectors, sized once.
  Eigen::VectorXd permuted_b_, permuted_x_;
  Eigen::VectorXd r1_, r2_, g_, dx_, dlambda_, best_dx_, best_dlambda_, mass_x_, residual_, direction_, image_,
      image_n_, kx_;
};

}  // namespace nbar
