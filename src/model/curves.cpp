#include "nbar/model/curves.hpp"

#include <Eigen/Sparse>
#include <Eigen/SparseLU>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "linear_algebra.hpp"
#include "nbar/model/diagnostics.hpp"

namespace nbar {

namespace {

using Eigen::Vector2d;

[[noreturn]] void refuse_curve(const std::string& message) { throw Error(ErrorKind::BadInput, message); }

// Distance from p to the segment a-b (not the line: a curve that doubles back is caught).
double distance_to_chord(const Vector2d& p, const Vector2d& a, const Vector2d& b) {
  const Vector2d ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

constexpr int kInitialIntervals = 16;
constexpr int kMaxDepth = 40;  // halvings of an initial interval: far below any useful chord

class AdaptiveSampler {
 public:
  AdaptiveSampler(const CurveFunction& f, double tolerance, int max_vertices)
      : f_(f), tolerance_(tolerance), max_vertices_(max_vertices) {}

  // Appends the vertices after p0 up to and including p1.
  void refine(double s0, const Vector2d& p0, double s1, const Vector2d& p1, int depth) {
    const double h = s1 - s0;
    const double sm = s0 + h / 2;
    const Vector2d pm = f_(sm);
    const Vector2d q1 = f_(s0 + h / 4), q3 = f_(s0 + 3 * h / 4);
    const double deviation =
        std::max({distance_to_chord(pm, p0, p1), distance_to_chord(q1, p0, p1), distance_to_chord(q3, p0, p1)});
    if (deviation > tolerance_ && depth < kMaxDepth && sm != s0 && sm != s1) {  // s1 < s0 runs backwards
      refine(s0, p0, sm, pm, depth + 1);
      refine(sm, pm, s1, p1, depth + 1);
      return;
    }
    push(p1);
  }

  void push(const Vector2d& p) {
    if (!p.allFinite()) refuse_curve("the curve has no finite point there");
    if (static_cast<int>(vertices.size()) >= max_vertices_) {
      refuse_curve("the curve needs more than " + std::to_string(max_vertices_) +
                   " vertices to stay within the tolerance (does it oscillate without end?)");
    }
    vertices.push_back(p);
  }

  std::vector<Vector2d> vertices;

 private:
  const CurveFunction& f_;
  double tolerance_;
  int max_vertices_;
};

}  // namespace

std::vector<Vector2d> sample_curve(const CurveFunction& f, double a, double b, double tolerance, int max_vertices) {
  if (!(tolerance > 0) || !std::isfinite(tolerance)) refuse_curve("the curve tolerance must be positive");
  if (!std::isfinite(b - a)) refuse_curve("the curve's parameter range must be finite");
  AdaptiveSampler sampler(f, tolerance, max_vertices);
  Vector2d previous = f(a);
  sampler.push(previous);
  if (a == b) return sampler.vertices;
  for (int k = 1; k <= kInitialIntervals; ++k) {
    const double s0 = a + (b - a) * (k - 1) / kInitialIntervals;
    const double s1 = k == kInitialIntervals ? b : a + (b - a) * k / kInitialIntervals;
    const Vector2d next = f(s1);
    sampler.refine(s0, previous, s1, next, 0);
    previous = next;
  }
  return sampler.vertices;
}

std::vector<Vector2d> sample_curve_uniform(const CurveFunction& f, double a, double b, int steps) {
  if (steps < 1) refuse_curve("a curve needs at least 1 step");
  if (!std::isfinite(b - a)) refuse_curve("the curve's parameter range must be finite");
  std::vector<Vector2d> out;
  out.reserve(static_cast<std::size_t>(steps) + 1);
  for (int k = 0; k <= steps; ++k) {
    const Vector2d p = f(k == steps ? b : a + (b - a) * k / steps);
    if (!p.allFinite()) refuse_curve("the curve has no finite point there");
    out.push_back(p);
  }
  return out;
}

CubicSpline::CubicSpline(std::vector<Vector2d> points, bool closed) : points_(std::move(points)) {
  const std::size_t given = points_.size();
  if (given < (closed ? 3u : 2u)) {
    refuse_curve(std::string("a spline needs at least ") + (closed ? "3 points when closed" : "2 points"));
  }
  for (const Vector2d& p : points_)
    if (!p.allFinite()) refuse_curve("a spline's points must be finite");
  if (closed) points_.push_back(points_.front());
  knots_.push_back(0.0);
  for (std::size_t i = 1; i < points_.size(); ++i) {
    const double h = (points_[i] - points_[i - 1]).norm();
    if (!(h > 0)) refuse_curve("a spline passes through point " + std::to_string(i % given + 1) + " twice in a row");
    knots_.push_back(knots_.back() + h);
  }
  const std::size_t n = points_.size();  // knots; intervals n - 1
  second_.assign(n, Vector2d::Zero());
  if (n == 2) return;  // a straight segment
  // Unknowns: the second derivatives at the interior knots (natural) or at every knot but the
  // repeated last one (periodic, indices taken cyclically).
  const std::size_t m = closed ? n - 1 : n - 2;
  const auto h = [&](std::size_t i) { return knots_[i + 1] - knots_[i]; };
  Eigen::SparseMatrix<double> a(static_cast<Eigen::Index>(m), static_cast<Eigen::Index>(m));
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixX2d rhs(static_cast<Eigen::Index>(m), 2);
  for (std::size_t row = 0; row < m; ++row) {
    const std::size_t i = closed ? row : row + 1;       // the knot of this equation
    const std::size_t before = i == 0 ? n - 2 : i - 1;  // interval before it (cyclic when closed)
    const double h0 = h(before), h1 = h(i);
    const Vector2d slope0 = (points_[before + 1] - points_[before]) / h0;
    const Vector2d slope1 = (points_[i + 1] - points_[i]) / h1;
    rhs.row(static_cast<Eigen::Index>(row)) = 6 * (slope1 - slope0).transpose();
    const auto r = static_cast<int>(row);
    entries.emplace_back(r, r, 2 * (h0 + h1));
    if (closed) {
      entries.emplace_back(r, static_cast<int>((row + m - 1) % m), h0);
      entries.emplace_back(r, static_cast<int>((row + 1) % m), h1);
    } else {
      if (row > 0) entries.emplace_back(r, r - 1, h0);
      if (row + 1 < m) entries.emplace_back(r, r + 1, h1);
    }
  }
  a.setFromTriplets(entries.begin(), entries.end());  // duplicates (m = 2, closed) add up
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(a);
  if (lu.info() != Eigen::Success) refuse_curve("the spline's equations could not be solved");
  const Eigen::MatrixX2d solved = lu.solve(rhs);
  for (std::size_t row = 0; row < m; ++row) {
    second_[closed ? row : row + 1] = solved.row(static_cast<Eigen::Index>(row)).transpose();
  }
  if (closed) second_.back() = second_.front();
}

Vector2d CubicSpline::operator()(double s) const {
  const auto upper = std::upper_bound(knots_.begin(), knots_.end(), s);
  std::size_t i = upper == knots_.begin() ? 0 : static_cast<std::size_t>(upper - knots_.begin()) - 1;
  i = std::min(i, knots_.size() - 2);
  const double h = knots_[i + 1] - knots_[i];
  const double u = knots_[i + 1] - s, v = s - knots_[i];
  return second_[i] * (u * u * u / (6 * h)) + second_[i + 1] * (v * v * v / (6 * h)) +
         (points_[i] / h - second_[i] * h / 6) * u + (points_[i + 1] / h - second_[i + 1] * h / 6) * v;
}

std::vector<Vector2d> sample_spline(const CubicSpline& spline, double tolerance) {
  const std::vector<double>& knots = spline.knots();
  std::vector<Vector2d> out{spline.points().front()};
  for (std::size_t i = 0; i + 1 < knots.size(); ++i) {
    std::vector<Vector2d> piece = sample_curve(std::cref(spline), knots[i], knots[i + 1], tolerance);
    piece.back() = spline.points()[i + 1];  // exactly, so that a closed spline ends where it starts
    out.insert(out.end(), piece.begin() + 1, piece.end());
  }
  return out;
}

Vector2d cubic_bezier(const Vector2d& p0, const Vector2d& p1, const Vector2d& p2, const Vector2d& p3, double t) {
  const double u = 1 - t;
  return u * u * u * p0 + 3 * u * u * t * p1 + 3 * u * t * t * p2 + t * t * t * p3;
}

BSpline::BSpline(int degree, std::vector<Vector2d> control, std::vector<double> knots, std::vector<double> weights)
    : degree_(degree), control_(std::move(control)), knots_(std::move(knots)), weights_(std::move(weights)) {
  if (degree_ < 1 || degree_ > 30) refuse_curve("a B-spline's degree must be 1 to 30, not " + std::to_string(degree_));
  if (control_.size() < static_cast<std::size_t>(degree_) + 1) {
    refuse_curve("a B-spline of degree " + std::to_string(degree_) + " needs at least " + std::to_string(degree_ + 1) +
                 " control points, not " + std::to_string(control_.size()));
  }
  if (knots_.size() != control_.size() + static_cast<std::size_t>(degree_) + 1) {
    refuse_curve("a B-spline with " + std::to_string(control_.size()) + " control points of degree " +
                 std::to_string(degree_) + " needs " + std::to_string(control_.size() + degree_ + 1) + " knots, not " +
                 std::to_string(knots_.size()));
  }
  if (weights_.empty()) weights_.assign(control_.size(), 1.0);
  if (weights_.size() != control_.size()) refuse_curve("a B-spline needs one weight per control point");
  for (std::size_t i = 0; i < knots_.size(); ++i) {
    if (!std::isfinite(knots_[i]) || (i > 0 && knots_[i] < knots_[i - 1]))
      refuse_curve("a B-spline's knots must not decrease");
  }
  for (double w : weights_)
    if (!(w > 0) || !std::isfinite(w)) refuse_curve("a B-spline's weights must be positive");
  for (const Vector2d& p : control_)
    if (!p.allFinite()) refuse_curve("a B-spline's control points must be finite");
  if (!(end() > start())) refuse_curve("a B-spline's knots span nothing");
}

Vector2d BSpline::operator()(double u) const {
  const auto p = static_cast<std::size_t>(degree_);
  const std::size_t n = control_.size();
  u = std::clamp(u, start(), end());
  // The knot span k with knots[k] <= u < knots[k + 1], the last non-empty one at the end.
  const auto after = std::upper_bound(knots_.begin() + static_cast<std::ptrdiff_t>(p + 1),
                                      knots_.begin() + static_cast<std::ptrdiff_t>(n), u);
  const std::size_t k = static_cast<std::size_t>(after - knots_.begin()) - 1;
  // De Boor's algorithm in homogeneous coordinates (w x, w y, w).
  std::vector<Eigen::Vector3d> d(p + 1);
  for (std::size_t j = 0; j <= p; ++j) {
    const std::size_t i = k - p + j;
    d[j] << weights_[i] * control_[i], weights_[i];
  }
  for (std::size_t r = 1; r <= p; ++r) {
    for (std::size_t j = p; j >= r; --j) {
      const std::size_t i = k - p + j;
      const double span = knots_[i + p - r + 1] - knots_[i];
      const double alpha = span > 0 ? (u - knots_[i]) / span : 0.0;
      d[j] = (1 - alpha) * d[j - 1] + alpha * d[j];
    }
  }
  return d[p].head<2>() / d[p].z();
}

}  // namespace nbar
