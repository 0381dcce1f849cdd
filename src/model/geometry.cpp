#include "nbar/model/geometry.hpp"

#include <Eigen/Geometry>
#include <cctype>
#include <string_view>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "model/box_index.hpp"
#include "nbar/model/diagnostics.hpp"

namespace nbar {

namespace {

using Eigen::Vector2d;
using Polygon = std::vector<Vector2d>;
constexpr double kPi = std::numbers::pi;

// Raw moments ∫1, ∫x, ∫y, ∫x², ∫y², ∫xy dA about a reference origin. Unlike centroidal
// properties they simply add and subtract, so regions are assembled in this form and
// converted once at the end. The origin is chosen near the region: moments about a far
// point would lose the centroidal second moments to cancellation.
//
// `scale` sums the magnitudes of every area term that went into `a`: an area within rounding
// of zero relative to it is nothing (a cut along an edge, a clip that only grazes a vertex),
// and must not be divided by to find a centroid.
struct Moments {
  double a = 0, sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
  double scale = 0;

  Moments& operator+=(const Moments& m) {
    a += m.a, sx += m.sx, sy += m.sy, sxx += m.sxx, syy += m.syy, sxy += m.sxy;
    scale += m.scale;
    return *this;
  }
  Moments& operator-=(const Moments& m) {
    a -= m.a, sx -= m.sx, sy -= m.sy, sxx -= m.sxx, syy -= m.syy, sxy -= m.sxy;
    scale += m.scale;
    return *this;
  }
  // Reverses orientation: the sign of every moment, not the size of the terms.
  Moments& negate() {
    a = -a, sx = -sx, sy = -sy, sxx = -sxx, syy = -syy, sxy = -sxy;
    return *this;
  }
};

Moments to_moments(const AreaProperties& p, const Vector2d& origin) {
  const Vector2d c = p.centroid - origin;
  Moments m;
  m.a = p.area;
  m.sx = p.area * c.x();
  m.sy = p.area * c.y();
  m.sxx = p.iyy + p.area * c.x() * c.x();
  m.syy = p.ixx + p.area * c.y() * c.y();
  m.sxy = p.ixy + p.area * c.x() * c.y();
  m.scale = std::abs(p.area);
  return m;
}

AreaProperties to_properties(const Moments& m, const Vector2d& origin) {
  AreaProperties p;
  if (!(m.a > 64 * std::numeric_limits<double>::epsilon() * m.scale)) return p;
  const Vector2d c(m.sx / m.a, m.sy / m.a);
  p.area = m.a;
  p.centroid = origin + c;
  p.ixx = m.syy - m.sy * c.y();
  p.iyy = m.sxx - m.sx * c.x();
  p.ixy = m.sxy - m.sx * c.y();
  return p;
}

// Green's theorem over the closed polygon: each edge contributes a closed-form term. Signed:
// positive for a counterclockwise polygon. Exact also for the degenerate polygons produced by
// clipping (edges doubled back along the cut line cancel).
Moments polygon_moments(const Polygon& poly, const Vector2d& origin) {
  Moments m;
  const std::size_t n = poly.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vector2d a = poly[i] - origin, b = poly[(i + 1) % n] - origin;
    const double c = a.x() * b.y() - b.x() * a.y();
    m.a += c;
    m.scale += std::abs(c);
    m.sx += (a.x() + b.x()) * c;
    m.sy += (a.y() + b.y()) * c;
    m.sxx += (a.x() * a.x() + a.x() * b.x() + b.x() * b.x()) * c;
    m.syy += (a.y() * a.y() + a.y() * b.y() + b.y() * b.y()) * c;
    m.sxy += (a.x() * (2 * a.y() + b.y()) + b.x() * (a.y() + 2 * b.y())) * c;
  }
  m.a /= 2;
  m.scale /= 2;
  m.sx /= 6;
  m.sy /= 6;
  m.sxx /= 12;
  m.syy /= 12;
  m.sxy /= 24;
  return m;
}

double signed_area(const Polygon& poly) { return poly.empty() ? 0.0 : polygon_moments(poly, poly[0]).a; }

Moments disc_moments(const Circle& c, const Vector2d& origin) {
  AreaProperties p;
  p.area = kPi * c.radius * c.radius;
  p.centroid = c.centre;
  p.ixx = p.iyy = kPi * std::pow(c.radius, 4) / 4;
  return to_moments(p, origin);
}

// The circular segment {u >= h} of a disc of radius r about its centre, 0 <= h < r, in a local
// frame with u along the segment's axis and v along the chord: area, ∫u, ∫u², ∫v² (∫v and ∫uv
// vanish by symmetry). With half-chord s and half-angle θ (cos θ = h/r), the textbook forms
// A = r²(θ − sinθcosθ), ∫u² = r⁴/4 (θ − sin4θ/4), ∫v² = r⁴ (θ/4 − sin2θ/6 + sin4θ/48) are
// written in h and s, and θ comes from atan2 rather than acos, which is ill-conditioned for
// thin segments.
struct Segment {
  double a, su, suu, svv;
};

Segment circular_segment(double r, double h) {
  const double s = std::sqrt((r - h) * (r + h));
  const double theta = std::atan2(s, h);
  const double r2 = r * r, r4 = r2 * r2;
  const double sh = s * h, sh_cos4 = sh * (h * h - s * s);
  return {r2 * theta - sh, 2.0 / 3.0 * s * s * s, r4 * theta / 4 - sh_cos4 / 4,
          r4 * theta / 4 - sh * r2 / 3 + sh_cos4 / 12};
}

// The part of disc c on the side m·(x − c.centre) >= -offset (m unit), as raw moments about
// origin. Segments larger than half the disc are the disc minus the small segment on the other
// side, so that the two sides of a cut add up to the disc to rounding.
Moments clipped_disc_moments(const Circle& c, const Vector2d& m, double offset, const Vector2d& origin) {
  const double r = c.radius, h = -offset;
  if (h >= r) return {};
  if (h <= -r) return disc_moments(c, origin);
  const bool small = h >= 0;
  const Vector2d axis = small ? m : Vector2d(-m);
  const Vector2d chord(-axis.y(), axis.x());
  const Segment g = circular_segment(r, std::abs(h));
  const Vector2d k = c.centre - origin;
  // x − origin = k + u axis + v chord, integrated term by term.
  const Vector2d first = g.a * k + g.su * axis;
  const Eigen::Matrix2d second = g.a * k * k.transpose() + g.su * (k * axis.transpose() + axis * k.transpose()) +
                                 g.suu * axis * axis.transpose() + g.svv * chord * chord.transpose();
  const Moments seg{g.a, first.x(), first.y(), second(0, 0), second(1, 1), second(0, 1), g.a};
  if (small) return seg;
  Moments rest = disc_moments(c, origin);
  rest -= seg;
  return rest;
}

// Bulges smaller than this are straight edges: below it the segment's closed forms (terms in r⁴
// with r ~ chord/bulge) lose more to cancellation than the segment itself weighs.
constexpr double kStraightBulge = 1e-8;

bool is_arc(double bulge) { return std::abs(bulge) > kStraightBulge; }

// Beyond this the arc is all but a full circle and its radius, chord / bulge, drowns the chord.
constexpr double kLargestBulge = 1e6;

double bulge_of(const std::vector<double>& bulges, std::size_t i) { return bulges.empty() ? 0.0 : bulges[i]; }

// The circular segment between the chord a-b and the arc of the given bulge, as raw moments
// about origin: the region's own moments, whatever side of the chord it is on.
Moments arc_segment_moments(const Vector2d& a, const Vector2d& b, double bulge, const Vector2d& origin) {
  const Vector2d chord = b - a;
  const double half = chord.norm() / 2;
  const Vector2d right = Vector2d(chord.y(), -chord.x()).normalized();
  const double radius = half * (1 + bulge * bulge) / (2 * std::abs(bulge));
  const Vector2d axis = bulge > 0 ? right : Vector2d(-right);  // from the centre towards the arc's middle
  const Vector2d arc_middle = (a + b) / 2 + bulge * half * right;
  const Circle circle{arc_middle - radius * axis, radius};
  // The segment is {axis·(x − centre) >= radius − sagitta}.
  return clipped_disc_moments(circle, axis, -(radius - std::abs(bulge) * half), origin);
}

// Green's theorem along a ring whose edges may be arcs: an arc's line integral is its chord's
// plus that over the boundary of its segment, which bulges to the right of a counterclockwise
// ring's edge (outwards) for a positive bulge. Signed like polygon_moments.
Moments ring_moments(const Polygon& ring, const std::vector<double>& bulges, const Vector2d& origin) {
  Moments m = polygon_moments(ring, origin);
  for (std::size_t i = 0; i < bulges.size(); ++i) {
    if (!is_arc(bulges[i])) continue;
    const Moments seg = arc_segment_moments(ring[i], ring[(i + 1) % ring.size()], bulges[i], origin);
    if (bulges[i] > 0) {
      m += seg;
    } else {
      m -= seg;
    }
  }
  return m;
}

Moments unsigned_ring_moments(const Polygon& ring, const std::vector<double>& bulges, const Vector2d& origin) {
  Moments m = ring_moments(ring, bulges, origin);
  if (m.a < 0) m.negate();
  return m;
}

void include_in_box(const Vector2d& v, Vector2d& lo, Vector2d& hi) {
  lo = lo.cwiseMin(v);
  hi = hi.cwiseMax(v);
}

// The ring's bounding box including the arcs' bulges: an arc reaches centre ± radius along an
// axis when its sweep passes that direction.
void ring_box(const Polygon& ring, const std::vector<double>& bulges, Vector2d& lo, Vector2d& hi) {
  for (std::size_t i = 0; i < ring.size(); ++i) {
    include_in_box(ring[i], lo, hi);
    if (!is_arc(bulge_of(bulges, i))) continue;
    const Arc arc = arc_from_bulge(ring[i], ring[(i + 1) % ring.size()], bulges[i]);
    // An unchecked ring may hold a bulge too large to place; check_region reports it.
    if (!std::isfinite(arc.radius) || !arc.centre.allFinite() || !std::isfinite(arc.start_angle)) continue;
    const double from = std::min(arc.start_angle, arc.start_angle + arc.sweep);
    const double to = std::max(arc.start_angle, arc.start_angle + arc.sweep);
    for (int k = static_cast<int>(std::ceil(from / (kPi / 2))); k * (kPi / 2) <= to; ++k) {
      include_in_box(arc.centre + arc.radius * Vector2d(std::cos(k * kPi / 2), std::sin(k * kPi / 2)), lo, hi);
    }
  }
}

// The ring with its arcs as chords within `tolerance`; `source`, when given, receives for every
// vertex of the result the index of the ring's vertex whose edge it lies on.
Polygon polygonised_ring(const Polygon& ring, const std::vector<double>& bulges, double tolerance,
                         std::vector<std::size_t>* source = nullptr) {
  Polygon out;
  if (source) source->clear();
  for (std::size_t i = 0; i < ring.size(); ++i) {
    out.push_back(ring[i]);
    if (source) source->push_back(i);
    if (!is_arc(bulge_of(bulges, i))) continue;
    const Arc arc = arc_from_bulge(ring[i], ring[(i + 1) % ring.size()], bulges[i]);
    // A chord spanning the angle φ strays r (1 − cos φ/2) from its arc.
    const double step = 2 * std::acos(std::max(-1.0, 1 - tolerance / arc.radius));
    const int pieces = static_cast<int>(std::clamp(std::ceil(std::abs(arc.sweep) / step), 2.0, 4096.0));
    for (int k = 1; k < pieces; ++k) {
      const double angle = arc.start_angle + arc.sweep * k / pieces;
      out.push_back(arc.centre + arc.radius * Vector2d(std::cos(angle), std::sin(angle)));
      if (source) source->push_back(i);
    }
  }
  return out;
}

double chord_tolerance_for(const Region& r) {
  Vector2d lo = Vector2d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  ring_box(r.outline, r.outline_bulges, lo, hi);
  return kRelativeChordTolerance * (hi - lo).norm();
}

// Sutherland–Hodgman against one half-plane. For a non-convex polygon the output may run back
// and forth along the cut line; Green's theorem integrates such a polygon exactly. A vertex on
// the line belongs to both sides; the crossing point is computed identically from either side,
// so the two halves of a cut share their cut edge exactly.
Polygon clip_polygon(const Polygon& poly, const Vector2d& p, const Vector2d& n) {
  Polygon out;
  const std::size_t count = poly.size();
  std::vector<double> dist(count);
  for (std::size_t i = 0; i < count; ++i) dist[i] = n.dot(poly[i] - p);
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t j = (i + 1) % count;
    const double da = dist[i], db = dist[j];
    if (da >= 0) out.push_back(poly[i]);
    if ((da > 0 && db < 0) || (da < 0 && db > 0)) {
      const double t = da / (da - db);
      out.push_back(poly[i] + t * (poly[j] - poly[i]));
    }
  }
  return out;
}

