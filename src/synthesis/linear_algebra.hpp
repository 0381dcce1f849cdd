// The Eigen decompositions of the synthesis library, compiled once (linear_algebra.cpp) instead
// of in every unit that uses them: JacobiSVD and ComplexEigenSolver alone took 60% of
// burmester.cpp's 55 s of compilation (issue 34). Internal to src/synthesis: the unit that
// defines them is compiled with the library's flags (-fcx-limited-range), so the numbers are the
// ones the callers computed inline before.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>

#include <complex>

namespace nbar::synthesis::linear_algebra {

using Complex = std::complex<double>;

// The eigenvalues of a square complex matrix, in ComplexEigenSolver's order (no eigenvectors).
Eigen::VectorXcd eigenvalues(const Eigen::MatrixXcd& m);

// The right singular vector of the smallest singular value of a complex 4 x 3 matrix (the third
// column of JacobiSVD's V): the direction its rows all but annihilate.
Eigen::Vector3cd smallest_right_singular_vector(const Eigen::Matrix<Complex, 4, 3>& m);

// x with a x = b, by LU with full pivoting.
Eigen::Vector4cd solve_full_pivoting(const Eigen::Matrix4cd& a, const Eigen::Vector4cd& b);

}  // namespace nbar::synthesis::linear_algebra

// The partial-pivoting LU of dynamic complex matrices (the path tracker's and the solver's
// Newton steps) is instantiated in linear_algebra.cpp only.
extern template class Eigen::PartialPivLU<Eigen::MatrixXcd>;
