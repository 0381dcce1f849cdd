// The homotopy solver against systems whose solutions are known in closed form.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <numbers>
#include <random>

#include "nbar/model/diagnostics.hpp"
#include "nbar/synthesis/solve.hpp"

namespace nbar::synthesis {
namespace {

Polynomial var(int n, int i) { return Polynomial::variable(n, i); }

// True when some solution equals `expected` to the tolerance.
bool contains(const std::vector<CVector>& solutions, const CVector& expected, double tolerance = 1e-10) {
  return std::any_of(solutions.begin(), solutions.end(),
                     [&](const CVector& s) { return (s - expected).norm() <= tolerance * (1 + expected.norm()); });
}

CVector point(std::initializer_list<Complex> values) {
  CVector v(static_cast<Eigen::Index>(values.size()));
  Eigen::Index i = 0;
  for (Complex c : values) v[i++] = c;
  return v;
}

TEST(PolynomialTest, ArithmeticAndGradientMatchHandExpansion) {
  const auto x = var(2, 0), y = var(2, 1);
  const Polynomial p = (x + 2.0) * (x - y) * y;  // x^2 y - x y^2 + 2 x y - 2 y^2
  EXPECT_EQ(p.degree(), 3);
  EXPECT_EQ(p.degree_in({0}), 2);
  EXPECT_EQ(p.degree_in({1}), 2);
  const CVector at = point({Complex(1.5, -0.5), Complex(-0.25, 2.0)});
  const Complex X = at[0], Y = at[1];
  CMatrix holder(1, 2);
  const Complex value = p.evaluate(at, holder.row(0));
  EXPECT_LT(std::abs(value - (X * X * Y - X * Y * Y + 2.0 * X * Y - 2.0 * Y * Y)), 1e-13);
  EXPECT_LT(std::abs(holder(0, 0) - (2.0 * X * Y - Y * Y + 2.0 * Y)), 1e-13);
  EXPECT_LT(std::abs(holder(0, 1) - (X * X - 2.0 * X * Y + 2.0 * X - 4.0 * Y)), 1e-13);
  EXPECT_EQ((p - p).degree(), -1);
}

TEST(HomotopySolverTest, FindsAllFourRootsOfTwoQuadrics) {
  const auto x = var(2, 0), y = var(2, 1);
  const PolynomialSystem f({x * x - 1.0, y * y - 4.0});
  const SolveResult r = solve_total_degree(f);
  ASSERT_EQ(r.endpoints.size(), 4u);
  const auto s = r.solutions();
  ASSERT_EQ(s.size(), 4u);
  for (double a : {-1.0, 1.0})
    for (double b : {-2.0, 2.0}) EXPECT_TRUE(contains(s, point({a, b}))) << a << " " << b;
  for (const auto& e : r.endpoints) {
    EXPECT_TRUE(e.real);
    EXPECT_LT(e.residual, 1e-13);
  }
}

TEST(HomotopySolverTest, KatsuraThreeHasEightSolutions) {
  const int n = 4;
  const auto u0 = var(n, 0), u1 = var(n, 1), u2 = var(n, 2), u3 = var(n, 3);
  const PolynomialSystem f(
      {u0 + 2.0 * u1 + 2.0 * u2 + 2.0 * u3 - 1.0, u0 * u0 + 2.0 * u1 * u1 + 2.0 * u2 * u2 + 2.0 * u3 * u3 - u0,
       2.0 * u0 * u1 + 2.0 * u1 * u2 + 2.0 * u2 * u3 - u1, u1 * u1 + 2.0 * u0 * u2 + 2.0 * u1 * u3 - u2});
  EXPECT_EQ(total_degree_count(f), 8);
  const SolveResult r = solve_total_degree(f);
  const auto s = r.solutions();
  EXPECT_EQ(s.size(), 8u);
  // (1, 0, 0, 0) is a solution by inspection.
  EXPECT_TRUE(contains(s, point({1.0, 0.0, 0.0, 0.0})));
  for (const auto* e : r.finite_regular()) EXPECT_LT(e->residual, 1e-12);
}

TEST(HomotopySolverTest, PathsToInfinityAreRecognised) {
  // x y = 1, x^2 = 4: two finite solutions, two of the four paths go to infinity.
  const auto x = var(2, 0), y = var(2, 1);
  const SolveResult r = solve_total_degree(PolynomialSystem({x * y - 1.0, x * x - 4.0}));
  EXPECT_EQ(r.count(EndpointKind::Finite), 2);
  EXPECT_EQ(r.count(EndpointKind::AtInfinity), 2);
  EXPECT_EQ(r.count(EndpointKind::Failed), 0);
  const auto s = r.solutions(true);
  EXPECT_TRUE(contains(s, point({2.0, 0.5})));
  EXPECT_TRUE(contains(s, point({-2.0, -0.5})));
}

TEST(HomotopySolverTest, HugeSolutionIsFoundAccurately) {
  // A near-slider-like solution: x = 1e6, y = 1e-6, found in projective coordinates.
  const auto x = var(2, 0), y = var(2, 1);
  const SolveResult r = solve_total_degree(PolynomialSystem({x * y - 1.0, 1e-6 * x * x - x}));
  const auto s = r.solutions();
  EXPECT_TRUE(contains(s, point({1e6, 1e-6}), 1e-10));
  EXPECT_TRUE(contains(s, point({0.0, 0.0}), 1e-10) == false);
}

TEST(HomotopySolverTest, DoubleRootEndsSingularWithWindingTwo) {
  const auto x = var(2, 0), y = var(2, 1);
  const SolveResult r = solve_total_degree(PolynomialSystem({x * x, y - 1.0}));
  ASSERT_EQ(r.endpoints.size(), 2u);
  for (const auto& e : r.endpoints) {
    ASSERT_EQ(e.kind, EndpointKind::Finite) << e.failure;
    EXPECT_TRUE(e.singular);
    EXPECT_EQ(e.winding, 2);
    EXPECT_LT(std::abs(e.x[0]), 1e-7);
    EXPECT_LT(std::abs(e.x[1] - 1.0), 1e-7);
  }
  EXPECT_TRUE(r.solutions().empty());  // no regular solution
}

TEST(HomotopySolverTest, MultihomogeneousCountsMatchHandCounts) {
  // Bilinear system in {x}{y}: x y + x + y = 1, x y - x = 2 -> 2-homogeneous Bezout 2.
  const auto x = var(2, 0), y = var(2, 1);
  const PolynomialSystem f({x * y + x + y - 1.0, x * y - x - 2.0});
  EXPECT_EQ(total_degree_count(f), 4);
  EXPECT_EQ(multihomogeneous_count(f, {{0}, {1}}), 2);
  const SolveResult r = solve_linear_product(f, {{0}, {1}});
  EXPECT_EQ(r.endpoints.size(), 2u);
  const auto s = r.solutions();
  ASSERT_EQ(s.size(), 2u);
  for (const auto& sol : s) {
    const Complex X = sol[0], Y = sol[1];
    EXPECT_LT(std::abs(X * Y + X + Y - 1.0), 1e-12);
    EXPECT_LT(std::abs(X * Y - X - 2.0), 1e-12);
  }
}

TEST(HomotopySolverTest, SameAnswerOnOneThreadAndOnMany) {
  const int n = 4;
  const auto u0 = var(n, 0), u1 = var(n, 1), u2 = var(n, 2), u3 = var(n, 3);
  const PolynomialSystem f({u0 * u1 - u2 + 0.3, u1 * u1 + u3 - 1.0, u2 * u3 + u0 - 0.5, u0 * u0 + u1 * u2 - 2.0});
  SolverOptions one, many;
  one.threads = 1;
  many.threads = 4;
  const SolveResult a = solve_total_degree(f, one), b = solve_total_degree(f, many);
  ASSERT_EQ(a.endpoints.size(), b.endpoints.size());
  for (size_t i = 0; i < a.endpoints.size(); ++i) {
    EXPECT_EQ(a.endpoints[i].kind, b.endpoints[i].kind);
    EXPECT_EQ(a.endpoints[i].steps, b.endpoints[i].steps);
    EXPECT_EQ((a.endpoints[i].x - b.endpoints[i].x).norm(), 0.0);  // bitwise identical
  }
}

TEST(HomotopySolverTest, RejectsNonSquareSystems) {
  const auto x = var(2, 0), y = var(2, 1);
  EXPECT_THROW(solve_total_degree(PolynomialSystem({x * y - 1.0})), nbar::Error);
  EXPECT_THROW(solve_linear_product(PolynomialSystem({x - 1.0, y - 1.0}), {{0}}), nbar::Error);
}

// Random dense quadrics in three unknowns have 2^3 = 8 isolated solutions.
RC_GTEST_PROP(HomotopySolverProperty, RandomDenseQuadricsHaveEightSolutions, ()) {
  const auto seed = *rc::gen::inRange<unsigned>(0, 1000000);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  const int n = 3;
  std::vector<Polynomial> eqs;
  for (int i = 0; i < n; ++i) {
    Polynomial p = Polynomial::constant(n, normal(rng));
    for (int a = 0; a < n; ++a) {
      p += normal(rng) * var(n, a);
      for (int b = a; b < n; ++b) p += normal(rng) * (var(n, a) * var(n, b));
    }
    eqs.push_back(p);
  }
  const PolynomialSystem f(eqs);
  SolverOptions options;
  options.seed = seed + 7;
  const SolveResult r = solve_total_degree(f, options);
  RC_ASSERT(r.solutions().size() == 8u);
  for (const auto* e : r.finite_regular()) RC_ASSERT(e->residual < 1e-9 * (1 + e->x.squaredNorm()));
}

}  // namespace
}  // namespace nbar::synthesis

