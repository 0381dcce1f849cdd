// The mesher: the Region's boundary as curves (straight edges, arcs, circles), a sizing function
// graded away from holes, arcs and re-entrant corners, the boundary cut to that size, conforming
// Delaunay refinement (delaunay_refinement.cpp), then mid-side nodes, on the true curve for
// boundary edges on arcs and circles.
#include "nbar/stress/mesh.hpp"
#include "nbar/model/diagnostics.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "delaunay_refinement.hpp"
#include "model/plane_vectors.hpp"

namespace nbar::fe {
namespace {

using Eigen::Vector2d;
constexpr double kPi = std::numbers::pi;

// Bulges at most this are straight edges, as in the geometry (src/model/geometry.cpp).
constexpr double kStraightBulge = 1e-8;
// A corner turning the boundary right by more than this (plate on the left) is re-entrant.
constexpr double kReentrantTurn = 0.05;
// Re-entrant corners get elements this many times smaller than their shortest edge or `size`.
constexpr double kCornerRefinement = 5.0;
constexpr double kMinAngleDeg = 28.0;

[[noreturn]] void fail(const std::string& message) { throw Error(ErrorKind::BadInput, "mesh: " + message); }

struct Curve {
  bool arc = false;
  Vector2d p0{0, 0}, p1{0, 0};  // a straight edge's ends
  Arc circle{{0, 0}, 0, 0, 0};  // an arc's
  BoundaryTag tag;

  Vector2d at(double t) const {
    if (!arc) return p0 + t * (p1 - p0);
    const double angle = circle.start_angle + t * circle.sweep;
    return circle.centre + circle.radius * Vector2d(std::cos(angle), std::sin(angle));
  }
  Vector2d derivative(double t) const {
    if (!arc) return p1 - p0;
    const double angle = circle.start_angle + t * circle.sweep;
    return circle.radius * circle.sweep * Vector2d(-std::sin(angle), std::cos(angle));
  }
  double length() const { return arc ? circle.radius * std::abs(circle.sweep) : (p1 - p0).norm(); }
};

// A curve travelled forwards or backwards, so that the plate is on the left.
struct Piece {
  int curve = 0;
  bool reversed = false;
  double param(double u) const { return reversed ? 1 - u : u; }
};

struct Ring {
  std::vector<Piece> pieces;
  bool has_corners = true;  // false for a circle hole
};

struct Boundary {
  std::vector<Curve> curves;
  std::vector<Ring> rings;
};

// An arc as the sizing function needs it: distances without trigonometry.
struct ArcFeature {
  Vector2d centre, start_direction, end_direction;
  double radius = 0, turn = 1;  // turn: +1 counterclockwise, −1 clockwise
  bool over_half = false;       // sweeps more than half a turn
  double h0 = 0;

  ArcFeature(const Arc& a, double size) : centre(a.centre), radius(a.radius), h0(size) {
    start_direction = Vector2d(std::cos(a.start_angle), std::sin(a.start_angle));
    end_direction = Vector2d(std::cos(a.start_angle + a.sweep), std::sin(a.start_angle + a.sweep));
    turn = a.sweep < 0 ? -1 : 1;
    over_half = std::abs(a.sweep) > kPi;
  }

  double distance(const Vector2d& x) const {
    const Vector2d r = x - centre;
    const bool after_start = turn * cross(start_direction, r) >= 0;
    const bool before_end = turn * cross(r, end_direction) >= 0;
    const bool within = over_half ? after_start || before_end : after_start && before_end;
    if (within) return std::abs(r.norm() - radius);
    return std::min((r - radius * start_direction).norm(), (r - radius * end_direction).norm());
  }
};

// Wanted edge length at a point: `size`, except near features, whose own length h0 grows by
// (grading − 1) per unit distance (elements growing by the factor `grading` one to the next).
struct Sizing {
  double size = 0, growth = 0;
  std::vector<std::pair<Circle, double>> circles;
  std::vector<ArcFeature> arcs;
  std::vector<std::pair<Vector2d, double>> points;

