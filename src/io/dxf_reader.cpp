#include "nbar/io/dxf_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <string_view>
#include <vector>

#include "nbar/io/model_file.hpp"

namespace nbar::io {

namespace {

using Eigen::Vector2d;

struct Pair {
  int code;
  std::string value;
  int line;  // of the group code
};

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

class Reader {
 public:
  Reader(const std::string& text, const std::string& file) : file_(file) { split(text); }

  [[noreturn]] void fail(int line, const std::string& message) const {
    throw ModelFileError(file_, SourceMark{line, 1}, message);
  }

  std::vector<Pair> pairs() const {
    std::vector<Pair> out;
    for (std::size_t i = 0; i < lines_.size(); i += 2) {
      const int line = static_cast<int>(i) + 1;
      const std::string_view code = trimmed(lines_[i]);
      if (code.empty() && i + 1 >= lines_.size()) break;  // a blank last line
      int value = 0;
      const auto [end, ec] = std::from_chars(code.data(), code.data() + code.size(), value);
      if (ec != std::errc() || end != code.data() + code.size()) {
        fail(line, "a DXF group code (an integer) was expected here, not '" + std::string(code) +
                       "': the group-code/value pairs are broken");
      }
      if (i + 1 >= lines_.size()) fail(line, "group code " + std::to_string(value) + " has no value after it");
      out.push_back({value, std::string(trimmed(lines_[i + 1])), line});
    }
    return out;
  }

  double number(const Pair& p) const {
    double value = 0;
    const std::string_view text = p.value;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
      fail(p.line + 1, "group " + std::to_string(p.code) + " needs a finite number, not '" + p.value + "'");
    }
    return value;
  }

 private:
  void split(const std::string& text) {
    std::size_t start = 0;
    while (start < text.size()) {
      const std::size_t end = text.find('\n', start);
      lines_.push_back(text.substr(start, end == std::string::npos ? std::string::npos : end - start));
      if (end == std::string::npos) break;
      start = end + 1;
    }
  }

  std::string file_;
  std::vector<std::string> lines_;
};

// One entity: its type, the line it starts on and its group pairs.
struct Entity {
  std::string type;
  int line = 0;
  std::vector<Pair> pairs;
};

// An edge to chain: from a to b, an arc when the bulge is not 0.
struct Piece {
  Vector2d a, b;
  double bulge;
  int line;
};

struct Loop {
  std::vector<Vector2d> vertices;
  std::vector<double> bulges;
};

struct Sketch {
  std::vector<Piece> pieces;
  std::vector<Loop> loops;
  std::vector<Circle> circles;
};

// DXF $INSUNITS codes nbar knows, in metres.
std::optional<double> insunits_metres(int code) {
  switch (code) {
    case 1: return 0.0254;
    case 2: return 0.3048;
    case 4: return 1e-3;
    case 5: return 1e-2;
    case 6: return 1.0;
    default: return std::nullopt;
  }
}

class SketchBuilder {
 public:
  explicit SketchBuilder(const Reader& reader) : reader_(reader) {}

  void add(const Entity& e) {
    if (e.type == "LINE") return line(e);
    if (e.type == "ARC") return arc(e);
    if (e.type == "CIRCLE") return circle(e);
    if (e.type == "LWPOLYLINE") return lwpolyline(e);
    if (e.type == "POLYLINE") {
      polyline_ = e;
      vertices_.clear();
      return;
    }
    if (e.type == "VERTEX") {
      if (!polyline_) reader_.fail(e.line, "a VERTEX outside a POLYLINE");
      vertices_.push_back(e);
      return;
    }
    if (e.type == "SEQEND") {
      if (!polyline_) reader_.fail(e.line, "a SEQEND outside a POLYLINE");
      polyline();
      return;
    }
    reader_.fail(e.line, "nbar reads LINE, ARC, CIRCLE, LWPOLYLINE and POLYLINE entities for a plate, not " +
                             e.type);
  }

  void finish(int line) const {
    if (polyline_) reader_.fail(polyline_->line, "a POLYLINE without its SEQEND");
    (void)line;
  }

  Sketch sketch;

 private:
  double get(const Entity& e, int code) const {
    for (const Pair& p : e.pairs)
      if (p.code == code) return reader_.number(p);
    reader_.fail(e.line, e.type + " without group " + std::to_string(code));
  }

