// Conforming Delaunay refinement: Bowyer-Watson insertion inside a frame around the plate,
// boundary segments recovered by splitting those that some vertex encroaches (a vertex inside a
// segment's diametral circle), then Ruppert's loop: a triangle with too small an angle or too
// large for the sizing function gets its circumcentre, unless that point would encroach a
// segment, in which case the segment is split instead. With no encroached segment every segment
// is a Delaunay edge, so the triangulation conforms to the boundary without constrained edges.
//
// Segments (straight or arcs) touching an input corner are split at powers of two from it
// (concentric shells), so the splits at a sharp corner match up and refinement there terminates.
#include "delaunay_refinement.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <numbers>
#include <string>
#include <unordered_map>

#include "nbar/model/diagnostics.hpp"

namespace nbar::fe::detail {
namespace {

using Eigen::Vector2d;

// Twice the signed area of a, b, c: positive when counterclockwise. Computed from the same end
// of the edge a-b whichever way round it is given, so that the two triangles sharing an edge
// never both see a point near it as outside (the walk would circle round it).
double orient(const Vector2d& a, const Vector2d& b, const Vector2d& c) {
  const bool swap = b.x() < a.x() || (b.x() == a.x() && b.y() < a.y());
  const Vector2d& p = swap ? b : a;
  const Vector2d& q = swap ? a : b;
  const double o = (q.x() - p.x()) * (c.y() - p.y()) - (q.y() - p.y()) * (c.x() - p.x());
  return swap ? -o : o;
}

// Positive when d is inside the circle through the counterclockwise a, b, c.
double incircle(const Vector2d& a, const Vector2d& b, const Vector2d& c, const Vector2d& d) {
  const double adx = a.x() - d.x(), ady = a.y() - d.y();
  const double bdx = b.x() - d.x(), bdy = b.y() - d.y();
  const double cdx = c.x() - d.x(), cdy = c.y() - d.y();
  const double alift = adx * adx + ady * ady, blift = bdx * bdx + bdy * bdy, clift = cdx * cdx + cdy * cdy;
  return alift * (bdx * cdy - cdx * bdy) + blift * (cdx * ady - adx * cdy) + clift * (adx * bdy - bdx * ady);
}

Vector2d circumcentre(const Vector2d& a, const Vector2d& b, const Vector2d& c) {
  const Vector2d ab = b - a, ac = c - a;
  const double d = 2 * (ab.x() * ac.y() - ab.y() * ac.x());
  const double ab2 = ab.squaredNorm(), ac2 = ac.squaredNorm();
  return a + Vector2d(ac.y() * ab2 - ab.y() * ac2, ab.x() * ac2 - ac.x() * ab2) / d;
}

// The square of the sine of the triangle's smallest angle (0 for a degenerate one), without
// square roots: sin = 2 area / (product of the two longer edges), the smallest angle facing
// the shortest edge.
double min_angle_sine_squared(const Vector2d& a, const Vector2d& b, const Vector2d& c) {
  const double area2 = orient(a, b, c);
  const double la = (b - c).squaredNorm(), lb = (c - a).squaredNorm(), lc = (a - b).squaredNorm();
  const double longer_pair = std::max({lb * lc, la * lc, la * lb});
  return longer_pair > 0 ? area2 * area2 / longer_pair : 0.0;
}

constexpr int kSuper = 4;  // vertices 0 to 3 frame everything

class Refiner {
 public:
  explicit Refiner(const RefinementInput& in)
      : in_(in), sin_min_squared_(std::pow(std::sin(in.min_angle_deg * std::numbers::pi / 180), 2)) {}

  RefinedMesh run() {
    make_frame();
    insert_boundary_points();
    for (BoundarySegment s : in_.segments) {
      s.a += kSuper;
      s.b += kSuper;
      add_segment(s);
    }
    for (int i = 0; i < static_cast<int>(segs_.size()); ++i) seg_queue_.push_back(i);
    drain_segments();
    classify();
    for (int t = 0; t < static_cast<int>(tris_.size()); ++t) {
      if (tris_[t].alive && tris_[t].inside) tri_queue_.push_back(t);
    }
    refine_triangles();
    classify();
    check_conformity();
    RefinedMesh out = collect();
    smooth(out);
    return out;
  }

