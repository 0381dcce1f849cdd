#include "nbar/stress/plane_stress.hpp"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>

#include "nbar/model/diagnostics.hpp"

#include "model/plane_vectors.hpp"
#include "t6_element.hpp"

namespace nbar::fe {

namespace {

using SparseColumns = Eigen::SparseMatrix<double>;
using SparseRows = Eigen::SparseMatrix<double, Eigen::RowMajor>;

std::string at_point(const Eigen::Vector2d& p) {
  std::string out(1, '(');  // appended piece by piece: GCC 12 warns (wrongly) on "(" + std::string
  out.append(std::to_string(p.x())).append(", ").append(std::to_string(p.y())).append(")");
  return out;
}

void check_material(const ElasticMaterial& m) {
  const auto bad = [](const std::string& what) { throw Error(ErrorKind::BadInput, "finite elements: " + what); };
  if (!(std::isfinite(m.youngs_modulus) && m.youngs_modulus > 0)) bad("Young's modulus must be a positive number");
  if (!(m.poisson_ratio >= 0 && m.poisson_ratio < 0.5)) bad("Poisson's ratio must be in [0, 0.5)");
  if (!(std::isfinite(m.thickness) && m.thickness > 0)) bad("the plate thickness must be a positive number");
  if (!(std::isfinite(m.density) && m.density >= 0)) bad("the density must be a number >= 0");
}

// Every index in range, every node finite and used, one connected piece (else the stiffness is
// singular beyond the three rigid-body modes the supports remove).
void check_mesh(const TriMesh& mesh) {
  const auto bad = [](const std::string& what) {
    throw Error(ErrorKind::BadInput, "finite elements: the mesh " + what);
  };
  const int n = static_cast<int>(mesh.nodes.size());
  if (mesh.triangles.empty() || n < 6) bad("has no triangles");
  for (const Eigen::Vector2d& p : mesh.nodes)
    if (!p.allFinite()) bad("has a node that is not a finite point");
  std::vector<int> parent(n);
  for (int i = 0; i < n; ++i) parent[i] = i;
  const auto root = [&parent](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::vector<char> used(n, 0);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int v : mesh.triangles[t]) {
      if (v < 0 || v >= n)
        bad("triangle " + std::to_string(t) + " refers to node " + std::to_string(v) + ", which does not exist");
      used[v] = 1;
      parent[root(v)] = root(mesh.triangles[t][0]);
    }
  }
  for (int i = 0; i < n; ++i) {
    if (!used[i]) bad("node " + std::to_string(i) + " at " + at_point(mesh.nodes[i]) + " belongs to no triangle");
    if (root(i) != root(0))
      bad("is in more than one piece (node " + std::to_string(i) + " at " + at_point(mesh.nodes[i]) +
          " is not connected to node 0)");
  }
  for (const BoundaryEdge& e : mesh.boundary)
    for (int v : e.nodes)
      if (v < 0 || v >= n) bad("has a boundary edge on node " + std::to_string(v) + ", which does not exist");
}

Eigen::Matrix3d plane_stress_elasticity(const ElasticMaterial& m) {
  const double e = m.youngs_modulus, nu = m.poisson_ratio, c = e / (1 - nu * nu);
  Eigen::Matrix3d d;
  d << c, c * nu, 0, c * nu, c, 0, 0, 0, c * (1 - nu) / 2;
  return d;
}

struct HoleGeometry {
  Eigen::Vector2d centre{0, 0};
  double radius = 0;
  std::vector<int> edges;                      // indices into TriMesh::boundary
  std::vector<int> nodes;                      // the nodes on the hole, each once
  std::vector<std::array<int, 3>> edge_nodes;  // per edge, its nodes' positions in `nodes`
};

// Least-squares circle through points that lie on one (Kasa's fit, then exact for them).
std::pair<Eigen::Vector2d, double> fit_circle(const std::vector<Eigen::Vector2d>& points) {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (const auto& p : points) {
    const Eigen::Vector2d q = p - mean;
    const Eigen::Vector3d row(q.x(), q.y(), 1.0);
    a += row * row.transpose();
    b += row * q.squaredNorm();
  }
  const Eigen::Vector3d s = a.ldlt().solve(b);  // |q|^2 = 2 c.q + (r^2 - |c|^2)
  const Eigen::Vector2d centre(s[0] / 2, s[1] / 2);
  return {mean + centre, std::sqrt(std::max(0.0, s[2] + centre.squaredNorm()))};
}

}  // namespace

