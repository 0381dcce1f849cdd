// Sketches from SVG: the path data of <path> (M L H V C S Q T A Z, absolute and relative),
// <line>, <polyline>, <polygon>, <rect>, <ellipse> and <circle> (round holes). A small XML
// scanner of its own, so that errors carry their line. The y axis is turned up (SVG's points
// down), so that a drawing keeps its look.
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "model/double_text.hpp"
#include "sketch_strokes.hpp"

namespace nbar::io::sketch_detail {

namespace {

using Eigen::Vector2d;

struct Element {
  std::string name;
  std::map<std::string, std::string> attributes;
  int line = 0;
  bool self_closing = false;
  bool closing = false;
};

class XmlScanner {
 public:
  XmlScanner(const std::string& text, const std::string& file) : text_(text), file_(file) {}

  // The next start or end tag, skipping text, comments, declarations and CDATA.
  std::optional<Element> next() {
    while (true) {
      const std::size_t open = text_.find('<', pos_);
      if (open == std::string::npos) return std::nullopt;
      advance_to(open);
      if (starts("<!--")) {
        skip_past("-->");
      } else if (starts("<![CDATA[")) {
        skip_past("]]>");
      } else if (starts("<?") || starts("<!")) {
        skip_past(">");
      } else {
        return tag();
      }
    }
  }

  int line() const { return line_; }

 private:
  bool starts(std::string_view s) const { return text_.compare(pos_, s.size(), s) == 0; }

  void advance_to(std::size_t to) {
    line_ += static_cast<int>(std::count(text_.begin() + static_cast<std::ptrdiff_t>(pos_),
                                         text_.begin() + static_cast<std::ptrdiff_t>(to), '\n'));
    pos_ = to;
  }

  void skip_past(std::string_view end) {
    const std::size_t at = text_.find(end, pos_);
    if (at == std::string::npos) fail_at(file_, line_, "the SVG ends inside a comment or declaration");
    advance_to(at + end.size());
  }

  void skip_space() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) advance_to(pos_ + 1);
  }

  std::string name() {
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[pos_])) && text_[pos_] != '>' &&
           text_[pos_] != '/' && text_[pos_] != '=') {
      ++pos_;
    }
    return text_.substr(start, pos_ - start);
  }

  Element tag() {
    Element e;
    e.line = line_;
    ++pos_;  // '<'
    if (pos_ < text_.size() && text_[pos_] == '/') {
      e.closing = true;
      ++pos_;
    }
    e.name = name();
    if (e.name.empty()) fail_at(file_, line_, "a '<' that starts no SVG element");
    while (true) {
      skip_space();
      if (pos_ >= text_.size()) fail_at(file_, e.line, "the element <" + e.name + "> is not closed by '>'");
      if (text_[pos_] == '>') {
        ++pos_;
        return e;
      }
      if (text_.compare(pos_, 2, "/>") == 0) {
        pos_ += 2;
        e.self_closing = true;
        return e;
      }
      const std::string key = name();
      skip_space();
      if (key.empty() || pos_ >= text_.size() || text_[pos_] != '=') {
        fail_at(file_, line_, "the attribute '" + key + "' of <" + e.name + "> needs =\"value\"");
      }
      ++pos_;
      skip_space();
      const char quote = pos_ < text_.size() ? text_[pos_] : '\0';
      if (quote != '"' && quote != '\'') fail_at(file_, line_, "the value of '" + key + "' needs quotes");
      const std::size_t end = text_.find(quote, pos_ + 1);
      if (end == std::string::npos) fail_at(file_, line_, "the value of '" + key + "' has no closing quote");
      e.attributes[key] = text_.substr(pos_ + 1, end - pos_ - 1);
      advance_to(end + 1);
    }
  }

  const std::string& text_;
  const std::string& file_;
  std::size_t pos_ = 0;
  int line_ = 1;
};

// Path data: numbers and command letters, flags as single digits where an arc wants them.
class PathData {
 public:
  PathData(std::string_view d, const std::string& file, int line) : d_(d), file_(file), line_(line) {}