 private:
  struct Tri {
    std::array<int, 3> v{};
    std::array<int, 3> n{};  // n[i]: the triangle across the edge opposite v[i], -1 none
    bool alive = true;
    bool inside = false;
  };
  struct Seg {
    BoundarySegment s;
    bool alive = true;
  };
  struct RimEdge {
    int a, b, outer;
  };

  const RefinementInput& in_;
  double sin_min_squared_;
  std::vector<Vector2d> pts_;
  std::vector<char> corner_, on_boundary_;
  std::vector<int> vertex_tri_;
  std::vector<Tri> tris_;
  std::vector<int> free_tris_;
  std::vector<Seg> segs_;
  std::unordered_map<std::uint64_t, int> seg_at_;
  std::deque<int> seg_queue_, tri_queue_;
  std::vector<int> mark_;
  int stamp_ = 0;
  std::vector<int> vertex_mark_;
  int vertex_stamp_ = 0;
  std::vector<int> cavity_, new_tris_, fan_start_;
  std::vector<RimEdge> rim_;
  std::vector<int> cavity_segments_;

  static std::uint64_t key(int a, int b) {
    const auto lo = static_cast<std::uint64_t>(std::min(a, b)), hi = static_cast<std::uint64_t>(std::max(a, b));
    return (lo << 32) | hi;
  }
  int segment_at(int a, int b) const {
    if (!on_boundary_[a] || !on_boundary_[b]) return -1;  // most edges: no hashing
    const auto it = seg_at_.find(key(a, b));
    return it == seg_at_.end() ? -1 : it->second;
  }
  void add_segment(const BoundarySegment& s) {
    seg_at_[key(s.a, s.b)] = static_cast<int>(segs_.size());
    segs_.push_back({s, true});
  }
  void remove_segment(int i) {
    segs_[i].alive = false;
    seg_at_.erase(key(segs_[i].s.a, segs_[i].s.b));
  }

  int add_vertex(const Vector2d& p, bool corner, bool on_boundary) {
    pts_.push_back(p);
    corner_.push_back(corner ? 1 : 0);
    on_boundary_.push_back(on_boundary ? 1 : 0);
    vertex_tri_.push_back(-1);
    fan_start_.push_back(-1);
    vertex_mark_.push_back(0);
    return static_cast<int>(pts_.size()) - 1;
  }

  int new_triangle() {
    if (!free_tris_.empty()) {
      const int t = free_tris_.back();
      free_tris_.pop_back();
      tris_[t] = Tri{};
      return t;
    }
    tris_.emplace_back();
    mark_.push_back(0);
    return static_cast<int>(tris_.size()) - 1;
  }

  // A frame around the plate: four vertices of a box twice the size of its bounding box, as
  // two triangles. Every boundary point is well inside, so none is ever on the hull and all
  // circles stay of the plate's size.
  void make_frame() {
    Vector2d lo = in_.points.front(), hi = lo;
    for (const Vector2d& p : in_.points) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    const double margin = std::max((hi - lo).maxCoeff(), 1e-300);
    lo -= Vector2d::Constant(margin);
    hi += Vector2d::Constant(margin);
    add_vertex(lo, false, false);
    add_vertex({hi.x(), lo.y()}, false, false);
    add_vertex(hi, false, false);
    add_vertex({lo.x(), hi.y()}, false, false);
    const int t0 = new_triangle(), t1 = new_triangle();
    tris_[t0].v = {0, 1, 2};
    tris_[t0].n = {-1, t1, -1};
    tris_[t1].v = {0, 2, 3};
    tris_[t1].n = {-1, -1, t0};
    vertex_tri_ = {t0, t0, t0, t1};
  }

  void insert_boundary_points() {
    int last = 0;
    for (std::size_t i = 0; i < in_.points.size(); ++i) {
      const int seed = locate(in_.points[i], last);
      if (seed < 0 || !make_cavity(in_.points[i], seed)) {
        throw Error(ErrorKind::Internal, "mesher: could not insert a boundary point");
      }
      commit(add_vertex(in_.points[i], in_.corner[i] != 0, true));
      last = new_tris_.front();
    }
  }

