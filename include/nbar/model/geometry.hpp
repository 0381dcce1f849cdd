// Exact plane geometry of flat link plates: area, centroid and second moments of a polygon
// minus polygonal and circular holes, and of the part of such a plate on one side of a line.
// Everything is closed form (Green's theorem for polygons, circle and circular-segment
// formulas for round holes), so results are exact up to rounding. All quantities SI.
#pragma once

#include <Eigen/Core>

#include <vector>

namespace nbar {

struct Circle {
  Eigen::Vector2d centre;
  double radius;
};

// A flat plate: an outline polygon (any orientation, simple, >= 3 vertices) minus holes.
struct Region {
  std::vector<Eigen::Vector2d> outline;
  std::vector<std::vector<Eigen::Vector2d>> polygon_holes;
  std::vector<Circle> circle_holes;
};

struct AreaProperties {
  double area = 0;                   // m^2
  Eigen::Vector2d centroid{0, 0};    // m
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
AreaProperties area_properties(const Region& r);

// The part of r on the side n·(x − p) >= 0 of the line through p with normal n (not necessarily
// unit). An empty part has area 0 and every other member 0. Throws std::invalid_argument when n
// is zero or p, n are not finite.
AreaProperties clipped_area_properties(const Region& r, const Eigen::Vector2d& p, const Eigen::Vector2d& n);

// Throws std::invalid_argument with a readable message when r is not a valid plate: fewer than 3
// vertices, non-finite values, zero area, repeated consecutive vertices, self-intersecting
// outline or hole, a hole not strictly inside the outline (touching counts as outside), holes
// overlapping or touching each other, a non-positive radius.
void check_region(const Region& r);

// A straight bar: the rectangle of `width` around the segment p->q, extended by `margin` beyond
// each end, with round holes of the given radii centred at p and q (radius 0 = no hole).
// Throws std::invalid_argument unless the result is a valid plate: p != q, width > 0,
// margin >= 0, each hole radius < width/2 and < margin, and the two holes apart.
Region make_bar(const Eigen::Vector2d& p, const Eigen::Vector2d& q, double width, double margin,
                double hole_radius_p, double hole_radius_q);

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
// Throws std::invalid_argument unless density >= 0 and thickness > 0 (both finite).
PlateMass plate_mass(const AreaProperties& a, double density, double thickness);

}  // namespace nbar