struct PlateModel::Impl {
  TriMesh mesh;
  ElasticMaterial material;
  Eigen::Matrix3d elasticity;
  double size = 0, area = 0;  // bounding-box diagonal (m), area (m^2)
  Eigen::Vector2d centroid{0, 0};
  // ∫N_i dA, ∫N_i x dA, ∫N_i y dA per node: body forces and inertia relief are linear in these.
  Eigen::VectorXd node_area, node_x, node_y;
  std::map<int, HoleGeometry> holes;
  std::array<Support, 3> supports;
  std::vector<int> reduced_index;  // per dof: its row in the reduced system, -1 when supported
  SparseRows support_rows;         // the stiffness rows of the three supported dofs (for the reactions)
  SparseRows recovery;  // nodal (σxx, σyy, τxy) from the displacements: element values at the node, averaged

  int dofs() const { return 2 * static_cast<int>(mesh.nodes.size()); }
  void choose_supports();
  void integrate_geometry();
  void find_holes();
  void assemble_and_factorise();
  void build_recovery();
  const HoleGeometry& hole(int index) const;

  double add_bearing(const BearingLoad& load, Eigen::VectorXd& f) const;
  double add_couple(const HoleCouple& load, Eigen::VectorXd& f) const;
  double add_point_force(const PointForce& load, Eigen::VectorXd& f) const;
  double add_body(const RigidBodyField& body, Eigen::VectorXd& f) const;
  // The nodal forces of a traction on hole h, per node of h.nodes.
  // The traction may have a kink where `cut`·(x − centre) changes sign (zero `cut`: none).
  template <class Traction>
  std::vector<Eigen::Vector2d> hole_traction(const HoleGeometry& h, Traction traction,
                                             const Eigen::Vector2d& cut) const;
  NodalLoads nodal_loads(const LoadCase& loads) const;

  // The factor L (P K P^T = L L^T) as plain arrays: strictly-lower entries by column and the
  // reciprocal diagonal, and each dof's row in the permuted system (-1 when supported).
  std::vector<int> lower_start, lower_row;
  std::vector<double> lower_value, inverse_diagonal;
  std::vector<int> solve_row;
  void keep_factor(const Eigen::SimplicialLLT<SparseColumns>& factor);
  // Several load cases at once, `kBlock` at most: each factor entry then updates a row of
  // right-hand sides, so the factor is read once per block instead of once per case.
  static constexpr int kBlock = 16;
  using Block = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  template <int Width>
  void substitute(double* x) const;
  void solve_block(const LoadCase* cases, int count, std::vector<StressField>& out) const;
};

void PlateModel::Impl::keep_factor(const Eigen::SimplicialLLT<SparseColumns>& factor) {
  const SparseColumns& l = factor.matrixL().nestedExpression();
  const int n = static_cast<int>(l.cols());
  lower_start.assign(1, 0);
  inverse_diagonal.assign(n, 0.0);
  for (int j = 0; j < n; ++j) {
    for (SparseColumns::InnerIterator it(l, j); it; ++it) {
      if (it.row() == j) {
        inverse_diagonal[j] = 1.0 / it.value();
      } else if (it.row() > j) {
        lower_row.push_back(static_cast<int>(it.row()));
        lower_value.push_back(it.value());
      }
    }
    lower_start.push_back(static_cast<int>(lower_row.size()));
  }
  const auto& p = factor.permutationP().indices();
  solve_row.assign(dofs(), -1);
  for (int i = 0; i < dofs(); ++i)
    if (reduced_index[i] >= 0) solve_row[i] = p.size() > 0 ? p[reduced_index[i]] : reduced_index[i];
}

