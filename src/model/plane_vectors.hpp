// The products of plane vectors that the geometry, the kinematics, the stresses and the dynamics
// share: written once, so that the library's files can be compiled together (unity builds)
// without each carrying its own copy.
#pragma once

#include <Eigen/Core>

namespace nbar {

// The z component of the cross product a x b: positive when b points anticlockwise of a.
inline double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// v turned a quarter turn anticlockwise.
inline Eigen::Vector2d perp(const Eigen::Vector2d& v) { return {-v.y(), v.x()}; }

}  // namespace nbar
