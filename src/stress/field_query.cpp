#include "nbar/stress/field_query.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

#include "t6_element.hpp"

namespace nbar::fe {

namespace {

// A point this close to an element, in natural coordinates, is in it: the second pass of
// locate() takes it when no element holds the point strictly (a point on a curved edge, whose
// parabola and the true circle differ by ~1e-10 of the hole's radius).
constexpr double kEdgeSlack = 1e-6;

}  // namespace

PointStress stress_state(const Eigen::Vector2d& at, const Eigen::Vector3d& s) {
  PointStress out;
  out.at = at;
  out.stress = s;
  out.von_mises = std::sqrt(std::max(0.0, s[0] * s[0] - s[0] * s[1] + s[1] * s[1] + 3 * s[2] * s[2]));
  const double centre = 0.5 * (s[0] + s[1]), radius = std::hypot(0.5 * (s[0] - s[1]), s[2]);
  out.principal_1 = centre + radius;
  out.principal_2 = centre - radius;
  out.principal_angle = 0.5 * std::atan2(2 * s[2], s[0] - s[1]);
  return out;
}

Eigen::Vector3d rotate_stress(const Eigen::Vector3d& s, double angle) {
  const double c = std::cos(angle), n = std::sin(angle);
  return {c * c * s[0] + n * n * s[1] + 2 * c * n * s[2], n * n * s[0] + c * c * s[1] - 2 * c * n * s[2],
          c * n * (s[1] - s[0]) + (c * c - n * n) * s[2]};
}

MeshLocator::MeshLocator(const TriMesh& mesh) : mesh_(mesh) {
  if (mesh.nodes.empty() || mesh.triangles.empty()) return;
  Eigen::Vector2d high = mesh.nodes.front();
  low_ = high;
  for (const Eigen::Vector2d& p : mesh.nodes) low_ = low_.cwiseMin(p), high = high.cwiseMax(p);
  const Eigen::Vector2d span = (high - low_).cwiseMax(1e-300);
  // About two elements a cell.
  const double cells = std::max(1.0, mesh.triangles.size() / 2.0);
  cell_ = std::sqrt(span.x() * span.y() / cells);
  if (!(cell_ > 0)) cell_ = std::max(span.x(), span.y());
  columns_ = std::clamp(static_cast<int>(span.x() / cell_) + 1, 1, 4096);
  rows_ = std::clamp(static_cast<int>(span.y() / cell_) + 1, 1, 4096);
  cell_ = std::max(span.x() / columns_, span.y() / rows_) * (1 + 1e-12);
  cells_.assign(static_cast<std::size_t>(columns_) * rows_, {});
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    Eigen::Vector2d lo = mesh.nodes[mesh.triangles[t][0]], hi = lo;
    for (int v : mesh.triangles[t]) lo = lo.cwiseMin(mesh.nodes[v]), hi = hi.cwiseMax(mesh.nodes[v]);
    // A curved edge bulges past its three nodes by at most a quarter of its sagitta's span.
    const Eigen::Vector2d slack = Eigen::Vector2d::Constant(0.05 * (hi - lo).norm());
    lo -= slack, hi += slack;
    const int c0 = std::clamp(static_cast<int>((lo.x() - low_.x()) / cell_), 0, columns_ - 1);
    const int c1 = std::clamp(static_cast<int>((hi.x() - low_.x()) / cell_), 0, columns_ - 1);
    const int r0 = std::clamp(static_cast<int>((lo.y() - low_.y()) / cell_), 0, rows_ - 1);
    const int r1 = std::clamp(static_cast<int>((hi.y() - low_.y()) / cell_), 0, rows_ - 1);
    for (int r = r0; r <= r1; ++r)
      for (int c = c0; c <= c1; ++c) cells_[static_cast<std::size_t>(r) * columns_ + c].push_back(static_cast<int>(t));
  }
}

std::optional<MeshLocator::Location> MeshLocator::locate(const Eigen::Vector2d& at) const {
  if (cells_.empty() || !at.allFinite()) return std::nullopt;
  const Eigen::Vector2d local = (at - low_) / cell_;
  const double reach = 1e-9;  // a point on the grid's edge is in its last cell
  if (local.x() < -reach || local.y() < -reach || local.x() > columns_ + reach || local.y() > rows_ + reach)
    return std::nullopt;
  const int c = std::clamp(static_cast<int>(local.x()), 0, columns_ - 1);
  const int r = std::clamp(static_cast<int>(local.y()), 0, rows_ - 1);
  const std::vector<int>& candidates = cells_[static_cast<std::size_t>(r) * columns_ + c];
  for (double tolerance : {1e-9, kEdgeSlack})
    for (int t : candidates)
      if (const auto natural = t6::locate(t6::element_nodes(mesh_, t), at, tolerance)) return Location{t, *natural};
  return std::nullopt;
}

std::optional<PointStress> stress_at(const MeshLocator& locator, const StressField& field, const Eigen::Vector2d& at) {
  const std::optional<MeshLocator::Location> where = locator.locate(at);
  if (!where) return std::nullopt;
  const Eigen::Matrix<double, 6, 1> n = t6::shape(where->natural.x(), where->natural.y());
  Eigen::Vector3d s = Eigen::Vector3d::Zero();
  for (int i = 0; i < 6; ++i) s += n[i] * field.stress.at(locator.mesh().triangles[where->element][i]);
  return stress_state(at, s);
}