Vector2d mean(const Polygon& poly) {
  Vector2d sum = Vector2d::Zero();
  for (const Vector2d& v : poly) sum += v;
  return sum / static_cast<double>(poly.size());
}

// ---- validation ----

std::string point_text(const Vector2d& v) {
  std::ostringstream os;
  os << '(' << v.x() << ", " << v.y() << ')';
  return os.str();
}

[[noreturn]] void fail(const std::string& message) { throw Error(ErrorKind::BadInput, message); }

double orient(const Vector2d& a, const Vector2d& b, const Vector2d& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

int sign(double x) { return (x > 0) - (x < 0); }

// c, known to be collinear with a-b, lies on the closed segment a-b.
bool on_segment(const Vector2d& a, const Vector2d& b, const Vector2d& c) {
  return std::min(a.x(), b.x()) <= c.x() && c.x() <= std::max(a.x(), b.x()) && std::min(a.y(), b.y()) <= c.y() &&
         c.y() <= std::max(a.y(), b.y());
}

// The closed segments a-b and c-d share a point (crossing or touching).
bool segments_meet(const Vector2d& a, const Vector2d& b, const Vector2d& c, const Vector2d& d) {
  const int o1 = sign(orient(a, b, c)), o2 = sign(orient(a, b, d));
  const int o3 = sign(orient(c, d, a)), o4 = sign(orient(c, d, b));
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  return (o1 == 0 && on_segment(a, b, c)) || (o2 == 0 && on_segment(a, b, d)) || (o3 == 0 && on_segment(c, d, a)) ||
         (o4 == 0 && on_segment(c, d, b));
}

double distance_to_segment(const Vector2d& x, const Vector2d& a, const Vector2d& b) {
  const Vector2d ab = b - a;
  const double t = std::clamp((x - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (x - (a + t * ab)).norm();
}

// Strictly inside: a point on the boundary is not.
bool strictly_inside(const Polygon& poly, const Vector2d& x) {
  const std::size_t n = poly.size();
  add_geometry_work(n);
  bool inside = false;
  for (std::size_t i = 0; i < n; ++i) {
    const Vector2d& a = poly[i];
    const Vector2d& b = poly[(i + 1) % n];
    if (orient(a, b, x) == 0 && on_segment(a, b, x)) return false;
    if ((a.y() > x.y()) != (b.y() > x.y())) {
      const double cross_x = a.x() + (x.y() - a.y()) / (b.y() - a.y()) * (b.x() - a.x());
      if (x.x() < cross_x) inside = !inside;
    }
  }
  return inside;
}

// The first pair (i, j), j > i + 1, of edges of a closed polygon that are not neighbours and
// meet, in the order (i, then j); {n, n} when none do. Edges are swept in the order of their
// leftmost x, each tested only against the edges whose x range it overlaps.
std::pair<std::size_t, std::size_t> first_meeting_edges(const Polygon& poly) {
  const std::size_t n = poly.size();
  const auto low = [&](std::size_t e) { return std::min(poly[e].x(), poly[(e + 1) % n].x()); };
  const auto high = [&](std::size_t e) { return std::max(poly[e].x(), poly[(e + 1) % n].x()); };
  std::vector<std::size_t> order(n);
  for (std::size_t e = 0; e < n; ++e) order[e] = e;
  std::sort(order.begin(), order.end(), [&](std::size_t p, std::size_t q) { return low(p) < low(q); });
  std::pair<std::size_t, std::size_t> first{n, n};
  std::vector<std::size_t> active;
  for (std::size_t e : order) {
    const double x = low(e);
    std::erase_if(active, [&](std::size_t f) { return high(f) < x; });
    add_geometry_work(active.size() + 1);
    const double y0 = std::min(poly[e].y(), poly[(e + 1) % n].y()), y1 = std::max(poly[e].y(), poly[(e + 1) % n].y());
    for (std::size_t f : active) {
      const std::size_t i = std::min(e, f), j = std::max(e, f);
      if (j < i + 2 || (i == 0 && j == n - 1)) continue;  // neighbours share a vertex
      if (std::make_pair(i, j) >= first) continue;
      if (std::max(poly[f].y(), poly[(f + 1) % n].y()) < y0 || std::min(poly[f].y(), poly[(f + 1) % n].y()) > y1)
        continue;
      if (segments_meet(poly[i], poly[(i + 1) % n], poly[j], poly[(j + 1) % n])) first = {i, j};
    }
    active.push_back(e);
  }
  return first;
}

// `source` (optional) maps the vertices of a polygonised ring back to the ring's own, so that
// messages name the vertices and edges the user wrote.
void check_polygon(const Polygon& poly, const std::string& what, const std::vector<std::size_t>* source = nullptr,
                   std::size_t source_count = 0) {
  const std::size_t n = poly.size();
  const auto src = [&](std::size_t i) { return source ? (*source)[i] : i; };
  const auto next = [&](std::size_t i) { return source ? ((*source)[i] + 1) % source_count : (i + 1) % n; };
  if (n < 3) {
    std::ostringstream os;
    os << what << " has " << n << (n == 1 ? " vertex" : " vertices") << "; a polygon needs at least 3";
    fail(os.str());
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!poly[i].allFinite()) fail(what + " vertex " + std::to_string(i) + " is not finite");
  }
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    if (poly[i] == poly[j]) {
      std::ostringstream os;
      os << what << " vertices " << i << " and " << j << " coincide at " << point_text(poly[i]);
      fail(os.str());
    }
  }
  // Collinear vertices first: they would otherwise be reported as doubling back.
  std::size_t far = 0;
  for (std::size_t i = 1; i < n; ++i) {
    if ((poly[i] - poly[0]).squaredNorm() > (poly[far] - poly[0]).squaredNorm()) far = i;
  }
  const double span2 = (poly[far] - poly[0]).squaredNorm();
  // Else an overflowing span would make every outline look flat below.
  if (!std::isfinite(span2)) fail(what + " is too large to compute with (its area overflows): check its sizes");
  double spread = 0;
  for (std::size_t i = 0; i < n; ++i) spread = std::max(spread, std::abs(orient(poly[0], poly[far], poly[i])));
  if (spread <= 64 * std::numeric_limits<double>::epsilon() * span2) {
    fail(what + " has zero area: its vertices are all on one line");
  }
  // The first fault in the order of a scan of edge i, then of the pairs (i, j > i + 1), as the
  // messages always named them; the pairs that can meet are found by a sweep over x, so that an
  // outline of 60 000 edges is not 1.8e9 tests.
  std::size_t doubles_back = n;
  for (std::size_t i = 0; i < n && doubles_back == n; ++i) {
    const Vector2d& a = poly[i];
    const Vector2d& b = poly[(i + 1) % n];
    // The next edge shares b; it only meets this one elsewhere by doubling back along it.
    const Vector2d& c = poly[(i + 2) % n];
    if (orient(a, b, c) == 0 && (b - a).dot(c - b) < 0) doubles_back = i;
  }
  const auto [i, j] = first_meeting_edges(poly);
  if (doubles_back < n && (i == n || doubles_back <= i)) {
    std::ostringstream os;
    os << what << " doubles back on itself at vertex " << src((doubles_back + 1) % n) << ' '
       << point_text(poly[(doubles_back + 1) % n]);
    fail(os.str());
  }
  if (i < n) {
    std::ostringstream os;
    os << what << " intersects itself: edge " << src(i) << "-" << next(i) << " meets edge " << src(j) << "-" << next(j);
    fail(os.str());
  }
  // A simple polygon that is not flat has area; this only catches what rounding let through.
  if (signed_area(poly) == 0) fail(what + " has zero area");
}

// A ring with arcs: its own vertices and bulges first, then its polygonisation as a polygon.
Polygon checked_ring(const Polygon& ring, const std::vector<double>& bulges, double tolerance,
                     const std::string& what) {
  bool arcs = false;
  if (!bulges.empty()) {
    if (bulges.size() != ring.size()) {
      fail(what + " has " + std::to_string(ring.size()) + " vertices but " + std::to_string(bulges.size()) + " bulges");
    }
    for (std::size_t i = 0; i < bulges.size(); ++i) {
      if (!std::isfinite(bulges[i])) fail(what + " bulge " + std::to_string(i) + " is not finite");
      if (std::abs(bulges[i]) > kLargestBulge) {
        fail(what + " bulge " + std::to_string(i) +
             " is larger than 1e6 (an arc of all but 0.0002 degrees of a circle)");
      }
      arcs = arcs || is_arc(bulges[i]);
    }
  }
  if (!arcs) {
    check_polygon(ring, what);
    return ring;
  }
  if (ring.size() < 2) fail(what + " has 1 vertex; an outline with arcs needs at least 2");
  for (std::size_t i = 0; i < ring.size(); ++i) {
    if (!ring[i].allFinite()) fail(what + " vertex " + std::to_string(i) + " is not finite");
    const std::size_t j = (i + 1) % ring.size();
    if (ring[i] == ring[j]) {
      std::ostringstream os;
      os << what << " vertices " << i << " and " << j << " coincide at " << point_text(ring[i]);
      fail(os.str());
    }
  }
  if (!(tolerance > 0) || !std::isfinite(tolerance)) fail(what + " has no extent");
  std::vector<std::size_t> source;
  Polygon chords = polygonised_ring(ring, bulges, tolerance, &source);
  check_polygon(chords, what, &source, ring.size());
  return chords;
}

std::string circle_name(std::size_t i, const Circle& c) {
  std::ostringstream os;
  os << "circle hole " << i << " (centre " << point_text(c.centre) << ", radius " << c.radius << ')';
  return os.str();
}

std::string polygon_name(std::size_t i) { return "polygon hole " + std::to_string(i); }

}  // namespace