  void skip_separators() {
    while (pos_ < d_.size() && (std::isspace(static_cast<unsigned char>(d_[pos_])) || d_[pos_] == ',')) ++pos_;
  }
  bool at_end() {
    skip_separators();
    return pos_ >= d_.size();
  }
  bool at_number() {
    skip_separators();
    if (pos_ >= d_.size()) return false;
    const char c = d_[pos_];
    return std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.';
  }
  char command() {
    skip_separators();
    const char c = d_[pos_++];
    if (!std::isalpha(static_cast<unsigned char>(c))) {
      fail_at(file_, line_, fmt::format("path data: a command letter was expected at character {}, not '{}'", pos_, c));
    }
    return c;
  }
  double number() {
    if (!at_number()) fail_at(file_, line_, fmt::format("path data: a number was expected at character {}", pos_ + 1));
    std::size_t start = pos_;
    if (d_[pos_] == '+') ++start;
    double value = 0;
    const auto [end, ec] = parse_double(d_.data() + start, d_.data() + d_.size(), value);
    if (ec != std::errc() || !std::isfinite(value)) {
      fail_at(file_, line_, fmt::format("path data: a bad number at character {}", pos_ + 1));
    }
    pos_ = static_cast<std::size_t>(end - d_.data());
    return value;
  }
  bool flag() {
    skip_separators();
    if (pos_ >= d_.size() || (d_[pos_] != '0' && d_[pos_] != '1')) {
      fail_at(file_, line_, fmt::format("path data: an arc flag (0 or 1) was expected at character {}", pos_ + 1));
    }
    return d_[pos_++] == '1';
  }
  Vector2d point() {
    const double x = number();
    return {x, number()};
  }

 private:
  std::string_view d_;
  const std::string& file_;
  int line_;
  std::size_t pos_ = 0;
};

double length_metres(std::string_view unit) {
  if (unit == "mm") return 1e-3;
  if (unit == "cm") return 1e-2;
  if (unit == "in") return 0.0254;
  if (unit == "pt") return 0.0254 / 72;
  if (unit == "pc") return 0.0254 / 6;
  if (unit == "px") return 0.0254 / 96;
  return 0;
}

std::vector<double> numbers_in(const std::string& text, const std::string& file, int line, const std::string& what) {
  std::vector<double> out;
  PathData d(text, file, line);
  while (!d.at_end()) {
    if (!d.at_number()) fail_at(file, line, what + " holds numbers only: '" + text + "'");
    out.push_back(d.number());
  }
  return out;
}

class SvgBuilder {
 public:
  SvgBuilder(const std::string& file) : file_(file) {}

  StrokeSet set;

