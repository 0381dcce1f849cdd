// Cross-sections of a flat link plate cut by a straight line, for beam stresses: the cut runs
// across the plate in its plane, so the section is a set of segments along the line, each as
// wide (out of plane) as the plate is thick. Used for σ = N/A ± M c/I at both extreme fibres
// and τ = V Q / (I t) with t = thickness.
#pragma once

#include <Eigen/Core>

#include <utility>
#include <vector>

#include "nbar/model/geometry.hpp"

namespace nbar {

// Material of region r along the line through p with direction d: the intervals [s0, s1] of the
// parameter s (point = p + s d) inside the outline and outside every hole, sorted, merged, each
// of positive length. With d of unit length, s is a distance. A line running exactly along an
// edge of the outline or of a hole gets the limit of lines shifted slightly to the right of d
// (sections are meant to cross the plate). r should pass check_region. Throws
// Error(ErrorKind::BadInput) when d is zero or p, d are not finite.
std::vector<std::pair<double, double>> section_intervals(const Region& r, const Eigen::Vector2d& p,
                                                         const Eigen::Vector2d& d);

struct SectionProperties {
  double area = 0;              // thickness * total length
  double centroid = 0;          // s of the centroid (neutral axis for in-plane bending)
  double inertia = 0;           // thickness * ∫ (s - centroid)^2 ds over the material
  double s_min = 0, s_max = 0;  // extreme fibres (s of the first and last material)
  double max_first_moment =
      0;                   // max over levels s of |Q(s)|, Q(s) = thickness * ∫_{material below s} (s' - centroid) ds'
  double shear_level = 0;  // the level s where that maximum is reached
};

// |Q| is largest at the centroid. When the centroid falls in a gap between intervals, Q is the
// same across the gap and shear_level is the nearer material edge of the gap (the lower one on
// a tie), where the stress actually acts. No intervals give all zeros. Throws
// Error(ErrorKind::BadInput) when the intervals are not finite, sorted and disjoint with s0 <= s1, or
// the thickness is not positive.
SectionProperties section_properties(const std::vector<std::pair<double, double>>& intervals, double thickness);

}  // namespace nbar
