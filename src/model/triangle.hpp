// A triangle's angle from its three sides, accurate where the triangle is needle-like: a
// four-bar's transmission angle and its input's limits are such angles, and they matter most
// exactly where the triangle flattens (a toggle, a change point). There the law of cosines'
// acos loses half the digits: its argument is within a rounding error of 1, and acos near 1 turns
// a relative error of 1e-16 into 1e-8 rad.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

namespace nbar {

// The angle between the sides `adjacent` and `other_adjacent`, opposite `opposite`, in [0, pi]:
// 0 when the opposite side is no longer than their difference, pi when it is no shorter than their
// sum (the triangle cannot close; the law of cosines' argument clamped, as before). Kahan's
// formula ("Miscalculating area and angles of a needle-like triangle", 2014): with a >= b the
// adjacent sides and c the opposite one, C = 2 atan(sqrt(((a - b) + c) mu / ((a + (b + c)) ((a - c) + b))))
// where mu = b + c - a, summed as c - (a - b) when b >= c and as b - (a - c) otherwise, so that
// every subtraction is of numbers close enough to be exact.
inline double angle_opposite(double opposite, double adjacent, double other_adjacent) {
  const double a = std::max(adjacent, other_adjacent), b = std::min(adjacent, other_adjacent), c = opposite;
  if (c <= a - b) return 0.0;
  if (c >= a + b) return std::numbers::pi;
  const double mu = b >= c ? c - (a - b) : b - (a - c);
  return 2.0 * std::atan(std::sqrt(((a - b) + c) * mu / ((a + (b + c)) * ((a - c) + b))));
}

}  // namespace nbar
