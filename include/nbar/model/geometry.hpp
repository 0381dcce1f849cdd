// Exact plane geometry of flat link plates: area, centroid and second moments of a polygon
// minus polygonal and circular holes, and of the part of such a plate on one side of a line.
// Everything is closed form (Green's theorem for polygons, circle and circular-segment
// formulas for round holes), so results are exact up to rounding. All quantities SI.
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

namespace nbar {

struct Circle {
  Eigen::Vector2d centre;
  double radius;
};

// A flat plate: an outline (any orientation, simple, >= 3 vertices, or >= 2 when some of its
// edges are arcs) minus holes.
//
// Edges may be circular arcs, given by a bulge as DXF writes it: bulges[i] makes the edge from
// vertex i to vertex i + 1 (the last vertex: back to vertex 0) an arc whose included angle is
// 4 atan(bulge), counterclockwise when positive; 0 is a straight edge, ±1 a half circle. An
// empty list means every edge is straight; otherwise it has one bulge per vertex.
// `polygon_hole_bulges` is empty or has one such list per polygon hole.
struct Region {
  std::vector<Eigen::Vector2d> outline;
  std::vector<std::vector<Eigen::Vector2d>> polygon_holes;
  std::vector<Circle> circle_holes;
  std::vector<double> outline_bulges;
  std::vector<std::vector<double>> polygon_hole_bulges;
};

// A circular arc from a start angle through a signed sweep (rad, counterclockwise positive).
struct Arc {
  Eigen::Vector2d centre;
  double radius;
  double start_angle;
  double sweep;
};

// The arc from a to b with the given bulge (non-zero, finite; a != b).
Arc arc_from_bulge(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double bulge);

// The bulge of the arc from a to b through m. Throws Error(ErrorKind::BadInput) when m is a or b, or
// lies on the line through a and b but not between them (no arc passes through it).
double bulge_through(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& m);

// Some edge of the outline or of a polygon hole is an arc.
bool has_arcs(const Region& r);

// r with every arc replaced by chords that stray at most `chord_tolerance` (> 0) from it; the
// chords' ends lie on the arc. Straight edges and circle holes are kept as they are.
Region polygonised(const Region& r, double chord_tolerance);

// The one polygonisation used wherever straight edges are needed (sections, clipping, drawing,
// validation): chords within 1e-5 of the outline's bounding-box diagonal. r itself when it has
// no arcs.
Region straight_edged(const Region& r);
constexpr double kRelativeChordTolerance = 1e-5;

struct AreaProperties {
  double area = 0;                 // m^2
  Eigen::Vector2d centroid{0, 0};  // m
  double ixx = 0, iyy = 0, ixy = 0;  // about the centroid, axes parallel to x, y: ∫y'^2 dA, ∫x'^2 dA, ∫x'y' dA (m^4)
  double polar() const { return ixx + iyy; }
};

// Second moments of an area about some point, axes parallel to x, y (m^4).
struct SecondMoments {
  double ixx = 0, iyy = 0, ixy = 0;
  double polar() const { return ixx + iyy; }
};

// Rigid-body mass of a plate of uniform density and thickness.
struct PlateMass {
  double mass = 0;               // kg
  Eigen::Vector2d centre{0, 0};  // centre of mass, m
  double inertia = 0;            // about the centre of mass, kg m^2
};

// The properties of the plate r (which must pass check_region; it is not re-checked here).
// Exact for arcs too: each arc adds the closed-form moments of its circular segment.
AreaProperties area_properties(const Region& r);

// The part of r on the side n·(x − p) >= 0 of the line through p with normal n (not necessarily
// unit). Arcs are cut as straight_edged(r). An empty part has area 0 and every other member 0. Throws
// Error(ErrorKind::BadInput) when n is zero or p, n are not finite.
AreaProperties clipped_area_properties(const Region& r, const Eigen::Vector2d& p, const Eigen::Vector2d& n);

// Whether an edge of the closed polygon p and one of q share a point (crossing or touching).
bool polygons_meet(const std::vector<Eigen::Vector2d>& p, const std::vector<Eigen::Vector2d>& q);

// Whether the circle's closed disc comes no nearer than its radius to every edge of the closed
// polygon.
bool circle_clear_of_edges(const Circle& c, const std::vector<Eigen::Vector2d>& polygon);

// How far x lies outside r's outline (straight_edged): 0 inside it or on it. Holes do not count:
// a pin sits in its hole.
double distance_outside_outline(const Region& r, const Eigen::Vector2d& x);

// Throws Error(ErrorKind::BadInput) with a readable message when r is not a valid plate: fewer than 3
// vertices, non-finite values, zero area, repeated consecutive vertices, self-intersecting
// outline or hole, a hole not strictly inside the outline (touching counts as outside), holes
// overlapping or touching each other, a non-positive radius.
void check_region(const Region& r);

// Every "edge a-b" a check_region message names (a, b: the region's vertex indices), with the
// span [begin, end) of that mention in the message, in order: for readers that point the user
// at the lines those vertices came from.
struct EdgeMention {
  std::size_t begin = 0, end = 0;
  std::size_t from = 0, to = 0;
};
std::vector<EdgeMention> edge_mentions(const std::string& message);

// A straight bar: the rectangle of `width` around the segment p->q, extended by `margin` beyond
// each end, with round holes of the given radii centred at p and q (radius 0 = no hole).
// Throws Error(ErrorKind::BadInput) unless the result is a valid plate: p != q, width > 0,
// margin >= 0, each hole radius < width/2 and < margin, and the two holes apart.
Region make_bar(const Eigen::Vector2d& p, const Eigen::Vector2d& q, double width, double margin, double hole_radius_p,
                double hole_radius_q);

// The second moments of a about `point` (parallel-axis theorem).
SecondMoments second_moments_about(const AreaProperties& a, const Eigen::Vector2d& point);

// The union of two areas that do not overlap.
AreaProperties combine(const AreaProperties& a, const AreaProperties& b);

// What is left of `whole` once `part` (an area inside it) is taken away. Returns the empty
// AreaProperties when nothing is left.
AreaProperties subtract(const AreaProperties& whole, const AreaProperties& part);

// The properties of the area moved rigidly: rotated by `angle` (rad, counterclockwise) about
// the origin, then shifted by `shift`. This puts a plate drawn in a body frame into the world.
AreaProperties transformed(const AreaProperties& a, double angle, const Eigen::Vector2d& shift);

// mass = density * thickness * area, inertia = density * thickness * polar second moment.
// Throws Error(ErrorKind::BadInput) unless density >= 0 and thickness > 0 (both finite).
PlateMass plate_mass(const AreaProperties& a, double density, double thickness);

}  // namespace nbar