  double operator()(const Vector2d& x) const {
    double h = size;
    for (const auto& [c, h0] : circles) h = std::min(h, h0 + growth * std::abs((x - c.centre).norm() - c.radius));
    for (const ArcFeature& a : arcs) h = std::min(h, a.h0 + growth * a.distance(x));
    for (const auto& [p, h0] : points) h = std::min(h, h0 + growth * (x - p).norm());
    return h;
  }
};

void check_options(const MeshOptions& o) {
  std::ostringstream os;
  if (!(std::isfinite(o.size) && o.size >= 0)) {
    os << "the element size must be a finite length >= 0 m (0 for automatic), not " << o.size;
  } else if (o.segments_per_hole < 8) {
    os << "segments_per_hole must be at least 8, not " << o.segments_per_hole;
  } else if (!(std::isfinite(o.grading) && o.grading > 1 && o.grading <= 4)) {
    os << "grading must be above 1 and at most 4, not " << o.grading;
  } else if (!(std::isfinite(o.edge_size) && o.edge_size >= 0)) {
    os << "the edge element size must be a finite length >= 0 m (0 for automatic), not " << o.edge_size;
  } else if (o.max_nodes < 6) {
    os << "max_nodes must be at least 6, not " << o.max_nodes;
  } else {
    return;
  }
  fail(os.str());
}

void add_polygon_ring(Boundary& b, const std::vector<Vector2d>& vertices, const std::vector<double>& bulges,
                      BoundaryTag tag) {
  Ring ring;
  const std::size_t n = vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    Curve c;
    c.tag = tag;
    c.p0 = vertices[i];
    c.p1 = vertices[(i + 1) % n];
    const double bulge = bulges.empty() ? 0.0 : bulges[i];
    if (std::abs(bulge) > kStraightBulge) {
      c.arc = true;
      c.circle = arc_from_bulge(c.p0, c.p1, bulge);
    }
    ring.pieces.push_back({static_cast<int>(b.curves.size()), false});
    b.curves.push_back(c);
  }
  b.rings.push_back(ring);
}

double signed_area(const Boundary& b, const Ring& ring) {
  std::vector<Vector2d> poly;
  for (const Piece& p : ring.pieces) {
    for (int k = 0; k < 8; ++k) poly.push_back(b.curves[p.curve].at(p.param(k / 8.0)));
  }
  double a = 0;
  for (std::size_t i = 0; i < poly.size(); ++i) a += cross(poly[i], poly[(i + 1) % poly.size()]);
  return a / 2;
}

void orient(const Boundary& b, Ring& ring, bool counterclockwise) {
  if ((signed_area(b, ring) > 0) == counterclockwise) return;
  std::reverse(ring.pieces.begin(), ring.pieces.end());
  for (Piece& p : ring.pieces) p.reversed = !p.reversed;
}

// The boundary as rings of curves, each travelled with the plate on its left.
Boundary boundary_of(const Region& r) {
  Boundary b;
  add_polygon_ring(b, r.outline, r.outline_bulges, {BoundaryTag::Kind::outline, 0});
  orient(b, b.rings.back(), true);
  for (std::size_t k = 0; k < r.polygon_holes.size(); ++k) {
    const std::vector<double> none;
    add_polygon_ring(b, r.polygon_holes[k], r.polygon_hole_bulges.empty() ? none : r.polygon_hole_bulges[k],
                     {BoundaryTag::Kind::polygon_hole, static_cast<int>(k)});
    orient(b, b.rings.back(), false);
  }
  for (std::size_t k = 0; k < r.circle_holes.size(); ++k) {
    Curve c;
    c.arc = true;
    c.circle = {r.circle_holes[k].centre, r.circle_holes[k].radius, 0.0, -2 * kPi};  // clockwise
    c.tag = {BoundaryTag::Kind::circle_hole, static_cast<int>(k)};
    b.rings.push_back({{{static_cast<int>(b.curves.size()), false}}, false});
    b.curves.push_back(c);
  }
  return b;
}

double bounding_diagonal(const Boundary& b, const Ring& ring) {
  Vector2d lo = Vector2d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Piece& p : ring.pieces) {
    for (int k = 0; k <= 16; ++k) {
      const Vector2d x = b.curves[p.curve].at(k / 16.0);
      lo = lo.cwiseMin(x);
      hi = hi.cwiseMax(x);
    }
  }
  return (hi - lo).norm();
}

// The element edge at a feature whose automatic edge is `automatic`: scaled with the size below the
// automatic size (`scale`), and at most the edge size asked for.
double feature_edge(double automatic, double scale, const MeshOptions& o) {
  const double h = automatic * scale;
  return o.edge_size > 0 ? std::min(h, o.edge_size) : h;
}