bool circle_clear_of_edges(const Circle& c, const std::vector<Vector2d>& poly) {
  add_geometry_work(poly.size());
  for (std::size_t i = 0; i < poly.size(); ++i) {
    if (distance_to_segment(c.centre, poly[i], poly[(i + 1) % poly.size()]) <= c.radius) return false;
  }
  return true;
}

AreaProperties area_properties(const Region& r) {
  if (r.outline.empty()) return {};
  const Vector2d origin = mean(r.outline);
  Moments m = unsigned_ring_moments(r.outline, r.outline_bulges, origin);
  for (std::size_t i = 0; i < r.polygon_holes.size(); ++i) {
    const std::vector<double> none;
    const std::vector<double>& bulges = i < r.polygon_hole_bulges.size() ? r.polygon_hole_bulges[i] : none;
    m -= unsigned_ring_moments(r.polygon_holes[i], bulges, origin);
  }
  for (const Circle& hole : r.circle_holes) m -= disc_moments(hole, origin);
  return to_properties(m, origin);
}

AreaProperties clipped_area_properties(const Region& r, const Vector2d& p, const Vector2d& n) {
  if (!p.allFinite() || !n.allFinite()) fail("clipped_area_properties: the cut line is not finite");
  const double norm = n.norm();
  if (!(norm > 0)) fail("clipped_area_properties: the normal of the cut line is zero");
  if (has_arcs(r)) return clipped_area_properties(straight_edged(r), p, n);
  const Polygon outline = clip_polygon(r.outline, p, n);
  if (outline.empty()) return {};
  const Vector2d origin = mean(outline);
  // The clipped polygon keeps the orientation of its source, even when it has no area left.
  Moments m = polygon_moments(outline, origin);
  if (signed_area(r.outline) < 0) m.negate();
  for (const Polygon& hole : r.polygon_holes) {
    Moments h = polygon_moments(clip_polygon(hole, p, n), origin);
    if (signed_area(hole) < 0) h.negate();
    m -= h;
  }
  const Vector2d unit = n / norm;
  for (const Circle& hole : r.circle_holes) m -= clipped_disc_moments(hole, unit, unit.dot(hole.centre - p), origin);
  return to_properties(m, origin);
}

