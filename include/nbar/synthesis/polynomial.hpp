// Sparse multivariate polynomials with complex coefficients, and square systems of them.
// Built by arithmetic on variables and constants, e.g.
//   auto x = Polynomial::variable(2, 0), y = Polynomial::variable(2, 1);
//   PolynomialSystem f({x * x + y * y - 1.0, x - y});
// They serve start systems, tests and the general solvers; the five-point problem has its own
// evaluator for speed.
#pragma once

#include <Eigen/Core>

#include <complex>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace nbar::synthesis {

using Complex = std::complex<double>;
using CVector = Eigen::VectorXcd;
using CMatrix = Eigen::MatrixXcd;

class Polynomial {
 public:
  using Exponents = std::vector<std::uint16_t>;

  explicit Polynomial(int variables = 0) : variables_(variables) {}
  static Polynomial constant(int variables, Complex value);
  static Polynomial variable(int variables, int index);

  int variables() const { return variables_; }
  int degree() const;                                  // total degree; -1 for the zero polynomial
  int degree_in(const std::vector<int>& group) const;  // degree in a set of variables
  const std::map<Exponents, Complex>& terms() const { return terms_; }
  void add_term(const Exponents& exponents, Complex coefficient);

  Complex evaluate(const CVector& x) const;
  // Value and gradient at x (gradient has one entry per variable).
  Complex evaluate(const CVector& x, Eigen::Ref<Eigen::RowVectorXcd, 0, Eigen::InnerStride<>> gradient) const;

  Polynomial& operator+=(const Polynomial& other);
  Polynomial& operator-=(const Polynomial& other);
  Polynomial& operator*=(Complex factor);
  friend Polynomial operator+(Polynomial a, const Polynomial& b) { return a += b; }
  friend Polynomial operator-(Polynomial a, const Polynomial& b) { return a -= b; }
  friend Polynomial operator*(const Polynomial& a, const Polynomial& b);
  friend Polynomial operator*(Polynomial a, Complex c) { return a *= c; }
  friend Polynomial operator*(Complex c, Polynomial a) { return a *= c; }
  friend Polynomial operator+(Polynomial a, Complex c);
  friend Polynomial operator-(Polynomial a, Complex c) { return a + (-c); }
  friend Polynomial operator-(Polynomial a) { return a *= -1.0; }

 private:
  int variables_;
  std::map<Exponents, Complex> terms_;  // no zero coefficients kept
};

// F: C^n -> C^m; the solvers need m == n.
class PolynomialSystem {
 public:
  PolynomialSystem() = default;
  explicit PolynomialSystem(std::vector<Polynomial> equations);

  int equations() const { return static_cast<int>(equations_.size()); }
  int variables() const { return variables_; }
  const Polynomial& operator[](int i) const { return equations_[i]; }
  const std::vector<Polynomial>& polynomials() const { return equations_; }

  void evaluate(const CVector& x, CVector& f) const;
  void evaluate(const CVector& x, CVector& f, CMatrix& jacobian) const;

 private:
  std::vector<Polynomial> equations_;
  int variables_ = 0;
};

}  // namespace nbar::synthesis