  // The triangle containing p: a visibility walk from `start` that tries the edges in a
  // pseudo-random (but fixed) order, since a fixed order can cycle; a scan of all triangles if
  // the walk gets lost. -1 if p is outside the frame.
  int locate(const Vector2d& p, int start) {
    int t = start;
    const std::size_t limit = 4 * tris_.size() + 64;
    for (std::size_t step = 0; step < limit && t >= 0; ++step) {
      if (contains(t, p, t)) return t;
    }
    for (int u = 0; u < static_cast<int>(tris_.size()); ++u) {
      int next = 0;
      if (tris_[u].alive && contains(u, p, next)) return u;
    }
    return -1;
  }

  // Whether triangle t contains p; if not, `next` is a neighbour on p's side of some edge.
  bool contains(int t, const Vector2d& p, int& next) {
    const Tri& tri = tris_[t];
    walk_state_ = walk_state_ * 6364136223846793005ULL + 1442695040888963407ULL;
    const int first = static_cast<int>((walk_state_ >> 33) % 3);
    for (int k = 0; k < 3; ++k) {
      const int i = (first + k) % 3;
      if (orient(pts_[tri.v[(i + 1) % 3]], pts_[tri.v[(i + 2) % 3]], p) < 0) {
        next = tri.n[i];
        return false;
      }
    }
    return true;
  }
  std::uint64_t walk_state_ = 1;

  bool in_circumcircle(const Tri& t, const Vector2d& p) const {
    return incircle(pts_[t.v[0]], pts_[t.v[1]], pts_[t.v[2]], p) > 0;
  }

  // The Bowyer-Watson cavity of p grown from `seed` (which must contain p or have it in its
  // circumcircle), and its rim. False when the cavity is not star-shaped from p even after
  // dropping the triangles that spoil it (rounding in near-degenerate configurations).
  bool make_cavity(const Vector2d& p, int seed) {
    ++stamp_;
    cavity_.assign(1, seed);
    mark_[seed] = stamp_;
    // A point on an edge of its triangle (a boundary segment's split point) is inside the circle
    // of the triangle across, but the incircle test cannot tell when that triangle is flat and
    // its circle huge: take that triangle in anyway.
    const Tri& s = tris_[seed];
    for (int i = 0; i < 3; ++i) {
      const Vector2d& a = pts_[s.v[(i + 1) % 3]];
      const Vector2d& b = pts_[s.v[(i + 2) % 3]];
      const int nb = s.n[i];
      if (nb >= 0 && mark_[nb] != stamp_ && orient(a, b, p) <= 1e-13 * (b - a).squaredNorm()) {
        mark_[nb] = stamp_;
        cavity_.push_back(nb);
      }
    }
    for (std::size_t k = 0; k < cavity_.size(); ++k) {
      const Tri& tri = tris_[cavity_[k]];
      for (int i = 0; i < 3; ++i) {
        const int nb = tri.n[i];
        if (nb < 0 || mark_[nb] == stamp_) continue;
        if (in_circumcircle(tris_[nb], p)) {
          mark_[nb] = stamp_;
          cavity_.push_back(nb);
        }
      }
    }
    for (int attempt = 0; attempt < 8; ++attempt) {
      const int spoiler = find_spoiler(p, seed);
      if (spoiler == -1) return true;
      if (spoiler == seed || spoiler == -2) return false;
      mark_[spoiler] = stamp_ - 1;
      cavity_.erase(std::find(cavity_.begin(), cavity_.end(), spoiler));
    }
    return false;
  }

  // Collects the cavity's rim and returns -1 when the cavity is a disk star-shaped from p with
  // every vertex on its rim, which is what exact arithmetic guarantees for a Delaunay cavity.
  // Otherwise (rounding near degenerate configurations) a cavity triangle to drop, or -2 when
  // there is none to drop.
  int find_spoiler(const Vector2d& p, int seed) {
    ++vertex_stamp_;
    rim_.clear();
    int spoiler = -1;
    for (int t : cavity_) {
      const Tri& tri = tris_[t];
      for (int i = 0; i < 3; ++i) {
        const int nb = tri.n[i];
        if (nb >= 0 && mark_[nb] == stamp_) continue;
        const int a = tri.v[(i + 1) % 3], b = tri.v[(i + 2) % 3];
        if (!(orient(pts_[a], pts_[b], p) > 0) && spoiler < 0) spoiler = t;
        if (vertex_mark_[a] == vertex_stamp_) return -2;  // the rim pinches: not a disk
        vertex_mark_[a] = vertex_stamp_;
        rim_.push_back({a, b, nb});
      }
    }
    if (spoiler >= 0) return spoiler;
    // A vertex inside the cavity would be lost from the mesh.
    for (int t : cavity_) {
      for (int v : tris_[t].v) {
        if (vertex_mark_[v] == vertex_stamp_) continue;
        for (int u : cavity_) {
          const Tri& other = tris_[u];
          if (u != seed && (other.v[0] == v || other.v[1] == v || other.v[2] == v)) return u;
        }
        return -2;
      }
    }
    return -1;
  }

