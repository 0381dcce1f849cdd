#include "nbar/io/sketch.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <string_view>

#include "model/box_index.hpp"
#include "model/double_text.hpp"
#include "nbar/io/model_file.hpp"
#include "nbar/model/diagnostics.hpp"
#include "sketch_strokes.hpp"

namespace nbar::io {

using Eigen::Vector2d;

double SketchLoop::area() const {
  Region r;
  r.outline = vertices;
  if (std::any_of(bulges.begin(), bulges.end(), [](double b) { return b != 0.0; })) r.outline_bulges = bulges;
  return std::abs(area_properties(r).area);
}

namespace sketch_detail {

void fail_at(const std::string& file, int line, const std::string& message) {
  throw ModelFileError(file, SourceMark{line, 1}, message);
}

namespace {

Stroke reversed(Stroke s) {
  std::reverse(s.segments.begin(), s.segments.end());
  for (Segment& g : s.segments) {
    std::swap(g.a, g.b);
    std::swap(g.s0, g.s1);
    g.bulge = -g.bulge;  // run backwards, an arc turns the other way
  }
  return s;
}

struct Chained {
  std::vector<Segment> segments;
  std::vector<int> lines;  // per segment
  std::string layer;
};

// The open strokes' end points in cells of twice the tolerance, so that finding the stroke that
// goes on from a point looks at a few strokes, not at all of them (60 000 LINEs took 109 s).
class EndPoints {
 public:
  EndPoints(const std::vector<Stroke>& strokes, double tolerance) : cell_(2.0 * tolerance) {
    for (std::size_t k = 0; k < strokes.size(); ++k) {
      if (strokes[k].closed) continue;
      cells_[key(strokes[k].segments.front().a)].push_back(k);
      cells_[key(strokes[k].segments.back().b)].push_back(k);
    }
  }
  // The strokes with an end point in the cells around p, in no particular order.
  template <class Visit>
  void near(const Vector2d& p, const Visit& visit) const {
    const auto [i, j] = key(p);
    for (long long di = -1; di <= 1; ++di)
      for (long long dj = -1; dj <= 1; ++dj)
        if (const auto it = cells_.find({i + di, j + dj}); it != cells_.end())
          for (std::size_t k : it->second) visit(k);
  }