namespace {

Eigen::AlignedBox2d edge_box(const Polygon& ring, std::size_t i) {
  Eigen::AlignedBox2d box(ring[i]);
  box.extend(ring[(i + 1) % ring.size()]);
  return box;
}

// The outline's edges in a BoxIndex: each test of a hole against the outline looks at the
// edges near the hole, and gives what the same test over every edge gives.
class OutlineEdges {
 public:
  explicit OutlineEdges(const Polygon& ring) : ring_(ring), index_(boxes(ring)) {}

  // polygons_meet(p, ring).
  bool meet(const Polygon& p) const {
    for (std::size_t i = 0; i < p.size(); ++i) {
      const Vector2d &a = p[i], &b = p[(i + 1) % p.size()];
      for (std::size_t j : index_.meeting(edge_box(p, i))) {
        add_geometry_work(1);
        if (segments_meet(a, b, ring_[j], ring_[(j + 1) % ring_.size()])) return true;
      }
    }
    return false;
  }

  // strictly_inside(ring, x): only the edges that reach x's height at or right of x can be
  // under x or cross the ray to its right.
  bool strictly_inside(const Vector2d& x) const {
    const double far = std::max(x.x(), index_.size() ? right_ : x.x());
    bool inside = false;
    for (std::size_t i : index_.meeting(Eigen::AlignedBox2d(x, Vector2d(far, x.y())))) {
      add_geometry_work(1);
      const Vector2d& a = ring_[i];
      const Vector2d& b = ring_[(i + 1) % ring_.size()];
      if (orient(a, b, x) == 0 && on_segment(a, b, x)) return false;
      if ((a.y() > x.y()) != (b.y() > x.y())) {
        const double cross_x = a.x() + (x.y() - a.y()) / (b.y() - a.y()) * (b.x() - a.x());
        if (x.x() < cross_x) inside = !inside;
      }
    }
    return inside;
  }

