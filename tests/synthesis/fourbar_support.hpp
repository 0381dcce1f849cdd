// An independent closed-form position analysis of a four-bar, for the synthesis tests.
#pragma once

#include <Eigen/Geometry>

#include <cmath>

#include "nbar/synthesis/fourbar_design.hpp"

namespace nbar::synthesis::test_support {

struct CouplerPose {
  Eigen::Vector2d point{NAN, NAN};  // the coupler point
  double rotation = NAN;            // of the coupler from the design's pose (rad)
};

inline double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// The coupler after the input link turns by `crank` from the design's pose, on the drawn
// branch (circle intersection); NaN when the linkage cannot reach it.
inline CouplerPose coupler_pose_at(const FourBarDesign& d, double crank) {
  const Eigen::Vector2d a1 = d.ground_a + Eigen::Rotation2Dd(crank) * (d.moving_a - d.ground_a);
  const double coupler = (d.moving_b - d.moving_a).norm(), output = (d.moving_b - d.ground_b).norm();
  const Eigen::Vector2d to_b0 = d.ground_b - a1;
  const double dist = to_b0.norm();
  const double along = (coupler * coupler - output * output + dist * dist) / (2 * dist);
  const double h2 = coupler * coupler - along * along;
  if (h2 < 0) return {};
  const Eigen::Vector2d u = to_b0 / dist, n(-u.y(), u.x());
  // the branch: B on the same side of the line A -> O4 as in the drawn pose
  const double side = cross(d.ground_b - d.moving_a, d.moving_b - d.moving_a) > 0 ? 1.0 : -1.0;
  const Eigen::Vector2d b1 = a1 + along * u + side * std::sqrt(h2) * n;
  const double turn = std::atan2(cross(d.moving_b - d.moving_a, b1 - a1), (d.moving_b - d.moving_a).dot(b1 - a1));
  return {a1 + Eigen::Rotation2Dd(turn) * (d.coupler_point - d.moving_a), turn};
}

}  // namespace nbar::synthesis::test_support
