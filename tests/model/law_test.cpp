#include "nbar/model/law.hpp"
#include "nbar/model/diagnostics.hpp"
#include "test_constants.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>
#include <string>

namespace nbar {
namespace {

using nbar::test_constants::kPi;

double eval(const std::string& text, double t = 0.0) { return Law::parse(text).value(t); }

// ---------------------------------------------------------------------------------------------
// Parsing and double evaluation

TEST(Law, Precedence) {
  EXPECT_DOUBLE_EQ(eval("1+2*3"), 7.0);
  EXPECT_DOUBLE_EQ(eval("(1+2)*3"), 9.0);
  EXPECT_DOUBLE_EQ(eval("2+3*4^2"), 50.0);
  EXPECT_DOUBLE_EQ(eval("2*3^2"), 18.0);
  EXPECT_DOUBLE_EQ(eval("12/3*2"), 8.0);
  EXPECT_DOUBLE_EQ(eval("1+6/3-1"), 2.0);
}

TEST(Law, BinaryOperatorsAssociateLeftExceptPower) {
  EXPECT_DOUBLE_EQ(eval("10-4-3"), 3.0);
  EXPECT_DOUBLE_EQ(eval("8/4/2"), 1.0);
  EXPECT_DOUBLE_EQ(eval("2^3^2"), 512.0);
  EXPECT_DOUBLE_EQ(eval("(2^3)^2"), 64.0);
  EXPECT_DOUBLE_EQ(eval("2^2^-1"), std::sqrt(2.0));
}

TEST(Law, UnaryMinusBindsLooserThanPower) {
  EXPECT_DOUBLE_EQ(eval("-2^2"), -4.0);
  EXPECT_DOUBLE_EQ(eval("(-2)^2"), 4.0);
  EXPECT_DOUBLE_EQ(eval("-t^2", 3.0), -9.0);
  EXPECT_DOUBLE_EQ(eval("2^-1"), 0.5);
  EXPECT_DOUBLE_EQ(eval("2^-t", 2.0), 0.25);
  EXPECT_DOUBLE_EQ(eval("2*-3"), -6.0);
  EXPECT_DOUBLE_EQ(eval("--2"), 2.0);
  EXPECT_DOUBLE_EQ(eval("+-+2"), -2.0);
  EXPECT_DOUBLE_EQ(eval("-t-t", 1.5), -3.0);
  EXPECT_DOUBLE_EQ(eval("1--t", 1.0), 2.0);
}

TEST(Law, Numbers) {
  EXPECT_DOUBLE_EQ(eval("1e-3"), 1e-3);
  EXPECT_DOUBLE_EQ(eval("1E2"), 100.0);
  EXPECT_DOUBLE_EQ(eval("1.5e+2"), 150.0);
  EXPECT_DOUBLE_EQ(eval(".5"), 0.5);
  EXPECT_DOUBLE_EQ(eval("2."), 2.0);
  EXPECT_DOUBLE_EQ(eval("007"), 7.0);
  EXPECT_DOUBLE_EQ(eval("0.1"), 0.1);
  EXPECT_DOUBLE_EQ(eval("1e3*t", 2.0), 2000.0);
}

TEST(Law, ConstantsAndVariable) {
  EXPECT_DOUBLE_EQ(eval("pi"), kPi);
  EXPECT_DOUBLE_EQ(eval("e"), std::numbers::e);
  EXPECT_DOUBLE_EQ(eval("t", -4.25), -4.25);
  EXPECT_DOUBLE_EQ(eval("2*pi*t", 0.5), kPi);
  // "e" after a number is an exponent only when digits follow.
  EXPECT_DOUBLE_EQ(eval("2*e"), 2.0 * std::numbers::e);
}

TEST(Law, WhitespaceIsIgnored) {
  EXPECT_DOUBLE_EQ(eval("  2 *\tt  + 1 ", 3.0), 7.0);
  EXPECT_DOUBLE_EQ(eval(" sin ( t ) ", 0.5), std::sin(0.5));
  EXPECT_DOUBLE_EQ(eval("- 2 ^ 2"), -4.0);
}

TEST(Law, KeepsTextAndScale) {
  const Law law = Law::parse("30*sin(t)", kPi / 180.0);
  EXPECT_EQ(law.text(), "30*sin(t)");
  EXPECT_DOUBLE_EQ(law.value(kPi / 2), 30.0 * kPi / 180.0);
}

struct FunctionCase {
  const char* name;
  double t;
  double (*f)(double);
  double (*df)(double);
};

// Each function at one point, value and first derivative against the textbook formulas.
TEST(Law, EveryFunction) {
  const FunctionCase cases[] = {
      {"sin", 0.7, [](double x) { return std::sin(x); }, [](double x) { return std::cos(x); }},
      {"cos", 0.7, [](double x) { return std::cos(x); }, [](double x) { return -std::sin(x); }},
      {"tan", 0.7, [](double x) { return std::tan(x); }, [](double x) { return 1.0 / (std::cos(x) * std::cos(x)); }},
      {"exp", 0.7, [](double x) { return std::exp(x); }, [](double x) { return std::exp(x); }},
      {"log", 0.7, [](double x) { return std::log(x); }, [](double x) { return 1.0 / x; }},
      {"sqrt", 0.7, [](double x) { return std::sqrt(x); }, [](double x) { return 0.5 / std::sqrt(x); }},
      {"abs", -0.7, [](double x) { return std::fabs(x); }, [](double x) { return x < 0 ? -1.0 : 1.0; }},
      {"abs", 0.7, [](double x) { return std::fabs(x); }, [](double x) { return x < 0 ? -1.0 : 1.0; }},
      {"asin", 0.7, [](double x) { return std::asin(x); }, [](double x) { return 1.0 / std::sqrt(1 - x * x); }},
      {"acos", 0.7, [](double x) { return std::acos(x); }, [](double x) { return -1.0 / std::sqrt(1 - x * x); }},
      {"atan", 0.7, [](double x) { return std::atan(x); }, [](double x) { return 1.0 / (1 + x * x); }},
      {"sinh", 0.7, [](double x) { return std::sinh(x); }, [](double x) { return std::cosh(x); }},
      {"cosh", 0.7, [](double x) { return std::cosh(x); }, [](double x) { return std::sinh(x); }},
      {"tanh", 0.7, [](double x) { return std::tanh(x); },
       [](double x) { return 1.0 / (std::cosh(x) * std::cosh(x)); }},
  };
  for (const FunctionCase& c : cases) {
    const Law law = Law::parse(std::string(c.name) + "(t)");
    EXPECT_DOUBLE_EQ(law.value(c.t), c.f(c.t)) << c.name;
    const Series s = law.series(c.t, 2);
    EXPECT_DOUBLE_EQ(s[0], c.f(c.t)) << c.name;
    EXPECT_NEAR(s[1], c.df(c.t), 1e-14) << c.name;
    // Chain rule through the parser: f(3t) has derivative 3 f'(3t).
    const Law scaled = Law::parse(std::string(c.name) + "(3*t)");
    EXPECT_NEAR(scaled.series(c.t / 3.0, 2)[1], 3.0 * c.df(c.t), 1e-13) << c.name;
  }
}

// ---------------------------------------------------------------------------------------------
// Series evaluation

TEST(Law, SeriesOfSinusoidHasClosedFormDerivatives) {
  // d^k/dt^k 30 sin(2 pi t) = 30 (2 pi)^k sin(2 pi t + k pi / 2), in degrees -> radians.
  const double scale = kPi / 180.0;
  const Law law = Law::parse("30*sin(2*pi*t)", scale);
  for (double t0 : {0.0, 0.1, 0.37, 1.25}) {
    const Series s = law.series(t0, Series::kCapacity);
    ASSERT_EQ(s.terms(), Series::kCapacity);
    for (int k = 0; k < Series::kCapacity; ++k) {
      const double expected = scale * 30.0 * std::pow(2.0 * kPi, k) * std::sin(2.0 * kPi * t0 + k * kPi / 2.0);
      EXPECT_NEAR(s.derivative(k), expected, 1e-12 * scale * 30.0 * std::pow(2.0 * kPi, k)) << t0 << " " << k;
    }
  }
}

TEST(Law, SeriesOfPolynomialIsExact) {
  // (t - 1)^2 at t = 0.5 uses the constant-exponent path, defined for a negative base.
  const Series a = Law::parse("(t-1)^2").series(0.5, 4);
  EXPECT_DOUBLE_EQ(a[0], 0.25);
  EXPECT_DOUBLE_EQ(a[1], -1.0);
  EXPECT_DOUBLE_EQ(a[2], 1.0);
  EXPECT_DOUBLE_EQ(a[3], 0.0);
  const Series b = Law::parse("(t-1)^3").series(0.0, 5);
  const double expected[] = {-1.0, 3.0, -3.0, 1.0, 0.0};
  for (int k = 0; k < 5; ++k) EXPECT_DOUBLE_EQ(b[k], expected[k]) << k;
  // The exponent is constant if it has no t, however it is written.
  EXPECT_DOUBLE_EQ(Law::parse("(t-3)^(1+2*1)").series(1.0, 2)[1], 3.0 * 4.0);
  EXPECT_DOUBLE_EQ(Law::parse("(t-3)^(4/2)").value(1.0), 4.0);
}

TEST(Law, ScaleMultipliesEveryCoefficient) {
  const Series s = Law::parse("t^2", 0.01).series(3.0, 3);
  EXPECT_DOUBLE_EQ(s[0], 0.09);
  EXPECT_DOUBLE_EQ(s[1], 0.06);
  EXPECT_DOUBLE_EQ(s[2], 0.01);
}

TEST(Law, ConstantLawHasZeroDerivatives) {
  const Series s = Law::parse("2*pi + sin(1)").series(4.0, 5);
  EXPECT_DOUBLE_EQ(s[0], 2.0 * kPi + std::sin(1.0));
  for (int k = 1; k < 5; ++k) EXPECT_EQ(s[k], 0.0);
}

TEST(Law, VariableExponent) {
  // d/dt t^t = t^t (log t + 1); d/dt 2^t = log 2 * 2^t.
  const Series s = Law::parse("t^t").series(1.5, 2);
  EXPECT_NEAR(s[0], std::pow(1.5, 1.5), 1e-15);
  EXPECT_NEAR(s[1], std::pow(1.5, 1.5) * (std::log(1.5) + 1.0), 1e-14);
  const Series p = Law::parse("2^t").series(3.0, 3);
  EXPECT_NEAR(p[1], std::log(2.0) * 8.0, 1e-14);
  EXPECT_NEAR(p.derivative(2), std::log(2.0) * std::log(2.0) * 8.0, 1e-13);
}

TEST(Law, AbsFollowsTheSignAwayFromZero) {
  const Law law = Law::parse("abs(t-1)");
  const Series right = law.series(2.0, 3);
  EXPECT_DOUBLE_EQ(right[0], 1.0);
  EXPECT_DOUBLE_EQ(right[1], 1.0);
  const Series left = law.series(0.0, 3);
  EXPECT_DOUBLE_EQ(left[0], 1.0);
  EXPECT_DOUBLE_EQ(left[1], -1.0);
  EXPECT_DOUBLE_EQ(left[2], 0.0);
}

TEST(Law, AbsAtAZeroCrossingThrows) {
  const Law law = Law::parse("abs(t)");
  EXPECT_DOUBLE_EQ(law.value(0.0), 0.0);  // the value itself is fine
  EXPECT_DOUBLE_EQ(law.series(0.0, 1)[0], 0.0);
  EXPECT_THROW(law.series(0.0, 2), Error);
  EXPECT_THROW(Law::parse("abs(sin(t))").series(0.0, 3), Error);
  try {
    law.series(0.0, 3);
    FAIL() << "expected a domain_error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("abs(t)"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("not differentiable"), std::string::npos) << e.what();
  }
}

TEST(Law, AbsOfAnEvenZeroIsSmooth) {
  // |(t-1)^2| = (t-1)^2 and |-(t-1)^2| = (t-1)^2 even at t = 1.
  for (const char* text : {"abs((t-1)^2)", "abs(-(t-1)^2)"}) {
    const Series s = Law::parse(text).series(1.0, 4);
    EXPECT_DOUBLE_EQ(s[0], 0.0) << text;
    EXPECT_DOUBLE_EQ(s[1], 0.0) << text;
    EXPECT_DOUBLE_EQ(s[2], 1.0) << text;
    EXPECT_DOUBLE_EQ(s[3], 0.0) << text;
  }
  // |t^3| at 0 is twice differentiable, not three times.
  EXPECT_DOUBLE_EQ(Law::parse("abs(t^3)").series(0.0, 3)[2], 0.0);
  EXPECT_THROW(Law::parse("abs(t^3)").series(0.0, 4), Error);
}

TEST(Law, SeriesAndValueAgree) {
  for (const char* text : {"t", "3*t^2-t+1", "sin(t)*exp(-t/2)", "atan(t)/(1+t^2)", "sqrt(1+t^2)^3", "cosh(t)-sinh(t)",
                           "2^t*t^-2", "tanh(t)*acos(t/4)", "log(2+cos(3*t))"}) {
    const Law law = Law::parse(text, 2.5);
    for (double t : {-1.3, 0.2, 1.7}) {
      for (int terms = 1; terms <= Series::kCapacity; ++terms) {
        const Series s = law.series(t, terms);
        ASSERT_EQ(s.terms(), terms);
        EXPECT_NEAR(s[0], law.value(t), 1e-14 * std::max(1.0, std::abs(law.value(t)))) << text << " at " << t;
      }
    }
  }
}

TEST(Law, RejectsAnInvalidNumberOfTerms) {
  const Law law = Law::parse("t");
  EXPECT_THROW(law.series(0.0, 0), nbar::Error);
  EXPECT_THROW(law.series(0.0, Series::kCapacity + 1), nbar::Error);
}

// ---------------------------------------------------------------------------------------------
// Domain errors throw instead of returning NaN or infinity

std::string domain_message(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no exception)";
}

TEST(Law, DomainErrorsThrow) {
  const Law log_law = Law::parse("log(t)");
  EXPECT_EQ(domain_message([&] { log_law.value(0.0); }), "law 'log(t)' is undefined at t = 0");
  EXPECT_EQ(domain_message([&] { log_law.series(0.0, 3); }), "law 'log(t)' is undefined at t = 0");
  EXPECT_EQ(domain_message([&] { log_law.value(-2.5); }), "law 'log(t)' is undefined at t = -2.5");
  EXPECT_THROW(Law::parse("1/t").value(0.0), Error);
  EXPECT_THROW(Law::parse("1/t").series(0.0, 2), Error);
  EXPECT_THROW(Law::parse("asin(t)").value(1.5), Error);
  EXPECT_THROW(Law::parse("acos(t)").series(-1.5, 1), Error);
  EXPECT_THROW(Law::parse("(t-2)^0.5").value(1.0), Error);
  EXPECT_THROW(Law::parse("(t-2)^0.5").series(1.0, 2), Error);
  EXPECT_THROW(Law::parse("exp(t)").value(1000.0), Error);
  // A constant subexpression outside its domain is caught at evaluation, not parse.
  const Law constant = Law::parse("t + log(-1)");
  EXPECT_THROW(constant.value(1.0), Error);
}

TEST(Law, InfiniteDerivativeThrowsNamingTheOrder) {
  const Law law = Law::parse("sqrt(t)");
  EXPECT_DOUBLE_EQ(law.value(0.0), 0.0);
  EXPECT_DOUBLE_EQ(law.series(0.0, 1)[0], 0.0);
  const std::string message = domain_message([&] { law.series(0.0, 2); });
  EXPECT_NE(message.find("'sqrt(t)'"), std::string::npos) << message;
  EXPECT_NE(message.find("1st derivative"), std::string::npos) << message;
  EXPECT_NE(message.find("t = 0"), std::string::npos) << message;
  // (t-1)^3 is a polynomial, but (t-1)^-1 has a pole at 1.
  EXPECT_NO_THROW(Law::parse("(t-1)^3").series(1.0, 5));
  EXPECT_THROW(Law::parse("(t-1)^-1").series(1.0, 1), Error);
}

// ---------------------------------------------------------------------------------------------
// Syntax errors

void expect_syntax_error(const std::string& text, int column, const std::string& message) {
  try {
    Law::parse(text);
    ADD_FAILURE() << "'" << text << "' parsed";
  } catch (const LawSyntaxError& e) {
    EXPECT_EQ(e.column(), column) << "'" << text << "': " << e.what();
    EXPECT_NE(std::string(e.what()).find(message), std::string::npos)
        << "'" << text << "': got \"" << e.what() << "\", expected it to contain \"" << message << '"';
  }
}

TEST(LawSyntax, EmptyLaw) {
  expect_syntax_error("", 0, "empty law");
  expect_syntax_error("   ", 0, "empty law");
}

TEST(LawSyntax, UnknownNames) {
  expect_syntax_error("x", 0, "unknown name 'x' (the variable is t)");
  expect_syntax_error("2*time", 2, "unknown name 'time' (the variable is t)");
  expect_syntax_error("T+1", 0, "unknown name 'T'");
  expect_syntax_error("1 + foo(t)", 4, "unknown function 'foo'");
  expect_syntax_error("ln(t)", 0, "unknown function 'ln'");
}

TEST(LawSyntax, MissingClosingParenthesis) {
  expect_syntax_error("sin(t", 5, "expected ')'");
  expect_syntax_error("(1+2", 4, "expected ')'");
  expect_syntax_error("(1+2 3)", 5, "expected ')'");
  expect_syntax_error("cos(t t)", 6, "expected ')'");
}

TEST(LawSyntax, UnexpectedEnd) {
  expect_syntax_error("1+", 2, "unexpected end of expression");
  expect_syntax_error("2*(", 3, "unexpected end of expression");
  expect_syntax_error("2^", 2, "unexpected end of expression");
  expect_syntax_error("-", 1, "unexpected end of expression");
  expect_syntax_error("sin(", 4, "unexpected end of expression");
}

TEST(LawSyntax, FunctionWithoutParentheses) {
  expect_syntax_error("sin", 3, "expected '(' after 'sin'");
  expect_syntax_error("2*sin t", 6, "expected '(' after 'sin'");
}

TEST(LawSyntax, UnexpectedTokens) {
  expect_syntax_error("1+*2", 2, "unexpected '*'");
  expect_syntax_error("()", 1, "unexpected ')'");
  expect_syntax_error("1 # 2", 2, "unexpected '#'");
  expect_syntax_error("1)", 1, "unmatched ')'");
  expect_syntax_error("2..3", 2, "unexpected '.'");
  expect_syntax_error("t^^2", 2, "unexpected '^'");
}

TEST(LawSyntax, NoImplicitMultiplication) {
  expect_syntax_error("2t", 1, "unexpected 't' (use '*' to multiply)");
  expect_syntax_error("2 pi", 2, "unexpected 'pi'");
  expect_syntax_error("t(2)", 1, "unexpected '('");
  expect_syntax_error("(t)(t)", 3, "unexpected '('");
  expect_syntax_error("2e", 1, "unexpected 'e'");
}

TEST(LawSyntax, BadNumbers) {
  expect_syntax_error(".", 0, "malformed number");
  expect_syntax_error("1+.e3", 2, "malformed number");
  expect_syntax_error("1e999", 0, "number out of range");
}

TEST(LawSyntax, NestingIsBounded) {
  const std::string ok = std::string(50, '(') + "t" + std::string(50, ')');
  EXPECT_DOUBLE_EQ(Law::parse(ok).value(2.0), 2.0);
  const std::string deep = std::string(100000, '(') + "t" + std::string(100000, ')');
  EXPECT_THROW(Law::parse(deep), LawSyntaxError);
  EXPECT_THROW(Law::parse(std::string(100000, '-') + "t"), LawSyntaxError);
}

// A synthesis task's function is a law in x: its messages name x, never the t of driver laws.
TEST(LawSyntax, AnotherVariableName) {
  const Law f = Law::parse("log10(x) + x^2", 1.0, "x");
  EXPECT_NEAR(f.value(100.0), 2.0 + 10000.0, 1e-12);
  // d/dx log10(x) = 1/(x ln 10); d/dx x^2 = 2x; at x = 1: 0.4342944819032518 + 2.
  EXPECT_NEAR(f.series(1.0, 2)[1], 1.0 / std::numbers::ln10 + 2.0, 1e-15);
  try {
    Law::parse("x x", 1.0, "x");
    ADD_FAILURE() << "'x x' parsed";
  } catch (const LawSyntaxError& e) {
    EXPECT_EQ(e.column(), 2);
    EXPECT_STREQ(e.what(), "unexpected 'x' (use '*' to multiply)");
  }
  try {
    Law::parse("sin(t)", 1.0, "x");
    ADD_FAILURE() << "'sin(t)' parsed as a law in x";
  } catch (const LawSyntaxError& e) {
    EXPECT_EQ(e.column(), 4);
    EXPECT_STREQ(e.what(), "unknown name 't' (the variable is x)");
  }
  try {
    (void)Law::parse("log(x)", 1.0, "x").value(0.0);
    ADD_FAILURE() << "log(0) had a value";
  } catch (const Error& e) {
    EXPECT_EQ(e.message(), "law 'log(x)' is undefined at x = 0");
  }
}

// Issue 16, item 13: 1000 nested log10( end in the depth limit, the scan staying linear (the
// test has no time limit of its own: a quadratic scan would show in Fuzz.Regression's).
TEST(LawSyntax, NestedFunctionsAreBounded) {
  std::string nested;
  for (int i = 0; i < 1000; ++i) nested += "log10(";
  nested += "x" + std::string(1000, ')');
  EXPECT_THROW(Law::parse(nested, 1.0, "x"), LawSyntaxError);
}

// ---------------------------------------------------------------------------------------------
// Random laws: series derivatives against central differences of the double evaluation

// A random expression whose value and derivatives stay moderate for |t| <= 1.5, so that the
// finite differences are accurate.
std::string random_law(int depth) {
  if (depth == 0 || *rc::gen::inRange(0, 4) == 0) {
    switch (*rc::gen::inRange(0, 4)) {
      case 0: return "t";
      case 1: return "pi/4";
      case 2: return std::to_string(*rc::gen::inRange(1, 20) / 10.0);
      default: return "(0.5*t-0.2)";
    }
  }
  const std::string a = random_law(depth - 1);
  switch (*rc::gen::inRange(0, 18)) {
    case 0: return a + "+" + random_law(depth - 1);
    case 1: return a + "-" + random_law(depth - 1);
    case 2: return "(" + a + ")*(" + random_law(depth - 1) + ")";
    case 3: return "(" + a + ")/(2+cos(" + random_law(depth - 1) + "))";
    case 4: return "sin(" + a + ")";
    case 5: return "cos(" + a + ")";
    case 6: return "atan(" + a + ")";
    case 7: return "exp(sin(" + a + "))";
    case 8: return "sqrt(1+(" + a + ")^2)";
    case 9: return "log(2+sin(" + a + "))";
    case 10: return "tanh(" + a + ")";
    case 11: return "asin(sin(" + a + ")/2)";
    case 12: return "acos(cos(" + a + ")/3)";
    case 13: return "((" + a + ")/2)^3";
    case 14: return "(2+sin(" + a + "))^(cos(" + random_law(depth - 1) + "))";
    case 15: return "-(" + a + ")";
    case 16: return "tan(atan(" + a + ")/2)";
    default: return "sinh(sin(" + a + "))*cosh(cos(" + a + "))";
  }
}

RC_GTEST_PROP(LawProperty, SeriesDerivativesMatchFiniteDifferences, ()) {
  const std::string text = random_law(3);
  const Law law = Law::parse(text);
  const double t = *rc::gen::inRange(-150, 151) / 100.0;
  RC_LOG() << "law " << text << " at t = " << t << '\n';
  const auto f = [&](double x) { return law.value(x); };
  const Series s = law.series(t, 4);
  RC_ASSERT(std::abs(s[0] - f(t)) <= 1e-13 * (1.0 + std::abs(f(t))));

  // Fourth-order central stencils, each extrapolated (Richardson) from steps h and h/2 to
  // sixth order, which keeps the truncation error small even for the fast-varying laws the
  // generator can build; h balances truncation against rounding (eps / h^k).
  const auto first = [&](double h) { return (-f(t + 2 * h) + 8 * f(t + h) - 8 * f(t - h) + f(t - 2 * h)) / (12 * h); };
  const auto second = [&](double h) {
    return (-f(t + 2 * h) + 16 * f(t + h) - 30 * f(t) + 16 * f(t - h) - f(t - 2 * h)) / (12 * h * h);
  };
  const auto third = [&](double h) {
    return (-f(t + 3 * h) + 8 * f(t + 2 * h) - 13 * f(t + h) + 13 * f(t - h) - 8 * f(t - 2 * h) + f(t - 3 * h)) /
           (8 * h * h * h);
  };
  const auto richardson = [](const auto& d, double h) { return (16 * d(h / 2) - d(h)) / 15; };
  const double d1 = richardson(first, 2e-3);
  const double d2 = richardson(second, 4e-3);
  const double d3 = richardson(third, 1e-2);
  const double magnitude =
      1.0 + std::abs(s[0]) + std::abs(s.derivative(1)) + std::abs(s.derivative(2)) + std::abs(s.derivative(3));
  RC_ASSERT(std::abs(s.derivative(1) - d1) <= 1e-9 * magnitude);
  RC_ASSERT(std::abs(s.derivative(2) - d2) <= 1e-8 * magnitude);
  RC_ASSERT(std::abs(s.derivative(3) - d3) <= 1e-6 * magnitude);
}

}  // namespace
}  // namespace nbar
