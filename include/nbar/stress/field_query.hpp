// Reading a plate's finite-element stress field anywhere, not only at its peak: at a point,
// along a line, around a circle hole's edge.
//
// Between nodes the nodal stresses (StressField::stress, averaged from the elements around each
// node) are interpolated with the containing element's own quadratic shape functions, so a query
// at a node gives that node's value and a field the elements can represent (up to quadratic) is
// reproduced exactly. Von Mises and the principal stresses follow from the interpolated
// components. Coordinates are the plate's frame (the Region's, the model's starting pose), m.
#pragma once

#include <Eigen/Core>

#include <optional>
#include <vector>

#include "nbar/stress/mesh.hpp"
#include "nbar/stress/plane_stress.hpp"

namespace nbar::fe {

// The plane stress state at one point and what follows from it (Pa).
struct PointStress {
  Eigen::Vector2d at{0, 0};                     // m
  Eigen::Vector3d stress{0, 0, 0};              // σxx, σyy, τxy
  double von_mises = 0.0;                       // √(σxx² − σxx σyy + σyy² + 3 τxy²)
  double principal_1 = 0.0, principal_2 = 0.0;  // principal_1 >= principal_2
  double principal_angle = 0.0;                 // of principal_1 from x, rad, in (−π/2, π/2]
};

// The state of stress components (σxx, σyy, τxy) at `at`.
PointStress stress_state(const Eigen::Vector2d& at, const Eigen::Vector3d& stress);

// The same stress seen in axes turned by `angle` (rad, counterclockwise): σx'x', σy'y', τx'y'.
Eigen::Vector3d rotate_stress(const Eigen::Vector3d& stress, double angle);

// Finds the element of a mesh that contains a point: a grid of the elements' bounding boxes, then
// Newton on each candidate's isoparametric map. Keeps a reference to the mesh, which must outlive it.
class MeshLocator {
 public:
  explicit MeshLocator(const TriMesh& mesh);

  struct Location {
    int element = -1;
    Eigen::Vector2d natural{0, 0};  // (ξ, η) in the element
  };
  // nullopt when the point is off the plate (outside it or in a hole); a point on an edge,
  // to rounding, is on the plate.
  std::optional<Location> locate(const Eigen::Vector2d& at) const;
  const TriMesh& mesh() const { return mesh_; }

 private:
  const TriMesh& mesh_;
  Eigen::Vector2d low_{0, 0};
  double cell_ = 1.0;
  int columns_ = 1, rows_ = 1;
  std::vector<std::vector<int>> cells_;  // row-major: the elements whose box meets the cell
};

// The field at a point, interpolated in its element; nullopt when the point is off the plate.
std::optional<PointStress> stress_at(const MeshLocator& locator, const StressField& field, const Eigen::Vector2d& at);

// Points evenly spaced from `from` to `to`, ends included (`samples` >= 2): each with its arc
// length from `from` (m) and its stress, or none where the line is off the plate (a hole it
// crosses, or beyond the outline).
struct LineSample {
  double arc = 0.0;
  Eigen::Vector2d at{0, 0};
  std::optional<PointStress> stress;
};
std::vector<LineSample> stress_along(const MeshLocator& locator, const StressField& field, const Eigen::Vector2d& from,
                                     const Eigen::Vector2d& to, int samples);

// The stress at every node on the edge of circle hole `hole` (corner and mid-side nodes), by
// angle around the hole's centre from the x axis, counterclockwise, in [0, 2π): the nodal values
// themselves, with the hoop stress σθθ (the only one a free edge carries) and the radial σrr.
struct HoleSample {
  double angle = 0.0;  // rad
  int node = -1;
  PointStress stress;
  double hoop = 0.0, radial = 0.0;  // Pa
};
std::vector<HoleSample> stress_around_hole(const PlateModel& plate, const StressField& field, int hole);

// Where a peak on a circle hole's edge is flat (nodal values there scatter by a few tenths of a
// percent, so the node that wins is arbitrary): the arc of that edge, through `node`, along which
// the nodal von Mises stress stays within `within` (relative) of `node`'s. None when `node` is
// not on a circle hole's edge.
struct FlatArc {
  int hole = -1;
  double from = 0.0, to = 0.0;                 // rad from x, counterclockwise from `from` to `to`, in [0, 2π)
  Eigen::Vector2d from_at{0, 0}, to_at{0, 0};  // the arc's end nodes, m
  Eigen::Vector2d centre{0, 0};
  double length = 0.0;  // along the edge, m (2πr when the whole edge is within)
};
std::optional<FlatArc> flat_arc_at_hole(const PlateModel& plate, const StressField& field, int node, double within);

// The parts of the segment from `from` to `to` that lie on the plate, as parameter intervals
// [t0, t1] of t in [0, 1]: the segment is sampled at `samples` points and each change between on
// and off the plate is found by bisection, to about 1e-7 of the segment's length (a point
// within 1e-6 of an element, in its natural coordinates, counts as on it). A part thinner than
// the sampling may be missed.
std::vector<std::pair<double, double>> segment_on_plate(const MeshLocator& locator, const Eigen::Vector2d& from,
                                                        const Eigen::Vector2d& to, int samples);

}  // namespace nbar::fe