// `scale`: size / the automatic size, at most 1 (MeshOptions::edge_size).
Sizing sizing_of(const Boundary& b, const MeshOptions& o, double size, double scale) {
  Sizing s;
  s.size = size;
  s.growth = o.grading - 1;
  for (const Curve& c : b.curves) {
    if (!c.arc) continue;
    const double h0 = feature_edge(2 * kPi * c.circle.radius / o.segments_per_hole, scale, o);
    if (c.tag.kind == BoundaryTag::Kind::circle_hole) {
      s.circles.push_back({Circle{c.circle.centre, c.circle.radius}, h0});
    } else if (h0 < size) {
      s.arcs.emplace_back(c.circle, h0);
    }
  }
  for (const Ring& ring : b.rings) {
    if (!ring.has_corners) continue;
    const std::size_t n = ring.pieces.size();
    for (std::size_t j = 0; j < n; ++j) {
      const Piece& in = ring.pieces[(j + n - 1) % n];
      const Piece& out = ring.pieces[j];
      const Curve& cin = b.curves[in.curve];
      const Curve& cout = b.curves[out.curve];
      const Vector2d d_in = cin.derivative(in.param(1)) * (in.reversed ? -1 : 1);
      const Vector2d d_out = cout.derivative(out.param(0)) * (out.reversed ? -1 : 1);
      const double turn = std::atan2(cross(d_in, d_out), d_in.dot(d_out));
      if (turn < -kReentrantTurn) {
        // The size is scaled already; the sides are not.
        const double h0 =
            feature_edge(std::min({size / scale, cin.length(), cout.length()}) / kCornerRefinement, scale, o);
        s.points.push_back({cout.at(out.param(0)), h0});
      }
    }
  }
  return s;
}

// A mesh of V corners has at least 2V - 3 edges, so 3V - 3 nodes with its mid-side ones: past
// this many corners it cannot fit in max_nodes.
std::size_t corner_budget(const MeshOptions& o) { return static_cast<std::size_t>(o.max_nodes) / 3 + 2; }

[[noreturn]] void fail_budget(double nodes, const MeshOptions& o) {
  std::ostringstream os;
  os << "the mesh would have about " << std::llround(std::min(nodes, 1e18))
     << " nodes, more than max_nodes = " << o.max_nodes << "; use a larger element size";
  fail(os.str());
}

// The area a ring encloses and its perimeter, from its curves sampled as for bounding_diagonal.
struct RingMeasure {
  double area = 0.0, perimeter = 0.0;
};
RingMeasure ring_measure(const Boundary& b, const Ring& ring) {
  std::vector<Vector2d> x;
  for (const Piece& p : ring.pieces)
    for (int k = 0; k < 16; ++k) x.push_back(b.curves[p.curve].at(p.param(k / 16.0)));
  double twice = 0.0, perimeter = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const Vector2d& a = x[i];
    const Vector2d& c = x[(i + 1) % x.size()];
    twice += a.x() * c.y() - a.y() * c.x();
    perimeter += (c - a).norm();
  }
  return {std::abs(twice) / 2, perimeter};
}

// Before any refinement: a region of area A meshed with edges no longer than `size` has at least
// about A / (sqrt(3)/2 size^2) corners V (equilateral triangles of that edge), and its quadratic
// mesh V + E nodes, E = 3V - 3 - B edges with B = perimeter / size corners on the boundary. A size
// whose nodes pass the budget fails at once instead of meshing for half a minute and 2 GB (the
// steel four-bar at 0.2 mm) until the budget stops it.
void check_interior_budget(const Boundary& b, double size, const MeshOptions& o) {
  double area = 0.0, perimeter = 0.0;
  for (std::size_t r = 0; r < b.rings.size(); ++r) {
    const RingMeasure m = ring_measure(b, b.rings[r]);
    area += r == 0 ? m.area : -m.area;
    perimeter += m.perimeter;
  }
  const double corners = area / (std::sqrt(3.0) / 2 * size * size);
  const double nodes = 4 * corners - perimeter / size;
  if (nodes > static_cast<double>(o.max_nodes)) fail_budget(nodes, o);
}