  void element(const Element& e, const Vector2d& shift, const std::string& layer) {
    shift_ = shift;
    layer_ = layer;
    line_ = e.line;
    if (e.name == "path") return path(attribute(e, "d"));
    if (e.name == "line") {
      return polyline({{number(e, "x1"), number(e, "y1")}, {number(e, "x2"), number(e, "y2")}}, false);
    }
    if (e.name == "polyline" || e.name == "polygon") {
      const std::vector<double> v = numbers_in(attribute(e, "points"), file_, line_, "`points`");
      if (v.size() % 2 != 0 || v.size() < 4) fail_at(file_, line_, "`points` needs pairs x, y: at least 2 of them");
      std::vector<Vector2d> points;
      for (std::size_t i = 0; i < v.size(); i += 2) points.emplace_back(v[i], v[i + 1]);
      return polyline(points, e.name == "polygon");
    }
    if (e.name == "rect") {
      if (e.attributes.count("rx") || e.attributes.count("ry")) {
        fail_at(file_, line_, "a <rect> with rounded corners: convert it to a path (Inkscape: Path > Object to Path)");
      }
      const double x = number(e, "x", 0), y = number(e, "y", 0), w = number(e, "width"), h = number(e, "height");
      return polyline({{x, y}, {x + w, y}, {x + w, y + h}, {x, y + h}}, true);
    }
    if (e.name == "circle") {
      const double r = number(e, "r");
      if (!(r > 0)) fail_at(file_, line_, "a <circle> needs a positive `r`");
      set.circles.push_back({{model({number(e, "cx", 0), number(e, "cy", 0)}), r}, line_, layer_});
      return;
    }
    if (e.name == "ellipse") {
      const Vector2d c(number(e, "cx", 0), number(e, "cy", 0));
      const double rx = number(e, "rx"), ry = number(e, "ry");
      if (!(rx > 0) || !(ry > 0)) fail_at(file_, line_, "an <ellipse> needs positive `rx` and `ry`");
      const auto f = [shift = shift_, c, rx, ry](double t) {
        return to_model(shift, c + Vector2d(rx * std::cos(t), ry * std::sin(t)));
      };
      Stroke s{{{f(0), f(0), 0, f, 0, 2 * std::numbers::pi}}, true, line_, layer_};
      set.strokes.push_back(std::move(s));
      return;
    }
    if (e.name == "text") {  // a note, no part of the drawing
      set.annotations.push_back("<text>");
      return;
    }
    if (e.name == "use" || e.name == "image") {
      fail_at(file_, line_,
              "nbar reads paths, lines, polylines, polygons, rects, circles and ellipses, not <" + e.name +
                  ">: convert it to paths (Inkscape: Edit > Clone > Unlink Clone, or trace the image) or "
                  "delete it (a shape's `layer` reads one group only)");
    }
  }

 private:
  // SVG user units to the sketch's: shifted by the groups' translations, y turned up.
  Vector2d model(const Vector2d& p) const { return to_model(shift_, p); }
  static Vector2d to_model(const Vector2d& shift, const Vector2d& p) {
    return {p.x() + shift.x(), -(p.y() + shift.y())};
  }

  std::string attribute(const Element& e, const std::string& key) const {
    const auto it = e.attributes.find(key);
    if (it == e.attributes.end()) fail_at(file_, line_, "<" + e.name + "> without its `" + key + "`");
    return it->second;
  }

  double number(const Element& e, const std::string& key, std::optional<double> otherwise = std::nullopt) const {
    const auto it = e.attributes.find(key);
    if (it == e.attributes.end()) {
      if (otherwise) return *otherwise;
      fail_at(file_, line_, "<" + e.name + "> without its `" + key + "`");
    }
    std::string_view text = it->second;
    if (text.size() > 2 && text.substr(text.size() - 2) == "px") text.remove_suffix(2);
    double value = 0;
    const auto [end, ec] = parse_double(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
      fail_at(file_, line_, "`" + key + "` of <" + e.name + "> needs a number, not '" + it->second + "'");
    }
    return value;
  }

  void polyline(const std::vector<Vector2d>& points, bool closed) {
    Stroke s{{}, closed, line_, layer_};
    for (std::size_t i = 0; i + 1 < points.size(); ++i) {
      if (points[i] != points[i + 1]) s.segments.push_back({model(points[i]), model(points[i + 1])});
    }
    if (!s.segments.empty()) set.strokes.push_back(std::move(s));
  }

  void line_to(Stroke& s, const Vector2d& a, const Vector2d& b) {
    if (a != b) s.segments.push_back({model(a), model(b)});
  }

  void cubic_to(Stroke& s, const Vector2d& p0, const Vector2d& p1, const Vector2d& p2, const Vector2d& p3) {
    const auto f = [shift = shift_, p0, p1, p2, p3](double t) {
      return to_model(shift, cubic_bezier(p0, p1, p2, p3, t));
    };
    s.segments.push_back({model(p0), model(p3), 0, f, 0, 1});
  }

