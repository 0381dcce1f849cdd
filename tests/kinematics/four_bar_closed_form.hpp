// A four-bar's pin B in closed form, from its model's drawn points: the input O2-A turned to an
// angle, and B at |AB| from A and |O4 B| from O4, on either side of the line A -> O4. An
// independent reference for the poses the solver gives on a rocking path, whose turns take B
// across to the other branch (the kinematics and the request tests).
#pragma once

#include <Eigen/Core>

#include <cmath>

#include "nbar/model/model.hpp"

namespace nbar::test_support {

struct FourBarClosedForm {
  Eigen::Vector2d o2, o4;
  double input = 0.0, coupler = 0.0, output = 0.0;  // |O2 A|, |A B|, |O4 B| as drawn
  double drawn_side = 1.0;                          // +1: B drawn left of A -> O4; -1: right

  explicit FourBarClosedForm(const Model& m) {
    const auto at = [&](const char* name) { return m.points[static_cast<std::size_t>(m.find_point(name))].position; };
    o2 = at("O2");
    o4 = at("O4");
    const Eigen::Vector2d a = at("A"), b = at("B"), to_o4 = o4 - a, to_b = b - a;
    input = (a - o2).norm();
    coupler = to_b.norm();
    output = (b - o4).norm();
    drawn_side = to_o4.x() * to_b.y() - to_o4.y() * to_b.x() > 0 ? 1.0 : -1.0;
  }

  // B with the input at `theta` (rad from +x), on `side` of A -> O4.
  Eigen::Vector2d pin_b(double theta, double side) const {
    const Eigen::Vector2d a = o2 + input * Eigen::Vector2d(std::cos(theta), std::sin(theta));
    const Eigen::Vector2d u = o4 - a;
    const double d = u.norm(), along = (coupler * coupler - output * output + d * d) / (2 * d);
    const double across = std::sqrt(coupler * coupler - along * along);
    return a + along * u / d + side * across * Eigen::Vector2d(-u.y(), u.x()) / d;
  }
};

}  // namespace nbar::test_support
