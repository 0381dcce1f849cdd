// Nine points on one circle, a task with infinitely many solutions. Apart from the solver, so
// that the task reader (and its fuzzer) can refuse such a task without linking the solver.
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>

#include "nbar/synthesis/nine_point.hpp"

namespace nbar::synthesis {

std::optional<NinePointCircle> common_circle(const std::array<Eigen::Vector2d, 9>& points) {
  // a (x² + y²) + b x + c y + d = 0 through every point, in coordinates centred on the points and
  // scaled by their spread: the null vector of the 9 x 4 matrix, when it has one.
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const auto& q : points) centroid += q / 9.0;
  double spread = 0.0;
  for (const auto& q : points) spread = std::max(spread, (q - centroid).norm());
  if (!(spread > 0)) return std::nullopt;
  Eigen::Matrix<double, 9, 4> rows;
  for (int i = 0; i < 9; ++i) {
    const Eigen::Vector2d u = (points[i] - centroid) / spread;
    rows.row(i) << u.squaredNorm(), u.x(), u.y(), 1.0;
  }
  const Eigen::JacobiSVD<Eigen::Matrix<double, 9, 4>> svd(rows, Eigen::ComputeFullV);
  const Eigen::Vector4d s = svd.singularValues();
  if (!(s[3] <= 1e-9 * s[0])) return std::nullopt;
  const Eigen::Vector4d v = svd.matrixV().col(3);
  if (std::abs(v[0]) <= 1e-9 * v.tail<3>().norm()) return std::nullopt;  // a line, not a circle
  const Eigen::Vector2d centre(-v[1] / (2 * v[0]), -v[2] / (2 * v[0]));
  const double radius_squared = centre.squaredNorm() - v[3] / v[0];
  if (!(radius_squared > 0)) return std::nullopt;
  return NinePointCircle{centroid + spread * centre, spread * std::sqrt(radius_squared)};
}

}  // namespace nbar::synthesis
