#include "dynamics/initial_velocity.hpp"

#include <Eigen/Dense>

#include <cmath>
#include <sstream>

#include "kinematics/constraints.hpp"

namespace nbar {

namespace {

Eigen::MatrixXd rows_of(const Eigen::MatrixXd& m, const std::vector<int>& rows) {
  Eigen::MatrixXd out(rows.size(), m.cols());
  for (std::size_t i = 0; i < rows.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = m.row(rows[i]);
  return out;
}

Eigen::VectorXd entries_of(const Eigen::VectorXd& v, const std::vector<int>& rows) {
  Eigen::VectorXd out(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) out(static_cast<Eigen::Index>(i)) = v(rows[i]);
  return out;
}

std::string speed_text(const Model& m, const Driver& d, double speed) {
  std::ostringstream s;
  s.precision(6);
  if (d.is_angular())
    s << speed / m.units.angle_scale << " " << m.units.angle << "/s";
  else
    s << speed / m.units.length_scale << " " << m.units.length << "/s";
  return s.str();
}

}  // namespace

Eigen::VectorXd consistent_initial_velocity(const Mechanism& mech, const Eigen::MatrixXd& jacobian,
                                            const Eigen::VectorXd& phi_t, std::vector<Warning>& warnings) {
  const Model& m = mech.model();
  const auto& equations = mech.equations().rows;
  std::vector<int> kept, free;
  for (std::size_t r = 0; r < equations.size(); ++r)
    (equations[r].is_driver() && m.drivers[equations[r].driver].free ? free : kept).push_back(static_cast<int>(r));
  const Eigen::MatrixXd kept_jacobian = rows_of(jacobian, kept);
  // The kept rows exactly (minimum norm), then the free rows as nearly as the null space allows.
  Eigen::VectorXd qd = Eigen::VectorXd::Zero(jacobian.cols());
  Eigen::MatrixXd null = Eigen::MatrixXd::Identity(jacobian.cols(), jacobian.cols());
  if (!kept.empty()) {
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(kept_jacobian, Eigen::ComputeThinU | Eigen::ComputeFullV);
    const Eigen::VectorXd& sigma = svd.singularValues();
    Eigen::Index rank = 0;
    while (rank < sigma.size() && sigma(rank) > 1e-10 * sigma(0)) ++rank;
    const Eigen::VectorXd projected = svd.matrixU().leftCols(rank).transpose() * -entries_of(phi_t, kept);
    qd = svd.matrixV().leftCols(rank) * projected.cwiseQuotient(sigma.head(rank));
    null = svd.matrixV().rightCols(jacobian.cols() - rank);  // orthonormal
  }
  if (free.empty() || null.cols() == 0) return qd;
  // The free rows, each scaled to a unit gradient, on the null space: a direction they move by less
  // than 1e-4 (a speed gain above 10^4, next to a singular pose) is not used, so that a speed
  // the pose cannot have is projected away rather than met by an enormous motion elsewhere.
  Eigen::MatrixXd free_jacobian = rows_of(jacobian, free);
  Eigen::VectorXd wanted = -entries_of(phi_t, free) - free_jacobian * qd;
  Eigen::MatrixXd on_null = free_jacobian * null;
  for (Eigen::Index i = 0; i < on_null.rows(); ++i) {
    const double norm = free_jacobian.row(i).norm();
    if (norm > 0.0) on_null.row(i) /= norm, wanted(i) /= norm;
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> free_svd(on_null, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd& gains = free_svd.singularValues();
  Eigen::VectorXd z = Eigen::VectorXd::Zero(null.cols());
  for (Eigen::Index i = 0; i < gains.size(); ++i)
    if (gains(i) > 1e-4) z += free_svd.matrixV().col(i) * (free_svd.matrixU().col(i).dot(wanted) / gains(i));
  qd += null * z;
  // A free driver's row is value(q) - (start + speed t): its residual is the speed got minus asked.
  const Eigen::VectorXd missed = free_jacobian * qd + entries_of(phi_t, free);
  const double size = mech.drawing_size();
  for (std::size_t i = 0; i < free.size(); ++i) {
    const Driver& d = m.drivers[equations[free[i]].driver];
    const double change = missed(static_cast<Eigen::Index>(i));
    const double scale = d.is_angular() ? 1.0 : size;
    if (!(std::abs(change) > 1e-9 * scale * std::max(1.0, std::abs(d.initial_speed) / scale))) continue;
    warnings.push_back({"initial_speed_projected", 0,
                        "the initial speeds cannot all hold with the constraints: driver '" + d.name + "' starts at " +
                            speed_text(m, d, d.initial_speed + change) + " instead of its initial_speed " +
                            speed_text(m, d, d.initial_speed) + " (a correction of " +
                            speed_text(m, d, std::abs(change)) + ", the least-squares projection)"});
  }
  return qd;
}

}  // namespace nbar