  // circle_clear_of_edges(c, ring).
  bool clear_of(const Circle& c) const {
    for (std::size_t i : index_.meeting(circle_bounds(c))) {
      add_geometry_work(1);
      if (distance_to_segment(c.centre, ring_[i], ring_[(i + 1) % ring_.size()]) <= c.radius) return false;
    }
    return true;
  }

 private:
  std::vector<Eigen::AlignedBox2d> boxes(const Polygon& ring) {
    std::vector<Eigen::AlignedBox2d> out;
    right_ = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < ring.size(); ++i) {
      out.push_back(edge_box(ring, i));
      right_ = std::max(right_, ring[i].x());
    }
    return out;
  }
  const Polygon& ring_;
  double right_ = 0;
  BoxIndex index_;
};

// Every hole inside the outline and clear of it, in the order of the holes (polygons first).
void check_holes_in_outline(const Region& r) {
  const OutlineEdges outline(r.outline);
  for (std::size_t i = 0; i < r.polygon_holes.size(); ++i) {
    const Polygon& hole = r.polygon_holes[i];
    if (outline.meet(hole)) fail(polygon_name(i) + " meets the outline");
    if (!outline.strictly_inside(hole[0])) fail(polygon_name(i) + " is outside the outline");
  }
  for (std::size_t i = 0; i < r.circle_holes.size(); ++i) {
    const Circle& c = r.circle_holes[i];
    if (!outline.strictly_inside(c.centre)) fail(circle_name(i, c) + " is outside the outline");
    if (!outline.clear_of(c)) fail(circle_name(i, c) + " meets the outline");
  }
}

