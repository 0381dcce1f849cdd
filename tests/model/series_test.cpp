#include "nbar/model/series.hpp"
#include "test_constants.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <complex>
#include <cstring>
#include <functional>
#include <numbers>
#include <ostream>
#include <string>
#include <vector>

namespace nbar {
namespace {

using Complex = std::complex<double>;
using nbar::test_constants::kPi;
constexpr int kMax = Series::kCapacity;

double factorial(int k) {
  double f = 1.0;
  for (int i = 2; i <= k; ++i) f *= i;
  return f;
}

Series make(std::initializer_list<double> coefficients) {
  Series s(static_cast<int>(coefficients.size()));
  int k = 0;
  for (double c : coefficients) s[k++] = c;
  return s;
}

// Taylor coefficients of an analytic f at 0 from Cauchy's integral formula, sampled on a circle
// of radius r: c_k = mean_j f(r w^j) w^(-jk) / r^k. Independent of every recurrence under test
// (it only needs std::complex), and exact to rounding when f is analytic on a disc of radius
// well above r. `bound` receives max |f| on the circle, which sets the rounding error.
std::vector<double> cauchy(const std::function<Complex(Complex)>& f, int n, double& bound, double r = 0.25) {
  constexpr int kSamples = 128;
  std::vector<Complex> values(kSamples);
  bound = 0.0;
  for (int j = 0; j < kSamples; ++j) {
    values[j] = f(std::polar(r, 2.0 * kPi * j / kSamples));
    bound = std::max(bound, std::abs(values[j]));
  }
  std::vector<double> c(n);
  for (int k = 0; k < n; ++k) {
    Complex sum = 0.0;
    for (int j = 0; j < kSamples; ++j) sum += values[j] * std::polar(1.0, -2.0 * kPi * j * k / kSamples);
    c[k] = sum.real() / kSamples / std::pow(r, k);
  }
  return c;
}

// Compares every coefficient of `s` with the Cauchy reference of `f`.
void expect_matches_cauchy(const Series& s, const std::function<Complex(Complex)>& f, const std::string& what) {
  constexpr double r = 0.25;
  double bound = 0.0;
  const auto ref = cauchy(f, s.terms(), bound, r);
  for (int k = 0; k < s.terms(); ++k) {
    const double tolerance = 1e-12 * std::max(bound, 1.0) / std::pow(r, k) + 1e-13 * std::abs(ref[k]);
    EXPECT_NEAR(s[k], ref[k], tolerance) << what << ", coefficient " << k;
  }
}

void expect_series_near(const Series& a, const Series& b, double tolerance, const std::string& what = "") {
  ASSERT_EQ(a.terms(), b.terms()) << what;
  for (int k = 0; k < a.terms(); ++k) {
    EXPECT_NEAR(a[k], b[k], tolerance * std::max(1.0, std::abs(b[k]))) << what << ", coefficient " << k;
  }
}

// A generic inner argument, so that the chain rule is exercised at every order and not only
// the function at a shifted point.
Series inner(double x0) { return make({x0, 0.5, -0.3, 0.2, 0.1, -0.05, 0.03, -0.02}); }
Complex inner(double x0, Complex s) {
  const double c[] = {x0, 0.5, -0.3, 0.2, 0.1, -0.05, 0.03, -0.02};
  Complex v = 0.0;
  for (int k = kMax - 1; k >= 0; --k) v = v * s + c[k];
  return v;
}

// ---------------------------------------------------------------------------------------------
// Basic properties

TEST(Series, DerivativeIsFactorialTimesCoefficient) {
  const Series s = make({1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0});
  EXPECT_DOUBLE_EQ(s.derivative(0), 1.0);
  EXPECT_DOUBLE_EQ(s.derivative(1), 2.0);
  EXPECT_DOUBLE_EQ(s.derivative(2), 6.0);
  EXPECT_DOUBLE_EQ(s.derivative(3), 24.0);
  EXPECT_DOUBLE_EQ(s.derivative(7), 8.0 * 5040.0);
}

TEST(Series, VariableHasUnitSlope) {
  const Series v = Series::variable(4, 2.5);
  EXPECT_EQ(v.terms(), 4);
  EXPECT_EQ(v[0], 2.5);
  EXPECT_EQ(v[1], 1.0);
  EXPECT_EQ(v[2], 0.0);
  EXPECT_EQ(Series::variable(1, 3.0).terms(), 1);
}

TEST(Series, GeometricSeriesFromDivision) {
  // 1/(1-s) = 1 + s + s^2 + ...
  const Series g = 1.0 / (1.0 - Series::variable(kMax, 0.0));
  for (int k = 0; k < kMax; ++k) EXPECT_DOUBLE_EQ(g[k], 1.0) << k;
  // 1/(2+s) = sum (-1)^k s^k / 2^(k+1)
  const Series h = 1.0 / Series::variable(kMax, 2.0);
  for (int k = 0; k < kMax; ++k) EXPECT_DOUBLE_EQ(h[k], (k % 2 ? -1.0 : 1.0) / std::pow(2.0, k + 1)) << k;
}

TEST(Series, DivisionMatchesCauchy) {
  const Series a = inner(0.7);
  const Series b = exp(inner(0.2));
  expect_matches_cauchy(
      a / b, [](Complex s) { return inner(0.7, s) / std::exp(inner(0.2, s)); }, "a/b");
  expect_matches_cauchy(
      3.0 / b, [](Complex s) { return 3.0 / std::exp(inner(0.2, s)); }, "3/b");
}

TEST(Series, BinaryOperationsKeepTheShorterLength) {
  const Series a = Series::variable(3, 1.0);
  const Series b = Series::variable(6, 2.0);
  EXPECT_EQ((a * b).terms(), 3);
  EXPECT_EQ((a / b).terms(), 3);
  EXPECT_EQ((b / a).terms(), 3);
  EXPECT_EQ(atan2(a, b).terms(), 3);
  EXPECT_EQ(atan2(b, a).terms(), 3);
  EXPECT_EQ(pow(b, a).terms(), 3);
  EXPECT_EQ(sin(b).terms(), 6);
  EXPECT_EQ((1.0 / b).terms(), 6);
}

TEST(Series, TruncationDoesNotChangeLowerCoefficients) {
  // Coefficient k depends only on coefficients 0..k of the operand.
  for (int n = 1; n <= kMax; ++n) {
    Series x(n);
    for (int k = 0; k < n; ++k) x[k] = inner(0.4)[k];
    const Series full = tan(exp(inner(0.4)) / 3.0);
    const Series part = tan(exp(x) / 3.0);
    ASSERT_EQ(part.terms(), n);
    for (int k = 0; k < n; ++k) EXPECT_DOUBLE_EQ(part[k], full[k]) << "n=" << n << " k=" << k;
  }
}

// ---------------------------------------------------------------------------------------------
// Closed-form derivatives of functions of the plain variable

// A sweep's drivers carry 3 or 4 terms, whose sine and cosine are unrolled for those sizes: every
// coefficient is the one the longer series have, bit for bit (a truncation changes no lower
// coefficient, and the recurrence is the same).
TEST(Series, SinCosOfThreeAndFourTermsAreTheLongerSeriesHeads) {
  const Series x = make({0.7, -1.3, 0.45, 2.25, -0.6, 0.125, 3.0});
  Series s_long, c_long;
  sincos(x, s_long, c_long);
  for (int terms = 1; terms < kMax; ++terms) {
    Series s, c;
    sincos(x.head(terms), s, c);
    ASSERT_EQ(s.terms(), terms);
    for (int k = 0; k < terms; ++k) {
      EXPECT_EQ(std::memcmp(&s[k], &s_long[k], sizeof(double)), 0) << terms << " terms, sin coefficient " << k;
      EXPECT_EQ(std::memcmp(&c[k], &c_long[k], sizeof(double)), 0) << terms << " terms, cos coefficient " << k;
    }
    for (int k = terms; k < kMax; ++k) EXPECT_EQ(s[k], 0.0) << terms << " terms, sin beyond them";
  }
}

TEST(Series, SinCosOfScaledVariable) {
  // d^k/dt^k sin(2t) = 2^k sin(2t + k pi/2).
  for (double t0 : {0.0, 0.3, -1.7, 4.0}) {
    const Series x = 2.0 * Series::variable(kMax, t0);
    const Series s = sin(x);
    const Series c = cos(x);
    for (int k = 0; k < kMax; ++k) {
      const double scale = std::pow(2.0, k);
      EXPECT_NEAR(s.derivative(k), scale * std::sin(2.0 * t0 + k * kPi / 2), 1e-12 * scale) << t0 << " " << k;
      EXPECT_NEAR(c.derivative(k), scale * std::cos(2.0 * t0 + k * kPi / 2), 1e-12 * scale) << t0 << " " << k;
    }
  }
}

TEST(Series, SinCosOutputsAgreeWithSeparateCalls) {
  const Series x = inner(1.1);
  Series s;
  Series c;
  sincos(x, s, c);
  expect_series_near(s, sin(x), 0.0);
  expect_series_near(c, cos(x), 0.0);
}

TEST(Series, ExpOfScaledVariable) {
  for (double t0 : {0.0, 0.5, -2.0}) {
    const Series e = exp(3.0 * Series::variable(kMax, t0));
    for (int k = 0; k < kMax; ++k) {
      const double expected = std::pow(3.0, k) * std::exp(3.0 * t0);
      EXPECT_NEAR(e.derivative(k), expected, 1e-13 * expected) << k;
    }
  }
}

TEST(Series, LogOfVariable) {
  // d^k/dt^k log t = (-1)^(k-1) (k-1)! / t^k.
  for (double t0 : {0.25, 1.0, 7.0}) {
    const Series l = log(Series::variable(kMax, t0));
    EXPECT_DOUBLE_EQ(l[0], std::log(t0));
    for (int k = 1; k < kMax; ++k) {
      const double expected = (k % 2 ? 1.0 : -1.0) * factorial(k - 1) / std::pow(t0, k);
      EXPECT_NEAR(l.derivative(k), expected, 1e-12 * std::abs(expected)) << t0 << " " << k;
    }
  }
}

// Falling factorial p (p-1) ... (p-k+1).
double falling(double p, int k) {
  double f = 1.0;
  for (int i = 0; i < k; ++i) f *= p - i;
  return f;
}

TEST(Series, SqrtAndPowOfVariable) {
  for (double t0 : {0.3, 2.0, 9.0}) {
    const Series t = Series::variable(kMax, t0);
    const Series r = sqrt(t);
    for (double p : {0.5, -1.5, 2.7, 1.0 / 3.0}) {
      const Series y = pow(t, p);
      for (int k = 0; k < kMax; ++k) {
        const double expected = falling(p, k) * std::pow(t0, p - k);
        EXPECT_NEAR(y.derivative(k), expected, 1e-12 * std::max(1.0, std::abs(expected))) << t0 << " " << p << " " << k;
        if (p == 0.5) {
          EXPECT_NEAR(r.derivative(k), expected, 1e-12 * std::max(1.0, std::abs(expected)));
        }
      }
    }
  }
}

TEST(Series, IntegerPowersOfNegativeAndZeroBase) {
  // (s - 1)^2 = 1 - 2s + s^2: a general pow would take log(-1) here.
  expect_series_near(pow(Series::variable(kMax, -1.0), 2.0), make({1, -2, 1, 0, 0, 0, 0, 0}), 0.0);
  // (s - 2)^3 = -8 + 12 s - 6 s^2 + s^3
  expect_series_near(pow(Series::variable(5, -2.0), 3.0), make({-8, 12, -6, 1, 0}), 0.0);
  // s^3 at 0
  expect_series_near(pow(Series::variable(5, 0.0), 3.0), make({0, 0, 0, 1, 0}), 0.0);
  // (s - 2)^-1 = -1/2 - s/4 - s^2/8 - ...
  const Series inv = pow(Series::variable(kMax, -2.0), -1.0);
  for (int k = 0; k < kMax; ++k) EXPECT_DOUBLE_EQ(inv[k], -1.0 / std::pow(2.0, k + 1)) << k;
  // (s - 1)^-2 = sum (k+1) s^k
  const Series inv2 = pow(Series::variable(kMax, 1.0) - 2.0, -2.0);
  for (int k = 0; k < kMax; ++k) EXPECT_NEAR(inv2[k], k + 1.0, 1e-13 * (k + 1)) << k;
  // x^0 is 1 even where x vanishes.
  expect_series_near(pow(Series::variable(3, 0.0), 0.0), make({1, 0, 0}), 0.0);
  // Large integer exponent through repeated squaring: (1 + s)^40 has binomial coefficients.
  const Series big = pow(Series::variable(kMax, 1.0), 40.0);
  double binomial = 1.0;
  for (int k = 0; k < kMax; ++k) {
    EXPECT_NEAR(big[k], binomial, 1e-12 * binomial) << k;
    binomial = binomial * (40 - k) / (k + 1);
  }
}

TEST(Series, AtanOfVariable) {
  // atan' = 1/(1+t^2), atan'' = -2t/(1+t^2)^2, atan''' = (6t^2-2)/(1+t^2)^3.
  for (double t0 : {0.0, 0.5, -3.0}) {
    const Series a = atan(Series::variable(4, t0));
    const double q = 1.0 + t0 * t0;
    EXPECT_DOUBLE_EQ(a.derivative(0), std::atan(t0));
    EXPECT_NEAR(a.derivative(1), 1.0 / q, 1e-15);
    EXPECT_NEAR(a.derivative(2), -2.0 * t0 / (q * q), 1e-15);
    EXPECT_NEAR(a.derivative(3), (6.0 * t0 * t0 - 2.0) / (q * q * q), 1e-14);
  }
}

TEST(Series, AtanOfVariableAtZeroIsTheAlternatingOddSeries) {
  const Series a = atan(Series::variable(kMax, 0.0));
  const double expected[] = {0, 1, 0, -1.0 / 3, 0, 1.0 / 5, 0, -1.0 / 7};
  for (int k = 0; k < kMax; ++k) EXPECT_NEAR(a[k], expected[k], 1e-16) << k;
}

TEST(Series, AsinAcosOfVariable) {
  // asin' = 1/sqrt(1-t^2), asin'' = t/(1-t^2)^(3/2); acos = pi/2 - asin.
  for (double t0 : {0.0, 0.6, -0.9}) {
    const Series as = asin(Series::variable(3, t0));
    const Series ac = acos(Series::variable(3, t0));
    const double q = 1.0 - t0 * t0;
    EXPECT_DOUBLE_EQ(as[0], std::asin(t0));
    EXPECT_DOUBLE_EQ(ac[0], std::acos(t0));
    EXPECT_NEAR(as.derivative(1), 1.0 / std::sqrt(q), 1e-14);
    EXPECT_NEAR(as.derivative(2), t0 / std::pow(q, 1.5), 1e-13);
    EXPECT_NEAR(ac.derivative(1), -1.0 / std::sqrt(q), 1e-14);
    EXPECT_NEAR(ac.derivative(2), -t0 / std::pow(q, 1.5), 1e-13);
  }
}

TEST(Series, HyperbolicOfVariable) {
  for (double t0 : {0.0, 0.8, -2.0}) {
    const Series t = Series::variable(kMax, t0);
    const Series sh = sinh(t);
    const Series ch = cosh(t);
    const Series th = tanh(t);
    for (int k = 0; k < kMax; ++k) {
      EXPECT_NEAR(sh.derivative(k), k % 2 ? std::cosh(t0) : std::sinh(t0), 1e-13 * std::cosh(t0)) << k;
      EXPECT_NEAR(ch.derivative(k), k % 2 ? std::sinh(t0) : std::cosh(t0), 1e-13 * std::cosh(t0)) << k;
    }
    // tanh' = 1 - tanh^2, tanh'' = -2 tanh (1 - tanh^2)
    const double y = std::tanh(t0);
    EXPECT_DOUBLE_EQ(th[0], y);
    EXPECT_NEAR(th.derivative(1), 1.0 - y * y, 1e-15);
    EXPECT_NEAR(th.derivative(2), -2.0 * y * (1.0 - y * y), 1e-15);
  }
}

TEST(Series, TanOfVariable) {
  // tan' = 1 + tan^2, tan'' = 2 tan (1 + tan^2), tan''' = (1 + tan^2)(2 + 6 tan^2)
  for (double t0 : {0.0, 0.7, -1.2}) {
    const Series y = tan(Series::variable(4, t0));
    const double v = std::tan(t0);
    const double w = 1.0 + v * v;
    EXPECT_DOUBLE_EQ(y[0], v);
    EXPECT_NEAR(y.derivative(1), w, 1e-13 * w);
    EXPECT_NEAR(y.derivative(2), 2.0 * v * w, 1e-13 * w * w);
    EXPECT_NEAR(y.derivative(3), w * (2.0 + 6.0 * v * v), 1e-13 * w * w * w);
  }
}

// ---------------------------------------------------------------------------------------------
// Every function of a nontrivial argument, against the Cauchy-integral reference

struct UnaryCase {
  const char* name;
  double x0;  // keeps the argument well inside the function's domain of analyticity
  Series (*series)(const Series&);
  Complex (*reference)(Complex);
};

void PrintTo(const UnaryCase& c, std::ostream* os) { *os << c.name << " at x0 = " << c.x0; }

class SeriesFunction : public ::testing::TestWithParam<UnaryCase> {};

TEST_P(SeriesFunction, MatchesCauchyReferenceToAllOrders) {
  const UnaryCase& c = GetParam();
  const double x0 = c.x0;
  expect_matches_cauchy(
      c.series(inner(x0)), [&](Complex s) { return c.reference(inner(x0, s)); }, c.name);
}

Series pow_2_5(const Series& x) { return pow(x, 2.5); }
Series pow_m1_7(const Series& x) { return pow(x, -1.7); }
Series pow_3(const Series& x) { return pow(x, 3.0); }
Series pow_m2(const Series& x) { return pow(x, -2.0); }
Series pow_series(const Series& x) { return pow(x, sin(x)); }
Series reciprocal(const Series& x) { return 1.0 / x; }
Series atan2_of(const Series& x) { return atan2(x, 0.4 - x * x); }
Series atan2_left(const Series& x) { return atan2(x, -1.0 - x * x); }

INSTANTIATE_TEST_SUITE_P(
    All, SeriesFunction,
    ::testing::Values(
        UnaryCase{"sin", 0.9, [](const Series& x) { return sin(x); }, [](Complex z) { return std::sin(z); }},
        UnaryCase{"cos", -2.1, [](const Series& x) { return cos(x); }, [](Complex z) { return std::cos(z); }},
        UnaryCase{"tan", 0.4, [](const Series& x) { return tan(x); }, [](Complex z) { return std::tan(z); }},
        UnaryCase{"exp", 1.3, [](const Series& x) { return exp(x); }, [](Complex z) { return std::exp(z); }},
        UnaryCase{"log", 1.5, [](const Series& x) { return log(x); }, [](Complex z) { return std::log(z); }},
        UnaryCase{"sqrt", 1.2, [](const Series& x) { return sqrt(x); }, [](Complex z) { return std::sqrt(z); }},
        UnaryCase{"pow 2.5", 1.4, pow_2_5, [](Complex z) { return std::pow(z, 2.5); }},
        UnaryCase{"pow -1.7", 1.4, pow_m1_7, [](Complex z) { return std::pow(z, -1.7); }},
        UnaryCase{"pow 3 of negative", -1.4, pow_3, [](Complex z) { return z * z * z; }},
        UnaryCase{"pow -2 of negative", -1.4, pow_m2, [](Complex z) { return 1.0 / (z * z); }},
        UnaryCase{"pow series", 1.6, pow_series, [](Complex z) { return std::exp(std::sin(z) * std::log(z)); }},
        UnaryCase{"reciprocal", -0.8, reciprocal, [](Complex z) { return 1.0 / z; }},
        UnaryCase{"atan", 0.7, [](const Series& x) { return atan(x); }, [](Complex z) { return std::atan(z); }},
        UnaryCase{"asin", 0.3, [](const Series& x) { return asin(x); }, [](Complex z) { return std::asin(z); }},
        UnaryCase{"acos", -0.2, [](const Series& x) { return acos(x); }, [](Complex z) { return std::acos(z); }},
        UnaryCase{"sinh", 0.6, [](const Series& x) { return sinh(x); }, [](Complex z) { return std::sinh(z); }},
        UnaryCase{"cosh", -1.1, [](const Series& x) { return cosh(x); }, [](Complex z) { return std::cosh(z); }},
        UnaryCase{"tanh", 0.4, [](const Series& x) { return tanh(x); }, [](Complex z) { return std::tanh(z); }},
        // atan2(y, x) with x > 0 is atan(y/x) exactly.
        UnaryCase{"atan2 right half", 0.3, atan2_of, [](Complex z) { return std::atan(z / (0.4 - z * z)); }},
        // In the left half plane it differs from atan(y/x) by the constant pi (here y > 0).
        UnaryCase{"atan2 left half", 0.5, atan2_left, [](Complex z) { return std::atan(z / (-1.0 - z * z)) + kPi; }}),
    [](const ::testing::TestParamInfo<UnaryCase>& info) {
      std::string name = info.param.name;
      for (char& ch : name) {
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      }
      return name;
    });

// ---------------------------------------------------------------------------------------------
// Identities to all orders

TEST(Series, PythagoreanIdentities) {
  for (double x0 : {0.0, 0.8, -2.5}) {
    const Series x = inner(x0);
    const Series s = sin(x);
    const Series c = cos(x);
    expect_series_near(s * s + c * c, Series(kMax, 1.0), 1e-14, "sin^2+cos^2");
    const Series sh = sinh(x);
    const Series ch = cosh(x);
    expect_series_near(ch * ch - sh * sh, Series(kMax, 1.0), 1e-13, "cosh^2-sinh^2");
    expect_series_near(tanh(x), sh / ch, 1e-13, "tanh");
  }
}

TEST(Series, Atan2OfSinCosIsTheAngleInEveryQuadrant) {
  for (double t0 : {0.1, 1.5, 2.5, 3.1, -0.4, -1.6, -2.9}) {
    const Series t = Series::variable(kMax, t0);
    expect_series_near(atan2(sin(t), cos(t)), t, 1e-14, "t0=" + std::to_string(t0));
    // Scaling both arguments by a positive function leaves the angle unchanged.
    const Series r = exp(t) + 1.0;
    expect_series_near(atan2(r * sin(t), r * cos(t)), t, 1e-13, "scaled t0=" + std::to_string(t0));
  }
}

TEST(Series, Atan2OnTheNegativeXAxisUsesTheBranchOfStdAtan2) {
  const Series y = Series::variable(3, 0.0);
  const Series x = Series(3, -1.0);
  EXPECT_DOUBLE_EQ(atan2(y, x)[0], kPi);
  EXPECT_DOUBLE_EQ(atan2(-1.0 * Series(3, 0.0), x)[0], std::atan2(-0.0, -1.0));
  // d/dy atan2(y, -1) at y = 0 is -1.
  EXPECT_NEAR(atan2(y, x)[1], -1.0, 1e-15);
}

TEST(Series, InverseFunctionsUndoTheirFunctions) {
  const Series x = inner(0.3);
  expect_series_near(asin(sin(x)), x, 1e-13, "asin(sin)");
  expect_series_near(acos(cos(x)), x, 1e-13, "acos(cos)");
  expect_series_near(atan(tan(x)), x, 1e-13, "atan(tan)");
  expect_series_near(log(exp(x)), x, 1e-13, "log(exp)");
  expect_series_near(sqrt(x * x), x, 1e-13, "sqrt(x^2)");
  expect_series_near(tan(x), sin(x) / cos(x), 1e-13, "tan");
  expect_series_near(pow(exp(x), Series(kMax, 2.0)), exp(2.0 * x), 1e-13, "pow(series)");
}

// ---------------------------------------------------------------------------------------------
// Outside the domain: no exception, non-finite values where the math has none

TEST(Series, DomainViolationsGiveNonFiniteNumbers) {
  const Series zero = Series::variable(3, 0.0);
  EXPECT_TRUE(std::isinf(log(zero)[0]));
  EXPECT_FALSE(std::isfinite(log(zero)[1]));
  EXPECT_EQ(sqrt(zero)[0], 0.0);
  EXPECT_FALSE(std::isfinite(sqrt(zero)[1]));
  EXPECT_TRUE(std::isnan(sqrt(Series::variable(3, -1.0))[0]));
  EXPECT_TRUE(std::isnan(log(Series::variable(3, -1.0))[0]));
  EXPECT_TRUE(std::isnan(asin(Series::variable(3, 2.0))[0]));
  EXPECT_FALSE(std::isfinite(asin(Series::variable(3, 1.0))[1]));
  EXPECT_FALSE(std::isfinite(acos(Series::variable(3, -1.0))[1]));
  EXPECT_FALSE(std::isfinite((1.0 / zero)[0]));
  EXPECT_TRUE(std::isnan(pow(Series::variable(3, -1.0), 0.5)[0]));
  EXPECT_FALSE(std::isfinite(pow(zero, 0.5)[1]));
  EXPECT_FALSE(std::isfinite(pow(zero, -1.0)[0]));
  EXPECT_FALSE(std::isfinite(atan2(zero * 0.0, zero * 0.0)[1]));
}

// ---------------------------------------------------------------------------------------------
// Properties over random series

double uniform(double lo, double hi) {
  const int u = *rc::gen::inRange(0, 1'000'001);
  return lo + (hi - lo) * u / 1e6;
}

// A random series; coefficient 0 in [lo0, hi0], the others in [-spread, spread].
Series random_series(int n, double lo0, double hi0, double spread) {
  Series s(n, uniform(lo0, hi0));
  for (int k = 1; k < n; ++k) s[k] = uniform(-spread, spread);
  return s;
}

bool near(const Series& a, const Series& b, double tolerance) {
  if (a.terms() != b.terms()) return false;
  for (int k = 0; k < a.terms(); ++k) {
    if (!(std::abs(a[k] - b[k]) <= tolerance * std::max(1.0, std::abs(b[k])))) return false;
  }
  return true;
}

RC_GTEST_PROP(SeriesProperty, ProductDividedByFactorIsTheOtherFactor, ()) {
  const int n = *rc::gen::inRange(1, kMax + 1);
  const Series a = random_series(n, -2.0, 2.0, 2.0);
  Series b = random_series(n, 1.0, 2.0, 1.0);
  if (*rc::gen::arbitrary<bool>()) b = -b;
  RC_ASSERT(near((a * b) / b, a, 1e-9));
  RC_ASSERT(near(b * (1.0 / b), Series(n, 1.0), 1e-9));
}

RC_GTEST_PROP(SeriesProperty, ExpAndLogAreInverse, ()) {
  const int n = *rc::gen::inRange(1, kMax + 1);
  const Series x = random_series(n, 0.5, 3.0, 1.0);
  RC_ASSERT(near(exp(log(x)), x, 1e-10));
  RC_ASSERT(near(sqrt(x) * sqrt(x), x, 1e-10));
  const double p = uniform(-3.0, 3.0);
  RC_ASSERT(near(pow(x, p) * pow(x, -p), Series(n, 1.0), 1e-9));
}

RC_GTEST_PROP(SeriesProperty, Atan2RecoversTheAngle, ()) {
  const int n = *rc::gen::inRange(1, kMax + 1);
  const Series angle = random_series(n, -3.0, 3.0, 1.0);
  const Series radius = random_series(n, 0.5, 2.0, 0.3);
  RC_ASSERT(near(atan2(radius * sin(angle), radius * cos(angle)), angle, 1e-10));
}

RC_GTEST_PROP(SeriesProperty, IntegerPowerIsRepeatedMultiplication, ()) {
  const int n = *rc::gen::inRange(1, kMax + 1);
  const Series x = random_series(n, -2.0, 2.0, 1.0);
  const int p = *rc::gen::inRange(0, 7);
  Series expected(n, 1.0);
  for (int i = 0; i < p; ++i) expected = expected * x;
  RC_ASSERT(near(pow(x, static_cast<double>(p)), expected, 1e-12));
}

// Random function of a random degree-7 polynomial argument against the Cauchy reference.
// Arguments stay within 0.5 of x0 on the disc |s| <= 0.5, and each x0 range keeps that disc
// away from the function's singularities, so the reference is accurate.
RC_GTEST_PROP(SeriesProperty, RandomCompositionMatchesCauchyReference, ()) {
  struct Case {
    double lo;
    double hi;
    Series (*series)(const Series&);
    Complex (*reference)(Complex);
  };
  static const Case kCases[] = {
      {-3, 3, [](const Series& x) { return sin(x); }, [](Complex z) { return std::sin(z); }},
      {-3, 3, [](const Series& x) { return cos(x); }, [](Complex z) { return std::cos(z); }},
      {-0.8, 0.8, [](const Series& x) { return tan(x); }, [](Complex z) { return std::tan(z); }},
      {-2, 2, [](const Series& x) { return exp(x); }, [](Complex z) { return std::exp(z); }},
      {1.2, 3, [](const Series& x) { return log(x); }, [](Complex z) { return std::log(z); }},
      {1.2, 3, [](const Series& x) { return sqrt(x); }, [](Complex z) { return std::sqrt(z); }},
      {1.2, 3, [](const Series& x) { return pow(x, -0.7); }, [](Complex z) { return std::pow(z, -0.7); }},
      {-2, 2, [](const Series& x) { return atan(x); }, [](Complex z) { return std::atan(z); }},
      {-0.3, 0.3, [](const Series& x) { return asin(x); }, [](Complex z) { return std::asin(z); }},
      {-0.3, 0.3, [](const Series& x) { return acos(x); }, [](Complex z) { return std::acos(z); }},
      {-2, 2, [](const Series& x) { return sinh(x); }, [](Complex z) { return std::sinh(z); }},
      {-2, 2, [](const Series& x) { return cosh(x); }, [](Complex z) { return std::cosh(z); }},
      {-2, 2, [](const Series& x) { return tanh(x); }, [](Complex z) { return std::tanh(z); }},
      {1.2, 3, [](const Series& x) { return 1.0 / x; }, [](Complex z) { return 1.0 / z; }},
  };
  const Case& c = kCases[*rc::gen::inRange<std::size_t>(0, std::size(kCases))];
  const int n = *rc::gen::inRange(1, kMax + 1);
  const Series x = random_series(n, c.lo, c.hi, 0.5);
  const auto argument = [&](Complex s) {
    Complex v = 0.0;
    for (int k = n - 1; k >= 0; --k) v = v * s + x[k];
    return v;
  };
  double bound = 0.0;
  constexpr double r = 0.25;
  const auto ref = cauchy([&](Complex s) { return c.reference(argument(s)); }, n, bound, r);
  const Series y = c.series(x);
  for (int k = 0; k < n; ++k) {
    RC_ASSERT(std::abs(y[k] - ref[k]) <= 1e-12 * std::max(bound, 1.0) / std::pow(r, k) + 1e-13 * std::abs(ref[k]));
  }
}

}  // namespace
}  // namespace nbar