// x := L^-T L^-1 x for `Width` right-hand sides stored row by row (x[Width * row + case]),
// column by column of L: each entry updates a whole row of cases at once.
template <int Width>
void PlateModel::Impl::substitute(double* x) const {
  const int n = static_cast<int>(inverse_diagonal.size());
  const int* rows = lower_row.data();
  const double* values = lower_value.data();
  for (int j = 0; j < n; ++j) {
    double* xj = x + static_cast<std::ptrdiff_t>(Width) * j;
    for (int c = 0; c < Width; ++c) xj[c] *= inverse_diagonal[j];
    for (int k = lower_start[j]; k < lower_start[j + 1]; ++k) {
      double* xi = x + static_cast<std::ptrdiff_t>(Width) * rows[k];
      const double l = values[k];
      for (int c = 0; c < Width; ++c) xi[c] -= l * xj[c];
    }
  }
  for (int j = n - 1; j >= 0; --j) {
    double* xj = x + static_cast<std::ptrdiff_t>(Width) * j;
    double sum[Width];
    for (int c = 0; c < Width; ++c) sum[c] = xj[c];
    for (int k = lower_start[j]; k < lower_start[j + 1]; ++k) {
      const double* xi = x + static_cast<std::ptrdiff_t>(Width) * rows[k];
      const double l = values[k];
      for (int c = 0; c < Width; ++c) sum[c] -= l * xi[c];
    }
    for (int c = 0; c < Width; ++c) xj[c] = sum[c] * inverse_diagonal[j];
  }
}

void PlateModel::Impl::solve_block(const LoadCase* cases, int count, std::vector<StressField>& out) const {
  const int n = static_cast<int>(mesh.nodes.size()), n_dofs = dofs();
  std::vector<NodalLoads> applied;
  applied.reserve(count);
  const int width = count == 1 ? 1 : kBlock;  // a block is padded with empty cases
  Block x = Block::Zero(n_dofs - 3, width);
  for (int c = 0; c < count; ++c) {
    applied.push_back(nodal_loads(cases[c]));
    for (int i = 0; i < n_dofs; ++i)
      if (solve_row[i] >= 0) x(solve_row[i], c) = applied[c].forces[i];
  }
  if (width == 1)
    substitute<1>(x.data());
  else
    substitute<kBlock>(x.data());
  Block displacement = Block::Zero(n_dofs, count);
  for (int i = 0; i < n_dofs; ++i)
    if (solve_row[i] >= 0) displacement.row(i) = x.row(solve_row[i]).head(count);
  const Block stress = recovery * displacement;
  const Block reactions = support_rows * displacement;
  // Row by row of the blocks (cases side by side in memory), filling every case's field at once.
  const std::size_t first = out.size();
  for (int c = 0; c < count; ++c) {
    StressField field;
    field.load_unbalance = applied[c].load_unbalance;
    if (applied[c].load_scale > 0) {
      double largest = 0;
      for (int k = 0; k < 3; ++k)
        largest = std::max(largest,
                           std::abs(reactions(k, c) - applied[c].forces[2 * supports[k].node + supports[k].direction]));
      field.support_reaction = largest / applied[c].load_scale;
    }
    field.displacement.resize(n_dofs);
    field.stress.resize(n);
    field.von_mises.resize(n);
    out.push_back(std::move(field));
  }
  StressField* fields = out.data() + first;
  for (int i = 0; i < n_dofs; ++i)
    for (int c = 0; c < count; ++c) fields[c].displacement[i] = displacement(i, c);
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < count; ++c) {
      const Eigen::Vector3d s(stress(3 * i, c), stress(3 * i + 1, c), stress(3 * i + 2, c));
      StressField& field = fields[c];
      field.stress[i] = s;
      field.von_mises[i] = std::sqrt(std::max(0.0, s[0] * s[0] - s[0] * s[1] + s[1] * s[1] + 3 * s[2] * s[2]));
      if (field.peak_node < 0 || field.von_mises[i] > field.peak) field.peak = field.von_mises[i], field.peak_node = i;
    }
  }
  for (int c = 0; c < count; ++c) fields[c].peak_at = mesh.nodes[fields[c].peak_node];
}