// No two holes overlap or touch. Only holes whose boxes meet can (the boxes hold the shapes,
// and the index pads them past rounding); each hole's neighbours come from the index in
// ascending order, polygons before circles, so the first pair that fails is the one the scan of
// every pair (polygon i with each later polygon, then each circle; then circle i with each
// later circle) would have found.
void check_holes_apart(const Region& r) {
  const std::size_t polygons = r.polygon_holes.size();
  std::vector<Eigen::AlignedBox2d> boxes;
  for (const Polygon& hole : r.polygon_holes) boxes.push_back(ring_bounds(hole, {}));
  for (const Circle& c : r.circle_holes) boxes.push_back(circle_bounds(c));
  const BoxIndex index(boxes);
  for (std::size_t i = 0; i < polygons; ++i) {
    const Polygon& a = r.polygon_holes[i];
    for (std::size_t k : index.meeting(boxes[i])) {
      if (k <= i) continue;
      if (k < polygons) {
        const Polygon& b = r.polygon_holes[k];
        if (polygons_meet(a, b) || strictly_inside(a, b[0]) || strictly_inside(b, a[0])) {
          fail(polygon_name(i) + " and " + polygon_name(k) + " overlap");
        }
        continue;
      }
      const Circle& c = r.circle_holes[k - polygons];
      if (strictly_inside(a, c.centre) || !circle_clear_of_edges(c, a)) {
        fail(polygon_name(i) + " and " + circle_name(k - polygons, c) + " overlap");
      }
    }
  }
  for (std::size_t i = 0; i < r.circle_holes.size(); ++i) {
    const Circle& a = r.circle_holes[i];
    for (std::size_t k : index.meeting(boxes[polygons + i])) {
      if (k <= polygons + i) continue;
      add_geometry_work(1);
      const Circle& b = r.circle_holes[k - polygons];
      if ((a.centre - b.centre).norm() <= a.radius + b.radius) {
        fail(circle_name(i, a) + " and " + circle_name(k - polygons, b) + " overlap");
      }
    }
  }
}

}  // namespace

Eigen::AlignedBox2d ring_bounds(const Polygon& ring, const std::vector<double>& bulges) {
  Vector2d lo = Vector2d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  ring_box(ring, bulges, lo, hi);
  return {lo, hi};
}

Eigen::AlignedBox2d circle_bounds(const Circle& c) {
  const Vector2d r = Vector2d::Constant(c.radius);
  return {c.centre - r, c.centre + r};
}