namespace nbar::synthesis {
namespace {

// x^3 = p0, y = p1 x: three solutions, the cube roots of p0.
class CubeRoots final : public ParameterizedSystem {
 public:
  int variables() const override { return 2; }
  int parameters() const override { return 2; }
  void evaluate(const CVector& x, const CVector& p, CVector& f, CMatrix* jx, CMatrix* jp) const override {
    f.resize(2);
    f << x[0] * x[0] * x[0] - p[0], x[1] - p[1] * x[0];
    if (jx) {
      jx->setZero(2, 2);
      (*jx)(0, 0) = 3.0 * x[0] * x[0];
      (*jx)(1, 0) = -p[1];
      (*jx)(1, 1) = 1.0;
    }
    if (jp) {
      jp->setZero(2, 2);
      (*jp)(0, 0) = -1.0;
      (*jp)(1, 1) = -x[0];
    }
  }
};

TEST(ParameterHomotopyTest, MovesEachSolutionToItsPartner) {
  const CubeRoots f;
  CVector from(2), to(2);
  from << Complex(0.3, 1.1), Complex(-0.7, 0.2);
  to << 8.0, 2.0;
  std::vector<CVector> starts;
  for (int k = 0; k < 3; ++k) {
    const Complex r = std::pow(from[0], 1.0 / 3.0) * std::polar(1.0, 2.0 * std::numbers::pi * k / 3.0);
    CVector s(2);
    s << r, from[1] * r;
    starts.push_back(s);
  }
  const SolveResult r = solve_parameter_homotopy(f, from, starts, to);
  const auto s = r.solutions();
  ASSERT_EQ(s.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    const Complex root = 2.0 * std::polar(1.0, 2.0 * std::numbers::pi * k / 3.0);
    EXPECT_TRUE(contains(s, point({root, 2.0 * root}), 1e-12)) << k;
  }
  EXPECT_EQ(r.solutions(true).size(), 1u);  // only x = 2 is real
}

TEST(MonodromyTest, GrowsOneSolutionIntoAllThree) {
  const CubeRoots f;
  CVector p(2), seed(2);
  p << Complex(1.0, 0.5), Complex(0.2, -0.4);
  const Complex r = std::pow(p[0], 1.0 / 3.0);
  seed << r, p[1] * r;
  SolverOptions options;
  options.seed = 3;
  // No target: stop after 12 loops in a row bring nothing new (a random triangle goes round
  // the branch point p0 = 0 only now and then).
  const MonodromyResult m = monodromy_solve(f, p, {seed}, 0, options, 12);
  EXPECT_EQ(m.solutions.size(), 3u);
  EXPECT_TRUE(m.stable);
  for (const auto& s : m.solutions) {
    EXPECT_LT(std::abs(s[0] * s[0] * s[0] - p[0]), 1e-12);
    EXPECT_LT(std::abs(s[1] - p[1] * s[0]), 1e-12);
  }
}

}  // namespace
}  // namespace nbar::synthesis