// x and y held at the leftmost node (lowest, on a tie), and the direction across the line to the
// node farthest from it held there: no rigid-body motion is left, and nothing more is held.
void PlateModel::Impl::choose_supports() {
  const auto& p = mesh.nodes;
  int a = 0;
  for (int i = 1; i < static_cast<int>(p.size()); ++i)
    if (p[i].x() < p[a].x() || (p[i].x() == p[a].x() && p[i].y() < p[a].y())) a = i;
  int b = a;
  for (int i = 0; i < static_cast<int>(p.size()); ++i)
    if ((p[i] - p[a]).squaredNorm() > (p[b] - p[a]).squaredNorm()) b = i;
  const Eigen::Vector2d d = p[b] - p[a];
  supports = {Support{a, 0}, Support{a, 1}, Support{b, std::abs(d.x()) >= std::abs(d.y()) ? 1 : 0}};
  reduced_index.assign(dofs(), 0);
  for (const Support& s : supports) reduced_index[2 * s.node + s.direction] = -1;
  int next = 0;
  for (int& r : reduced_index) r = r < 0 ? -1 : next++;
}

void PlateModel::Impl::integrate_geometry() {
  const int n = static_cast<int>(mesh.nodes.size());
  node_area = node_x = node_y = Eigen::VectorXd::Zero(n);
  Eigen::Vector2d lo = mesh.nodes[0], hi = mesh.nodes[0];
  for (const auto& p : mesh.nodes) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  size = (hi - lo).norm();
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const t6::Element e = t6::element_nodes(mesh, static_cast<int>(t));
    for (const auto& q : t6::kGauss6) {
      const Eigen::Matrix<double, 6, 1> shape = t6::shape(q.xi, q.eta);
      const double det_j = t6::jacobian(e, t6::shape_derivatives(q.xi, q.eta)).determinant();
      if (!(det_j > 0))
        throw Error(ErrorKind::BadInput, "finite elements: triangle " + std::to_string(t) + " near " +
                                             at_point(t6::position(e, shape)) + " is inverted or degenerate");
      const Eigen::Vector2d x = t6::position(e, shape);
      for (int i = 0; i < 6; ++i) {
        const int node = mesh.triangles[t][i];
        const double w = q.weight * det_j * shape[i];
        node_area[node] += w;
        node_x[node] += w * x.x();
        node_y[node] += w * x.y();
      }
    }
  }
  area = node_area.sum();
  centroid = {node_x.sum() / area, node_y.sum() / area};
}

void PlateModel::Impl::find_holes() {
  std::map<int, std::vector<Eigen::Vector2d>> points;
  for (std::size_t i = 0; i < mesh.boundary.size(); ++i) {
    const BoundaryEdge& e = mesh.boundary[i];
    if (e.on.kind != BoundaryTag::Kind::circle_hole) continue;
    holes[e.on.index].edges.push_back(static_cast<int>(i));
    for (int v : e.nodes) points[e.on.index].push_back(mesh.nodes[v]);
  }
  for (auto& [index, h] : holes) {
    std::tie(h.centre, h.radius) = fit_circle(points[index]);
    std::map<int, int> position;
    for (int edge : h.edges) {
      std::array<int, 3> local{};
      for (int k = 0; k < 3; ++k) {
        const int node = mesh.boundary[edge].nodes[k];
        const auto [it, added] = position.emplace(node, static_cast<int>(h.nodes.size()));
        if (added) h.nodes.push_back(node);
        local[k] = it->second;
      }
      h.edge_nodes.push_back(local);
    }
  }
}

const HoleGeometry& PlateModel::Impl::hole(int index) const {
  const auto it = holes.find(index);
  if (it == holes.end())
    throw Error(ErrorKind::BadInput, "finite elements: the plate has no circle hole " + std::to_string(index) +
                                         " (it has " + std::to_string(holes.size()) + ")");
  return it->second;
}

