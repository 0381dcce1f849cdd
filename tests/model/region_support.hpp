// Point-in-region tests written independently of src/model/geometry, for quadrature checks
// in the geometry and section tests.
#pragma once

#include <Eigen/Core>

#include <vector>

#include "nbar/model/geometry.hpp"

namespace nbar::test_support {

// Even-odd crossing rule.
inline bool inside_polygon(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& x) {
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    if ((poly[i].y() > x.y()) != (poly[j].y() > x.y()) &&
        x.x() < poly[j].x() + (x.y() - poly[j].y()) / (poly[i].y() - poly[j].y()) * (poly[i].x() - poly[j].x())) {
      in = !in;
    }
  }
  return in;
}

inline bool inside_region(const Region& r, const Eigen::Vector2d& x) {
  if (!inside_polygon(r.outline, x)) return false;
  for (const auto& h : r.polygon_holes) {
    if (inside_polygon(h, x)) return false;
  }
  for (const Circle& c : r.circle_holes) {
    if ((x - c.centre).norm() < c.radius) return false;
  }
  return true;
}

}  // namespace nbar::test_support
