// The isoparametric 6-node triangle (T6) and the Gauss rules the plane-stress solver uses.
// Internal to the library (src/stress).
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>  // the 2x2 determinant() and inverse() of locate(): declared by Core, defined here

#include <array>
#include <cmath>
#include <optional>

#include "nbar/stress/mesh.hpp"

namespace nbar::fe::t6 {

struct TrianglePoint {
  double xi, eta, weight;  // weights sum to 1/2, the reference triangle's area
};

// Degree 2: exact for the stiffness of a straight-sided T6 (B is linear there).
inline constexpr std::array<TrianglePoint, 3> kGauss3{
    {{1.0 / 6, 1.0 / 6, 1.0 / 6}, {2.0 / 3, 1.0 / 6, 1.0 / 6}, {1.0 / 6, 2.0 / 3, 1.0 / 6}}};

// Degree 4 (Dunavant): curved elements, whose Jacobian varies, and loads of degree 3-4.
inline constexpr double kA1 = 0.445948490915965, kW1 = 0.223381589678011 / 2;
inline constexpr double kA2 = 0.091576213509771, kW2 = 0.109951743655322 / 2;
inline constexpr std::array<TrianglePoint, 6> kGauss6{{{kA1, kA1, kW1},
                                                       {1 - 2 * kA1, kA1, kW1},
                                                       {kA1, 1 - 2 * kA1, kW1},
                                                       {kA2, kA2, kW2},
                                                       {1 - 2 * kA2, kA2, kW2},
                                                       {kA2, 1 - 2 * kA2, kW2}}};

// Natural coordinates of the six nodes: corners, then mid-sides 0-1, 1-2, 2-0.
inline constexpr std::array<std::array<double, 2>, 6> kNodeNatural{
    {{0, 0}, {1, 0}, {0, 1}, {0.5, 0}, {0.5, 0.5}, {0, 0.5}}};

// 5-point Gauss-Legendre on [-1, 1] for edge tractions (the bearing pressure's cosine cut-off
// makes the integrand only piecewise smooth, so more points than the minimum).
inline constexpr std::array<std::array<double, 2>, 5> kGaussLine5{{{-0.9061798459386640, 0.2369268850561891},
                                                                   {-0.5384693101056831, 0.4786286704993665},
                                                                   {0.0, 0.5688888888888889},
                                                                   {0.5384693101056831, 0.4786286704993665},
                                                                   {0.9061798459386640, 0.2369268850561891}}};

using Element = std::array<Eigen::Vector2d, 6>;

inline Eigen::Matrix<double, 6, 1> shape(double xi, double eta) {
  const double l1 = 1 - xi - eta, l2 = xi, l3 = eta;
  Eigen::Matrix<double, 6, 1> n;
  n << l1 * (2 * l1 - 1), l2 * (2 * l2 - 1), l3 * (2 * l3 - 1), 4 * l1 * l2, 4 * l2 * l3, 4 * l3 * l1;
  return n;
}

// Rows: d/dxi, d/deta.
inline Eigen::Matrix<double, 2, 6> shape_derivatives(double xi, double eta) {
  const double l1 = 1 - xi - eta, l2 = xi, l3 = eta;
  Eigen::Matrix<double, 2, 6> d;
  d << -(4 * l1 - 1), 4 * l2 - 1, 0, 4 * (l1 - l2), 4 * l3, -4 * l3,  //
      -(4 * l1 - 1), 0, 4 * l3 - 1, -4 * l2, 4 * l2, 4 * (l1 - l3);
  return d;
}

inline Element element_nodes(const TriMesh& mesh, int triangle) {
  Element e;
  for (int i = 0; i < 6; ++i) e[i] = mesh.nodes[mesh.triangles[triangle][i]];
  return e;
}

inline Eigen::Vector2d position(const Element& e, const Eigen::Matrix<double, 6, 1>& n) {
  Eigen::Vector2d x = Eigen::Vector2d::Zero();
  for (int i = 0; i < 6; ++i) x += n[i] * e[i];
  return x;
}

// Jacobian [dx/dxi dx/deta; dy/dxi dy/deta].
inline Eigen::Matrix2d jacobian(const Element& e, const Eigen::Matrix<double, 2, 6>& d) {
  Eigen::Matrix2d j = Eigen::Matrix2d::Zero();
  for (int i = 0; i < 6; ++i) j += e[i] * d.col(i).transpose();
  return j;
}

// A mid-side node off its chord's midpoint: the element is curved and needs the finer rule.
inline bool is_curved(const Element& e) {
  constexpr int kMid[3][3] = {{3, 0, 1}, {4, 1, 2}, {5, 2, 0}};
  for (const auto& m : kMid) {
    const double chord = (e[m[2]] - e[m[1]]).norm();
    if ((e[m[0]] - 0.5 * (e[m[1]] + e[m[2]])).norm() > 1e-9 * chord) return true;
  }
  return false;
}

// Natural coordinates of x in element e by Newton on the isoparametric map; nullopt when x is
// not inside it (to `tolerance` in natural coordinates).
inline std::optional<Eigen::Vector2d> locate(const Element& e, const Eigen::Vector2d& x, double tolerance = 1e-9) {
  Eigen::Vector2d nat(1.0 / 3, 1.0 / 3);
  for (int it = 0; it < 30; ++it) {
    const Eigen::Vector2d r = position(e, shape(nat.x(), nat.y())) - x;
    const Eigen::Matrix2d j = jacobian(e, shape_derivatives(nat.x(), nat.y()));
    if (!(std::abs(j.determinant()) > 0)) return std::nullopt;
    const Eigen::Vector2d step = j.inverse() * r;
    nat -= step;
    if (!nat.allFinite() || nat.norm() > 10) return std::nullopt;
    if (step.norm() < 1e-13) break;
  }
  if (nat.x() < -tolerance || nat.y() < -tolerance || nat.x() + nat.y() > 1 + tolerance) return std::nullopt;
  return nat;
}

// Strain-displacement matrix (3 x 12, dofs u0 v0 u1 v1 ...) and det J at (xi, eta).
// Returns false when the map is not orientation-preserving there.
inline bool strain_matrix(const Element& e, double xi, double eta, Eigen::Matrix<double, 3, 12>& b, double& det_j) {
  const Eigen::Matrix<double, 2, 6> d = shape_derivatives(xi, eta);
  const Eigen::Matrix2d j = jacobian(e, d);
  det_j = j.determinant();
  if (!(det_j > 0)) return false;
  const Eigen::Matrix<double, 2, 6> dxy = j.transpose().inverse() * d;  // rows d/dx, d/dy
  b.setZero();
  for (int i = 0; i < 6; ++i) {
    b(0, 2 * i) = dxy(0, i);
    b(1, 2 * i + 1) = dxy(1, i);
    b(2, 2 * i) = dxy(1, i);
    b(2, 2 * i + 1) = dxy(0, i);
  }
  return true;
}

// Quadratic edge a (s = -1), b (s = +1), middle m (s = 0).
inline Eigen::Vector3d edge_shape(double s) { return {0.5 * s * (s - 1), 0.5 * s * (s + 1), 1 - s * s}; }
inline Eigen::Vector3d edge_shape_derivative(double s) { return {s - 0.5, s + 0.5, -2 * s}; }

}  // namespace nbar::fe::t6
