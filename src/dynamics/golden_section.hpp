// Golden-section search, the one the dynamics' searches share: where a simulation's toggle
// measure dips (forward_dynamics.cpp) and where an equilibrium's way from the start comes nearest
// a toggle (equilibrium.cpp).
#pragma once

#include <cmath>
#include <functional>

namespace nbar {

// Where f is smallest on [a, b] (f unimodal there), by golden-section search to `tolerance`.
inline double golden_minimum(const std::function<double(double)>& f, double a, double b, double tolerance) {
  const double ratio = (std::sqrt(5.0) - 1) / 2;
  double c = b - ratio * (b - a), d = a + ratio * (b - a), fc = f(c), fd = f(d);
  while (b - a > tolerance) {
    if (fc < fd) {
      b = d, d = c, fd = fc;
      c = b - ratio * (b - a), fc = f(c);
    } else {
      a = c, c = d, fc = fd;
      d = a + ratio * (b - a), fd = f(d);
    }
  }
  return fc < fd ? c : d;
}

}  // namespace nbar