void PlateModel::Impl::assemble_and_factorise() {
  const int n_dofs = dofs(), n_free = n_dofs - 3;
  std::vector<Eigen::Triplet<double>> free_part, support_part;
  free_part.reserve(mesh.triangles.size() * 78);
  const double thickness = material.thickness;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const t6::Element e = t6::element_nodes(mesh, static_cast<int>(t));
    Eigen::Matrix<double, 12, 12> k = Eigen::Matrix<double, 12, 12>::Zero();
    const auto add_point = [&](const t6::TrianglePoint& q) {
      Eigen::Matrix<double, 3, 12> b;
      double det_j = 0;
      if (!t6::strain_matrix(e, q.xi, q.eta, b, det_j))
        throw Error(ErrorKind::BadInput,
                    "finite elements: triangle " + std::to_string(t) + " is inverted or degenerate");
      k.noalias() += (q.weight * det_j * thickness) * (b.transpose() * elasticity * b);
    };
    if (t6::is_curved(e))
      for (const auto& q : t6::kGauss6) add_point(q);
    else
      for (const auto& q : t6::kGauss3) add_point(q);
    for (int i = 0; i < 12; ++i) {
      const int gi = 2 * mesh.triangles[t][i / 2] + i % 2;
      for (int j = 0; j < 12; ++j) {
        const int gj = 2 * mesh.triangles[t][j / 2] + j % 2;
        const int ri = reduced_index[gi], rj = reduced_index[gj];
        if (ri < 0) {
          int row = 0;
          while (2 * supports[row].node + supports[row].direction != gi) ++row;
          support_part.emplace_back(row, gj, k(i, j));
        } else if (rj >= 0 && rj <= ri) {
          free_part.emplace_back(ri, rj, k(i, j));  // the lower triangle is all the factorisation reads
        }
      }
    }
  }
  SparseColumns stiffness(n_free, n_free);
  stiffness.setFromTriplets(free_part.begin(), free_part.end());
  support_rows.resize(3, n_dofs);
  support_rows.setFromTriplets(support_part.begin(), support_part.end());
  const Eigen::SimplicialLLT<SparseColumns> factor(stiffness);
  if (factor.info() != Eigen::Success)
    throw Error(ErrorKind::BadInput,
                "finite elements: the stiffness matrix could not be factorised (degenerate mesh?)");
  keep_factor(factor);
}

void PlateModel::Impl::build_recovery() {
  const int n = static_cast<int>(mesh.nodes.size());
  std::vector<int> sharing(n, 0);
  for (const auto& tri : mesh.triangles)
    for (int v : tri) ++sharing[v];
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(mesh.triangles.size() * 6 * 3 * 12);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const t6::Element e = t6::element_nodes(mesh, static_cast<int>(t));
    for (int local = 0; local < 6; ++local) {
      Eigen::Matrix<double, 3, 12> b;
      double det_j = 0;
      if (!t6::strain_matrix(e, t6::kNodeNatural[local][0], t6::kNodeNatural[local][1], b, det_j))
        throw Error(ErrorKind::BadInput, "finite elements: triangle " + std::to_string(t) +
                                             " is inverted at its node " + at_point(e[local]));
      const int node = mesh.triangles[t][local];
      const Eigen::Matrix<double, 3, 12> db = (1.0 / sharing[node]) * (elasticity * b);
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 12; ++c) entries.emplace_back(3 * node + r, 2 * mesh.triangles[t][c / 2] + c % 2, db(r, c));
    }
  }
  recovery.resize(3 * n, 2 * n);
  recovery.setFromTriplets(entries.begin(), entries.end());
}

