// The sparse LU with kept pivots against Eigen's dense LU: solves, transposed solves, the sign
// of the determinant and the condition estimate, on random sparse matrices and on a sequence of
// slowly turning ones (the way a linkage's Jacobian changes along a sweep), where it must reuse
// its eliminations and still choose again when a kept pivot becomes small.
#include "kinematics/sparse_lu.hpp"

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>
#include <Eigen/Dense>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace nbar {
namespace {

struct Problem {
  int n = 0;
  std::vector<SparseLU::Entry> entries;
  std::vector<double> values;

  Eigen::MatrixXd dense() const {
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
    for (std::size_t e = 0; e < entries.size(); ++e) a(entries[e].row, entries[e].col) += values[e];
    return a;
  }
};

// A random n x n pattern with `per_row` entries a row besides a random permutation's (so that a
// transversal exists), one entry repeated, and values in [-1, 1].
Problem random_problem(int n, int per_row, std::mt19937& rng) {
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::uniform_int_distribution<int> column(0, n - 1);
  std::vector<int> permutation(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) permutation[static_cast<std::size_t>(i)] = i;
  std::shuffle(permutation.begin(), permutation.end(), rng);
  Problem p;
  p.n = n;
  for (int r = 0; r < n; ++r) {
    p.entries.push_back({r, permutation[static_cast<std::size_t>(r)]});
    for (int k = 0; k < per_row; ++k) p.entries.push_back({r, column(rng)});
  }
  p.entries.push_back(p.entries.front());
  for (std::size_t e = 0; e < p.entries.size(); ++e) p.values.push_back(value(rng));
  return p;
}

double relative_residual(const Eigen::MatrixXd& a, const Eigen::VectorXd& x, const Eigen::VectorXd& b) {
  return (a * x - b).lpNorm<Eigen::Infinity>() /
         (a.lpNorm<Eigen::Infinity>() * x.lpNorm<Eigen::Infinity>() + b.lpNorm<Eigen::Infinity>());
}

// Solves, transposed solves, the sign of det(A) and the condition estimate against the dense
// matrix's.
void expect_agrees_with_dense(const SparseLU& lu, const Problem& p) {
  const Eigen::MatrixXd a = p.dense();
  const Eigen::FullPivLU<Eigen::MatrixXd> reference(a);
  ASSERT_TRUE(reference.isInvertible());
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(p.n, -1.0, 2.0);
  Eigen::VectorXd x(p.n);
  lu.solve(b.data(), x.data());
  EXPECT_LT(relative_residual(a, x, b), 1e-13);
  lu.solve_transposed(b.data(), x.data());
  EXPECT_LT(relative_residual(a.transpose(), x, b), 1e-13);
  Eigen::VectorXd in_place = b;
  lu.solve(in_place.data(), in_place.data());
  EXPECT_LT(relative_residual(a, in_place, b), 1e-13);
  EXPECT_EQ(lu.determinant_sign(), reference.determinant() > 0 ? 1 : -1);

  // Hager's estimate of |A^-1|_1 is a lower bound, exact or nearly so on such matrices.
  const double exact =
      1.0 / (a.cwiseAbs().colwise().sum().maxCoeff() * a.inverse().cwiseAbs().colwise().sum().maxCoeff());
  const double estimate = lu.reciprocal_condition_estimate(p.values.data());
  EXPECT_GE(estimate, exact * (1 - 1e-9));
  EXPECT_LE(estimate, 10 * exact);
}

TEST(SparseLU, AgreesWithDenseLUOnRandomSparseMatrices) {
  std::mt19937 rng(20261127);
  for (int n : {1, 2, 3, 4, 5, 8, 9, 12, 40, 150}) {
    for (int trial = 0; trial < 20; ++trial) {
      Problem p = random_problem(n, n < 4 ? 1 : 3, rng);
      if (!Eigen::FullPivLU<Eigen::MatrixXd>(p.dense()).isInvertible()) continue;
      SparseLU lu;
      lu.set_pattern(p.n, p.entries);
      ASSERT_TRUE(lu.factorize(p.values.data())) << "n = " << n;
      SCOPED_TRACE("n = " + std::to_string(n) + ", trial " + std::to_string(trial));
      expect_agrees_with_dense(lu, p);
      EXPECT_GE(lu.factor_nonzeros(), n);
    }
  }
}

// A block-diagonal matrix of 2 x 2 rotations turning with a parameter, plus a fixed sparse
// coupling below the blocks: the largest entry of each column moves from row to row as the
// blocks turn, as a crank's x and y components take turns to lead. 3 blocks (6 x 6, the dense
// path) or more (the sparse one, with more pivot patterns than the four kept eliminations).
Problem turning_problem(double angle, int blocks = 3) {
  Problem p;
  p.n = 2 * blocks;
  for (int b = 0; b < blocks; ++b) {
    const double t = angle * (1 + b) + b;
    const int o = 2 * b;
    p.entries.insert(p.entries.end(), {{o, o}, {o, o + 1}, {o + 1, o}, {o + 1, o + 1}});
    p.values.insert(p.values.end(), {std::cos(t), -std::sin(t), std::sin(t), std::cos(t)});
  }
  for (int b = 1; b < blocks; ++b) {
    p.entries.insert(p.entries.end(), {{2 * b, 2 * b - 2}, {2 * b + 1, 2 * b - 1}});
    p.values.insert(p.values.end(), {0.3, -0.2});
  }
  return p;
}

TEST(SparseLU, KeepsItsPivotsAlongASweepAndChoosesAgainWhenTheyFail) {
  for (const int blocks : {3, 7}) {
    SparseLU lu;
    Problem p = turning_problem(0.0, blocks);
    lu.set_pattern(p.n, p.entries);
    const int steps = 720;
    for (int i = 0; i <= steps; ++i) {
      p = turning_problem(2 * std::numbers::pi * i / steps, blocks);
      ASSERT_TRUE(lu.factorize(p.values.data())) << "step " << i;
      SCOPED_TRACE(std::to_string(blocks) + " blocks, step " + std::to_string(i));
      expect_agrees_with_dense(lu, p);
    }
    // Chosen again only where a kept pivot fell below the threshold and no kept elimination
    // would do: now and then, not every step, and more than once.
    EXPECT_GT(lu.analyses(), 1) << blocks << " blocks";
    EXPECT_LT(lu.analyses(), 30 * blocks) << blocks << " blocks";
  }
}

TEST(SparseLU, AFailedFactorisationLeavesNoNumbersBehind) {
  for (const int blocks : {3, 7}) {  // dense and sparse paths
    Problem p = turning_problem(0.4, blocks);
    SparseLU lu;
    lu.set_pattern(p.n, p.entries);
    ASSERT_TRUE(lu.factorize(p.values.data()));
    EXPECT_NE(lu.determinant_sign(), 0);
    // A NaN or an infinity in any one entry, wherever the elimination would carry it (into L, U or
    // a pivot): refused, and the solves say so.
    for (std::size_t at = 0; at < p.values.size(); ++at) {
      for (const double bad : {std::nan(""), HUGE_VAL, -HUGE_VAL}) {
        Problem q = p;
        q.values[at] = bad;
        EXPECT_FALSE(lu.factorize(q.values.data())) << bad << " at entry " << at << ", " << blocks << " blocks";
        EXPECT_EQ(lu.determinant_sign(), 0);
        EXPECT_EQ(lu.pivot_ratio(), 0.0);
        std::vector<double> b(static_cast<std::size_t>(p.n), 1.0), x(static_cast<std::size_t>(p.n), 0.0);
        lu.solve(b.data(), x.data());
        for (double v : x) EXPECT_TRUE(std::isnan(v));
        lu.solve_transposed(b.data(), x.data());
        for (double v : x) EXPECT_TRUE(std::isnan(v));
      }
    }
    // And it recovers at the next good matrix.
    ASSERT_TRUE(lu.factorize(p.values.data()));
    expect_agrees_with_dense(lu, p);
  }
  SparseLU empty;
  empty.set_pattern(0, {});
  EXPECT_TRUE(empty.factorize(nullptr));
  EXPECT_EQ(empty.determinant_sign(), 1);
  empty.solve(nullptr, nullptr);
}

TEST(SparseLU, SolvesInPlaceBothWays) {
  for (const int blocks : {3, 7}) {
    const Problem p = turning_problem(1.1, blocks);
    SparseLU lu;
    lu.set_pattern(p.n, p.entries);
    ASSERT_TRUE(lu.factorize(p.values.data()));
    const Eigen::MatrixXd a = p.dense();
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(p.n, 2.0, -1.0);
    Eigen::VectorXd x = b;
    lu.solve(x.data(), x.data());
    EXPECT_LT(relative_residual(a, x, b), 1e-14);
    x = b;
    lu.solve_transposed(x.data(), x.data());
    EXPECT_LT(relative_residual(a.transpose(), x, b), 1e-14);
  }
}

TEST(SparseLU, RefusesSingularAndNonFiniteMatrices) {
  SparseLU lu;
  lu.set_pattern(3, {{0, 0}, {0, 1}, {1, 0}, {1, 1}, {2, 2}});
  const std::vector<double> singular{1.0, 2.0, 2.0, 4.0, 1.0};
  EXPECT_FALSE(lu.factorize(singular.data()));
  EXPECT_EQ(lu.determinant_sign(), 0);
  const std::vector<double> regular{1.0, 2.0, 3.0, 4.0, 1.0};
  EXPECT_TRUE(lu.factorize(regular.data()));
  EXPECT_EQ(lu.determinant_sign(), -1);  // (1 * 4 - 2 * 3) * 1
  const std::vector<double> not_a_number{1.0, std::nan(""), 3.0, 4.0, 1.0};
  EXPECT_FALSE(lu.factorize(not_a_number.data()));
  // A column with no entry at all.
  SparseLU empty_column;
  empty_column.set_pattern(2, {{0, 0}, {1, 0}});
  const std::vector<double> values{1.0, 1.0};
  EXPECT_FALSE(empty_column.factorize(values.data()));
}

RC_GTEST_PROP(SparseLU, SolvesWhatDenseLUSolves, ()) {
  const int n = *rc::gen::inRange(1, 30);
  std::mt19937 rng(*rc::gen::arbitrary<unsigned>());
  const Problem p = random_problem(n, *rc::gen::inRange(0, 4), rng);
  const Eigen::MatrixXd a = p.dense();
  const Eigen::FullPivLU<Eigen::MatrixXd> reference(a);
  RC_PRE(reference.isInvertible() && reference.rcond() > 1e-8);
  SparseLU lu;
  lu.set_pattern(p.n, p.entries);
  RC_ASSERT(lu.factorize(p.values.data()));
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(n);
  Eigen::VectorXd x(n);
  lu.solve(b.data(), x.data());
  RC_ASSERT(relative_residual(a, x, b) < 1e-12);
  RC_ASSERT(lu.determinant_sign() == (reference.determinant() > 0 ? 1 : -1));
}

}  // namespace
}  // namespace nbar
