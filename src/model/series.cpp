// Truncated Taylor arithmetic. Every elementary function below satisfies a first-order ODE
// (e.g. y = exp(x) has y' = x' y), and matching coefficients of s^(k-1) in that ODE gives
// y[k] from y[0..k-1] in O(k) work: O(n^2) per call, no allocation, no symbolic algebra.
#include "nbar/model/series.hpp"

#include <cstdint>

namespace nbar {

namespace {

// Solves g * y' = h for y[1..n-1] given y[0]; h[m] is the coefficient of s^m of the
// right-hand side (m = 0..n-2). Every function with a derivative of the form
// "something / g" (atan, asin, acos, atan2) reduces to this.
void integrate_quotient(Series& y, const Series& g, const double* h) {
  const int n = y.terms();
  for (int k = 1; k < n; ++k) {
    double sum = h[k - 1];
    for (int i = 1; i < k; ++i) sum -= g[i] * (k - i) * y[k - i];
    y[k] = sum / (k * g[0]);
  }
}

// Coefficients of x' (shifted down by one), padded so that integrate_quotient can read
// h[0..n-2].
std::array<double, Series::kCapacity> derivative_coefficients(const Series& x) {
  std::array<double, Series::kCapacity> d{};
  for (int k = 1; k < x.terms(); ++k) d[k - 1] = k * x[k];
  return d;
}

// y' = (1 + sigma y^2) x' covers tan (sigma = +1) and tanh (sigma = -1); w = 1 + sigma y^2
// is built alongside y because w[m] only needs y[0..m].
Series riccati(const Series& x, double y0, double square_sign) {
  const int n = x.terms();
  Series y(n, y0);
  std::array<double, Series::kCapacity> w{};
  w[0] = 1.0 + square_sign * y0 * y0;
  for (int k = 1; k < n; ++k) {
    double sum = 0.0;
    for (int j = 1; j <= k; ++j) sum += j * x[j] * w[k - j];
    y[k] = sum / k;
    double sq = 0.0;
    for (int i = 0; i <= k; ++i) sq += y[i] * y[k - i];
    w[k] = square_sign * sq;
  }
  return y;
}

// Shared by sin/cos (sign = -1) and sinh/cosh (sign = +1): s' = c x', c' = sign * s x'.
// In place (a driver's sine and cosine, every step of a sweep): a temporary copied in would read
// back as vectors what was just stored as scalars. Division by k = 1 or 2 is a multiplication,
// the same number exactly, off the critical path of the first terms.
// Terms > 0: that many terms, known when compiled (the loops unroll); 0: x's.
template <int Terms>
void coupled_terms(const Series& x, double s0, double c0, double sign, Series& s, Series& c) {
  const int n = Terms > 0 ? Terms : x.terms();
  s.reset(n, s0);
  c.reset(n, c0);
  for (int k = 1; k < n; ++k) {
    double ss = 0.0;
    double cc = 0.0;
    for (int j = 1; j <= k; ++j) {
      ss += j * x[j] * c[k - j];
      cc += j * x[j] * s[k - j];
    }
    if (k <= 2) {
      const double inverse = k == 1 ? 1.0 : 0.5;
      s[k] = ss * inverse;
      c[k] = sign * cc * inverse;
    } else {
      s[k] = ss / k;
      c[k] = sign * cc / k;
    }
  }
}

// A sweep's drivers carry 3 or 4 terms (order 2 or 3), the predictor's 4. In line: a driver's
// sine and cosine run at every step of a sweep.
[[gnu::always_inline]] inline void coupled(const Series& x, double s0, double c0, double sign, Series& s, Series& c) {
  switch (x.terms()) {
    case 3: return coupled_terms<3>(x, s0, c0, sign, s, c);
    case 4: return coupled_terms<4>(x, s0, c0, sign, s, c);
    default: return coupled_terms<0>(x, s0, c0, sign, s, c);
  }
}

Series integer_power(const Series& x, std::int64_t p) {
  const bool negative = p < 0;
  // Magnitude as unsigned so that INT64_MIN does not overflow on negation.
  std::uint64_t e = negative ? 0 - static_cast<std::uint64_t>(p) : static_cast<std::uint64_t>(p);
  Series result(x.terms(), 1.0);
  Series base = x;
  while (e != 0) {
    if (e & 1U) result = result * base;
    e >>= 1U;
    if (e != 0) base = base * base;
  }
  return negative ? 1.0 / result : result;
}

}  // namespace

double Series::derivative(int k) const {
  assert(k >= 0 && k < n_);
  double factorial = 1.0;
  for (int i = 2; i <= k; ++i) factorial *= i;
  return factorial * c_[k];
}

Series operator/(const Series& a, const Series& b) {
  const int n = std::min(a.terms(), b.terms());
  Series q(n);
  for (int k = 0; k < n; ++k) {
    double sum = a[k];
    for (int j = 1; j <= k; ++j) sum -= b[j] * q[k - j];
    q[k] = sum / b[0];
  }
  return q;
}

Series operator/(double a, const Series& b) { return Series(b.terms(), a) / b; }

void sincos(const Series& x, Series& s, Series& c) { coupled(x, std::sin(x[0]), std::cos(x[0]), -1.0, s, c); }

Series sin(const Series& x) {
  Series s;
  Series c;
  sincos(x, s, c);
  return s;
}

Series cos(const Series& x) {
  Series s;
  Series c;
  sincos(x, s, c);
  return c;
}

Series tan(const Series& x) { return riccati(x, std::tan(x[0]), 1.0); }

Series tanh(const Series& x) { return riccati(x, std::tanh(x[0]), -1.0); }

Series sinh(const Series& x) {
  Series s;
  Series c;
  coupled(x, std::sinh(x[0]), std::cosh(x[0]), 1.0, s, c);
  return s;
}

Series cosh(const Series& x) {
  Series s;
  Series c;
  coupled(x, std::sinh(x[0]), std::cosh(x[0]), 1.0, s, c);
  return c;
}

Series exp(const Series& x) {
  const int n = x.terms();
  Series y(n, std::exp(x[0]));
  for (int k = 1; k < n; ++k) {
    double sum = 0.0;
    for (int j = 1; j <= k; ++j) sum += j * x[j] * y[k - j];
    y[k] = sum / k;
  }
  return y;
}

// x y' = x'  =>  k x0 y[k] = k x[k] - sum_{j=1}^{k-1} j y[j] x[k-j].
Series log(const Series& x) {
  const int n = x.terms();
  Series y(n, std::log(x[0]));
  for (int k = 1; k < n; ++k) {
    double sum = k * x[k];
    for (int j = 1; j < k; ++j) sum -= j * y[j] * x[k - j];
    y[k] = sum / (k * x[0]);
  }
  return y;
}

// y * y = x, solved for the new coefficient: 2 y0 y[k] = x[k] - sum_{j=1}^{k-1} y[j] y[k-j].
Series sqrt(const Series& x) {
  const int n = x.terms();
  Series y(n, std::sqrt(x[0]));
  for (int k = 1; k < n; ++k) {
    double sum = x[k];
    for (int j = 1; j < k; ++j) sum -= y[j] * y[k - j];
    y[k] = sum / (2.0 * y[0]);
  }
  return y;
}

Series pow(const Series& x, double p) {
  if (p == 0.0) return Series(x.terms(), 1.0);
  // Integer powers by repeated multiplication stay defined for x0 <= 0, where the
  // general recurrence divides by x0 or takes the log of a negative number. Beyond 2^62
  // every double is an even integer and the result overflows or underflows anyway.
  constexpr double kIntegerLimit = 4611686018427387904.0;  // 2^62
  if (std::abs(p) < kIntegerLimit && p == std::trunc(p)) {
    return integer_power(x, static_cast<std::int64_t>(p));
  }
  // x y' = p x' y  =>  k x0 y[k] = sum_{j=1}^{k} (p j - (k - j)) x[j] y[k-j].
  const int n = x.terms();
  Series y(n, std::pow(x[0], p));
  for (int k = 1; k < n; ++k) {
    double sum = 0.0;
    for (int j = 1; j <= k; ++j) sum += (p * j - (k - j)) * x[j] * y[k - j];
    y[k] = sum / (k * x[0]);
  }
  return y;
}

Series pow(const Series& x, const Series& p) { return exp(p * log(x)); }

Series atan(const Series& x) {
  Series y(x.terms(), std::atan(x[0]));
  const auto h = derivative_coefficients(x);
  integrate_quotient(y, 1.0 + x * x, h.data());
  return y;
}

// d/ds atan2(y, x) = (x y' - y x') / (x^2 + y^2), which stays regular where atan(y/x)
// would divide by x = 0.
Series atan2(const Series& y, const Series& x) {
  const int n = std::min(y.terms(), x.terms());
  Series r(n, std::atan2(y[0], x[0]));
  const auto dy = derivative_coefficients(y);
  const auto dx = derivative_coefficients(x);
  std::array<double, Series::kCapacity> h{};
  for (int m = 0; m + 1 < n; ++m) {
    double sum = 0.0;
    for (int i = 0; i <= m; ++i) sum += x[i] * dy[m - i] - y[i] * dx[m - i];
    h[m] = sum;
  }
  integrate_quotient(r, x * x + y * y, h.data());
  return r;
}

Series asin(const Series& x) {
  Series y(x.terms(), std::asin(x[0]));
  const auto h = derivative_coefficients(x);
  integrate_quotient(y, sqrt(1.0 - x * x), h.data());
  return y;
}

Series acos(const Series& x) {
  Series y(x.terms(), std::acos(x[0]));
  auto h = derivative_coefficients(x);
  for (double& v : h) v = -v;
  integrate_quotient(y, sqrt(1.0 - x * x), h.data());
  return y;
}

}  // namespace nbar