  // Replaces the cavity by the fan of triangles from the new vertex v to the rim.
  void commit(int v) {
    for (int t : cavity_) {
      tris_[t].alive = false;
      free_tris_.push_back(t);
    }
    new_tris_.clear();
    for (const RimEdge& r : rim_) {
      const int t = new_triangle();
      Tri& tri = tris_[t];
      tri.v = {r.a, r.b, v};
      tri.n = {-1, -1, r.outer};
      const int s = segment_at(r.a, r.b);
      if (s >= 0) {
        tri.inside = segs_[s].s.a == r.a;
      } else {
        tri.inside = r.outer >= 0 && tris_[r.outer].inside;
      }
      if (r.outer >= 0) {
        Tri& o = tris_[r.outer];
        for (int j = 0; j < 3; ++j) {
          if (o.v[(j + 1) % 3] == r.b && o.v[(j + 2) % 3] == r.a) o.n[j] = t;
        }
      }
      fan_start_[r.a] = t;
      vertex_tri_[r.a] = t;
      new_tris_.push_back(t);
    }
    for (int t : new_tris_) {
      Tri& tri = tris_[t];
      const int across_bv = fan_start_[tri.v[1]];  // (b, c, v) shares the edge b-v
      if (across_bv < 0) throw Error(ErrorKind::Internal, "mesher: a cavity's rim is not closed");
      tri.n[0] = across_bv;
      tris_[across_bv].n[1] = t;
    }
    for (const RimEdge& r : rim_) fan_start_[r.a] = -1;
    vertex_tri_[v] = new_tris_.front();
  }

  // The triangle with the directed edge a -> b and the index of a in it, or {-1, -1}.
  std::pair<int, int> find_edge(int a, int b) const {
    const int start = vertex_tri_[a];
    int t = start;
    for (int dir = 0; dir < 2; ++dir) {
      t = start;
      for (int step = 0; step < 100000 && t >= 0; ++step) {
        const Tri& tri = tris_[t];
        const int i = tri.v[0] == a ? 0 : tri.v[1] == a ? 1 : 2;
        if (tri.v[(i + 1) % 3] == b) return {t, i};
        t = dir == 0 ? tri.n[(i + 2) % 3] : tri.n[(i + 1) % 3];
        if (t == start) return {-1, -1};
      }
    }
    return {-1, -1};
  }

  bool encroached(const Seg& seg) const {
    const int a = seg.s.a, b = seg.s.b;
    for (const auto& [t, i] : {find_edge(a, b), find_edge(b, a)}) {
      if (t < 0) return true;
      const int apex = tris_[t].v[(i + 2) % 3];
      if (apex < kSuper) continue;
      if ((pts_[a] - pts_[apex]).dot(pts_[b] - pts_[apex]) < 0) return true;
    }
    return in_.curved[seg.s.curve] && too_curved(seg);
  }

  // A 6-node triangle whose edge bulges by the sagitta s towards the opposite corner, at height
  // h above it, has det J = L (h − 4 s x / L) at the edge's ends (x: the corner's offset along
  // the edge), positive only while s < h / 4. A curved segment whose triangle inside is not
  // six times taller than the arc's sagitta is split (which quarters the sagitta). Not more:
  // three consecutive points of an arc make a triangle only about 8 sagittas tall, and splitting
  // would reproduce it at every scale.
  bool too_curved(const Seg& seg) const {
    const auto [t, i] = find_edge(seg.s.a, seg.s.b);
    if (t < 0) return false;
    const Vector2d& a = pts_[seg.s.a];
    const Vector2d& b = pts_[seg.s.b];
    const Vector2d& apex = pts_[tris_[t].v[(i + 2) % 3]];
    const double length = (b - a).norm();
    const double height = orient(a, b, apex) / length;
    const double sagitta = (in_.curve_point(seg.s.curve, (seg.s.ta + seg.s.tb) / 2) - (a + b) / 2).norm();
    return height < kHeightPerSagitta * sagitta;
  }
  static constexpr double kHeightPerSagitta = 6.0;

