// Curves of plate outlines — parametric curves, function profiles, splines, Béziers, ellipses —
// turned into the polyline vertices a Region carries (circular arcs stay bulges; see
// geometry.hpp). The polygonisation is adaptive and its accuracy is stated: every chord lies
// within `tolerance` of the curve at the midpoint and the quarter points of its parameter
// interval, so for a curve smooth at the scale of the chords the polygon strays at most
// `tolerance` from it, and the area it encloses differs from the curve's by at most about
// (2/3) tolerance × the curve's length.
#pragma once

#include <Eigen/Core>

#include <functional>
#include <vector>

namespace nbar {

// A curve's point at parameter s.
using CurveFunction = std::function<Eigen::Vector2d(double)>;

// The tolerance curves of an outline are polygonised to: this fraction of the diagonal of the
// outline's bounding box (0.01 mm on a 100 mm link).
constexpr double kRelativeCurveTolerance = 1e-4;

// The most vertices one curve may become (adaptive or by steps): the checks of an outline and
// its sections grow with its vertices (the crossing check as their square), so that no input
// makes them run for long.
constexpr int kMaxCurveSteps = 10000;

// The vertices of the curve from s = a to s = b, both ends included, adaptive as described
// above, starting from 16 equal parameter intervals. Throws Error(ErrorKind::BadInput) when the
// tolerance is not positive, a or b is not finite, or the curve would need more than
// `max_vertices` vertices (a curve that never settles, such as sin(1/s) near 0). Exceptions
// from `f` pass through.
std::vector<Eigen::Vector2d> sample_curve(const CurveFunction& f, double a, double b, double tolerance,
                                          int max_vertices = kMaxCurveSteps);

// The vertices at `steps` equal parameter intervals from a to b: steps + 1 vertices, b
// included (the convention of the thesis tool's `f{a, b, steps}`).
std::vector<Eigen::Vector2d> sample_curve_uniform(const CurveFunction& f, double a, double b, int steps);

// A cubic spline through points (C2), parametrised by the cumulative chord length: natural
// ends (zero curvature) when open, periodic when closed (the last point joins the first).
// Throws Error(ErrorKind::BadInput) for fewer than 2 points (3 when closed), non-finite points or
// two consecutive equal points.
class CubicSpline {
 public:
  CubicSpline(std::vector<Eigen::Vector2d> points, bool closed);
  Eigen::Vector2d operator()(double s) const;
  // The parameter of the last point (of the first again, when closed).
  double end() const { return knots_.back(); }
  // The parameters of the points, 0 first.
  const std::vector<double>& knots() const { return knots_; }
  // The points it passes through at the knots (the first again at the end when closed).
  const std::vector<Eigen::Vector2d>& points() const { return points_; }

 private:
  std::vector<Eigen::Vector2d> points_;  // with the first repeated at the end when closed
  std::vector<double> knots_;
  std::vector<Eigen::Vector2d> second_;  // second derivatives at the knots
};

// The vertices of a spline sampled as sample_curve does, each interval between two of its
// points refined separately so that every given point is a vertex.
std::vector<Eigen::Vector2d> sample_spline(const CubicSpline& spline, double tolerance);

// A cubic Bézier curve with control points p0..p3 at t in [0, 1]; a quadratic one given as a
// cubic by elevating its degree.
Eigen::Vector2d cubic_bezier(const Eigen::Vector2d& p0, const Eigen::Vector2d& p1, const Eigen::Vector2d& p2,
                             const Eigen::Vector2d& p3, double t);

// A non-uniform rational B-spline of `degree` (>= 1) with control points, knots
// (control points + degree + 1 of them, non-decreasing) and weights (empty: all 1), at u in
// [knots[degree], knots[n]]. Throws Error(ErrorKind::BadInput) when the sizes do not agree, the
// knots decrease or span nothing, or a weight is not positive.
class BSpline {
 public:
  BSpline(int degree, std::vector<Eigen::Vector2d> control, std::vector<double> knots, std::vector<double> weights);
  Eigen::Vector2d operator()(double u) const;
  double start() const { return knots_[static_cast<std::size_t>(degree_)]; }
  double end() const { return knots_[control_.size()]; }

 private:
  int degree_;
  std::vector<Eigen::Vector2d> control_;
  std::vector<double> knots_;
  std::vector<double> weights_;
};

}  // namespace nbar
