// Conforming Delaunay refinement (Ruppert's algorithm with Chew-style size control), private to
// the mesher (src/stress/mesh.cpp), which supplies the discretised boundary, its curves and the
// sizing function, and turns the straight-sided triangles into 6-node ones.
#pragma once

#include <Eigen/Core>

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "nbar/model/diagnostics.hpp"

namespace nbar::fe::detail {

// Refinement needs more vertices than RefinementInput::max_vertices allows.
class VertexBudgetExceeded : public Error {
 public:
  explicit VertexBudgetExceeded(const std::string& message) : Error(ErrorKind::BadInput, message) {}
};

// A piece of boundary from vertex a to vertex b with the plate on its left, lying on curve
// `curve` between its parameters ta (at a) and tb (at b).
struct BoundarySegment {
  int a = 0, b = 0;
  int curve = 0;
  double ta = 0.0, tb = 0.0;
};

struct RefinementInput {
  std::vector<Eigen::Vector2d> points;        // boundary vertices
  std::vector<char> corner;                   // per point: an input vertex where two curves meet
  std::vector<BoundarySegment> segments;      // closed rings, plate on the left
  std::vector<char> curved;                   // per curve: split at the curve's point, not the chord's
  std::vector<double> arc_radius, arc_sweep;  // per curved curve: radius, sweep (rad) over t in [0, 1]
  std::function<Eigen::Vector2d(int curve, double t)> curve_point;
  std::function<double(const Eigen::Vector2d&)> size_at;  // wanted edge length near a point
  double min_angle_deg = 28.0;                            // triangles with a smaller angle are refined
  double min_length = 0.0;                                // triangles and segments shorter than this are left alone
  int max_vertices = 0;                                   // refinement throws VertexBudgetExceeded beyond this
  int smoothing_passes = 2;
};

struct RefinedMesh {
  std::vector<Eigen::Vector2d> points;         // only the vertices of the plate's triangles
  std::vector<std::array<int, 3>> triangles;   // counterclockwise
  std::vector<std::array<int, 3>> neighbours;  // across the edge from corner i to i + 1; -1: boundary
  std::vector<BoundarySegment> segments;       // the boundary, subdivided, plate on the left
};

// Throws VertexBudgetExceeded when the mesh would need more than max_vertices vertices, and
// Error(ErrorKind::Internal) if the boundary cannot be recovered (a bug, not bad input).
RefinedMesh refine(const RefinementInput& input);

}  // namespace nbar::fe::detail