  bool is_edge(int a, int b) const { return find_edge(a, b).first >= 0; }

  void split_segment(int si) {
    const BoundarySegment s = segs_[si].s;
    const Vector2d& pa = pts_[s.a];
    const Vector2d& pb = pts_[s.b];
    double f = 0.5;
    if (corner_[s.a] != corner_[s.b]) {
      // Concentric shells: the split's distance from the corner is a power of two, so that the
      // splits on the two sides of a sharp corner match and stop encroaching each other.
      const double length = (pb - pa).norm();
      const double d = std::exp2(std::round(std::log2(length / 2)));
      double from_corner = d / length;
      if (in_.curved[s.curve]) {
        // Along an arc of radius R the chord d subtends 2 asin(d / 2R) of the segment's angle.
        const double radius = in_.arc_radius[s.curve];
        const double angle = std::abs((s.tb - s.ta) * in_.arc_sweep[s.curve]);
        from_corner = 2 * std::asin(std::min(1.0, d / (2 * radius))) / angle;
      }
      if (from_corner > 0.2 && from_corner < 0.8) f = corner_[s.a] ? from_corner : 1 - from_corner;
    }
    const double tm = s.ta + f * (s.tb - s.ta);
    const Vector2d m = in_.curved[s.curve] ? in_.curve_point(s.curve, tm) : Vector2d(pa + f * (pb - pa));
    const int seed = locate(m, vertex_tri_[s.a]);
    if (seed < 0) throw Error(ErrorKind::Internal, "mesher: could not locate a boundary split");
    if (!make_cavity(m, seed)) throw Error(ErrorKind::Internal, "mesher: could not split a boundary segment");
    remove_segment(si);
    // Other segments inside the cavity would stop being edges: split them too.
    find_cavity_segments();
    const int v = add_vertex(m, false, true);
    commit(v);
    // A segment that was no edge may leave halves that are none either: check them too.
    seg_queue_.push_back(static_cast<int>(segs_.size()));
    add_segment({s.a, v, s.curve, s.ta, tm});
    seg_queue_.push_back(static_cast<int>(segs_.size()));
    add_segment({v, s.b, s.curve, tm, s.tb});
    for (int other : cavity_segments_) seg_queue_.push_back(other);
    after_insertion();
  }

  // Segments that are edges between two triangles of the cavity.
  void find_cavity_segments() {
    cavity_segments_.clear();
    for (int t : cavity_) {
      const Tri& tri = tris_[t];
      for (int i = 0; i < 3; ++i) {
        const int nb = tri.n[i];
        if (nb < 0 || mark_[nb] != stamp_ || nb < t) continue;
        const int s = segment_at(tri.v[(i + 1) % 3], tri.v[(i + 2) % 3]);
        if (s >= 0) cavity_segments_.push_back(s);
      }
    }
  }

  void after_insertion() {
    for (int t : new_tris_) {
      const Tri& tri = tris_[t];
      // Only the rim edge (opposite the new vertex) and the new vertex's own segments can have
      // changed encroachment; checking all three edges covers both.
      for (int i = 0; i < 3; ++i) {
        const int s = segment_at(tri.v[(i + 1) % 3], tri.v[(i + 2) % 3]);
        if (s >= 0 && encroached(segs_[s])) seg_queue_.push_back(s);
      }
      if (tri.inside && is_bad(t)) tri_queue_.push_back(t);
    }
    if (static_cast<int>(pts_.size()) - kSuper > in_.max_vertices) {
      throw VertexBudgetExceeded("mesher: more than " + std::to_string(in_.max_vertices) + " vertices");
    }
  }

  bool long_enough(const Seg& seg) const { return (pts_[seg.s.a] - pts_[seg.s.b]).norm() > in_.min_length; }

  void drain_segments() {
    while (!seg_queue_.empty()) {
      const int s = seg_queue_.front();
      seg_queue_.pop_front();
      if (!segs_[s].alive) continue;
      const bool edge = is_edge(segs_[s].s.a, segs_[s].s.b);
      if (!edge && !long_enough(segs_[s])) {
        const Vector2d& at = pts_[segs_[s].s.a];
        throw Error(ErrorKind::BadInput, "the boundary cannot be resolved near (" + std::to_string(at.x()) + ", " +
                                             std::to_string(at.y()) + ") m: a corner too sharp or parts too close");
      }
      if (!edge || (long_enough(segs_[s]) && encroached(segs_[s]))) split_segment(s);
    }
  }