template <class Traction>
std::vector<Eigen::Vector2d> PlateModel::Impl::hole_traction(const HoleGeometry& h, Traction traction,
                                                             const Eigen::Vector2d& cut) const {
  std::vector<Eigen::Vector2d> out(h.nodes.size(), Eigen::Vector2d::Zero());
  for (std::size_t e = 0; e < h.edges.size(); ++e) {
    const auto& nodes = mesh.boundary[h.edges[e]].nodes;  // first, second, middle
    const std::array<Eigen::Vector2d, 3> x{mesh.nodes[nodes[0]], mesh.nodes[nodes[1]], mesh.nodes[nodes[2]]};
    const auto point = [&](double s) {
      const Eigen::Vector3d n = t6::edge_shape(s);
      return Eigen::Vector2d(n[0] * x[0] + n[1] * x[1] + n[2] * x[2]);
    };
    const auto side = [&](double s) { return cut.dot(point(s) - h.centre); };
    // Integrate each smooth piece on its own: split where the traction has its kink.
    std::array<double, 3> ends{-1, 1, 1};
    int pieces = 1;
    if (cut.squaredNorm() > 0 && (side(-1) > 0) != (side(1) > 0)) {
      double lo = -1, hi = 1;
      for (int it = 0; it < 60; ++it) ((side(lo) > 0) == (side(0.5 * (lo + hi)) > 0) ? lo : hi) = 0.5 * (lo + hi);
      ends = {-1, 0.5 * (lo + hi), 1};
      pieces = 2;
    }
    for (int piece = 0; piece < pieces; ++piece) {
      const double a = ends[piece], b = ends[piece + 1];
      for (const auto& [g, w] : t6::kGaussLine5) {
        const double s = 0.5 * (a + b) + 0.5 * (b - a) * g;
        const Eigen::Vector3d n = t6::edge_shape(s), dn = t6::edge_shape_derivative(s);
        const Eigen::Vector2d tangent = dn[0] * x[0] + dn[1] * x[1] + dn[2] * x[2];
        const Eigen::Vector2d t =
            traction((point(s) - h.centre).normalized()) * (0.5 * (b - a) * w * tangent.norm() * material.thickness);
        for (int i = 0; i < 3; ++i) out[h.edge_nodes[e][i]] += n[i] * t;
      }
    }
  }
  return out;
}

// The pin presses on the hole wall facing the force: p(θ) = p0 cos(θ − θ_F) over that half, with
// p0 = 2|F| / (π r t) so the resultant is F; the discrete resultant is made F exactly.
double PlateModel::Impl::add_bearing(const BearingLoad& load, Eigen::VectorXd& f) const {
  const HoleGeometry& h = hole(load.hole);
  if (!load.force.allFinite())
    throw Error(ErrorKind::BadInput,
                "finite elements: the bearing force on hole " + std::to_string(load.hole) + " is not finite");
  const double magnitude = load.force.norm();
  if (magnitude == 0) return 0;
  const Eigen::Vector2d direction = load.force / magnitude;
  const double p0 = 2 * magnitude / (std::numbers::pi * h.radius * material.thickness);
  const std::vector<Eigen::Vector2d> part = hole_traction(
      h,
      [&](const Eigen::Vector2d& radial) -> Eigen::Vector2d {
        return std::max(0.0, radial.dot(direction)) * p0 * radial;
      },
      direction);
  Eigen::Vector2d resultant = Eigen::Vector2d::Zero();
  for (const auto& p : part) resultant += p;
  // The discrete circle bends the resultant by ~1e-8: turn and scale it onto F (a tangential
  // part of that size is negligible, a force off F would be reported as unbalance).
  const double turn = std::atan2(cross(resultant, load.force), resultant.dot(load.force));
  const Eigen::Matrix2d onto = (magnitude / resultant.norm()) * Eigen::Rotation2Dd(turn).toRotationMatrix();
  for (std::size_t i = 0; i < part.size(); ++i) f.segment<2>(2 * h.nodes[i]) += onto * part[i];
  return magnitude;
}

// A uniform shear traction τ = M / (2π r² t) around the hole, rescaled so the discrete moment
// about its centre is M exactly.
double PlateModel::Impl::add_couple(const HoleCouple& load, Eigen::VectorXd& f) const {
  const HoleGeometry& h = hole(load.hole);
  if (!std::isfinite(load.moment))
    throw Error(ErrorKind::BadInput,
                "finite elements: the couple on hole " + std::to_string(load.hole) + " is not finite");
  if (load.moment == 0) return 0;
  const double tau = load.moment / (2 * std::numbers::pi * h.radius * h.radius * material.thickness);
  const std::vector<Eigen::Vector2d> part = hole_traction(
      h,
      [&](const Eigen::Vector2d& radial) -> Eigen::Vector2d { return tau * Eigen::Vector2d(-radial.y(), radial.x()); },
      Eigen::Vector2d::Zero());
  double moment = 0;
  for (std::size_t i = 0; i < part.size(); ++i) moment += cross(mesh.nodes[h.nodes[i]] - h.centre, part[i]);
  for (std::size_t i = 0; i < part.size(); ++i) f.segment<2>(2 * h.nodes[i]) += (load.moment / moment) * part[i];
  return std::abs(load.moment) / size;
}

