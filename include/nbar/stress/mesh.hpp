// Quality triangle meshes of flat link plates for plane-stress finite elements.
//
// mesh_region() triangulates a Region (outline minus polygonal and circular holes; arcs given by
// bulges) into quadratic 6-node triangles. Triangles are graded: about `size` long far from
// features, finer around holes and re-entrant corners. Mid-side nodes of edges on a circle hole
// or an arc lie on the true curve, so curved boundaries are represented isoparametrically. The
// result depends only on the inputs (no randomness, no threads), so a mesh is reproducible.
// Every triangle is counterclockwise with a positive Jacobian at its six nodes, and has no angle
// under 28° when no corner of the plate is sharper than 60° (conforming Delaunay refinement;
// docs/fe.md, "Mesher").
#pragma once

#include <Eigen/Core>

#include <array>
#include <vector>

#include "nbar/model/geometry.hpp"

namespace nbar::fe {

struct MeshOptions {
  // Target edge length far from holes and corners, m. 0: a twentieth of the outline's bounding
  // box diagonal.
  double size = 0.0;
  // Edges along each circle hole (and per full turn of an arc), at least.
  int segments_per_hole = 48;
  // Element edge along holes, arcs and re-entrant corners, m, at most (growing by `grading` away
  // from them); 0: automatic. Automatic: 2πr / segments_per_hole at a hole or an arc, a fifth of
  // the shorter of `size` and the corner's sides at a corner, each scaled by size /
  // automatic_mesh_size(region) when `size` is below the automatic size, so that halving `size`
  // halves every element, at the holes too.
  double edge_size = 0.0;
  // Growth of element size away from a refined feature, per element (> 1).
  double grading = 1.25;
  // Refuse to make more nodes than this (Error(ErrorKind::BadInput)), so a bad size cannot hang.
  int max_nodes = 400000;
};

// Where a boundary edge lies.
struct BoundaryTag {
  enum class Kind { outline, circle_hole, polygon_hole };
  Kind kind = Kind::outline;
  int index = 0;  // the circle or polygon hole's index in the Region; 0 for the outline
};

struct BoundaryEdge {
  std::array<int, 3> nodes{};  // first end, second end, middle; the plate lies to the left of first -> second
  BoundaryTag on;
};

struct TriMesh {
  std::vector<Eigen::Vector2d> nodes;  // corner nodes first (`corner_count` of them), then mid-side nodes
  int corner_count = 0;
  // Corners 0, 1, 2 counterclockwise, then mid-side nodes 3 (0-1), 4 (1-2), 5 (2-0).
  std::vector<std::array<int, 6>> triangles;
  std::vector<BoundaryEdge> boundary;
};

// Quality figures of a mesh, for tests and reports.
struct MeshQuality {
  double min_angle_deg = 0.0;             // smallest corner angle of any triangle (straight-sided measure)
  double max_edge = 0.0, min_edge = 0.0;  // m
  double area = 0.0;                      // sum of the triangles' areas, with curved edges, m^2
};

// Throws Error(ErrorKind::BadInput) with a readable message when r fails check_region or the mesh
// would exceed options.max_nodes.
TriMesh mesh_region(const Region& r, const MeshOptions& options = {});

// What mesh_region checks before it meshes: the region, the options, and whether the element size
// needs more nodes than options.max_nodes (estimated from the area). Throws as mesh_region does,
// in milliseconds, so that a program meshing several plates refuses before meshing any.
void check_mesh_budget(const Region& r, const MeshOptions& options = {});

MeshQuality mesh_quality(const TriMesh& mesh);

// The element size mesh_region uses when MeshOptions::size is 0: a twentieth of the diagonal of
// the outline's bounding box, m.
double automatic_mesh_size(const Region& r);

// The number of nodes (corner and mid-side) check_mesh_budget expects mesh_region to make of r:
// the element density 1 / (√3/2 h²) integrated over the plate for the graded sizing h, as for
// equilateral triangles. Within 20 % of the mesh's count on the plates of tests/stress/mesh_test.cpp.
double estimated_mesh_nodes(const Region& r, const MeshOptions& options = {});

}  // namespace nbar::fe