  // The elliptical arc of the path data (SVG 1.1, F.6.5: from its end points to its centre).
  void arc_to(Stroke& s, const Vector2d& from, double rx, double ry, double rotation_deg, bool large, bool sweep,
              const Vector2d& to) {
    if (from == to) return;
    rx = std::abs(rx);
    ry = std::abs(ry);
    if (rx == 0 || ry == 0) return line_to(s, from, to);
    const double phi = rotation_deg * std::numbers::pi / 180, cp = std::cos(phi), sp = std::sin(phi);
    const Vector2d half = (from - to) / 2;
    const Vector2d p(cp * half.x() + sp * half.y(), -sp * half.x() + cp * half.y());
    const double lambda = p.x() * p.x() / (rx * rx) + p.y() * p.y() / (ry * ry);
    // Radii that reach half the chord to within what the rounding of the end points' coordinates
    // can tell (lambda 1: a half ellipse, as a semicircle drawn by A is) put the centre on the
    // chord. The square root below would turn that rounding, 1e-16 of the coordinates, into a
    // centre 1e-8 of the radius off the chord, and a semicircle's bulge of 1 into 0.99999999, in
    // a drawing made in one unit and not in another. Relative: a ratio of lengths.
    const double rounding = 8 * std::numeric_limits<double>::epsilon() *
                            (1 + std::max(from.cwiseAbs().maxCoeff(), to.cwiseAbs().maxCoeff()) / half.norm());
    const bool on_chord = lambda >= 1 - rounding;
    if (lambda > 1) {
      rx *= std::sqrt(lambda);
      ry *= std::sqrt(lambda);
    }
    const double num = rx * rx * ry * ry - rx * rx * p.y() * p.y() - ry * ry * p.x() * p.x();
    const double den = rx * rx * p.y() * p.y() + ry * ry * p.x() * p.x();
    const double root = on_chord ? 0.0 : (large == sweep ? -1 : 1) * std::sqrt(std::max(0.0, num / den));
    const Vector2d cprime(root * rx * p.y() / ry, -root * ry * p.x() / rx);
    const Vector2d centre =
        Vector2d(cp * cprime.x() - sp * cprime.y(), sp * cprime.x() + cp * cprime.y()) + (from + to) / 2;
    const Vector2d u((p.x() - cprime.x()) / rx, (p.y() - cprime.y()) / ry);
    const Vector2d v((-p.x() - cprime.x()) / rx, (-p.y() - cprime.y()) / ry);
    const double start = std::atan2(u.y(), u.x());
    double delta = std::atan2(u.x() * v.y() - u.y() * v.x(), u.dot(v));
    if (!sweep && delta > 0) delta -= 2 * std::numbers::pi;
    if (sweep && delta < 0) delta += 2 * std::numbers::pi;
    if (std::abs(rx - ry) <= 1e-12 * std::max(rx, ry)) {
      // A circular arc stays exact: a bulge, its turn reversed with the y axis.
      s.segments.push_back({model(from), model(to), -std::tan(delta / 4)});
      return;
    }
    // Sampled after the builder is gone: the curve keeps the shift, never `this`.
    const auto f = [shift = shift_, centre, rx, ry, cp, sp](double t) {
      const double x = rx * std::cos(t), y = ry * std::sin(t);
      return to_model(shift, centre + Vector2d(cp * x - sp * y, sp * x + cp * y));
    };
    s.segments.push_back({model(from), model(to), 0, f, start, start + delta});
  }

  void finish_stroke(Stroke& s, bool closed) {
    s.closed = closed;
    if (!s.segments.empty()) set.strokes.push_back(s);
    s = Stroke{{}, false, line_, layer_};
  }

  // Where the path data's pen is: its point, the start of its subpath (for Z) and the last
  // control point (for the smooth curves S and T).
  struct Pen {
    Vector2d current{0, 0}, start{0, 0}, last_control{0, 0};
  };

  void path(const std::string& d_text) {
    PathData d(d_text, file_, line_);
    Stroke s{{}, false, line_, layer_};
    Pen pen;
    char previous = ' ';
    char command = ' ';
    while (!d.at_end()) {
      command = next_command(d, command);
      path_command(d, command, previous, pen, s);
      previous = command;
    }
    finish_stroke(s, false);
  }

