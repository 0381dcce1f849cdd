// A four-bar found by synthesis, as pivots in the first precision position, and what the
// kinematics engine says about it.
#pragma once

#include <Eigen/Core>

namespace nbar::synthesis {

// Positions with the coupler in its first precision position.
struct FourBarDesign {
  Eigen::Vector2d ground_a{0, 0};   // fixed pivot of the input link
  Eigen::Vector2d ground_b{0, 0};   // fixed pivot of the output link
  Eigen::Vector2d moving_a{0, 0};   // coupler-input joint
  Eigen::Vector2d moving_b{0, 0};   // coupler-output joint
  Eigen::Vector2d coupler_point{0, 0};
};

}  // namespace nbar::synthesis
