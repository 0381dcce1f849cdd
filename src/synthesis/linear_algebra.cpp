#include "linear_algebra.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

template class Eigen::PartialPivLU<Eigen::MatrixXcd>;

namespace nbar::synthesis::linear_algebra {

Eigen::VectorXcd eigenvalues(const Eigen::MatrixXcd& m) {
  const Eigen::ComplexEigenSolver<Eigen::MatrixXcd> solver(m, false);
  return solver.eigenvalues();
}

Eigen::Vector3cd smallest_right_singular_vector(const Eigen::Matrix<Complex, 4, 3>& m) {
  const Eigen::JacobiSVD<Eigen::Matrix<Complex, 4, 3>> svd(m, Eigen::ComputeFullV);
  return svd.matrixV().col(2);
}

Eigen::Vector4cd solve_full_pivoting(const Eigen::Matrix4cd& a, const Eigen::Vector4cd& b) {
  return a.fullPivLu().solve(b);
}

}  // namespace nbar::synthesis::linear_algebra
