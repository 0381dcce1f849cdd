// Truncated Taylor series in one variable s: a(s) = a[0] + a[1] s + ... + a[n-1] s^(n-1).
// The k-th time derivative of a quantity is k! * a[k]. Small fixed capacity, no allocation:
// it is evaluated in the inner loop of every kinematic step.
#pragma once

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

namespace nbar {

class Series {
 public:
  static constexpr int kCapacity = 8;  // up to the 7th derivative

  Series() = default;
  explicit Series(int terms, double constant = 0.0) : n_(terms) {
    assert(terms >= 1 && terms <= kCapacity);
    c_[0] = constant;
  }
  // The series of s0 + s (the independent variable around s0).
  static Series variable(int terms, double s0) {
    Series v(terms, s0);
    if (terms > 1) v.c_[1] = 1.0;
    return v;
  }
  // Makes this the constant series `constant` with `terms` terms, in place.
  void reset(int terms, double constant) {
    assert(terms >= 1 && terms <= kCapacity);
    n_ = terms;
    c_.fill(0.0);
    c_[0] = constant;
  }
  // Makes this the series of a + b (s0 + s), the same numbers as a + b * variable(terms, s0),
  // in place: no temporary, whose copy would read back as vectors what was just stored as
  // scalars (a store-forwarding stall on every step of a sweep).
  void set_line(int terms, double a, double b, double s0) {
    assert(terms >= 1 && terms <= kCapacity);
    n_ = terms;
    c_.fill(0.0);
    c_[0] = a + b * s0;
    if (terms > 1) c_[1] = b;
  }

  int terms() const { return n_; }
  double& operator[](int k) { return c_[k]; }
  double operator[](int k) const { return c_[k]; }
  double value() const { return c_[0]; }
  // The first `terms` coefficients (a truncation is exact for every lower coefficient).
  Series head(int terms) const {
    Series r(terms);
    for (int k = 0; k < terms; ++k) r.c_[k] = c_[k];
    return r;
  }
  // k-th derivative with respect to s at s = 0.
  double derivative(int k) const;

  Series& operator+=(const Series& b) {
    for (int k = 0; k < n_; ++k) c_[k] += b.c_[k];
    return *this;
  }
  Series& operator-=(const Series& b) {
    for (int k = 0; k < n_; ++k) c_[k] -= b.c_[k];
    return *this;
  }
  Series& operator*=(double f) {
    for (int k = 0; k < n_; ++k) c_[k] *= f;
    return *this;
  }
  Series& operator+=(double f) {
    c_[0] += f;
    return *this;
  }

 private:
  int n_ = 1;
  std::array<double, kCapacity> c_{};
};

inline Series operator+(Series a, const Series& b) { return a += b; }
inline Series operator-(Series a, const Series& b) { return a -= b; }
inline Series operator-(Series a) { return a *= -1.0; }
inline Series operator*(Series a, double f) { return a *= f; }
inline Series operator*(double f, Series a) { return a *= f; }
inline Series operator+(Series a, double f) { return a += f; }
inline Series operator+(double f, Series a) { return a += f; }
inline Series operator-(Series a, double f) { return a += -f; }
inline Series operator-(double f, const Series& a) { return -a + f; }
inline Series operator/(Series a, double f) { return a *= 1.0 / f; }

// Cauchy product, truncated to the shorter operand.
inline Series operator*(const Series& a, const Series& b) {
  const int n = std::min(a.terms(), b.terms());
  Series r(n);
  for (int k = 0; k < n; ++k) {
    double sum = 0.0;
    for (int i = 0; i <= k; ++i) sum += a[i] * b[k - i];
    r[k] = sum;
  }
  return r;
}

Series operator/(const Series& a, const Series& b);
Series operator/(double a, const Series& b);
Series sin(const Series& x);
Series cos(const Series& x);
void sincos(const Series& x, Series& s, Series& c);
Series tan(const Series& x);
Series exp(const Series& x);
Series log(const Series& x);
Series sqrt(const Series& x);
Series pow(const Series& x, double p);
Series pow(const Series& x, const Series& p);
Series atan(const Series& x);
Series atan2(const Series& y, const Series& x);
Series asin(const Series& x);
Series acos(const Series& x);
Series sinh(const Series& x);
Series cosh(const Series& x);
Series tanh(const Series& x);

}  // namespace nbar