  void line(const Entity& e) {
    const Vector2d a(get(e, 10), get(e, 20)), b(get(e, 11), get(e, 21));
    if (a == b) return;  // a zero-length line joins nothing
    sketch.pieces.push_back({a, b, 0.0, e.line});
  }

  void arc(const Entity& e) {
    const Vector2d c(get(e, 10), get(e, 20));
    const double r = get(e, 40);
    if (!(r > 0)) reader_.fail(e.line, "ARC with a radius that is not positive");
    const double deg = std::numbers::pi / 180;
    const double from = get(e, 50), to = get(e, 51);
    double sweep = std::fmod(to - from, 360.0);
    if (sweep <= 0) sweep += 360;  // counterclockwise from start to end
    const Vector2d a = c + r * Vector2d(std::cos(from * deg), std::sin(from * deg));
    const Vector2d b = c + r * Vector2d(std::cos(to * deg), std::sin(to * deg));
    sketch.pieces.push_back({a, b, std::tan(sweep * deg / 4), e.line});
  }

  void circle(const Entity& e) {
    const double r = get(e, 40);
    if (!(r > 0)) reader_.fail(e.line, "CIRCLE with a radius that is not positive");
    sketch.circles.push_back({{get(e, 10), get(e, 20)}, r});
  }

  // Vertices (10, 20) each followed by its optional bulge (42), as LWPOLYLINE stores them.
  void add_polyline(const Entity& e, const std::vector<Vector2d>& v, const std::vector<double>& bulges,
                    bool closed) {
    if (v.size() < 2) reader_.fail(e.line, e.type + " with fewer than 2 vertices");
    if (closed) {
      sketch.loops.push_back({v, bulges});
      return;
    }
    for (std::size_t i = 0; i + 1 < v.size(); ++i) sketch.pieces.push_back({v[i], v[i + 1], bulges[i], e.line});
  }

  void lwpolyline(const Entity& e) {
    std::vector<Vector2d> v;
    std::vector<double> bulges;
    int flags = 0;
    for (const Pair& p : e.pairs) {
      if (p.code == 70) flags = static_cast<int>(reader_.number(p));
      if (p.code == 10) {
        v.emplace_back(reader_.number(p), 0.0);
        bulges.push_back(0.0);
      }
      if (p.code == 20 && !v.empty()) v.back().y() = reader_.number(p);
      if (p.code == 42 && !v.empty()) bulges.back() = reader_.number(p);
    }
    add_polyline(e, v, bulges, (flags & 1) != 0);
  }

  void polyline() {
    const Entity& e = *polyline_;
    int flags = 0;
    for (const Pair& p : e.pairs)
      if (p.code == 70) flags = static_cast<int>(reader_.number(p));
    std::vector<Vector2d> v;
    std::vector<double> bulges;
    for (const Entity& vertex : vertices_) {
      v.emplace_back(get(vertex, 10), get(vertex, 20));
      double bulge = 0;
      for (const Pair& p : vertex.pairs)
        if (p.code == 42) bulge = reader_.number(p);
      bulges.push_back(bulge);
    }
    add_polyline(e, v, bulges, (flags & 1) != 0);
    polyline_.reset();
  }