 private:
  std::pair<long long, long long> key(const Vector2d& p) const { return {cell_of(p.x()), cell_of(p.y())}; }
  // A coordinate's cell. Beyond what a cell's index can count (a drawing of 1e3 with a tolerance
  // of 1e-20: the cast overflowed) the cells clamp to the last one, which only makes the search
  // there slower; a coordinate that is not a number shares cell 0.
  long long cell_of(double coordinate) const {
    constexpr double kLastCell = 4e18;  // within long long, with room for the neighbours' +-1
    const double cell = std::floor(coordinate / cell_);
    if (!(cell == cell)) return 0;
    return static_cast<long long>(std::clamp(cell, -kLastCell, kLastCell));
  }
  double cell_;
  std::map<std::pair<long long, long long>, std::vector<std::size_t>> cells_;
};

std::vector<Chained> chain(const std::vector<Stroke>& strokes, double tolerance, const std::string& file) {
  std::vector<Chained> loops;
  std::vector<bool> used(strokes.size(), false);
  const EndPoints ends(strokes, tolerance);
  const auto append = [](Chained& c, const Stroke& s) {
    for (const Segment& g : s.segments) {
      c.segments.push_back(g);
      c.lines.push_back(s.line);
    }
  };
  for (std::size_t first = 0; first < strokes.size(); ++first) {
    if (used[first]) continue;
    used[first] = true;
    Chained loop;
    loop.layer = strokes[first].layer;
    append(loop, strokes[first]);
    const Vector2d start = loop.segments.front().a;
    if (strokes[first].closed && (loop.segments.back().b - start).norm() > tolerance) {
      loop.segments.push_back({loop.segments.back().b, start});
      loop.lines.push_back(strokes[first].line);
    }
    while ((loop.segments.back().b - start).norm() > tolerance) {
      const Vector2d end = loop.segments.back().b;
      // The first stroke in the file's order that goes on from `end`, as a scan of them all
      // would find it: the outline's order does not depend on the cells.
      std::size_t next = strokes.size();
      ends.near(end, [&](std::size_t k) {
        if (used[k] || k >= next) return;
        if ((strokes[k].segments.front().a - end).norm() <= tolerance ||
            (strokes[k].segments.back().b - end).norm() <= tolerance)
          next = k;
      });
      if (next == strokes.size()) {
        fail_at(file, loop.lines.back(),
                fmt::format("the outline is not closed: the entity here ends at ({:.6g}, {:.6g}) and no other entity "
                            "starts there (within {:.3g})",
                            end.x(), end.y(), tolerance));
      }
      const Stroke& s = strokes[next];
      append(loop, (s.segments.front().a - end).norm() <= tolerance ? s : reversed(s));
      used[next] = true;
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

SketchLoop polygonised_loop(const Chained& c, double tolerance, const std::string& file) {
  SketchLoop loop;
  loop.layer = c.layer;
  for (std::size_t i = 0; i < c.segments.size(); ++i) {
    const Segment& g = c.segments[i];
    if (!g.curve) {
      loop.vertices.push_back(g.a);
      loop.bulges.push_back(g.bulge);
      loop.lines.push_back(c.lines[i]);
      continue;
    }
    std::vector<Vector2d> points;
    try {
      points = sample_curve(g.curve, g.s0, g.s1, tolerance);
    } catch (const Error& error) {
      fail_at(file, c.lines[i], std::string("this curve: ") + error.what());
    }
    points.front() = g.a;
    for (std::size_t k = 0; k + 1 < points.size(); ++k) {
      loop.vertices.push_back(points[k]);
      loop.bulges.push_back(0.0);
      loop.lines.push_back(c.lines[i]);
    }
  }
  // Ends that met within the tolerance but not exactly: drop the doubled vertices.
  const double same = 1e-9 * tolerance / kRelativeCurveTolerance;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < loop.vertices.size(); ++i) {
    if (kept > 0 && (loop.vertices[i] - loop.vertices[kept - 1]).norm() <= same && loop.bulges[kept - 1] == 0) {
      loop.bulges[kept - 1] = loop.bulges[i];
      continue;
    }
    loop.vertices[kept] = loop.vertices[i];
    loop.bulges[kept] = loop.bulges[i];
    loop.lines[kept] = loop.lines[i];
    ++kept;
  }
  // And the last vertex that came back to within `same` of the first by a straight edge: an
  // SVG subpath of relative moves closed by Z, whose sums of decimals land a rounding error off
  // its start (0.06 + -0.02 is 0.039999999999999994). Kept, it was an edge 1e-17 long that the
  // model written rounded to two coinciding vertices, in drawings of one unit and not of another.
  if (kept > 2 && (loop.vertices[kept - 1] - loop.vertices[0]).norm() <= same && loop.bulges[kept - 1] == 0) --kept;
  loop.vertices.resize(kept);
  loop.bulges.resize(kept);
  loop.lines.resize(kept);
  return loop;
}

double cross(const Vector2d& u, const Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); }

// Where the closed segments ab and cd meet, if they do: the crossing, or where they overlap.
std::optional<Vector2d> meeting_point(const Vector2d& a, const Vector2d& b, const Vector2d& c, const Vector2d& d) {
  const Vector2d u = b - a, v = d - c;
  const double denominator = cross(u, v);
  if (denominator != 0) {
    const double t = cross(c - a, v) / denominator, s = cross(c - a, u) / denominator;
    if (t < 0 || t > 1 || s < 0 || s > 1) return std::nullopt;
    return Vector2d(a + t * u);
  }
  if (cross(c - a, u) != 0) return std::nullopt;  // parallel, apart
  const auto on = [](const Vector2d& p, const Vector2d& from, const Vector2d& to) {
    return (p - from).dot(to - from) >= 0 && (p - to).dot(from - to) >= 0;
  };
  for (const Vector2d& p : {c, d}) {
    if (on(p, a, b)) return p;
  }
  if (on(a, c, d)) return a;
  return std::nullopt;
}

// The first point where two edges of the loop, arcs cut into chords, that are not neighbours
// meet: where it crosses itself. The edges near each edge come from a BoxIndex in ascending
// order, so the pair is the one a scan of every pair finds, without the scan's n² (an outline
// of 10⁶ chords).
std::optional<Vector2d> crossing_of(const Region& r) {
  const std::vector<Vector2d> p = straight_edged(r).outline;
  const std::size_t n = p.size();
  std::vector<Eigen::AlignedBox2d> boxes;
  for (std::size_t i = 0; i < n; ++i) boxes.push_back(Eigen::AlignedBox2d(p[i]).extend(p[(i + 1) % n]));
  const BoxIndex index(boxes);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j : index.meeting(boxes[i])) {
      if (j < i + 2 || (i == 0 && j == n - 1)) continue;
      add_geometry_work(1);
      if (auto at = meeting_point(p[i], p[(i + 1) % n], p[j], p[(j + 1) % n])) return at;
    }
  }
  return std::nullopt;
}

// A loop that crosses itself (or is otherwise no outline) is reported at its entities' lines.
void check_loop(const SketchLoop& loop, const std::string& file) {
  Region r;
  r.outline = loop.vertices;
  if (std::any_of(loop.bulges.begin(), loop.bulges.end(), [](double b) { return b != 0.0; })) {
    r.outline_bulges = loop.bulges;
  }
  try {
    check_region(r);
  } catch (const Error& error) {
    const std::string message = error.what();
    const std::vector<EdgeMention> edges = edge_mentions(message);
    if (edges.size() == 2 && message.find(" meets ") != std::string::npos) {
      const std::size_t i = edges[0].from, k = edges[1].from;
      if (i < loop.lines.size() && k < loop.lines.size()) {
        const std::optional<Vector2d> at = crossing_of(r);
        const std::string where = at ? fmt::format(" at ({:.6g}, {:.6g})", at->x(), at->y()) : std::string();
        // One entity (a polyline) may draw the whole loop: then naming its own line again says nothing.
        const std::string which = loop.lines[i] == loop.lines[k]
                                      ? std::string(", within the entity here")
                                      : ": the entity here meets the one at line " + std::to_string(loop.lines[k]);
        fail_at(file, loop.lines[i], "the outline crosses itself" + where + which);
      }
    }
    fail_at(file, loop.lines.empty() ? 1 : loop.lines.front(), "the loop starting here is not an outline: " + message);
  }
}

}  // namespace

namespace {

void check_entity_count(const StrokeSet& set, const std::string& file) {
  const std::size_t count = set.strokes.size() + set.circles.size() + set.points.size();
  if (count <= kMaxSketchEntities) return;
  std::vector<int> lines;
  for (const Stroke& s : set.strokes) lines.push_back(s.line);
  for (const SketchCircle& c : set.circles) lines.push_back(c.line);
  for (const SketchPoint& p : set.points) lines.push_back(p.line);
  std::nth_element(lines.begin(), lines.begin() + kMaxSketchEntities, lines.end());
  fail_at(file, lines[kMaxSketchEntities],
          fmt::format("the drawing has {} entities (lines, arcs, curves, circles and points); at most {} are read, "
                      "and this is the first one over",
                      count, kMaxSketchEntities));
}

}  // namespace

Sketch finish_sketch(StrokeSet set, const std::string& file, int last_line, const std::string& what) {
  check_entity_count(set, file);
  Vector2d lo = Vector2d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  const auto grow = [&](const Vector2d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  };
  for (const Stroke& s : set.strokes) {
    for (const Segment& g : s.segments) {
      grow(g.a);
      grow(g.b);
      if (!g.curve) continue;
      for (int k = 1; k < 16; ++k) grow(g.curve(g.s0 + (g.s1 - g.s0) * k / 16));
    }
  }
  const double size = set.strokes.empty() ? 0.0 : (hi - lo).norm();
  if (!std::isfinite(size)) fail_at(file, last_line, "the drawing's coordinates are too large");
  // Below this the drawing's points merge in the arithmetic (cubes of its lengths underflow,
  // tolerances relative to it vanish): say so, not that some outline has 1 vertex or no extent.
  constexpr double kSmallestDrawing = 1e-100;
  // hypot, not norm(): the squares of so small an extent underflow to 0.
  const double extent = set.strokes.empty() ? 0.0 : std::hypot(hi.x() - lo.x(), hi.y() - lo.y());
  if (extent > 0 && extent < kSmallestDrawing)
    fail_at(file, set.strokes.front().line,
            fmt::format("the drawing is too small to compute with: it spans {:.3g} (the diagonal of its bounding "
                        "box, in the drawing's units), below {:.0e}, where its points merge; scale it up",
                        extent, kSmallestDrawing));
  Sketch sketch;
  sketch.circles = std::move(set.circles);
  sketch.points = std::move(set.points);
  sketch.metres_per_unit = set.metres_per_unit;
  sketch.annotations = std::move(set.annotations);
  const double tolerance = size > 0 ? kRelativeCurveTolerance * size : 1.0;
  for (const Chained& c : chain(set.strokes, 1e-6 * size, file)) {
    sketch.loops.push_back(polygonised_loop(c, tolerance, file));
    if (sketch.loops.back().vertices.size() > kMaxLoopVertices)
      fail_at(file, sketch.loops.back().lines.front(),
              fmt::format("the outline starting here has {} vertices once its curves are cut into chords; at most {}",
                          sketch.loops.back().vertices.size(), kMaxLoopVertices));
    check_loop(sketch.loops.back(), file);
  }
  if (sketch.loops.empty()) fail_at(file, last_line, "the drawing has no closed outline" + what);
  return sketch;
}

namespace {

std::string_view trim_whitespace(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

bool to_number(std::string_view text, double& value) {
  text = trim_whitespace(text);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  const auto [end, ec] = parse_double(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && end == text.data() + text.size() && std::isfinite(value);
}

// The entities of the thesis tool's CSV that are drawn as points all round a circle: the
// least-squares circle x² + y² + D x + E y + F = 0 (Kåsa's fit), about the points' mean for
// conditioning; nothing when a point strays from it by more than 1e-3 of the radius.
std::optional<Circle> fitted_circle(const std::vector<Vector2d>& points) {
  if (points.size() < 3) return std::nullopt;
  Vector2d mean = Vector2d::Zero();
  for (const Vector2d& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  Eigen::MatrixX3d a(static_cast<Eigen::Index>(points.size()), 3);
  Eigen::VectorXd b(static_cast<Eigen::Index>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vector2d q = points[i] - mean;
    a.row(static_cast<Eigen::Index>(i)) << q.x(), q.y(), 1.0;
    b(static_cast<Eigen::Index>(i)) = -q.squaredNorm();
  }
  const Eigen::Vector3d def = a.colPivHouseholderQr().solve(b);
  const Vector2d centre = mean - def.head<2>() / 2;
  const double r2 = def.head<2>().squaredNorm() / 4 - def(2);
  if (!(r2 > 0) || !centre.allFinite()) return std::nullopt;
  const double radius = std::sqrt(r2);
  for (const Vector2d& p : points) {
    if (std::abs((p - centre).norm() - radius) > 1e-3 * radius) return std::nullopt;
  }
  return Circle{centre, radius};
}

}  // namespace

StrokeSet read_csv_strokes(const std::string& text, const std::string& file, int& last_line) {
  StrokeSet set;
  struct Entity {
    std::string name;
    int line;
    std::vector<Vector2d> points;
  };
  std::vector<Entity> entities;
  bool awaiting_point = false;
  int line = 0;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string_view row = trim_whitespace(std::string_view(text).substr(start, end - start));
    start = end + 1;
    ++line;
    if (line == 1 || row.empty()) continue;  // the first line is a header, ignored
    if (row.find("New") != std::string_view::npos) {
      entities.push_back({std::string(trim_whitespace(row.substr(row.find("New") + 3))), line, {}});
      continue;
    }
    if (row.find("Point") != std::string_view::npos) {
      awaiting_point = true;
      continue;
    }
    const std::size_t comma = row.find(',');
    double x = 0, y = 0;
    if (comma == std::string_view::npos || !to_number(row.substr(0, comma), x) ||
        !to_number(row.substr(comma + 1), y)) {
      fail_at(file, line, "a sketch CSV line is 'x, y', 'New <name>' or 'Point', not '" + std::string(row) + "'");
    }
    if (awaiting_point) {
      set.points.push_back({{x, y}, line});
      awaiting_point = false;
      continue;
    }
    if (entities.empty()) fail_at(file, line, "coordinates before the first 'New <name>' line");
    entities.back().points.emplace_back(x, y);
  }
  last_line = std::max(line, 1);
  if (awaiting_point) fail_at(file, last_line, "a 'Point' line without its 'x, y' line after it");
  for (const Entity& e : entities) {
    std::string lowered = e.name;
    for (char& c : lowered) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (lowered.find("circle") != std::string::npos) {
      const std::optional<Circle> c = fitted_circle(e.points);
      if (e.points.size() < 3)
        fail_at(file, e.line,
                "the circle '" + e.name + "' has " + std::to_string(e.points.size()) + " point" +
                    (e.points.size() == 1 ? "" : "s") + "; a circle needs at least 3");
      if (!c) fail_at(file, e.line, "the points of the circle '" + e.name + "' do not lie on a circle");
      set.circles.push_back({*c, e.line, e.name});
      continue;
    }
    Stroke s;
    s.line = e.line;
    s.layer = e.name;
    for (std::size_t i = 0; i + 1 < e.points.size(); ++i) {
      if (e.points[i] != e.points[i + 1]) s.segments.push_back({e.points[i], e.points[i + 1]});
    }
    if (s.segments.empty()) fail_at(file, e.line, "the entity '" + e.name + "' needs at least 2 different points");
    set.strokes.push_back(std::move(s));
  }
  return set;
}

}  // namespace sketch_detail

std::optional<SketchFormat> sketch_format(const std::string& file_name) {
  const std::size_t dot = file_name.rfind('.');
  if (dot == std::string::npos) return std::nullopt;
  std::string extension = file_name.substr(dot + 1);
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (extension == "dxf") return SketchFormat::kDxf;
  if (extension == "svg") return SketchFormat::kSvg;
  if (extension == "csv" || extension == "txt") return SketchFormat::kCsv;
  return std::nullopt;
}

namespace {

// A sketch is text: a NUL byte is UTF-16 or UTF-32 (what Windows' editors call "Unicode") or a
// binary file, which the readers would otherwise misread at some later place ("the value of '").
void check_is_text(const std::string& text, const std::string& file_name) {
  const std::size_t nul = text.find('\0');
  if (nul == std::string::npos) return;
  const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(nul), '\n'));
  const bool utf16 =
      text.size() >= 2 && ((text[0] == '\xFF' && text[1] == '\xFE') || (text[0] == '\xFE' && text[1] == '\xFF'));
  sketch_detail::fail_at(
      file_name, line,
      std::string("the file is not text: it holds a NUL byte") +
          (utf16 ? " and starts with a UTF-16 byte-order mark" : " (UTF-16, UTF-32 or a binary file?)") +
          "; save it as UTF-8 (or ASCII)");
}

}  // namespace

