#include "nbar/stress/section.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "model/plane_vectors.hpp"
#include "nbar/model/diagnostics.hpp"

namespace nbar {

namespace {

using Eigen::Vector2d;
using Interval = std::pair<double, double>;
using Intervals = std::vector<Interval>;

// The chords of a simple polygon along the line. Vertices exactly on the line count as lying to
// its left: the crossings are then those of a line shifted infinitesimally to the right, which
// pair up into chords without any special case for vertices or edges on the line.
Intervals polygon_chords(const std::vector<Vector2d>& poly, const Vector2d& p, const Vector2d& d) {
  const double dd = d.squaredNorm();
  std::vector<double> crossings;
  const std::size_t n = poly.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vector2d& a = poly[i];
    const Vector2d& b = poly[(i + 1) % n];
    const double ha = cross(d, a - p), hb = cross(d, b - p);
    if ((ha >= 0) == (hb >= 0)) continue;
    const double sa = d.dot(a - p) / dd, sb = d.dot(b - p) / dd;
    const double t = ha / (ha - hb);
    // From the nearer end, so that a vertex on the line gives its own s exactly.
    crossings.push_back(t <= 0.5 ? sa + t * (sb - sa) : sb + (1 - t) * (sa - sb));
  }
  std::sort(crossings.begin(), crossings.end());
  Intervals chords;
  for (std::size_t i = 0; i + 1 < crossings.size(); i += 2) chords.emplace_back(crossings[i], crossings[i + 1]);
  return chords;
}

// The open chord of the disc along the line, if the line passes through it.
void circle_chord(const Circle& c, const Vector2d& p, const Vector2d& d, Intervals& out) {
  const double len = d.norm();
  const double h = std::abs(cross(d, c.centre - p)) / len;  // distance of the centre from the line
  if (!(h < c.radius)) return;
  const double mid = d.dot(c.centre - p) / (len * len);
  const double half = std::sqrt((c.radius - h) * (c.radius + h)) / len;
  out.emplace_back(mid - half, mid + half);
}

// Sorted, overlapping or touching intervals joined, empty ones dropped.
Intervals merged(Intervals v) {
  std::sort(v.begin(), v.end());
  Intervals out;
  for (const Interval& i : v) {
    if (!(i.second > i.first)) continue;
    if (!out.empty() && i.first <= out.back().second) {
      out.back().second = std::max(out.back().second, i.second);
    } else {
      out.push_back(i);
    }
  }
  return out;
}

// Both sorted and merged.
Intervals minus(const Intervals& material, const Intervals& holes) {
  Intervals out;
  std::size_t k = 0;
  for (const Interval& m : material) {
    double from = m.first;
    while (k < holes.size() && holes[k].second <= from) ++k;
    for (std::size_t j = k; j < holes.size() && holes[j].first < m.second; ++j) {
      if (holes[j].first > from) out.emplace_back(from, holes[j].first);
      from = std::max(from, holes[j].second);
    }
    if (from < m.second) out.emplace_back(from, m.second);
  }
  return out;
}

[[noreturn]] void refuse_section(const std::string& message) { throw Error(ErrorKind::BadInput, message); }

}  // namespace

std::vector<std::pair<double, double>> section_intervals(const Region& r, const Vector2d& p, const Vector2d& d) {
  if (!p.allFinite() || !d.allFinite()) refuse_section("section_intervals: the section line is not finite");
  if (!(d.squaredNorm() > 0)) refuse_section("section_intervals: the direction of the section line is zero");
  if (has_arcs(r)) return section_intervals(straight_edged(r), p, d);
  Intervals holes;
  for (const auto& hole : r.polygon_holes) {
    const Intervals chords = polygon_chords(hole, p, d);
    holes.insert(holes.end(), chords.begin(), chords.end());
  }
  for (const Circle& hole : r.circle_holes) circle_chord(hole, p, d, holes);
  return merged(minus(merged(polygon_chords(r.outline, p, d)), merged(holes)));
}

SectionProperties section_properties(const std::vector<std::pair<double, double>>& intervals, double thickness) {
  if (!std::isfinite(thickness) || !(thickness > 0))
    refuse_section("section_properties: the thickness must be positive");
  for (std::size_t i = 0; i < intervals.size(); ++i) {
    const auto [s0, s1] = intervals[i];
    if (!std::isfinite(s0) || !std::isfinite(s1) || !(s0 <= s1) || (i > 0 && s0 < intervals[i - 1].second)) {
      std::ostringstream os;
      os << "section_properties: interval " << i << " [" << s0 << ", " << s1
         << "] is not finite, reversed, or out of order with the one before";
      refuse_section(os.str());
    }
  }
  SectionProperties out;
  double length = 0, weighted = 0;
  if (intervals.empty()) return out;
  const double ref = intervals.front().first;  // offsets from the section keep the sums accurate
  for (const auto& [s0, s1] : intervals) {
    length += s1 - s0;
    weighted += (s1 - s0) * ((s0 + s1) / 2 - ref);
  }
  if (!(length > 0)) return out;
  const double c = ref + weighted / length;
  double inertia = 0, q = 0;
  for (const auto& [s0, s1] : intervals) {
    const double a = s0 - c, b = s1 - c;
    inertia += (b - a) * (a * a + a * b + b * b) / 3;
    if (s0 < c) {
      const double top = std::min(s1, c);
      q += (top - s0) * (c - (s0 + top) / 2);
    }
  }
  out.area = thickness * length;
  out.centroid = c;
  out.inertia = thickness * inertia;
  out.s_min = intervals.front().first;
  out.s_max = intervals.back().second;
  out.max_first_moment = thickness * q;
  // Q is constant across a gap, so either of its edges reaches the maximum; pick the nearer.
  out.shear_level = c;
  for (std::size_t i = 0; i + 1 < intervals.size(); ++i) {
    const double below = intervals[i].second, above = intervals[i + 1].first;
    if (below < c && c < above) out.shear_level = (c - below <= above - c) ? below : above;
  }
  return out;
}

}  // namespace nbar