// Whether a point lies on the plate: inside the outline's polygon (its curves sampled as for
// ring_measure), outside every polygon hole's, and outside every circle hole.
class PlateTest {
 public:
  explicit PlateTest(const Boundary& b) {
    for (const Ring& ring : b.rings) {
      if (!ring.has_corners) {
        const Arc& c = b.curves[ring.pieces.front().curve].circle;
        circles_.push_back({c.centre, c.radius});
        continue;
      }
      std::vector<Vector2d> x;
      for (const Piece& p : ring.pieces) {
        const int samples = b.curves[p.curve].arc ? 16 : 1;
        for (int k = 0; k < samples; ++k) x.push_back(b.curves[p.curve].at(p.param(static_cast<double>(k) / samples)));
      }
      polygons_.push_back(std::move(x));
    }
  }
  bool contains(const Vector2d& x) const {
    for (const Circle& c : circles_)
      if ((x - c.centre).squaredNorm() < c.radius * c.radius) return false;
    for (std::size_t k = 0; k < polygons_.size(); ++k)
      if (inside(polygons_[k], x) != (k == 0)) return false;
    return true;
  }

 private:
  static bool inside(const std::vector<Vector2d>& polygon, const Vector2d& x) {
    bool in = false;
    for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
      const Vector2d& a = polygon[i];
      const Vector2d& c = polygon[j];
      if ((a.y() > x.y()) != (c.y() > x.y()) && x.x() < a.x() + (x.y() - a.y()) / (c.y() - a.y()) * (c.x() - a.x()))
        in = !in;
    }
    return in;
  }
  std::vector<std::vector<Vector2d>> polygons_;
  std::vector<Circle> circles_;
};

// The boundary's corners B of the graded mesh: the integral of ds / h along every curve.
double boundary_corners(const Boundary& b, const Sizing& h) {
  constexpr int kSamples = 256;
  double corners = 0.0;
  for (const Curve& c : b.curves)
    for (int k = 0; k < kSamples; ++k) corners += c.length() / kSamples / h(c.at((k + 0.5) / kSamples));
  return corners;
}

// Conforming Delaunay refinement leaves its triangles smaller than the sizing asks (a circumradius
// at most 0.65 h, angles of 28 deg and more): its meshes have 1.55 to 1.75 times the nodes of
// equilateral triangles of edge h (tests/stress/mesh_test.cpp, NodeEstimateFollowsTheGrading).
constexpr double kRefinedDensity = 1.6;

// The graded mesh's nodes, kRefinedDensity (4 V - B) as in check_interior_budget, with V the integral of
// 1 / (sqrt(3)/2 h^2) over the plate: cells of a quadtree over the bounding box, each split until
// it is no wider than h at its centre, counted when their centre is on the plate. Stops as soon as
// the count passes `stop_above` (the refusal needs no more) and returns what it had.
double graded_nodes(const Boundary& b, const Sizing& h, double stop_above) {
  Vector2d lo = Vector2d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Curve& c : b.curves) {
    for (int k = 0; k <= 16; ++k) {
      lo = lo.cwiseMin(c.at(k / 16.0));
      hi = hi.cwiseMax(c.at(k / 16.0));
    }
  }
  const PlateTest plate(b);
  const double boundary = boundary_corners(b, h);
  const Vector2d extent = hi - lo;
  const double side = std::max(extent.minCoeff(), extent.maxCoeff() / 64);
  std::vector<std::pair<Vector2d, double>> cells;  // centre, side
  for (double x = lo.x(); x < hi.x(); x += side)
    for (double y = lo.y(); y < hi.y(); y += side) cells.push_back({{x + side / 2, y + side / 2}, side});
  double corners = 0.0;
  while (!cells.empty()) {
    const auto [centre, width] = cells.back();
    cells.pop_back();
    const double wanted = h(centre);
    if (width > wanted) {
      for (int k = 0; k < 4; ++k)
        cells.push_back({centre + width / 4 * Vector2d(k % 2 ? 1 : -1, k / 2 ? 1 : -1), width / 2});
      continue;
    }
    if (!plate.contains(centre)) continue;
    corners += width * width / (std::sqrt(3.0) / 2 * wanted * wanted);
    if (kRefinedDensity * (4 * corners - boundary) > stop_above) break;
  }
  return kRefinedDensity * (4 * corners - boundary);
}