std::vector<LineSample> stress_along(const MeshLocator& locator, const StressField& field, const Eigen::Vector2d& from,
                                     const Eigen::Vector2d& to, int samples) {
  samples = std::max(samples, 2);
  std::vector<LineSample> out(samples);
  const double length = (to - from).norm();
  for (int i = 0; i < samples; ++i) {
    const double t = static_cast<double>(i) / (samples - 1);
    out[i].arc = t * length;
    out[i].at = i == samples - 1 ? to : Eigen::Vector2d(from + t * (to - from));
    out[i].stress = stress_at(locator, field, out[i].at);
  }
  return out;
}

std::vector<HoleSample> stress_around_hole(const PlateModel& plate, const StressField& field, int hole) {
  const auto [centre, radius] = plate.hole_circle(hole);  // throws for a hole the plate lacks
  std::set<int> nodes;
  for (const BoundaryEdge& e : plate.mesh().boundary)
    if (e.on.kind == BoundaryTag::Kind::circle_hole && e.on.index == hole) nodes.insert(e.nodes.begin(), e.nodes.end());
  std::vector<HoleSample> out;
  out.reserve(nodes.size());
  for (int node : nodes) {
    HoleSample s;
    s.node = node;
    const Eigen::Vector2d arm = plate.mesh().nodes[node] - centre;
    s.angle = std::atan2(arm.y(), arm.x());
    if (s.angle < 0) s.angle += 2 * std::numbers::pi;
    s.stress = stress_state(plate.mesh().nodes[node], field.stress.at(node));
    const Eigen::Vector3d polar = rotate_stress(s.stress.stress, s.angle);  // x' radial, y' hoop
    s.radial = polar[0];
    s.hoop = polar[1];
    out.push_back(s);
  }
  std::sort(out.begin(), out.end(), [](const HoleSample& a, const HoleSample& b) { return a.angle < b.angle; });
  return out;
}

std::optional<FlatArc> flat_arc_at_hole(const PlateModel& plate, const StressField& field, int node, double within) {
  int hole = -1;
  for (const BoundaryEdge& e : plate.mesh().boundary)
    if (e.on.kind == BoundaryTag::Kind::circle_hole && std::find(e.nodes.begin(), e.nodes.end(), node) != e.nodes.end())
      hole = e.on.index;
  if (hole < 0) return std::nullopt;
  const std::vector<HoleSample> edge = stress_around_hole(plate, field, hole);
  const long n = static_cast<long>(edge.size());
  long k = 0;
  while (k < n && edge[k].node != node) ++k;
  const double floor = (1.0 - within) * edge[k].stress.von_mises;
  const auto at = [&](long i) -> const HoleSample& { return edge[((i % n) + n) % n]; };
  long back = 0, ahead = 0;  // nodes within, each way from k
  while (back + ahead + 1 < n && at(k - back - 1).stress.von_mises >= floor) ++back;
  while (back + ahead + 1 < n && at(k + ahead + 1).stress.von_mises >= floor) ++ahead;
  FlatArc arc;
  arc.hole = hole;
  const auto [centre, radius] = plate.hole_circle(hole);
  arc.centre = centre;
  arc.from = at(k - back).angle;
  arc.to = at(k + ahead).angle;
  arc.from_at = plate.mesh().nodes[at(k - back).node];
  arc.to_at = plate.mesh().nodes[at(k + ahead).node];
  const bool whole = back + ahead + 1 == n;
  double span = arc.to - arc.from;
  if (span < 0.0) span += 2 * std::numbers::pi;
  arc.length = radius * (whole ? 2 * std::numbers::pi : span);
  return arc;
}

std::vector<std::pair<double, double>> segment_on_plate(const MeshLocator& locator, const Eigen::Vector2d& from,
                                                        const Eigen::Vector2d& to, int samples) {
  samples = std::max(samples, 2);
  const auto on = [&](double t) { return locator.locate(from + t * (to - from)).has_value(); };
  // The parameter where on(t) changes between `a` (whose state is `state_a`) and `b`.
  const auto crossing = [&](double a, double b, bool state_a) {
    while (b - a > 1e-9) {
      const double m = 0.5 * (a + b);
      (on(m) == state_a ? a : b) = m;
    }
    return 0.5 * (a + b);
  };
  std::vector<std::pair<double, double>> parts;
  double previous_t = 0;
  bool previous = on(0);
  double start = 0;
  for (int i = 1; i < samples; ++i) {
    const double t = static_cast<double>(i) / (samples - 1);
    const bool now = on(t);
    if (now != previous) {
      const double at = crossing(previous_t, t, previous);
      if (now)
        start = at;
      else
        parts.emplace_back(start, at);
    }
    previous = now;
    previous_t = t;
  }
  if (previous) parts.emplace_back(start, 1.0);
  return parts;
}

}  // namespace nbar::fe
