#include "nbar/io/dxf_reader.hpp"

#include <fmt/format.h>

#include <Eigen/Core>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <string_view>
#include <tuple>
#include <utility>
#include <vector>

#include "model/double_text.hpp"
#include "nbar/io/model_file.hpp"
#include "nbar/io/sketch.hpp"
#include "nbar/model/curves.hpp"
#include "nbar/model/diagnostics.hpp"
#include "sketch_strokes.hpp"

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

// A piece of the file quoted in a message: at most 40 characters, bytes that are not printable
// ASCII as \xNN, so that a binary file's garbage does not go to the terminal as it is.
std::string shown(std::string_view text) {
  constexpr std::size_t kMost = 40;
  std::string out;
  for (std::size_t i = 0; i < text.size() && i < kMost; ++i) {
    const auto byte = static_cast<unsigned char>(text[i]);
    out += byte >= 0x20 && byte < 0x7f ? std::string(1, text[i]) : fmt::format("\\x{:02x}", byte);
  }
  return text.size() > kMost ? out + "..." : out;
}

class Reader {
 public:
  Reader(const std::string& text, const std::string& file) : file_(file) {
    constexpr std::string_view kBinary = "AutoCAD Binary DXF";
    if (text.starts_with(kBinary)) fail(1, "binary DXF is not supported: save the drawing as ASCII DXF");
    // Windows editors may start a UTF-8 file with a byte-order mark, which is no part of the first group code.
    constexpr std::string_view kByteOrderMark = "\xEF\xBB\xBF";
    split(text.starts_with(kByteOrderMark) ? text.substr(kByteOrderMark.size()) : text);
  }

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
        fail(line, "a DXF group code (an integer) was expected here, not '" + shown(code) +
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
    const auto [end, ec] = parse_double(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
      fail(p.line + 1, "group " + std::to_string(p.code) + " needs a finite number, not '" + shown(p.value) + "'");
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

using sketch_detail::Segment;
using sketch_detail::Stroke;
using sketch_detail::StrokeSet;

// A group's integer value; a value out of int's range (which a cast would make undefined)
// becomes one no code means.
int whole(double v) { return std::abs(v) < 1e9 ? static_cast<int>(v) : -1; }

// The metres in a unit of the DXF $INSUNITS codes: 0 is unitless (the model's unit), codes past
// 21 are no unit.
std::optional<double> insunits_metres(int code) {
  constexpr double kInch = 0.0254;
  switch (code) {
    case 1: return kInch;
    case 2: return 12 * kInch;
    case 3: return 63360 * kInch;  // mile
    case 4: return 1e-3;
    case 5: return 1e-2;
    case 6: return 1.0;
    case 7: return 1e3;
    case 8: return 1e-6 * kInch;  // microinch
    case 9: return 1e-3 * kInch;  // mil
    case 10: return 36 * kInch;   // yard
    case 11: return 1e-10;        // angstrom
    case 12: return 1e-9;
    case 13: return 1e-6;
    case 14: return 1e-1;
    case 15: return 1e1;
    case 16: return 1e2;
    case 17: return 1e9;
    case 18: return 1.495978707e11;         // astronomical unit (IAU 2012)
    case 19: return 9.4607304725808e15;     // light year (Julian)
    case 20: return 3.0856775814913673e16;  // parsec
    case 21: return 1200.0 / 3937.0;        // US survey foot
    default: return std::nullopt;
  }
}

// Notes on the drawing (text, dimensions, hatching, attributes) draw no part of it: a sketch is
// commonly annotated on the layers of its parts, so they are left out rather than refused.
bool annotation(std::string_view type) {
  for (std::string_view note : {"TEXT", "MTEXT", "DIMENSION", "ARC_DIMENSION", "LARGE_RADIAL_DIMENSION", "LEADER",
                                "MLEADER", "MULTILEADER", "TOLERANCE", "HATCH", "ATTDEF", "ATTRIB"}) {
    if (type == note) return true;
  }
  return false;
}

class SketchBuilder {
 public:
  explicit SketchBuilder(const Reader& reader) : reader_(reader) {}

  void add(const Entity& e) {
    layer_ = layer_of(e);
    if (e.type == "LINE") return line(e);
    if (e.type == "ARC") return arc(e);
    if (e.type == "CIRCLE") return circle(e);
    if (e.type == "LWPOLYLINE") return lwpolyline(e);
    if (e.type == "SPLINE") return spline(e);
    if (e.type == "ELLIPSE") return ellipse(e);
    if (annotation(e.type)) {
      set.annotations.push_back(e.type);
      return;
    }
    if (e.type == "POINT") {
      set.points.push_back({{get(e, 10), get(e, 20)}, e.line});
      return;
    }
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
    reader_.fail(e.line,
                 "nbar reads LINE, ARC, CIRCLE, LWPOLYLINE, POLYLINE, SPLINE, ELLIPSE and POINT entities, not " +
                     e.type + ": explode it into those or delete it (a shape's `layer` reads one layer only)");
  }

  void finish() const {
    if (polyline_) reader_.fail(polyline_->line, "a POLYLINE without its SEQEND");
  }

  StrokeSet set;

 private:
  static std::string layer_of(const Entity& e) {
    for (const Pair& p : e.pairs)
      if (p.code == 8) return p.value;
    return std::string(1, '0');
  }

  double get(const Entity& e, int code) const {
    for (const Pair& p : e.pairs)
      if (p.code == code) return reader_.number(p);
    reader_.fail(e.line, e.type + " without group " + std::to_string(code));
  }

  double get_or(const Entity& e, int code, double otherwise) const {
    for (const Pair& p : e.pairs)
      if (p.code == code) return reader_.number(p);
    return otherwise;
  }

  void add_stroke(const Entity& e, std::vector<Segment> segments, bool closed) {
    set.strokes.push_back({std::move(segments), closed, e.line, layer_});
  }

  // The sign of the entity's OCS x axis in the drawing's x. Points of an entity drawn in its
  // own coordinate system (the arbitrary-axis rule) with the extrusion (0, 0, -1), as SolidWorks
  // and mirrored AutoCAD geometry write, have x reversed (OCS x = -WCS x, y = WCS y); read as
  // they stand the part comes in mirrored. Any other extrusion tilts the entity out of the plane.
  double ocs_x_sign(const Entity& e) const {
    Eigen::Vector3d n(get_or(e, 210, 0.0), get_or(e, 220, 0.0), get_or(e, 230, 1.0));
    int line = e.line;
    for (const Pair& p : e.pairs)
      if (p.code == 210 || p.code == 220 || p.code == 230) {
        line = p.line;
        break;
      }
    const double length = n.norm();
    if (length > 0 && std::isfinite(length)) n /= length;
    constexpr double kPlane = 1e-9;
    if (!(length > 0) || std::abs(n.x()) > kPlane || std::abs(n.y()) > kPlane) {
      reader_.fail(line, fmt::format("this {}'s extrusion direction (groups 210, 220, 230) ({:.6g}, {:.6g}, {:.6g}) "
                                     "puts it out of the drawing plane: nbar reads 2-D drawings, whose extrusion is "
                                     "(0, 0, 1) or (0, 0, -1)",
                                     e.type, get_or(e, 210, 0.0), get_or(e, 220, 0.0), get_or(e, 230, 1.0)));
    }
    return n.z() < 0 ? -1.0 : 1.0;
  }

  void line(const Entity& e) {
    const Vector2d a(get(e, 10), get(e, 20)), b(get(e, 11), get(e, 21));
    if (a == b) return;  // a zero-length line joins nothing
    add_stroke(e, {{a, b}}, false);
  }

  void arc(const Entity& e) {
    const double mirror = ocs_x_sign(e);
    const Vector2d c(mirror * get(e, 10), get(e, 20));
    const double r = get(e, 40);
    if (!(r > 0)) reader_.fail(e.line, "ARC with a radius that is not positive");
    const double deg = std::numbers::pi / 180;
    double from = get(e, 50), to = get(e, 51);
    // Mirrored in x, the counterclockwise OCS arc from a1 to a2 is the WCS one from 180 - a2 to 180 - a1.
    if (mirror < 0) std::tie(from, to) = std::pair(180 - to, 180 - from);
    double sweep = std::fmod(to - from, 360.0);
    if (sweep <= 0) sweep += 360;  // counterclockwise from start to end
    const Vector2d a = c + r * Vector2d(std::cos(from * deg), std::sin(from * deg));
    if (sweep >= 360 - 1e-9) {
      // Round from its start back to it (0 to 360): a loop of its own, as two half circles,
      // since one edge from a point to itself has no chord to bulge from.
      const Vector2d opposite = 2 * c - a;
      add_stroke(e, {{a, opposite, 1.0}, {opposite, a, 1.0}}, true);
      return;
    }
    const Vector2d b = c + r * Vector2d(std::cos(to * deg), std::sin(to * deg));
    add_stroke(e, {{a, b, std::tan(sweep * deg / 4)}}, false);
  }

  void circle(const Entity& e) {
    const double r = get(e, 40);
    if (!(r > 0)) reader_.fail(e.line, "CIRCLE with a radius that is not positive");
    set.circles.push_back({{{ocs_x_sign(e) * get(e, 10), get(e, 20)}, r}, e.line, layer_});
  }

  // Vertices each with the bulge of the edge it starts, as polylines store them, in the
  // entity's OCS: mirrored in x (ocs_x_sign), an arc turns the other way.
  void add_polyline(const Entity& e, std::vector<Vector2d> v, std::vector<double> bulges, bool closed, double mirror) {
    if (v.size() < 2) reader_.fail(e.line, e.type + " with fewer than 2 vertices");
    for (Vector2d& p : v) p.x() *= mirror;
    for (double& b : bulges) b *= mirror;
    std::vector<Segment> segments;
    for (std::size_t i = 0; i + 1 < v.size(); ++i) {
      if (v[i] != v[i + 1]) segments.push_back({v[i], v[i + 1], bulges[i]});
    }
    if (closed && v.back() != v.front()) segments.push_back({v.back(), v.front(), bulges.back()});
    if (segments.empty()) reader_.fail(e.line, e.type + " whose vertices are all the same point");
    add_stroke(e, std::move(segments), closed);
  }

  void lwpolyline(const Entity& e) {
    std::vector<Vector2d> v;
    std::vector<double> bulges;
    int flags = 0;
    for (const Pair& p : e.pairs) {
      if (p.code == 70) flags = whole(reader_.number(p));
      if (p.code == 10) {
        v.emplace_back(reader_.number(p), 0.0);
        bulges.push_back(0.0);
      }
      if (p.code == 20 && !v.empty()) v.back().y() = reader_.number(p);
      if (p.code == 42 && !v.empty()) bulges.back() = reader_.number(p);
    }
    add_polyline(e, std::move(v), std::move(bulges), (flags & 1) != 0, ocs_x_sign(e));
  }

  void polyline() {
    const Entity& e = *polyline_;
    const int flags = whole(get_or(e, 70, 0));
    std::vector<Vector2d> v;
    std::vector<double> bulges;
    for (const Entity& vertex : vertices_) {
      // A spline-fit polyline (flag 4) keeps the frame it was fitted to as vertices flagged 16
      // after the fitted ones; the outline is the fitted curve alone.
      if ((whole(get_or(vertex, 70, 0)) & 16) != 0) continue;
      v.emplace_back(get(vertex, 10), get(vertex, 20));
      bulges.push_back(get_or(vertex, 42, 0.0));
    }
    layer_ = layer_of(e);
    // A 3-D polyline (8), mesh (16) or polyface (64) has its vertices in the WCS; a 2-D one in its OCS.
    const double mirror = (flags & (8 | 16 | 64)) != 0 ? 1.0 : ocs_x_sign(e);
    add_polyline(e, std::move(v), std::move(bulges), (flags & 1) != 0, mirror);
    polyline_.reset();
  }

  // Fit points (11, 21) make a cubic spline through them; otherwise the control points
  // (10, 20), knots (40) and weights (41) make the NURBS.
  void spline(const Entity& e) {
    const int flags = whole(get_or(e, 70, 0));
    std::vector<Vector2d> control, fit;
    std::vector<double> knots, weights;
    for (const Pair& p : e.pairs) {
      if (p.code == 10) control.emplace_back(reader_.number(p), 0.0);
      if (p.code == 20 && !control.empty()) control.back().y() = reader_.number(p);
      if (p.code == 11) fit.emplace_back(reader_.number(p), 0.0);
      if (p.code == 21 && !fit.empty()) fit.back().y() = reader_.number(p);
      if (p.code == 40) knots.push_back(reader_.number(p));
      if (p.code == 41) weights.push_back(reader_.number(p));
    }
    const bool closed = (flags & 1) != 0;
    try {
      if (control.empty()) {
        if (closed && fit.size() > 2 && fit.front() == fit.back()) fit.pop_back();
        auto through = std::make_shared<const CubicSpline>(fit, closed);
        const Vector2d a = through->points().front(), b = through->points().back();
        add_stroke(e, {{a, b, 0, [through](double s) { return (*through)(s); }, 0.0, through->end()}}, closed);
        return;
      }
      const int degree = whole(get_or(e, 71, 3));
      auto nurbs = std::make_shared<const BSpline>(degree, control, knots, weights);
      const Vector2d a = (*nurbs)(nurbs->start()), b = (*nurbs)(nurbs->end());
      add_stroke(e, {{a, b, 0, [nurbs](double u) { return (*nurbs)(u); }, nurbs->start(), nurbs->end()}}, closed);
    } catch (const ModelFileError&) {
      throw;                        // already placed in the file
    } catch (const Error& error) {  // the curve's own complaint
      reader_.fail(e.line, std::string("SPLINE: ") + error.what());
    }
  }

  void ellipse(const Entity& e) {
    const Vector2d c(get(e, 10), get(e, 20)), major(get(e, 11), get(e, 21));
    const double ratio = get(e, 40);
    if (!(major.norm() > 0) || !(ratio > 0)) reader_.fail(e.line, "ELLIPSE with an axis that is not positive");
    const double from = get_or(e, 41, 0.0);
    double to = get_or(e, 42, 2 * std::numbers::pi);
    while (to <= from) to += 2 * std::numbers::pi;
    // The centre and major axis are in the WCS, but the minor axis is the extrusion x the major:
    // with the extrusion (0, 0, -1) the ellipse runs the other way round.
    const Vector2d minor = ocs_x_sign(e) * ratio * Vector2d(-major.y(), major.x());
    const auto point = [c, major, minor](double t) { return Vector2d(c + std::cos(t) * major + std::sin(t) * minor); };
    const bool whole = to - from >= 2 * std::numbers::pi - 1e-12;
    if (whole) to = from + 2 * std::numbers::pi;
    add_stroke(e, {{point(from), whole ? point(from) : point(to), 0, point, from, to}}, whole);
  }

  const Reader& reader_;
  std::optional<Entity> polyline_;
  std::vector<Entity> vertices_;
  std::string layer_;
};

bool same_layer(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

// Paper space (group 67 = 1) holds the sheet's frame, title block and viewports onto the model,
// not the part; a VIEWPORT is a window onto model space wherever it is.
bool in_model_space(const Entity& e) {
  if (e.type == "VIEWPORT") return false;
  return std::none_of(e.pairs.begin(), e.pairs.end(), [](const Pair& p) { return p.code == 67 && p.value == "1"; });
}

bool on_layer(const Entity& e, const std::string& layer) {
  if (layer.empty()) return true;
  for (const Pair& p : e.pairs)
    if (p.code == 8) return same_layer(p.value, layer);
  return same_layer("0", layer);
}

}  // namespace

namespace sketch_detail {

StrokeSet read_dxf_strokes(const std::string& text, const std::string& file_name, const std::string& layer,
                           int& last_line) {
  const Reader reader(text, file_name);
  const std::vector<Pair> pairs = reader.pairs();
  SketchBuilder builder(reader);
  std::string section;
  std::optional<Entity> current;
  bool saw_eof = false;
  bool polyline_kept = false;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const Pair& p = pairs[i];
    if (p.code == 0 && current) {
      // A polyline's VERTEXes and SEQEND follow its layer.
      const bool part = current->type == "VERTEX" || current->type == "SEQEND";
      const bool kept = in_model_space(*current) && on_layer(*current, layer);
      if (part ? polyline_kept : kept) builder.add(*current);
      if (current->type == "POLYLINE") polyline_kept = kept;
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
      const int code = whole(reader.number(pairs[i + 1]));
      if (code < 0 || code > 21) {
        reader.fail(pairs[i + 1].line + 1, fmt::format("$INSUNITS {} is no DXF unit (0 unitless, 1 inches to 21 US "
                                                       "survey feet)",
                                                       pairs[i + 1].value));
      }
      builder.set.metres_per_unit = insunits_metres(code);
      continue;
    }
    if (section != "ENTITIES") continue;
    if (p.code == 0) {
      current = Entity{p.value, p.line, {}};
    } else if (current) {
      current->pairs.push_back(p);
    }
  }
  last_line = pairs.empty() ? 1 : pairs.back().line;
  if (!saw_eof) reader.fail(last_line, "the DXF file ends without EOF (is it cut short?)");
  builder.finish();
  return std::move(builder.set);
}

}  // namespace sketch_detail

Region read_dxf_plate(const std::string& text, const std::string& file_name, double model_metres_per_unit,
                      const std::string& layer) {
  const Sketch sketch = read_sketch(text, file_name, SketchFormat::kDxf, layer);
  return plate_from_sketch(sketch, sketch_scale(sketch, std::nullopt, model_metres_per_unit));
}

}  // namespace nbar::io