// Where a piece's boundary vertices go: parameters u in [0, 1), the first at 0.
std::vector<double> piece_stations(const Curve& c, const Piece& p, const Sizing& h, double h_min,
                                   const MeshOptions& o) {
  const double length = c.length();
  // Fine enough to see the smallest feature's size change along the piece.
  const int samples = static_cast<int>(std::clamp(std::ceil(length / h_min), 16.0, 4096.0));
  // The number of elements along the piece is the integral of ds / h.
  std::vector<double> cumulative(samples + 1, 0.0);
  for (int k = 0; k < samples; ++k) {
    const double u = (k + 0.5) / samples;
    cumulative[k + 1] = cumulative[k] + length / samples / h(c.at(p.param(u)));
  }
  const double total = cumulative.back();
  if (!(total < static_cast<double>(corner_budget(o)))) {
    fail("the boundary alone needs more than max_nodes = " + std::to_string(o.max_nodes) +
         " nodes; use a larger element size or fewer segments per hole");
  }
  const int segments = o.segments_per_hole;
  std::vector<double> u;
  if (c.arc) {
    const double sweep = std::abs(c.circle.sweep);
    const int n =
        std::max({static_cast<int>(std::ceil(segments * sweep / (2 * kPi) - 1e-9)),
                  static_cast<int>(std::ceil(sweep / (kPi / 4) - 1e-9)), static_cast<int>(std::lround(total)), 1});
    for (int j = 0; j < n; ++j) u.push_back(static_cast<double>(j) / n);
    return u;
  }
  const int n = std::max(1, static_cast<int>(std::lround(total)));
  u.push_back(0.0);
  int k = 0;
  for (int j = 1; j < n; ++j) {
    const double target = total * j / n;
    while (cumulative[k + 1] < target) ++k;
    const double f = (target - cumulative[k]) / (cumulative[k + 1] - cumulative[k]);
    u.push_back((k + f) / samples);
  }
  return u;
}

detail::RefinementInput refinement_input(const Boundary& b, const Sizing& h, const MeshOptions& o) {
  double h_min = h.size;
  for (const auto& c : h.circles) h_min = std::min(h_min, c.second);
  for (const ArcFeature& a : h.arcs) h_min = std::min(h_min, a.h0);
  for (const auto& p : h.points) h_min = std::min(h_min, p.second);

  detail::RefinementInput in;
  std::size_t count = 0;
  std::vector<std::vector<std::vector<double>>> stations(b.rings.size());
  for (std::size_t r = 0; r < b.rings.size(); ++r) {
    for (const Piece& p : b.rings[r].pieces) {
      stations[r].push_back(piece_stations(b.curves[p.curve], p, h, h_min, o));
      count += stations[r].back().size();
      if (count > corner_budget(o)) {
        fail("the boundary alone needs more than max_nodes = " + std::to_string(o.max_nodes) +
             " nodes; use a larger element size or fewer segments per hole");
      }
    }
  }
  for (std::size_t r = 0; r < b.rings.size(); ++r) {
    const Ring& ring = b.rings[r];
    const int first = static_cast<int>(in.points.size());
    for (std::size_t j = 0; j < ring.pieces.size(); ++j) {
      const Piece& p = ring.pieces[j];
      const std::vector<double>& u = stations[r][j];
      for (std::size_t k = 0; k < u.size(); ++k) {
        const int here = static_cast<int>(in.points.size());
        in.points.push_back(b.curves[p.curve].at(p.param(u[k])));
        in.corner.push_back(k == 0 && ring.has_corners ? 1 : 0);
        const double u_next = k + 1 < u.size() ? u[k + 1] : 1.0;
        in.segments.push_back({here, here + 1, p.curve, p.param(u[k]), p.param(u_next)});
      }
    }
    in.segments.back().b = first;  // close the ring
  }
  double shortest = std::numeric_limits<double>::infinity();
  for (const detail::BoundarySegment& s : in.segments)
    shortest = std::min(shortest, (in.points[s.a] - in.points[s.b]).norm());
  for (const Curve& c : b.curves) {
    in.curved.push_back(c.arc ? 1 : 0);
    in.arc_radius.push_back(c.arc ? c.circle.radius : 0.0);
    in.arc_sweep.push_back(c.arc ? c.circle.sweep : 0.0);
  }
  in.curve_point = [&b](int curve, double t) { return b.curves[curve].at(t); };
  in.size_at = [&h](const Vector2d& x) { return h(x); };
  in.min_angle_deg = kMinAngleDeg;
  in.min_length = shortest / 1024;
  in.max_vertices = static_cast<int>(corner_budget(o));  // refinement stops early past it
  return in;
}

