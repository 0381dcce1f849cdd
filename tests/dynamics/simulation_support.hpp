// What the forward-dynamics tests share: a mechanism from a model's text, a body's angle at a
// sample, and the classical Runge-Kutta method that integrates their one-coordinate references.
#pragma once

#include <Eigen/Core>

#include <cmath>
#include <functional>
#include <string>
#include <utility>

#include "nbar/io/model_file.hpp"
#include "nbar/kinematics/mechanism.hpp"
#include "nbar/kinematics/sweep.hpp"

namespace nbar::test_support {

inline Mechanism mechanism_of(const std::string& text) { return Mechanism(io::parse_model(text).model); }

// The direction of the body's first two points, rad.
inline double angle_of(const Mechanism& mech, const Sample& s, const std::string& body) {
  const Body& b = mech.model().bodies[mech.model().find_body(body)];
  const Eigen::Vector2d u =
      mech.point_position(b.points[1], s.positions()) - mech.point_position(b.points[0], s.positions());
  return std::atan2(u.y(), u.x());
}

// y'' = f(y, y') by the classical Runge-Kutta method, `steps` steps to time t: {y, y'}.
inline std::pair<double, double> rk4(const std::function<double(double, double)>& f, double y, double v, double t,
                                     int steps) {
  const double h = t / steps;
  for (int i = 0; i < steps; ++i) {
    const double k1y = v, k1v = f(y, v);
    const double k2y = v + 0.5 * h * k1v, k2v = f(y + 0.5 * h * k1y, v + 0.5 * h * k1v);
    const double k3y = v + 0.5 * h * k2v, k3v = f(y + 0.5 * h * k2y, v + 0.5 * h * k2v);
    const double k4y = v + h * k3v, k4v = f(y + h * k3y, v + h * k3v);
    y += h / 6 * (k1y + 2 * k2y + 2 * k3y + k4y);
    v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
  }
  return {y, v};
}

}  // namespace nbar::test_support
