// The Eigen decompositions of dynamic double matrices that several units of the core library
// use, instantiated once (linear_algebra.cpp) instead of in each of them: the units that include
// this header compile only the calls. Internal to the core library, whose units share one set of
// flags, so the numbers are the ones each unit computed with its own copy before.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

extern template class Eigen::PartialPivLU<Eigen::MatrixXd>;
extern template class Eigen::FullPivLU<Eigen::MatrixXd>;
extern template class Eigen::ColPivHouseholderQR<Eigen::MatrixXd>;
extern template class Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>;
extern template class Eigen::JacobiSVD<Eigen::MatrixXd>;
extern template class Eigen::SparseLU<Eigen::SparseMatrix<double>>;