Sketch read_sketch(const std::string& text, const std::string& file_name, SketchFormat format,
                   const std::string& layer) {
  using namespace sketch_detail;
  // The DXF reader says a binary file (and a binary DXF) itself, in DXF's terms.
  if (format != SketchFormat::kDxf) check_is_text(text, file_name);
  int last_line = 1;
  StrokeSet set;
  switch (format) {
    case SketchFormat::kDxf: set = read_dxf_strokes(text, file_name, layer, last_line); break;
    case SketchFormat::kSvg: set = read_svg_strokes(text, file_name, layer, last_line); break;
    case SketchFormat::kCsv:
      if (!layer.empty()) fail_at(file_name, 1, "a sketch CSV has no layers: leave `layer` out");
      set = read_csv_strokes(text, file_name, last_line);
      break;
  }
  const std::string what =
      layer.empty() ? std::string()
                    : std::string(format == SketchFormat::kSvg ? " in the group '" : " on the layer '") + layer + "'";
  return finish_sketch(std::move(set), file_name, last_line, what);
}

double sketch_scale(const Sketch& sketch, std::optional<double> stated, double model_metres_per_unit) {
  if (stated) return *stated / model_metres_per_unit;
  if (sketch.metres_per_unit) return *sketch.metres_per_unit / model_metres_per_unit;
  return 1.0;
}