// Spread over the element holding the point as a linearly varying load whose resultant is the
// force and whose centre is the point (so its moment is exact), instead of one node's singularity.
double PlateModel::Impl::add_point_force(const PointForce& load, Eigen::VectorXd& f) const {
  if (!load.force.allFinite() || !load.at.allFinite())
    throw Error(ErrorKind::BadInput, "finite elements: a point force or its point is not finite");
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const t6::Element e = t6::element_nodes(mesh, static_cast<int>(t));
    Eigen::Vector2d lo = e[0], hi = e[0];
    for (const auto& p : e) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    const double slack = 0.05 * (hi - lo).norm();
    if ((load.at.array() < lo.array() - slack).any() || (load.at.array() > hi.array() + slack).any()) continue;
    if (!t6::locate(e, load.at)) continue;
    double a = 0;
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    Eigen::Matrix2d second = Eigen::Matrix2d::Zero();
    std::array<double, 6> det_j{};
    for (std::size_t q = 0; q < t6::kGauss6.size(); ++q) {
      const auto& g = t6::kGauss6[q];
      det_j[q] = g.weight * t6::jacobian(e, t6::shape_derivatives(g.xi, g.eta)).determinant();
      a += det_j[q];
      centre += det_j[q] * t6::position(e, t6::shape(g.xi, g.eta));
    }
    centre /= a;
    for (std::size_t q = 0; q < t6::kGauss6.size(); ++q) {
      const auto& g = t6::kGauss6[q];
      const Eigen::Vector2d r = t6::position(e, t6::shape(g.xi, g.eta)) - centre;
      second += det_j[q] * r * r.transpose();
    }
    const Eigen::Vector2d gradient = a * second.inverse() * (load.at - centre);
    for (std::size_t q = 0; q < t6::kGauss6.size(); ++q) {
      const auto& g = t6::kGauss6[q];
      const Eigen::Matrix<double, 6, 1> n = t6::shape(g.xi, g.eta);
      const double density = (1 + gradient.dot(t6::position(e, n) - centre)) * det_j[q] / a;
      for (int i = 0; i < 6; ++i) f.segment<2>(2 * mesh.triangles[t][i]) += n[i] * density * load.force;
    }
    return load.force.norm();
  }
  throw Error(ErrorKind::BadInput,
              "finite elements: the point force at " + at_point(load.at) + " is outside the plate");
}

// b(x) = c + α (r_y, −r_x) + ω² r with c = g − a_O and r = x − O; ∫N_i b dA from the node integrals.
double PlateModel::Impl::add_body(const RigidBodyField& body, Eigen::VectorXd& f) const {
  if (!body.origin.allFinite() || !body.origin_acceleration.allFinite() || !body.gravity.allFinite() ||
      !std::isfinite(body.omega) || !std::isfinite(body.alpha))
    throw Error(ErrorKind::BadInput, "finite elements: the body-force field is not finite");
  const double rho_t = material.density * material.thickness;
  if (rho_t == 0) return 0;
  const Eigen::Vector2d c = body.gravity - body.origin_acceleration;
  const double w2 = body.omega * body.omega;
  double reach = 0;
  for (int i = 0; i < static_cast<int>(mesh.nodes.size()); ++i) {
    const double rx = node_x[i] - body.origin.x() * node_area[i], ry = node_y[i] - body.origin.y() * node_area[i];
    f[2 * i] += rho_t * (c.x() * node_area[i] + body.alpha * ry + w2 * rx);
    f[2 * i + 1] += rho_t * (c.y() * node_area[i] - body.alpha * rx + w2 * ry);
    reach = std::max(reach, (mesh.nodes[i] - body.origin).norm());
  }
  return rho_t * area * (c.norm() + (std::abs(body.alpha) + w2) * reach);
}

