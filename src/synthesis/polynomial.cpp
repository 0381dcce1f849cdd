#include "nbar/synthesis/polynomial.hpp"

#include <stdexcept>

#include "nbar/model/diagnostics.hpp"

namespace nbar::synthesis {

Polynomial Polynomial::constant(int variables, Complex value) {
  Polynomial p(variables);
  p.add_term(Exponents(variables, 0), value);
  return p;
}

Polynomial Polynomial::variable(int variables, int index) {
  if (index < 0 || index >= variables) throw Error(ErrorKind::BadInput, "Polynomial::variable: index out of range");
  Exponents e(variables, 0);
  e[index] = 1;
  Polynomial p(variables);
  p.add_term(e, 1.0);
  return p;
}

int Polynomial::degree() const {
  int best = -1;
  for (const auto& [e, c] : terms_) {
    int d = 0;
    for (auto k : e) d += k;
    best = std::max(best, d);
  }
  return best;
}

int Polynomial::degree_in(const std::vector<int>& group) const {
  int best = -1;
  for (const auto& [e, c] : terms_) {
    int d = 0;
    for (int v : group) d += e[v];
    best = std::max(best, d);
  }
  return best;
}

void Polynomial::add_term(const Exponents& exponents, Complex coefficient) {
  if (static_cast<int>(exponents.size()) != variables_)
    throw Error(ErrorKind::BadInput, "Polynomial: term has the wrong number of exponents");
  if (coefficient == Complex(0.0)) return;
  auto [it, inserted] = terms_.emplace(exponents, coefficient);
  if (!inserted) {
    it->second += coefficient;
    if (it->second == Complex(0.0)) terms_.erase(it);
  }
}

static Complex monomial(const CVector& x, const Polynomial::Exponents& e) {
  Complex value = 1.0;
  for (size_t v = 0; v < e.size(); ++v)
    for (int k = 0; k < e[v]; ++k) value *= x[static_cast<Eigen::Index>(v)];
  return value;
}

Complex Polynomial::evaluate(const CVector& x) const {
  Complex sum = 0.0;
  for (const auto& [e, c] : terms_) sum += c * monomial(x, e);
  return sum;
}

Complex Polynomial::evaluate(const CVector& x,
                             Eigen::Ref<Eigen::RowVectorXcd, 0, Eigen::InnerStride<>> gradient) const {
  gradient.setZero();
  Complex sum = 0.0;
  Exponents lowered;
  for (const auto& [e, c] : terms_) {
    sum += c * monomial(x, e);
    for (int v = 0; v < variables_; ++v) {
      if (e[v] == 0) continue;
      lowered = e;
      --lowered[v];
      gradient[v] += c * static_cast<double>(e[v]) * monomial(x, lowered);
    }
  }
  return sum;
}

Polynomial& Polynomial::operator+=(const Polynomial& other) {
  if (other.variables_ != variables_) throw Error(ErrorKind::BadInput, "Polynomial: different numbers of variables");
  for (const auto& [e, c] : other.terms_) add_term(e, c);
  return *this;
}

Polynomial& Polynomial::operator-=(const Polynomial& other) {
  if (other.variables_ != variables_) throw Error(ErrorKind::BadInput, "Polynomial: different numbers of variables");
  for (const auto& [e, c] : other.terms_) add_term(e, -c);
  return *this;
}

Polynomial& Polynomial::operator*=(Complex factor) {
  if (factor == Complex(0.0)) {
    terms_.clear();
    return *this;
  }
  for (auto& [e, c] : terms_) c *= factor;
  return *this;
}

Polynomial operator*(const Polynomial& a, const Polynomial& b) {
  if (a.variables_ != b.variables_) throw Error(ErrorKind::BadInput, "Polynomial: different numbers of variables");
  Polynomial product(a.variables_);
  Polynomial::Exponents e(a.variables_);
  for (const auto& [ea, ca] : a.terms_)
    for (const auto& [eb, cb] : b.terms_) {
      for (int v = 0; v < a.variables_; ++v) e[v] = static_cast<std::uint16_t>(ea[v] + eb[v]);
      product.add_term(e, ca * cb);
    }
  return product;
}

Polynomial operator+(Polynomial a, Complex c) {
  a.add_term(Polynomial::Exponents(a.variables_, 0), c);
  return a;
}

PolynomialSystem::PolynomialSystem(std::vector<Polynomial> equations) : equations_(std::move(equations)) {
  if (equations_.empty()) throw Error(ErrorKind::BadInput, "PolynomialSystem: no equations");
  variables_ = equations_.front().variables();
  for (const auto& p : equations_)
    if (p.variables() != variables_)
      throw Error(ErrorKind::BadInput, "PolynomialSystem: equations have different numbers of variables");
}

void PolynomialSystem::evaluate(const CVector& x, CVector& f) const {
  f.resize(equations());
  for (int i = 0; i < equations(); ++i) f[i] = equations_[i].evaluate(x);
}

void PolynomialSystem::evaluate(const CVector& x, CVector& f, CMatrix& jacobian) const {
  f.resize(equations());
  jacobian.resize(equations(), variables_);
  for (int i = 0; i < equations(); ++i) f[i] = equations_[i].evaluate(x, jacobian.row(i));
}

}  // namespace nbar::synthesis