Region plate_from_sketch(const Sketch& sketch, double scale) {
  std::size_t outer = 0;
  for (std::size_t i = 1; i < sketch.loops.size(); ++i) {
    if (sketch.loops[i].area() > sketch.loops[outer].area()) outer = i;
  }
  Region r;
  for (std::size_t i = 0; i < sketch.loops.size(); ++i) {
    const SketchLoop& l = sketch.loops[i];
    std::vector<Vector2d> vertices = l.vertices;
    for (Vector2d& v : vertices) v *= scale;
    const bool arcs = std::any_of(l.bulges.begin(), l.bulges.end(), [](double b) { return b != 0.0; });
    if (i == outer) {
      r.outline = std::move(vertices);
      if (arcs) r.outline_bulges = l.bulges;
    } else {
      r.polygon_holes.push_back(std::move(vertices));
      r.polygon_hole_bulges.push_back(arcs ? l.bulges : std::vector<double>{});
    }
  }
  for (const SketchCircle& c : sketch.circles)
    r.circle_holes.push_back({c.circle.centre * scale, c.circle.radius * scale});
  return r;
}

namespace {

// "polygon hole 3" or "circle hole 3 (centre (x, y), radius r)", as check_region names them, with
// where its loop or circle starts in the drawing: {begin, end, line} of the first mention.
struct HoleMention {
  std::size_t begin = std::string::npos, end = 0;
  int line = 0;
};

HoleMention first_hole(const std::string& message, const Sketch& sketch, std::size_t outer) {
  HoleMention first;
  for (const std::string kind : {"polygon hole ", "circle hole "}) {
    const std::size_t at = message.find(kind);
    if (at == std::string::npos || at > first.begin) continue;
    std::size_t end = at + kind.size(), index = 0;
    if (end >= message.size() || !std::isdigit(static_cast<unsigned char>(message[end]))) continue;
    while (end < message.size() && std::isdigit(static_cast<unsigned char>(message[end])))
      index = index * 10 + static_cast<std::size_t>(message[end++] - '0');
    int line = 0;
    if (kind == "polygon hole ") {
      const std::size_t loop = index < outer ? index : index + 1;  // the outline is not a hole
      if (loop < sketch.loops.size() && !sketch.loops[loop].lines.empty()) line = sketch.loops[loop].lines.front();
    } else if (index < sketch.circles.size()) {
      line = sketch.circles[index].line;
    }
    if (line > 0) first = {at, end, line};
  }
  return first;
}

}  // namespace

Region checked_plate_from_sketch(const Sketch& sketch, double scale, const std::string& file) {
  Region r = plate_from_sketch(sketch, scale);
  try {
    check_region(r);
  } catch (const Error& error) {
    std::size_t outer = 0;
    for (std::size_t i = 1; i < sketch.loops.size(); ++i)
      if (sketch.loops[i].area() > sketch.loops[outer].area()) outer = i;
    std::string message = error.what();
    const HoleMention hole = first_hole(message, sketch, outer);
    if (hole.begin == std::string::npos) throw;  // about the outline alone: said where the model imports it
    message.replace(hole.begin, hole.end - hole.begin, "the hole drawn here");
    // A second hole the message names ("... and polygon hole 1 overlap"), by its line too.
    if (const HoleMention other = first_hole(message, sketch, outer); other.begin != std::string::npos)
      message.replace(other.begin, other.end - other.begin, "the one at line " + std::to_string(other.line));
    const int outline_line = sketch.loops[outer].lines.empty() ? 0 : sketch.loops[outer].lines.front();
    if (outline_line > 0) message += " (the outline starts at line " + std::to_string(outline_line) + ")";
    sketch_detail::fail_at(file, hole.line, message);
  }
  return r;
}

}  // namespace nbar::io