NodalLoads PlateModel::Impl::nodal_loads(const LoadCase& loads) const {
  NodalLoads out;
  out.forces = Eigen::VectorXd::Zero(dofs());
  Eigen::VectorXd& f = out.forces;
  double scale = 0;
  for (const auto& b : loads.bearings) scale = std::max(scale, add_bearing(b, f));
  for (const auto& c : loads.couples) scale = std::max(scale, add_couple(c, f));
  for (const auto& p : loads.forces) scale = std::max(scale, add_point_force(p, f));
  if (loads.body) scale = std::max(scale, add_body(*loads.body, f));
  double nodal_total = 0;  // half the sum of magnitudes: P for a pair of opposite tractions of resultant P
  for (const auto& p : loads.nodal) {
    if (p.node < 0 || p.node >= static_cast<int>(mesh.nodes.size()))
      throw Error(ErrorKind::BadInput,
                  "finite elements: a nodal force is on node " + std::to_string(p.node) + ", which does not exist");
    if (!p.force.allFinite())
      throw Error(ErrorKind::BadInput,
                  "finite elements: the force on node " + std::to_string(p.node) + " is not finite");
    f.segment<2>(2 * p.node) += p.force;
    nodal_total += 0.5 * p.force.norm();
  }
  scale = std::max(scale, nodal_total);
  out.load_scale = scale;
  if (scale == 0) return out;
  // Inertia relief: the net force and moment (about the centroid) are cancelled by a rigid-body
  // acceleration field a + α × (x − C) of the plate's own area distribution.
  const int n = static_cast<int>(mesh.nodes.size());
  Eigen::Vector2d net_force = Eigen::Vector2d::Zero();
  double net_moment = 0, polar = 0;
  for (int i = 0; i < n; ++i) {
    net_force += f.segment<2>(2 * i);
    net_moment += cross(mesh.nodes[i] - centroid, f.segment<2>(2 * i));
    polar += (mesh.nodes[i].x() - centroid.x()) * (node_x[i] - centroid.x() * node_area[i]) +
             (mesh.nodes[i].y() - centroid.y()) * (node_y[i] - centroid.y() * node_area[i]);
  }
  out.load_unbalance = (net_force.norm() + std::abs(net_moment) / size) / scale;
  const Eigen::Vector2d a = net_force / area;
  const double alpha = net_moment / polar;
  for (int i = 0; i < n; ++i) {
    const double rx = node_x[i] - centroid.x() * node_area[i], ry = node_y[i] - centroid.y() * node_area[i];
    f[2 * i] -= a.x() * node_area[i] - alpha * ry;
    f[2 * i + 1] -= a.y() * node_area[i] + alpha * rx;
  }
  return out;
}

PlateModel::PlateModel(TriMesh mesh, ElasticMaterial material) : impl_(std::make_unique<Impl>()) {
  check_material(material);
  check_mesh(mesh);
  Impl& m = *impl_;
  m.mesh = std::move(mesh);
  m.material = material;
  m.elasticity = plane_stress_elasticity(material);
  m.integrate_geometry();
  m.find_holes();
  m.choose_supports();
  m.assemble_and_factorise();
  m.build_recovery();
}

PlateModel::~PlateModel() = default;
PlateModel::PlateModel(PlateModel&&) noexcept = default;
PlateModel& PlateModel::operator=(PlateModel&&) noexcept = default;

const TriMesh& PlateModel::mesh() const { return impl_->mesh; }
const ElasticMaterial& PlateModel::material() const { return impl_->material; }
const std::array<Support, 3>& PlateModel::supports() const { return impl_->supports; }
NodalLoads PlateModel::nodal_loads(const LoadCase& loads) const { return impl_->nodal_loads(loads); }

std::pair<Eigen::Vector2d, double> PlateModel::hole_circle(int hole) const {
  const HoleGeometry& h = impl_->hole(hole);
  return {h.centre, h.radius};
}

StressField PlateModel::solve(const LoadCase& loads) const { return std::move(solve_many({loads})[0]); }

std::vector<StressField> PlateModel::solve_many(const std::vector<LoadCase>& cases) const {
  std::vector<StressField> out;
  out.reserve(cases.size());
  for (std::size_t first = 0; first < cases.size(); first += Impl::kBlock) {
    const std::size_t count = std::min<std::size_t>(Impl::kBlock, cases.size() - first);
    impl_->solve_block(cases.data() + first, static_cast<int>(count), out);
  }
  return out;
}

}  // namespace nbar::fe