  bool is_bad(int t) const {
    const Tri& tri = tris_[t];
    if (tri.v[0] < kSuper || tri.v[1] < kSuper || tri.v[2] < kSuper) return false;
    const Vector2d &a = pts_[tri.v[0]], &b = pts_[tri.v[1]], &c = pts_[tri.v[2]];
    const double la = (b - c).squaredNorm(), lb = (c - a).squaredNorm(), lc = (a - b).squaredNorm();
    if (std::min({la, lb, lc}) <= in_.min_length * in_.min_length) return false;
    const double area2 = orient(a, b, c);
    if (area2 * area2 < sin_min_squared_ * std::max({lb * lc, la * lc, la * lb})) return true;
    // Circumradius R = |a - b| |b - c| |c - a| / (4 area), squared; area2 is twice the area.
    const double radius_squared = la * lb * lc / (4 * area2 * area2);
    const double wanted = kRadiusPerSize * in_.size_at((a + b + c) / 3);
    return radius_squared > wanted * wanted;
  }
  // An equilateral triangle of edge h has circumradius h / sqrt(3) = 0.577 h; refining above
  // 0.65 h leaves edges of about the wanted length.
  static constexpr double kRadiusPerSize = 0.65;

  void refine_triangles() {
    for (;;) {
      if (!seg_queue_.empty()) {
        drain_segments();
        continue;
      }
      if (tri_queue_.empty()) break;
      const int t = tri_queue_.front();
      tri_queue_.pop_front();
      if (tris_[t].alive && tris_[t].inside && is_bad(t)) split_triangle(t);
    }
  }

  void split_triangle(int t) {
    const Tri& tri = tris_[t];
    const Vector2d c = circumcentre(pts_[tri.v[0]], pts_[tri.v[1]], pts_[tri.v[2]]);
    if (!c.allFinite() || !make_cavity(c, t)) return;
    // A circumcentre that would encroach a segment (or lies beyond one) is not inserted: the
    // segment is split instead and the triangle tried again (Ruppert).
    find_cavity_segments();
    std::vector<int> to_split = cavity_segments_;
    for (const RimEdge& r : rim_) {
      const int s = segment_at(r.a, r.b);
      if (s >= 0 && (pts_[r.a] - c).dot(pts_[r.b] - c) < 0) to_split.push_back(s);
    }
    if (!to_split.empty()) {
      bool split_any = false;
      for (int s : to_split) {
        if (segs_[s].alive && long_enough(segs_[s])) {
          split_segment(s);
          split_any = true;
        }
      }
      if (split_any && tris_[t].alive) tri_queue_.push_back(t);
      return;
    }
    commit(add_vertex(c, false, false));
    after_insertion();
  }

  // Inside: reachable from the left side of a segment without crossing one.
  void classify() {
    for (Tri& tri : tris_) tri.inside = false;
    std::vector<int> stack;
    for (const Seg& seg : segs_) {
      if (!seg.alive) continue;
      const int t = find_edge(seg.s.a, seg.s.b).first;
      if (t >= 0 && !tris_[t].inside) {
        tris_[t].inside = true;
        stack.push_back(t);
      }
    }
    while (!stack.empty()) {
      const int t = stack.back();
      stack.pop_back();
      for (int i = 0; i < 3; ++i) {
        const int nb = tris_[t].n[i];
        if (nb < 0 || tris_[nb].inside) continue;
        if (segment_at(tris_[t].v[(i + 1) % 3], tris_[t].v[(i + 2) % 3]) >= 0) continue;
        tris_[nb].inside = true;
        stack.push_back(nb);
      }
    }
  }

  void check_conformity() const {
    for (const Seg& seg : segs_) {
      if (seg.alive && !is_edge(seg.s.a, seg.s.b))
        throw Error(ErrorKind::Internal, "mesher: a boundary segment was lost");
    }
    for (const Tri& tri : tris_) {
      if (tri.alive && tri.inside && (tri.v[0] < kSuper || tri.v[1] < kSuper || tri.v[2] < kSuper)) {
        throw Error(ErrorKind::Internal, "mesher: the boundary is not closed");
      }
    }
  }

