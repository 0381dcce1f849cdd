#include "nbar/model/bar_width.hpp"

#include <cmath>

namespace nbar {

namespace {

// x > 0 to two significant digits, a tie rounded up (as JavaScript's toPrecision(2)). The digits
// are scaled by one correctly rounded operation, so 1.2 is the double nearest 1.2.
double two_significant_digits(double x) {
  const int exponent = static_cast<int>(std::floor(std::log10(x))) - 1;
  const double scale = std::pow(10.0, std::abs(exponent));
  const double digits = exponent < 0 ? std::floor(x * scale + 0.5) : std::floor(x / scale + 0.5);
  return exponent < 0 ? digits / scale : digits * scale;
}

}  // namespace

double default_bar_width(const Model& model, int body) {
  const std::vector<int>& points = model.bodies.at(static_cast<std::size_t>(body)).points;
  if (points.size() < 2) return 1.0;
  const double drawn =
      (model.points[points[1]].position - model.points[points[0]].position).norm() / model.units.length_scale;
  const double width = drawn / 10.0;
  return width > 0.0 && std::isfinite(width) ? two_significant_digits(width) : 1.0;
}

}  // namespace nbar