  // The command of the next segment: a letter, or numbers that repeat the last command
  // (numbers after a moveto are linetos).
  char next_command(PathData& d, char command) const {
    if (!d.at_number()) {
      command = d.command();
    } else if (command == ' ') {
      fail_at(file_, line_, "path data must start with M or m");
    } else if (command == 'M') {
      command = 'L';  // numbers after a moveto are linetos
    } else if (command == 'm') {
      command = 'l';
    } else if (command == 'Z' || command == 'z') {
      fail_at(file_, line_, "path data: numbers after Z");
    }
    return command;
  }

  // One segment of `command` (its numbers read from `d`), drawn into `s` from the pen.
  void path_command(PathData& d, char command, char previous, Pen& pen, Stroke& s) {
    const bool relative = std::islower(static_cast<unsigned char>(command));
    const Vector2d base = relative ? pen.current : Vector2d(0, 0);
    switch (std::toupper(static_cast<unsigned char>(command))) {
      case 'M':
        finish_stroke(s, false);
        pen.current = pen.start = base + d.point();
        break;
      case 'L': {
        const Vector2d to = base + d.point();
        line_to(s, pen.current, to);
        pen.current = to;
        break;
      }
      case 'H': {
        const Vector2d to(d.number() + (relative ? pen.current.x() : 0), pen.current.y());
        line_to(s, pen.current, to);
        pen.current = to;
        break;
      }
      case 'V': {
        const Vector2d to(pen.current.x(), d.number() + (relative ? pen.current.y() : 0));
        line_to(s, pen.current, to);
        pen.current = to;
        break;
      }
      case 'C': {
        const Vector2d c1 = base + d.point(), c2 = base + d.point(), to = base + d.point();
        cubic_to(s, pen.current, c1, c2, to);
        pen.last_control = c2;
        pen.current = to;
        break;
      }
      case 'S': {
        const bool smooth = std::strchr("CcSs", previous) != nullptr && previous != ' ';
        const Vector2d c1 = smooth ? 2 * pen.current - pen.last_control : pen.current;
        const Vector2d c2 = base + d.point(), to = base + d.point();
        cubic_to(s, pen.current, c1, c2, to);
        pen.last_control = c2;
        pen.current = to;
        break;
      }
      case 'Q':
      case 'T': {
        const bool smooth = std::strchr("QqTt", previous) != nullptr && previous != ' ';
        const Vector2d q = std::toupper(static_cast<unsigned char>(command)) == 'Q'
                               ? Vector2d(base + d.point())
                               : (smooth ? Vector2d(2 * pen.current - pen.last_control) : pen.current);
        const Vector2d to = base + d.point();
        cubic_to(s, pen.current, pen.current + 2.0 / 3 * (q - pen.current), to + 2.0 / 3 * (q - to), to);
        pen.last_control = q;
        pen.current = to;
        break;
      }
      case 'A': {
        const double rx = d.number(), ry = d.number(), rotation = d.number();
        const bool large = d.flag(), sweep = d.flag();
        const Vector2d to = base + d.point();
        arc_to(s, pen.current, rx, ry, rotation, large, sweep, to);
        pen.current = to;
        break;
      }
      case 'Z':
        line_to(s, pen.current, pen.start);
        pen.current = pen.start;
        finish_stroke(s, true);
        break;
      default: fail_at(file_, line_, std::string("path data: unknown command '") + command + "'");
    }
  }

  const std::string& file_;
  Vector2d shift_ = Vector2d::Zero();
  std::string layer_;
  int line_ = 0;
};

