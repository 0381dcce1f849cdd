// Private to the explanation: small expression trees for the equations it writes (sums with
// numeric coefficients, products, squares, sin and cos), printed as plain text or LaTeX, and the
// way it prints numbers.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace nbar::explain_detail {

struct Ex;
using E = std::shared_ptr<const Ex>;

struct Ex {
  enum class Kind { Num, Sym, Sum, Prod, Square, Sin, Cos } kind = Kind::Num;
  double value = 0.0;                       // Num; Sum: the constant term
  std::string text, latex;                  // Sym
  std::vector<std::pair<double, E>> terms;  // Sum: coefficient * term (none of them a Num)
  E a, b;                                   // Prod a*b; Square a^2; Sin, Cos of a
};

E num(double v);
E sym(std::string text, std::string latex);
// Folds numbers into one constant, drops zero coefficients, merges a one-term sum's coefficient.
E sum(const std::vector<std::pair<double, E>>& terms);
E mul(const E& a, const E& b);
E scale(const E& e, double c);
E sq(const E& e);
E call(bool sine, const E& arg);
bool is_zero(const E& e);

std::string text(const E& e);
std::string latex(const E& e);

// Names as symbols: plain text keeps letters, digits and '_' (others become '_'); LaTeX escapes
// what it must and sets multi-letter names upright.
std::string plain_name(const std::string& name);
// Text set in LaTeX: _ # % & $ { } escaped, \ ^ ~ (which have no text form) as a dash.
std::string tex_escape(const std::string& s);
std::string latex_name(const std::string& name);

// Six significant digits, no "-0", no exponent for ordinary magnitudes.
std::string number(double v, int digits = 6);
// The same in LaTeX: 1.5 \times 10^{-7}.
std::string latex_number(double v, int digits = 6);
// v, or 0 when |v| <= tolerance (rounding noise).
inline double clean(double v, double tolerance) { return v <= tolerance && v >= -tolerance ? 0.0 : v; }

}  // namespace nbar::explain_detail