// det J of the 6-node triangle t at the reference point (xi, eta).
double jacobian(const std::vector<Vector2d>& nodes, const std::array<int, 6>& t, double xi, double eta) {
  const double l1 = 1 - xi - eta;
  const double dxi[6] = {-(4 * l1 - 1), 4 * xi - 1, 0, 4 * (l1 - xi), 4 * eta, -4 * eta};
  const double deta[6] = {-(4 * l1 - 1), 0, 4 * eta - 1, -4 * xi, 4 * xi, 4 * (l1 - eta)};
  Vector2d along_xi(0, 0), along_eta(0, 0);
  for (int i = 0; i < 6; ++i) {
    along_xi += dxi[i] * nodes[t[i]];
    along_eta += deta[i] * nodes[t[i]];
  }
  return cross(along_xi, along_eta);
}

// det J is quadratic: positive at the six nodes is the usual test of a usable element.
bool positive_at_nodes(const std::vector<Vector2d>& nodes, const std::array<int, 6>& t) {
  constexpr double kNodes[6][2] = {{0, 0}, {1, 0}, {0, 1}, {0.5, 0}, {0.5, 0.5}, {0, 0.5}};
  for (const auto& p : kNodes) {
    if (!(jacobian(nodes, t, p[0], p[1]) > 0)) return false;
  }
  return true;
}

std::uint64_t edge_key(int a, int b) {
  return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | static_cast<std::uint64_t>(std::max(a, b));
}

TriMesh quadratic_mesh(const detail::RefinedMesh& m, const Boundary& b, int max_nodes) {
  TriMesh mesh;
  mesh.nodes = m.points;
  mesh.corner_count = static_cast<int>(m.points.size());
  const std::size_t triangles = m.triangles.size();
  std::size_t total = mesh.nodes.size();
  for (std::size_t t = 0; t < triangles; ++t) {
    for (int nb : m.neighbours[t]) total += nb < 0 || static_cast<std::size_t>(nb) > t;  // each edge once
  }
  if (total > static_cast<std::size_t>(max_nodes)) {
    fail("the mesh would have " + std::to_string(total) + " nodes, more than max_nodes = " + std::to_string(max_nodes) +
         "; use a larger element size");
  }
  std::unordered_map<std::uint64_t, int> segment_at;
  for (std::size_t i = 0; i < m.segments.size(); ++i)
    segment_at[edge_key(m.segments[i].a, m.segments[i].b)] = static_cast<int>(i);

  mesh.nodes.reserve(total);
  mesh.triangles.resize(triangles);
  for (std::size_t t = 0; t < triangles; ++t) {
    for (int i = 0; i < 3; ++i) {
      mesh.triangles[t][i] = m.triangles[t][i];
      mesh.triangles[t][3 + i] = -1;
    }
  }
  std::vector<int> middle_of_segment(m.segments.size(), -1);
  std::vector<char> curved(triangles, 0);
  for (std::size_t t = 0; t < triangles; ++t) {
    for (int i = 0; i < 3; ++i) {
      if (mesh.triangles[t][3 + i] >= 0) continue;  // made from the triangle across
      const int from = m.triangles[t][i], to = m.triangles[t][(i + 1) % 3];
      const int id = static_cast<int>(mesh.nodes.size());
      Vector2d mid = (m.points[from] + m.points[to]) / 2;
      const int across = m.neighbours[t][i];
      if (across >= 0) {
        for (int j = 0; j < 3; ++j) {
          if (m.triangles[across][j] == to) mesh.triangles[across][3 + j] = id;
        }
      } else {
        const int s = segment_at.at(edge_key(from, to));
        const detail::BoundarySegment& seg = m.segments[s];
        const Curve& curve = b.curves[seg.curve];
        if (curve.arc) {
          mid = curve.at((seg.ta + seg.tb) / 2);
          curved[t] = 1;
        }
        middle_of_segment[s] = id;
      }
      mesh.nodes.push_back(mid);
      mesh.triangles[t][3 + i] = id;
    }
  }
  // Refinement keeps curved triangles tall enough for a positive Jacobian; should one still
  // fold, its edge goes straight (a sagitta's error in the boundary, not an unusable element).
  for (std::size_t t = 0; t < triangles; ++t) {
    if (!curved[t] || positive_at_nodes(mesh.nodes, mesh.triangles[t])) continue;
    const auto& c = mesh.triangles[t];
    for (int i = 0; i < 3; ++i) mesh.nodes[c[3 + i]] = (mesh.nodes[c[i]] + mesh.nodes[c[(i + 1) % 3]]) / 2;
  }
  for (std::size_t i = 0; i < m.segments.size(); ++i) {
    const detail::BoundarySegment& s = m.segments[i];
    mesh.boundary.push_back({{s.a, s.b, middle_of_segment[i]}, b.curves[s.curve].tag});
  }
  return mesh;
}

}  // namespace

