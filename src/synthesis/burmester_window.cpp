// The size of a set of poses and the widest window the Burmester curves are traced in: kept apart
// from burmester.cpp so that the task reader, which checks a task's window, links without the
// curve tracer (the fuzz harnesses link only what the readers reach).
#include <algorithm>
#include <cmath>

#include "nbar/synthesis/burmester.hpp"

namespace nbar::synthesis {

double pose_scale(std::span<const BodyPose> poses) {
  Eigen::Vector2d origin{0, 0};
  for (const BodyPose& p : poses) origin += p.point;
  origin /= static_cast<double>(poses.size());
  double sum = 0;
  for (const BodyPose& p : poses) sum += (p.point - origin).squaredNorm();
  const double rms = std::sqrt(sum / static_cast<double>(poses.size()));
  // Reference points all at one place: any unit will do, the motion is a rotation there.
  return rms > 1e-14 * std::max(1.0, origin.norm()) ? rms : 1.0;
}

double largest_window_radius(std::span<const BodyPose> poses) { return kMaxWindowRadius * pose_scale(poses); }

}  // namespace nbar::synthesis