  const Reader& reader_;
  std::optional<Entity> polyline_;
  std::vector<Entity> vertices_;
};

// Chains the pieces into closed loops, ends meeting within `tolerance`.
void chain(Sketch& s, double tolerance, const Reader& reader) {
  std::vector<bool> used(s.pieces.size(), false);
  for (std::size_t first = 0; first < s.pieces.size(); ++first) {
    if (used[first]) continue;
    used[first] = true;
    Loop loop;
    loop.vertices.push_back(s.pieces[first].a);
    loop.bulges.push_back(s.pieces[first].bulge);
    Vector2d end = s.pieces[first].b;
    int last_line = s.pieces[first].line;
    while ((end - loop.vertices.front()).norm() > tolerance) {
      bool found = false;
      for (std::size_t k = 0; k < s.pieces.size() && !found; ++k) {
        if (used[k]) continue;
        const Piece& p = s.pieces[k];
        if ((p.a - end).norm() <= tolerance) {
          loop.vertices.push_back(p.a);
          loop.bulges.push_back(p.bulge);
          end = p.b;
        } else if ((p.b - end).norm() <= tolerance) {
          loop.vertices.push_back(p.b);
          loop.bulges.push_back(-p.bulge);  // run backwards, the arc turns the other way
          end = p.a;
        } else {
          continue;
        }
        used[k] = true;
        last_line = p.line;
        found = true;
      }
      if (!found) {
        reader.fail(last_line, fmt::format("the outline is not closed: the entity here ends at ({:.6g}, {:.6g}) and no "
                                           "other entity starts there (within {:.3g})",
                                           end.x(), end.y(), tolerance));
      }
    }
    s.loops.push_back(std::move(loop));
  }
}

double loop_area(const Loop& loop) {
  Region r;
  r.outline = loop.vertices;
  r.outline_bulges = loop.bulges;
  return std::abs(area_properties(r).area);
}

bool same_layer(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

bool on_layer(const Entity& e, const std::string& layer) {
  if (layer.empty()) return true;
  for (const Pair& p : e.pairs)
    if (p.code == 8) return same_layer(p.value, layer);
  return same_layer("0", layer);
}

}  // namespace

Region read_dxf_plate(const std::string& text, const std::string& file_name, double model_metres_per_unit,
                      const std::string& layer) {
  const Reader reader(text, file_name);
  const std::vector<Pair> pairs = reader.pairs();
  SketchBuilder builder(reader);
  std::string section;
  std::optional<Entity> current;
  double scale = 1;
  bool saw_eof = false;
  bool polyline_kept = false;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const Pair& p = pairs[i];
    if (p.code == 0 && current) {
      // A polyline's VERTEXes and SEQEND follow its layer.
      const bool part = current->type == "VERTEX" || current->type == "SEQEND";
      if (part ? polyline_kept : on_layer(*current, layer)) builder.add(*current);
      if (current->type == "POLYLINE") polyline_kept = on_layer(*current, layer);
      current.reset();
    }
    if (p.code == 0 && p.value == "SECTION") {
      if (i + 1 >= pairs.size() || pairs[i + 1].code != 2) reader.fail(p.line, "SECTION without its name (group 2)");
      section = pairs[++i].value;
      continue;
    }
    if (p.code == 0 && p.value == "ENDSEC") {
      section.clear();
      continue;
    }
    if (p.code == 0 && p.value == "EOF") {
      saw_eof = true;
      break;
    }
    if (section == "HEADER" && p.code == 9 && p.value == "$INSUNITS" && i + 1 < pairs.size()) {
      const auto metres = insunits_metres(static_cast<int>(reader.number(pairs[i + 1])));
      if (metres) scale = *metres / model_metres_per_unit;
      continue;
    }
    if (section != "ENTITIES") continue;
    if (p.code == 0) {
      current = Entity{p.value, p.line, {}};
    } else if (current) {
      current->pairs.push_back(p);
    }
  }
  const int last_line = pairs.empty() ? 1 : pairs.back().line;
  if (!saw_eof) reader.fail(last_line, "the DXF file ends without EOF (is it cut short?)");
  builder.finish(last_line);
  Sketch& s = builder.sketch;

  Vector2d lo = Vector2d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Piece& p : s.pieces) {
    lo = lo.cwiseMin(p.a).cwiseMin(p.b);
    hi = hi.cwiseMax(p.a).cwiseMax(p.b);
  }
  for (const Loop& l : s.loops)
    for (const Vector2d& v : l.vertices) {
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
    }
  const double size = s.pieces.empty() && s.loops.empty() ? 0.0 : (hi - lo).norm();
  chain(s, 1e-6 * size, reader);
  if (s.loops.empty()) {
    reader.fail(last_line, "the drawing has no closed outline (LINEs, ARCs or polylines)" +
                               (layer.empty() ? std::string() : " on the layer '" + layer + "'"));
  }

  std::size_t outer = 0;
  for (std::size_t i = 1; i < s.loops.size(); ++i)
    if (loop_area(s.loops[i]) > loop_area(s.loops[outer])) outer = i;
  Region r;
  for (std::size_t i = 0; i < s.loops.size(); ++i) {
    Loop& l = s.loops[i];
    for (Vector2d& v : l.vertices) v *= scale;
    const bool arcs = std::any_of(l.bulges.begin(), l.bulges.end(), [](double b) { return b != 0.0; });
    if (i == outer) {
      r.outline = l.vertices;
      if (arcs) r.outline_bulges = l.bulges;
    } else {
      r.polygon_holes.push_back(l.vertices);
      r.polygon_hole_bulges.push_back(arcs ? l.bulges : std::vector<double>{});
    }
  }
  for (Circle c : s.circles) r.circle_holes.push_back({c.centre * scale, c.radius * scale});
  return r;
}

}  // namespace nbar::io