namespace {
thread_local std::size_t work_on_this_thread = 0;
}  // namespace

std::size_t geometry_work() { return work_on_this_thread; }
void add_geometry_work(std::size_t tests) { work_on_this_thread += tests; }

void check_region(const Region& r) {
  const std::size_t holes = r.polygon_holes.size() + r.circle_holes.size();
  if (holes > kMaxHolesPerPlate) {
    fail("the plate has " + std::to_string(holes) + " holes; at most " + std::to_string(kMaxHolesPerPlate) +
         " are allowed");
  }
  if (!r.polygon_hole_bulges.empty() && r.polygon_hole_bulges.size() != r.polygon_holes.size()) {
    fail("the region has " + std::to_string(r.polygon_holes.size()) + " polygon holes but " +
         std::to_string(r.polygon_hole_bulges.size()) + " lists of bulges");
  }
  const double tolerance = chord_tolerance_for(r);
  const std::vector<double> none;
  const auto hole_bulges = [&](std::size_t i) -> const std::vector<double>& {
    return r.polygon_hole_bulges.empty() ? none : r.polygon_hole_bulges[i];
  };
  checked_ring(r.outline, r.outline_bulges, tolerance, "the outline");
  for (std::size_t i = 0; i < r.polygon_holes.size(); ++i) {
    checked_ring(r.polygon_holes[i], hole_bulges(i), tolerance, polygon_name(i));
  }
  if (has_arcs(r)) {
    // The rest (holes inside the outline and apart) on the one polygonisation.
    Region chords = straight_edged(r);
    chords.outline_bulges.clear();
    chords.polygon_hole_bulges.clear();
    check_region(chords);
    return;
  }
  for (std::size_t i = 0; i < r.circle_holes.size(); ++i) {
    const Circle& c = r.circle_holes[i];
    if (!c.centre.allFinite() || !std::isfinite(c.radius)) fail(circle_name(i, c) + " is not finite");
    if (!(c.radius > 0)) fail(circle_name(i, c) + " has a non-positive radius");
  }

  check_holes_in_outline(r);
  check_holes_apart(r);
}

Region make_bar(const Vector2d& p, const Vector2d& q, double width, double margin, double hole_radius_p,
                double hole_radius_q) {
  if (!p.allFinite() || !q.allFinite() || !std::isfinite(width) || !std::isfinite(margin) ||
      !std::isfinite(hole_radius_p) || !std::isfinite(hole_radius_q)) {
    fail("make_bar: every dimension must be finite");
  }
  const double length = (q - p).norm();
  if (!(length > 0)) fail("make_bar: the two ends coincide at " + point_text(p));
  if (!(width > 0)) fail("make_bar: the width must be positive");
  if (!(margin >= 0)) fail("make_bar: the margin must not be negative");
  if (!(hole_radius_p >= 0) || !(hole_radius_q >= 0)) fail("make_bar: a hole radius is negative");
  for (const double radius : {hole_radius_p, hole_radius_q}) {
    if (radius > 0 && !(radius < width / 2 && radius < margin)) {
      std::ostringstream os;
      os << "make_bar: a hole of radius " << radius << " does not fit in a bar of width " << width << " with margin "
         << margin << " (it needs radius < width/2 and radius < margin)";
      fail(os.str());
    }
  }
  if (hole_radius_p > 0 && hole_radius_q > 0 && !(hole_radius_p + hole_radius_q < length)) {
    fail("make_bar: the holes at the two ends overlap");
  }
  const Vector2d u = (q - p) / length;
  const Vector2d v(-u.y(), u.x());
  const Vector2d along = margin * u, across = width / 2 * v;
  Region r;
  r.outline = {p - along - across, q + along - across, q + along + across, p - along + across};
  if (hole_radius_p > 0) r.circle_holes.push_back({p, hole_radius_p});
  if (hole_radius_q > 0) r.circle_holes.push_back({q, hole_radius_q});
  return r;
}

SecondMoments second_moments_about(const AreaProperties& a, const Vector2d& point) {
  const Vector2d d = a.centroid - point;
  return {a.ixx + a.area * d.y() * d.y(), a.iyy + a.area * d.x() * d.x(), a.ixy + a.area * d.x() * d.y()};
}

AreaProperties combine(const AreaProperties& a, const AreaProperties& b) {
  const Vector2d origin = a.centroid;
  Moments m = to_moments(a, origin);
  m += to_moments(b, origin);
  return to_properties(m, origin);
}

AreaProperties subtract(const AreaProperties& whole, const AreaProperties& part) {
  const Vector2d origin = whole.centroid;
  Moments m = to_moments(whole, origin);
  m -= to_moments(part, origin);
  return to_properties(m, origin);
}

AreaProperties transformed(const AreaProperties& a, double angle, const Vector2d& shift) {
  const Eigen::Matrix2d rot = Eigen::Rotation2Dd(angle).toRotationMatrix();
  // The covariance-like tensor [[∫x², ∫xy], [∫xy, ∫y²]] turns as R J Rᵀ.
  Eigen::Matrix2d j;
  j << a.iyy, a.ixy, a.ixy, a.ixx;
  const Eigen::Matrix2d jr = rot * j * rot.transpose();
  AreaProperties out;
  out.area = a.area;
  out.centroid = rot * a.centroid + shift;
  out.iyy = jr(0, 0);
  out.ixx = jr(1, 1);
  out.ixy = jr(0, 1);
  return out;
}