  RefinedMesh collect() const {
    RefinedMesh out;
    std::vector<int> index(pts_.size(), -1);
    for (const Tri& tri : tris_) {
      if (!tri.alive || !tri.inside) continue;
      for (int v : tri.v) index[v] = 0;
    }
    for (std::size_t v = 0; v < pts_.size(); ++v) {
      if (index[v] == 0) {
        index[v] = static_cast<int>(out.points.size());
        out.points.push_back(pts_[v]);
      }
    }
    std::vector<int> tri_index(tris_.size(), -1);
    for (std::size_t t = 0; t < tris_.size(); ++t) {
      const Tri& tri = tris_[t];
      if (!tri.alive || !tri.inside) continue;
      tri_index[t] = static_cast<int>(out.triangles.size());
      out.triangles.push_back({index[tri.v[0]], index[tri.v[1]], index[tri.v[2]]});
    }
    for (const Tri& tri : tris_) {
      if (!tri.alive || !tri.inside) continue;
      std::array<int, 3> across{};
      for (int i = 0; i < 3; ++i) {
        const int nb = tri.n[(i + 2) % 3];  // across the edge v[i] -> v[i + 1]
        across[i] = nb >= 0 ? tri_index[nb] : -1;
      }
      out.neighbours.push_back(across);
    }
    for (const Seg& seg : segs_) {
      if (!seg.alive) continue;
      BoundarySegment s = seg.s;
      s.a = index[s.a];
      s.b = index[s.b];
      out.segments.push_back(s);
    }
    return out;
  }

  // Smart Laplacian smoothing: an interior vertex moves to the mean of its neighbours only if
  // that does not lower the smallest angle of the triangles around it (so none inverts).
  void smooth(RefinedMesh& m) const {
    const int n = static_cast<int>(m.points.size());
    std::vector<char> fixed(n, 0);
    for (const BoundarySegment& s : m.segments) fixed[s.a] = fixed[s.b] = 1;
    // The corners facing curved edges stay too: their height above the edge keeps the curved
    // triangle's Jacobian positive (too_curved()).
    std::unordered_map<std::uint64_t, char> curved_edge;
    for (const BoundarySegment& s : m.segments) {
      if (in_.curved[s.curve]) curved_edge[key(s.a, s.b)] = 1;
    }
    for (const auto& t : m.triangles) {
      for (int i = 0; i < 3; ++i) {
        if (curved_edge.count(key(t[i], t[(i + 1) % 3]))) fixed[t[(i + 2) % 3]] = 1;
      }
    }
    std::vector<int> first(n + 1, 0);
    for (const auto& t : m.triangles) {
      for (int v : t) ++first[v + 1];
    }
    for (int v = 0; v < n; ++v) first[v + 1] += first[v];
    std::vector<int> around(first[n]), fill(first.begin(), first.end() - 1);
    for (int t = 0; t < static_cast<int>(m.triangles.size()); ++t) {
      for (int v : m.triangles[t]) around[fill[v]++] = t;
    }
    auto worst = [&](int v) {
      double w = 1.0;
      for (int k = first[v]; k < first[v + 1]; ++k) {
        const auto& t = m.triangles[around[k]];
        const Vector2d &a = m.points[t[0]], &b = m.points[t[1]], &c = m.points[t[2]];
        if (!(orient(a, b, c) > 0)) return -1.0;
        w = std::min(w, min_angle_sine_squared(a, b, c));
      }
      return w;
    };
    for (int pass = 0; pass < in_.smoothing_passes; ++pass) {
      for (int v = 0; v < n; ++v) {
        if (fixed[v] || first[v] == first[v + 1]) continue;
        Vector2d sum(0, 0);
        int count = 0;
        for (int k = first[v]; k < first[v + 1]; ++k) {
          for (int u : m.triangles[around[k]]) {
            if (u != v) {
              sum += m.points[u];
              ++count;
            }
          }
        }
        const Vector2d old = m.points[v];
        const double before = worst(v);
        m.points[v] = sum / count;
        if (!(worst(v) >= before)) m.points[v] = old;
      }
    }
  }
};

}  // namespace

RefinedMesh refine(const RefinementInput& input) { return Refiner(input).run(); }

}  // namespace nbar::fe::detail