bool same_name(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

// A group's translate(x[, y]); any other transform cannot be applied to arcs kept exact.
Vector2d translation(const Element& e, const std::string& file) {
  const auto it = e.attributes.find("transform");
  if (it == e.attributes.end()) return Vector2d::Zero();
  const std::string& t = it->second;
  const std::size_t open = t.find('('), close = t.rfind(')');
  if (t.rfind("translate", 0) != 0 || open == std::string::npos || close == std::string::npos) {
    fail_at(file, e.line,
            "nbar applies only translate() of SVG transforms, not '" + t +
                "' (Inkscape: Extensions > Modify Path > Apply Transform)");
  }
  const std::vector<double> v = numbers_in(t.substr(open + 1, close - open - 1), file, e.line, "translate()");
  if (v.empty() || v.size() > 2) fail_at(file, e.line, "translate() takes 1 or 2 numbers");
  return {v[0], v.size() == 2 ? v[1] : 0.0};
}

// The size of a user unit in metres, when the root states its width in an absolute unit.
std::optional<double> svg_unit(const Element& root, const std::string& file) {
  const auto width = root.attributes.find("width");
  if (width == root.attributes.end()) return std::nullopt;
  std::string_view w = width->second;
  std::size_t digits = 0;
  while (digits < w.size() && (std::isdigit(static_cast<unsigned char>(w[digits])) || w[digits] == '.')) ++digits;
  const double metres = length_metres(w.substr(digits));
  double value = 0;
  if (metres == 0 || parse_double(w.data(), w.data() + digits, value).ec != std::errc() || !(value > 0)) {
    return std::nullopt;
  }
  const auto box = root.attributes.find("viewBox");
  if (box == root.attributes.end()) return 0.0254 / 96;  // user units are px
  const std::vector<double> v = numbers_in(box->second, file, root.line, "`viewBox`");
  if (v.size() != 4 || !(v[2] > 0)) fail_at(file, root.line, "`viewBox` needs 4 numbers, the width positive");
  return value * metres / v[2];
}

}  // namespace

StrokeSet read_svg_strokes(const std::string& text, const std::string& file, const std::string& layer, int& last_line) {
  XmlScanner scanner(text, file);
  SvgBuilder builder(file);
  struct Open {
    std::string name;
    Vector2d shift;
    bool in_layer;
    bool in_defs;
    std::string group;  // the id of the innermost group with one
  };
  std::vector<Open> stack;
  std::optional<std::pair<std::string, int>> matched;  // the group `layer` names, and its line
  bool saw_svg = false;
  while (std::optional<Element> e = scanner.next()) {
    if (e->closing) {
      if (stack.empty() || stack.back().name != e->name) {
        fail_at(file, e->line, "</" + e->name + "> closes no open <" + e->name + ">");
      }
      stack.pop_back();
      continue;
    }
    const Open parent = stack.empty() ? Open{"", Vector2d::Zero(), layer.empty(), false, ""} : stack.back();
    if (!saw_svg) {
      if (e->name != "svg") fail_at(file, e->line, "an SVG file starts with <svg>, not <" + e->name + ">");
      saw_svg = true;
      builder.set.metres_per_unit = svg_unit(*e, file);
    }
    Open here{e->name, parent.shift + translation(*e, file), parent.in_layer, parent.in_defs || e->name == "defs",
              parent.group};
    if (e->name == "g" && !layer.empty()) {
      for (const char* key : {"id", "inkscape:label"}) {
        const auto it = e->attributes.find(key);
        if (it == e->attributes.end() || !same_name(it->second, layer) || here.in_layer) continue;
        // Compared without case, 'Crank' and 'crank' both match: reading both would merge two plates.
        if (matched) {
          fail_at(file, e->line,
                  fmt::format("the groups '{}' (line {}) and '{}' (here) both match the layer '{}' "
                              "(compared without case): rename one",
                              matched->first, matched->second, it->second, layer));
        }
        matched = std::pair(it->second, e->line);
        here.in_layer = true;
      }
    }
    if (e->name == "g") {
      const auto id = e->attributes.find("id");
      if (id != e->attributes.end()) here.group = id->second;
    }
    if (here.in_layer && !here.in_defs) builder.element(*e, here.shift, here.group);
    if (!e->self_closing) stack.push_back(here);
  }
  last_line = scanner.line();
  if (!saw_svg) fail_at(file, last_line, "no <svg> element: is this an SVG file?");
  if (!stack.empty()) fail_at(file, last_line, "the SVG ends with <" + stack.back().name + "> still open");
  return std::move(builder.set);
}

}  // namespace nbar::io::sketch_detail