PlateMass plate_mass(const AreaProperties& a, double density, double thickness) {
  if (!std::isfinite(density) || !(density >= 0)) fail("plate_mass: the density must be finite and not negative");
  if (!std::isfinite(thickness) || !(thickness > 0)) fail("plate_mass: the thickness must be finite and positive");
  const double areal = density * thickness;
  return {areal * a.area, a.centroid, areal * a.polar()};
}

Arc arc_from_bulge(const Vector2d& a, const Vector2d& b, double bulge) {
  const Vector2d chord = b - a;
  const double half = chord.norm() / 2;
  const Vector2d right = Vector2d(chord.y(), -chord.x()).normalized();
  const double radius = half * (1 + bulge * bulge) / (2 * std::abs(bulge));
  const Vector2d axis = bulge > 0 ? right : Vector2d(-right);
  const Vector2d centre = (a + b) / 2 + bulge * half * right - radius * axis;
  const Vector2d from = a - centre;
  return {centre, radius, std::atan2(from.y(), from.x()), 4 * std::atan(bulge)};
}

double bulge_through(const Vector2d& a, const Vector2d& b, const Vector2d& m) {
  if (m == a || m == b) fail("the arc's middle point coincides with one of its ends " + point_text(m));
  if (a == b) fail("the arc's two ends coincide at " + point_text(a));
  // The inscribed angle φ at m sees the arc's included angle θ = 2π − 2φ, so bulge = tan(θ/4)
  // = cot(φ/2); the arc bulges to the right of a->b (positive bulge) when m is on the right.
  const Vector2d ma = a - m, mb = b - m;
  const double cross = ma.x() * mb.y() - ma.y() * mb.x();
  const double phi = std::atan2(std::abs(cross), ma.dot(mb));
  if (!(phi > 0)) fail("the point " + point_text(m) + " is on the line through the arc's ends but not between them");
  const double size = 1 / std::tan(phi / 2);
  return orient(a, b, m) < 0 ? size : -size;
}

bool has_arcs(const Region& r) {
  for (double b : r.outline_bulges)
    if (is_arc(b)) return true;
  for (const auto& bulges : r.polygon_hole_bulges)
    for (double b : bulges)
      if (is_arc(b)) return true;
  return false;
}

Region polygonised(const Region& r, double chord_tolerance) {
  if (!(chord_tolerance > 0)) fail("polygonised: the chord tolerance must be positive");
  Region out;
  out.outline = polygonised_ring(r.outline, r.outline_bulges, chord_tolerance);
  for (std::size_t i = 0; i < r.polygon_holes.size(); ++i) {
    const std::vector<double> none;
    const std::vector<double>& bulges = i < r.polygon_hole_bulges.size() ? r.polygon_hole_bulges[i] : none;
    out.polygon_holes.push_back(polygonised_ring(r.polygon_holes[i], bulges, chord_tolerance));
  }
  out.circle_holes = r.circle_holes;
  return out;
}

Region straight_edged(const Region& r) {
  if (!has_arcs(r)) return r;
  const double tolerance = chord_tolerance_for(r);
  if (!(tolerance > 0) || !std::isfinite(tolerance)) return r;
  return polygonised(r, tolerance);
}

std::vector<EdgeMention> edge_mentions(const std::string& message) {
  std::vector<EdgeMention> out;
  const auto digits_at = [&](std::size_t at) {
    std::size_t end = at;
    while (end < message.size() && std::isdigit(static_cast<unsigned char>(message[end]))) ++end;
    return end;
  };
  static constexpr std::string_view kWord = "edge ";
  for (std::size_t at = message.find(kWord); at != std::string::npos; at = message.find(kWord, at + 1)) {
    const std::size_t a = at + kWord.size(), a_end = digits_at(a);
    if (a_end == a || a_end - a > 9 || a_end >= message.size() || message[a_end] != '-') continue;
    const std::size_t b = a_end + 1, b_end = digits_at(b);
    if (b_end == b || b_end - b > 9) continue;
    EdgeMention m;
    m.begin = at;
    m.end = b_end;
    m.from = std::stoul(message.substr(a, a_end - a));
    m.to = std::stoul(message.substr(b, b_end - b));
    out.push_back(m);
  }
  return out;
}

bool polygons_meet(const std::vector<Vector2d>& p, const std::vector<Vector2d>& q) {
  add_geometry_work(p.size() * q.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t j = 0; j < q.size(); ++j) {
      if (segments_meet(p[i], p[(i + 1) % p.size()], q[j], q[(j + 1) % q.size()])) return true;
    }
  }
  return false;
}

double distance_outside_outline(const Region& r, const Vector2d& x) {
  const Region straight = straight_edged(r);
  const Polygon& outline = straight.outline;
  const std::size_t n = outline.size();
  if (n < 3 || strictly_inside(outline, x)) return 0.0;
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i)
    nearest = std::min(nearest, distance_to_segment(x, outline[i], outline[(i + 1) % n]));
  return nearest;
}

}  // namespace nbar