namespace {

// The region's boundary and element sizing, once the region, the options and the node budget are
// checked: what mesh_region meshes, and all that check_mesh_budget needs.
struct CheckedRegion {
  Boundary boundary;
  Sizing sizing;
  double estimated_nodes = 0.0;
};
// The estimate refuses a mesh only when it passes the budget by this much: it is within 20 % of
// the mesh's count, and the refinement's own count (VertexBudgetExceeded) refuses what it lets by.
constexpr double kEstimateMargin = 1.25;

CheckedRegion checked_region(const Region& r, const MeshOptions& options) {
  check_options(options);
  check_region(r);
  CheckedRegion out{boundary_of(r), {}, 0.0};
  const Boundary& b = out.boundary;
  const double automatic = bounding_diagonal(b, b.rings.front()) / 20;
  const double size = options.size > 0 ? options.size : automatic;
  // The uniform estimate first: it bounds the graded estimate's work.
  check_interior_budget(b, size, options);
  out.sizing = sizing_of(b, options, size, std::min(1.0, size / automatic));
  const double budget = kEstimateMargin * options.max_nodes;
  out.estimated_nodes = graded_nodes(b, out.sizing, budget);
  if (out.estimated_nodes > budget) fail_budget(out.estimated_nodes, options);
  return out;
}

}  // namespace

void check_mesh_budget(const Region& r, const MeshOptions& options) { checked_region(r, options); }

double estimated_mesh_nodes(const Region& r, const MeshOptions& options) {
  MeshOptions unbounded = options;
  unbounded.max_nodes = std::numeric_limits<int>::max();
  return checked_region(r, unbounded).estimated_nodes;
}

double automatic_mesh_size(const Region& r) {
  check_region(r);
  const Boundary b = boundary_of(r);
  return bounding_diagonal(b, b.rings.front()) / 20;
}

TriMesh mesh_region(const Region& r, const MeshOptions& options) {
  const CheckedRegion checked = checked_region(r, options);
  const Boundary& b = checked.boundary;
  const detail::RefinementInput in = refinement_input(b, checked.sizing, options);
  detail::RefinedMesh refined;
  try {
    refined = detail::refine(in);
  } catch (const detail::VertexBudgetExceeded&) {
    fail("the mesh would have more than max_nodes = " + std::to_string(options.max_nodes) +
         " nodes; use a larger element size");
  } catch (const Error& e) {
    fail(std::string("could not mesh the plate: ") + e.what());
  }
  return quadratic_mesh(refined, b, options.max_nodes);
}

MeshQuality mesh_quality(const TriMesh& mesh) {
  MeshQuality q;
  q.min_angle_deg = 180;
  q.min_edge = std::numeric_limits<double>::infinity();
  // A 3-point rule exact for quadratics integrates det J of a 6-node triangle exactly.
  constexpr double kRule[3][2] = {{0.5, 0.0}, {0.5, 0.5}, {0.0, 0.5}};
  for (const auto& t : mesh.triangles) {
    const Vector2d& a = mesh.nodes[t[0]];
    const Vector2d& b = mesh.nodes[t[1]];
    const Vector2d& c = mesh.nodes[t[2]];
    const double la = (b - c).norm(), lb = (c - a).norm(), lc = (a - b).norm();
    q.max_edge = std::max({q.max_edge, la, lb, lc});
    q.min_edge = std::min({q.min_edge, la, lb, lc});
    const double area2 = std::abs(cross(b - a, c - a));
    const double sine = area2 / std::max({lb * lc, la * lc, la * lb});
    q.min_angle_deg = std::min(q.min_angle_deg, std::asin(std::min(1.0, sine)) * 180 / kPi);
    for (const auto& p : kRule) q.area += jacobian(mesh.nodes, t, p[0], p[1]) / 6;
  }
  if (mesh.triangles.empty()) q.min_angle_deg = q.min_edge = 0;
  return q;
}

}  // namespace nbar::fe
