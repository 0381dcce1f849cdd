// The model file's shapes of bodies: outlines, curves, arcs, holes, bars and drawings imported
// (model_file_parser.hpp).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "model/box_index.hpp"
#include "model_file_parser.hpp"
#include "nbar/io/file_text.hpp"
#include "nbar/io/sketch.hpp"

namespace nbar::io::model_file_detail {

// [x, y] in model units, as written (not converted).
Eigen::Vector2d Parser::coordinates(const YAML::Node& node, std::string_view what) const {
  if (!node.IsSequence() || node.size() != 2) {
    fail(node, std::string(what) + " needs [x, y], not " + describe(node));
  }
  return {number(node[0], mark(node[0]), "x"), number(node[1], mark(node[1]), "y")};
}

// An expression in `variable` (model length units, angles of sin and cos in radians), its
// syntax errors reported at their character.
Law Parser::curve_law(const YAML::Node& node, const std::string& text, std::string_view variable) const {
  try {
    return Law::parse(text, 1.0, variable);
  } catch (const LawSyntaxError& error) {
    const std::optional<SourceMark> where = column_in_scalar(node, error.column());
    fail(where.value_or(mark(node)), "in the expression '" + text + "': " + error.what());
  }
}

std::string_view Parser::trimmed(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

// A number, or an expression of numbers such as "2*pi", written in `node`.
double Parser::constant_text(const YAML::Node& node, std::string_view written, std::string_view what) const {
  const std::string text(trimmed(written));
  double value = 0;
  if (yaml::parse_number(text, value) == yaml::NumberStatus::Ok) return value;
  Law law;
  try {
    law = Law::parse(text, 1.0, "nothing");
  } catch (const LawSyntaxError& error) {
    fail(node, std::string(what) + " '" + text + "': " + error.what());
  }
  try {
    return law.value(0.0);
  } catch (const Error& error) {
    fail(node, std::string(what) + ": " + error.what());
  }
}

double Parser::curve_constant(const YAML::Node& node, std::string_view what) const {
  if (!node.IsScalar()) fail(node, std::string(what) + " must be a number, not " + describe(node));
  return constant_text(node, node.Scalar(), what);
}

std::pair<double, double> Parser::curve_interval(const YAML::Node& node, std::string_view what) const {
  if (!node.IsSequence() || node.size() != 2)
    fail(node, std::string(what) + " must be [from, to], not " + describe(node));
  const double a = curve_constant(node[0], "the start"), b = curve_constant(node[1], "the end");
  if (a == b) fail(node, std::string(what) + " is empty: [" + node[0].Scalar() + ", " + node[1].Scalar() + "]");
  return {a, b};
}

int Parser::curve_steps(const YAML::Node& node) const {
  const double n = number(node, mark(node), "`steps`");
  if (n != std::floor(n) || n < 1 || n > kMaxCurveSteps) {
    fail(node, "`steps` must be a whole number from 1 to " + std::to_string(kMaxCurveSteps));
  }
  return static_cast<int>(n);
}

// A function profile: `expression` of `variable` (x or y), over [a, b], giving the other
// coordinate. The thesis tool's "f{a, b, steps}" gives the interval and steps inline.
Parser::CurveItem Parser::profile(const YAML::Node& node, const YAML::Node& function, std::string_view variable,
                                  const YAML::Node* interval, const YAML::Node* steps) const {
  if (!function.IsScalar()) fail(function, "a profile is an expression like \"x^2\", not " + describe(function));
  std::string text = function.Scalar();
  CurveItem c;
  c.node = node;
  const std::size_t brace = text.rfind('{');
  const bool inline_interval = brace != std::string::npos && !text.empty() && text.back() == '}';
  if (inline_interval) {
    if (interval) fail(*interval, "this profile gives its interval in braces already ('" + text + "')");
    std::vector<std::string> parts{""};
    for (char ch : text.substr(brace + 1, text.size() - brace - 2)) {
      if (ch == ',') {
        parts.emplace_back();
      } else {
        parts.back() += ch;
      }
    }
    if (parts.size() != 3) {
      fail(function,
           "a profile's braces hold {from, to, steps}, as in \"x^2{0, 2, 15}\", not '" + text.substr(brace) + "'");
    }
    c.from = constant_text(function, parts[0], "the start in the braces");
    c.to = constant_text(function, parts[1], "the end in the braces");
    if (c.from == c.to) fail(function, "the profile's interval " + text.substr(brace) + " is empty");
    double n = 0;
    if (yaml::parse_number(std::string(trimmed(parts[2])), n) != yaml::NumberStatus::Ok || n != std::floor(n) ||
        n < 1 || n > kMaxCurveSteps) {
      fail(function, "the steps in a profile's braces must be a whole number from 1 to " +
                         std::to_string(kMaxCurveSteps) + ", not '" + parts[2] + "'");
    }
    c.steps = static_cast<int>(n);
    text.resize(brace);
  } else {
    if (!interval) {
      fail(node, "a profile " + std::string(variable == "x" ? "y" : "x") + " = f(" + std::string(variable) +
                     ") needs its interval: `" + std::string(variable) + ": [from, to]`, or \"f{from, to, steps}\"");
    }
    std::tie(c.from, c.to) = curve_interval(*interval, "the interval");
  }
  if (steps) {
    if (inline_interval) fail(*steps, "this profile gives its steps in braces already");
    c.steps = curve_steps(*steps);
  }
  const Law law = curve_law(function, text, variable);
  const bool of_x = variable == "x";
  c.point = [law, of_x](double v) {
    const double w = law.value(v);
    return of_x ? Eigen::Vector2d(v, w) : Eigen::Vector2d(w, v);
  };
  return c;
}

Parser::CurveItem Parser::curve_item(const YAML::Node& node) const {
  const Fields f = fields(node, kCurveKeys);
  const Entry* x = f.find("x");
  const Entry* y = f.find("y");
  const Entry* s = f.find("s");
  const Entry* steps = f.find("steps");
  const YAML::Node* steps_node = steps ? &steps->value : nullptr;
  if (const Entry* spline = f.find("spline")) {
    for (const Entry* other : {x, y, s, steps}) {
      if (other) fail(other->key_node, "a spline is {spline: [[x, y], ...]} alone, without `" + other->key + "`");
    }
    if (!spline->value.IsSequence()) fail(mark(*spline), "`spline` is a list of points [[x, y], ...]");
    std::vector<Eigen::Vector2d> points;
    for (const YAML::Node& p : spline->value) points.push_back(coordinates(p, "a spline point"));
    CurveItem c;
    c.node = node;
    try {
      c.spline = std::make_shared<const CubicSpline>(std::move(points), false);
    } catch (const Error& error) {
      fail(mark(*spline), error.what());
    }
    return c;
  }
  if (s) {
    if (!x || !y || !x->value.IsScalar() || !y->value.IsScalar()) {
      fail(node, "a parametric curve is {x: \"expression in s\", y: \"expression in s\", s: [from, to]}");
    }
    CurveItem c;
    c.node = node;
    std::tie(c.from, c.to) = curve_interval(s->value, "`s`");
    if (steps) c.steps = curve_steps(steps->value);
    const Law lx = curve_law(x->value, x->value.Scalar(), "s"), ly = curve_law(y->value, y->value.Scalar(), "s");
    c.point = [lx, ly](double v) { return Eigen::Vector2d(lx.value(v), ly.value(v)); };
    return c;
  }
  // A function profile: the expression is the scalar of x and y, the other (if any) its interval.
  if (y && y->value.IsScalar() && (!x || x->value.IsSequence())) {
    return profile(node, y->value, "x", x ? &x->value : nullptr, steps_node);
  }
  if (x && x->value.IsScalar() && (!y || y->value.IsSequence())) {
    return profile(node, x->value, "y", y ? &y->value : nullptr, steps_node);
  }
  fail(node,
       "a curve is {x: \"f(s)\", y: \"g(s)\", s: [a, b]}, {y: \"f(x)\", x: [a, b]}, {x: \"f(y)\", y: [a, b]} "
       "or {spline: [[x, y], ...]}, not " +
           describe(node));
}

// {centre: [x, y], radius: r, angles: [from, to]}: the arc from angle `from` to `to` (the
// model's angle unit, counterclockwise when to > from), as its two ends and the bulge between.
Parser::RingItem Parser::arc_item(const YAML::Node& node) const {
  const Fields f = fields(node, kArcKeys);
  const Entry* centre = f.find("centre");
  const Entry* radius = f.find("radius");
  const Entry* angles = f.find("angles");
  if (!centre || !radius || !angles) fail(node, "an arc is {centre: [x, y], radius: r, angles: [from, to]}");
  const Eigen::Vector2d c = coordinates(centre->value, "`centre`");
  const double r = number(radius->value, mark(*radius), "the radius");
  if (!(r > 0)) fail(mark(*radius), "an arc's radius must be > 0, not " + describe(radius->value));
  if (!angles->value.IsSequence() || angles->value.size() != 2) {
    fail(mark(*angles), "`angles` is [from, to] in the model's angle unit, not " + describe(angles->value));
  }
  const double scale = model_.units.angle_scale;
  const double from = scale * number(angles->value[0], mark(angles->value[0]), "the start angle");
  const double to = scale * number(angles->value[1], mark(angles->value[1]), "the end angle");
  const double sweep = to - from;
  if (!(std::abs(sweep) > 1e-9) || !(std::abs(sweep) < 2 * std::numbers::pi - 1e-9)) {
    fail(mark(*angles), "an arc sweeps more than 0 and less than a full turn; use a circle hole for a whole circle");
  }
  RingItem item;
  item.node = node;
  item.vertex = c + r * Eigen::Vector2d(std::cos(from), std::sin(from));
  item.arc_end = c + r * Eigen::Vector2d(std::cos(to), std::sin(to));
  item.bulge = std::tan(sweep / 4);
  return item;
}

Parser::RingItem Parser::ring_item(const YAML::Node& v) const {
  RingItem item;
  item.node = v;
  if (v.IsMap() && v["centre"]) return arc_item(v);
  if (v.IsMap()) {
    item.curve = curve_item(v);
    return item;
  }
  const bool with_arc = v.IsSequence() && v.size() == 3;
  if (!v.IsSequence() || (v.size() != 2 && !with_arc)) {
    fail(v, "a vertex needs [x, y], not " + describe(v) +
                " (or [x, y, {bulge: b}] for an arc to the next vertex, or a curve {x: ..., y: ...})");
  }
  item.vertex = Eigen::Vector2d(number(v[0], mark(v[0]), "x"), number(v[1], mark(v[1]), "y"));
  if (!with_arc) return item;
  const YAML::Node arc = v[2];
  if (!arc.IsMap() || arc.size() != 1 || !(arc["bulge"] || arc["through"])) {
    fail(arc, "an arc on a vertex is {bulge: b} or {through: [x, y]}, not " + describe(arc));
  }
  if (arc["bulge"]) {
    item.bulge = number(arc["bulge"], mark(arc["bulge"]), "the bulge");
  } else {
    item.through = std::make_pair(arc["through"], coordinates(arc["through"], "`through`"));
  }
  return item;
}

// The vertices of a curve item, at the ring's tolerance (or its fixed steps).
std::vector<Eigen::Vector2d> Parser::curve_vertices(const CurveItem& c, double tolerance) const {
  try {
    if (c.spline) return sample_spline(*c.spline, tolerance);
    if (c.steps > 0) return sample_curve_uniform(c.point, c.from, c.to, c.steps);
    return sample_curve(c.point, c.from, c.to, tolerance);
  } catch (const Error& error) {
    fail(c.node, std::string("this curve: ") + error.what());
  }
}

// The tolerance of a ring's curves: kRelativeCurveTolerance of the diagonal of the box
// around its vertices and a first coarse sampling of its curves.
double Parser::ring_tolerance(const std::vector<RingItem>& items) const {
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  const auto grow = [&](const Eigen::Vector2d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  };
  for (const RingItem& item : items) {
    if (item.vertex) grow(*item.vertex);
    if (!item.curve) continue;
    CurveItem coarse = *item.curve;
    coarse.steps = 64;
    if (coarse.spline) {
      for (double k = 0; k <= 64; ++k) grow((*coarse.spline)(coarse.spline->end() * k / 64));
    } else {
      for (const Eigen::Vector2d& p : curve_vertices(coarse, 1.0)) grow(p);
    }
  }
  const double diagonal = (hi - lo).norm();
  return diagonal > 0 && std::isfinite(diagonal) ? kRelativeCurveTolerance * diagonal : 1.0;
}

Parser::Ring Parser::ring_of(const std::vector<RingItem>& items, SourceMark where, std::string_view what) const {
  Ring ring;
  const double tolerance = ring_tolerance(items);
  // Where a curve ends on the next item's start, up to its rounding (cos(2 pi) is not 1).
  const double same = 1e-9 * tolerance / kRelativeCurveTolerance;
  bool after_curve = false;
  std::vector<double> bulges;
  std::vector<std::optional<std::pair<YAML::Node, Eigen::Vector2d>>> through;
  bool arcs = false;
  for (const RingItem& item : items) {
    std::vector<Eigen::Vector2d> added;
    if (item.curve) {
      added = curve_vertices(*item.curve, tolerance);
      ring.curves = true;
    } else {
      added.push_back(*item.vertex);
    }
    for (const Eigen::Vector2d& p : added) {
      // A curve that starts where the previous item ended shares that vertex.
      if ((item.curve || item.arc_end || after_curve) && !ring.vertices.empty() &&
          (p - ring.vertices.back()).norm() <= same && bulges.back() == 0 && !through.back()) {
        continue;
      }
      ring.vertices.push_back(p);
      ring.origin.push_back(item.node);
      bulges.push_back(0.0);
      through.emplace_back();
    }
    after_curve = item.curve.has_value() || item.arc_end.has_value();
    if (item.vertex && (item.bulge != 0 || item.through || item.node.size() == 3 || item.arc_end)) {
      arcs = true;
      bulges.back() = item.bulge;
      through.back() = item.through;
    }
    if (item.arc_end) {
      ring.vertices.push_back(*item.arc_end);
      ring.origin.push_back(item.node);
      bulges.push_back(0.0);
      through.emplace_back();
    }
  }
  // A closed curve (or an arc) ends where the ring starts.
  const bool ends_with_arc = !items.empty() && items.back().arc_end.has_value();
  while ((ring.curves || ends_with_arc) && ring.vertices.size() > 1 &&
         (ring.vertices.back() - ring.vertices.front()).norm() <= same && bulges.back() == 0) {
    ring.vertices.pop_back();
    ring.origin.pop_back();
    bulges.pop_back();
    through.pop_back();
  }
  const std::size_t n = ring.vertices.size();
  if (ring.curves && n > 2 * static_cast<std::size_t>(kMaxCurveSteps)) {
    fail(where, std::string(what) + " has " + std::to_string(n) + " vertices with its curves, more than " +
                    std::to_string(2 * kMaxCurveSteps) + ": give its curves fewer `steps`");
  }
  if (n < (arcs ? 2u : 3u)) {
    fail(where, std::string(what) + " needs at least " + (arcs ? "2 vertices with an arc" : "3 vertices") + ", not " +
                    std::to_string(n));
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!through[i]) continue;
    try {
      bulges[i] = bulge_through(ring.vertices[i], ring.vertices[(i + 1) % n], through[i]->second);
    } catch (const Error& error) {
      fail(through[i]->first, std::string("`through`: ") + error.what());
    }
  }
  if (arcs) ring.bulges = std::move(bulges);
  return ring;
}

Parser::Ring Parser::polygon(const Entry& e, std::string_view what) const {
  if (!e.value.IsSequence()) {
    fail(mark(e),
         "`" + e.key + "` must be a list of vertices like [[0, 0], [100, 0], [100, 20]], not " + describe(e.value));
  }
  std::vector<RingItem> items;
  for (const YAML::Node& v : e.value) items.push_back(ring_item(v));
  // A ring that is one spline through points that close on themselves is a periodic spline.
  if (items.size() == 1 && items[0].curve && items[0].curve->spline) {
    const YAML::Node points = e.value[0]["spline"];
    std::vector<Eigen::Vector2d> p;
    for (const YAML::Node& q : points) p.push_back(coordinates(q, "a spline point"));
    if (p.size() > 3 && p.front() == p.back()) {
      p.pop_back();
      items[0].curve->spline = std::make_shared<const CubicSpline>(std::move(p), true);
    }
  }
  return ring_of(items, mark(e), what);
}

// The outline between a lower and an upper profile, as the thesis tool builds a link: the
// lower profiles from left to right, then the upper ones from right to left, joined by
// straight edges.
Parser::Ring Parser::profiles_ring(const Entry* lower, const Entry* upper, const YAML::Node& shape) const {
  if (!lower || !upper) {
    fail(shape,
         "a shape by profiles needs both `lower` and `upper` (each like \"x^2{0, 2, 15}\" or "
         "{y: \"x^2\", x: [0, 2]})");
  }
  const auto profiles = [&](const Entry& e) {
    std::vector<RingItem> items;
    const auto one = [&](const YAML::Node& p) {
      RingItem item;
      item.node = p;
      if (p.IsScalar()) {
        item.curve = profile(p, p, "x", nullptr, nullptr);
      } else if (p.IsMap()) {
        item.curve = curve_item(p);
        if (item.curve->spline || !p["y"] || !p["y"].IsScalar()) {
          fail(p, "an upper or lower profile is y = f(x): \"f{from, to, steps}\" or {y: \"f\", x: [from, to]}");
        }
      } else {
        fail(p, "an upper or lower profile is \"f{from, to, steps}\" or {y: \"f\", x: [from, to]}, not " + describe(p));
      }
      if (item.curve->from > item.curve->to) std::swap(item.curve->from, item.curve->to);
      items.push_back(std::move(item));
    };
    if (e.value.IsSequence()) {
      for (const YAML::Node& p : e.value) one(p);
    } else {
      one(e.value);
    }
    std::vector<double> starts;
    for (const RingItem& item : items) starts.push_back(item.curve->from);
    std::vector<std::size_t> order(items.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return starts[a] < starts[b]; });
    std::vector<RingItem> sorted;
    for (std::size_t i : order) sorted.push_back(items[i]);
    return sorted;
  };
  std::vector<RingItem> items = profiles(*lower);
  std::vector<RingItem> top = profiles(*upper);
  for (auto it = top.rbegin(); it != top.rend(); ++it) {
    std::swap(it->curve->from, it->curve->to);
    items.push_back(std::move(*it));
  }
  return ring_of(items, mark(shape), "an outline by profiles");
}

// check_region names vertices of the polygonised ring; with curves, say where they came from.
std::string Parser::with_origins(std::string message, const Ring& ring) {
  if (!ring.curves) return message;
  std::string out;
  std::size_t last = 0;
  for (const EdgeMention& edge : edge_mentions(message)) {
    out.append(message, last, edge.end - last);
    if (edge.from < ring.origin.size())
      out += " (of the item at line " + std::to_string(mark(ring.origin[edge.from]).line) + ")";
    last = edge.end;
  }
  out.append(message, last, std::string::npos);
  return out;
}

// The position of a point in model units, for geometry written in model units.
Eigen::Vector2d Parser::drawn(int point) const { return model_.points[point].position / model_.units.length_scale; }

Region Parser::to_si(Region r) const {
  const double s = model_.units.length_scale;
  for (Eigen::Vector2d& v : r.outline) v *= s;
  for (auto& hole : r.polygon_holes) {
    for (Eigen::Vector2d& v : hole) v *= s;
  }
  for (Circle& c : r.circle_holes) {
    c.centre *= s;
    c.radius *= s;
  }
  return r;
}

// Every polygon hole gets its list of bulges, empty when straight, so the lists stay aligned.
// Each listed hole alone against the outline, then against each earlier hole near it (their
// boxes meet; holes whose boxes are apart cannot overlap): the pairs a scan of every earlier hole
// would report, in its order, without the 32 million pair checks of 8 000 holes.
void Parser::check_listed_holes(const Region& region, const std::vector<Hole>& holes,
                                const std::string& invalid) const {
  std::vector<Eigen::AlignedBox2d> boxes;
  for (const Hole& h : holes) {
    boxes.push_back(h.circle ? circle_bounds(*h.circle) : ring_bounds(h.polygon.vertices, h.polygon.bulges));
  }
  const BoxIndex index(boxes);
  for (std::size_t k = 0; k < holes.size(); ++k) {
    Region alone{region.outline, {}, {}, region.outline_bulges, {}};
    add_hole(alone, holes[k]);
    try {
      check_region(alone);
    } catch (const Error& error) {
      // The hole is the only one checked, so it is "hole 0" to check_region.
      std::string reason = error.what();
      for (std::string_view name : {"circle hole 0", "polygon hole 0"}) {
        if (reason.rfind(name, 0) == 0) reason = "the hole" + reason.substr(name.size());
      }
      fail(holes[k].node, invalid + reason);
    }
    for (std::size_t j : index.meeting(boxes[k])) {
      if (j >= k) break;
      Region pair{region.outline, {}, {}, region.outline_bulges, {}};
      add_hole(pair, holes[j]);
      add_hole(pair, holes[k]);
      try {
        check_region(pair);
      } catch (const Error&) {
        fail(holes[k].node, invalid + "this hole overlaps or touches hole " + std::to_string(j + 1) + " (line " +
                                std::to_string(mark(holes[j].node).line) + ")");
      }
    }
  }
}

void Parser::add_hole(Region& r, const Hole& h) {
  if (h.circle) {
    r.circle_holes.push_back(*h.circle);
  } else {
    r.polygon_holes.push_back(h.polygon.vertices);
    r.polygon_hole_bulges.push_back(h.polygon.bulges);
  }
}

Parser::Hole Parser::parse_hole(const YAML::Node& item) const {
  if (!item.IsMap()) {
    fail(item,
         "a hole is a mapping like {at: A, radius: 5}, {circle: [50, 10], radius: 4} or "
         "{polygon: [[x, y], ...]}, not " +
             describe(item));
  }
  const Fields f = fields(item, kHoleKeys);
  const Entry* kind = nullptr;
  for (const Entry& field : f.entries) {
    if (field.key != "at" && field.key != "circle" && field.key != "polygon") continue;
    if (kind) {
      fail(field.key_node,
           "a hole has exactly one of `at`, `circle` or `polygon`; this one already has `" + kind->key + "`");
    }
    kind = &field;
  }
  if (!kind) fail(item, "a hole needs one of `at: <point>`, `circle: [x, y]` or `polygon: [[x, y], ...]`");
  Hole hole;
  hole.node = item;
  const Entry* radius = f.find("radius");
  if (kind->key == "polygon") {
    if (radius) fail(radius->key_node, "`radius` applies only to a round hole (`at` or `circle`)");
    hole.polygon = polygon(*kind, "a polygon hole");
    return hole;
  }
  if (!radius) fail(item, "a round hole needs `radius`");
  const Eigen::Vector2d centre =
      kind->key == "at" ? drawn(point_ref(kind->value)) : coordinates(kind->value, "`circle`");
  hole.circle = Circle{centre, non_negative(*radius, "the radius", true)};
  return hole;
}

// Checked piece by piece so that an error points at the outline or at the hole concerned.
Region Parser::parse_shape(const Entry& e, const std::string& body) const {
  if (!e.value.IsMap()) {
    fail(mark(e),
         "`shape` must be a mapping like {outline: [[0, 0], [100, 0], [100, 20], [0, 20]]}, not " + describe(e.value));
  }
  const Fields f = fields(e.value, kShapeKeys);
  const std::string invalid = "the shape of " + body + " is not valid: ";
  const Entry* imported = f.find("import");
  const Entry* lower = f.find("lower");
  const Entry* upper = f.find("upper");
  const Entry* written = f.find("outline");
  {
    int ways = 0;
    const Entry* second = nullptr;
    for (const Entry* way : {written, imported, lower ? lower : upper}) {
      if (way && ++ways == 2) second = way;
    }
    if (second) fail(second->key_node, "a shape has one of `outline`, `import` or `lower` and `upper`");
  }
  if (!imported && !lower && !upper) required(f, e.value, "outline", "a shape");
  const Entry& outline = imported ? *imported : written ? *written : lower ? *lower : *upper;
  Region region;
  const Entry* layer = f.find("layer");
  if (layer && !imported)
    fail(layer->key_node, "`layer` goes with `import`: the layer (DXF) or group (SVG) of the drawing to read");
  const Entry* units = f.find("units");
  if (units && !imported) fail(units->key_node, "`units` goes with `import`: the length unit of the file read");
  Ring outer;
  if (imported) {
    region = import_plate(*imported, layer ? text_value(*layer, "`layer`") : std::string(), units);
  } else {
    outer = written ? polygon(*written, "an outline") : profiles_ring(lower, upper, e.value);
    region.outline = outer.vertices;
    region.outline_bulges = outer.bulges;
  }
  try {
    check_region(region);
  } catch (const Error& error) {
    fail(mark(outline), invalid + with_origins(error.what(), outer));
  }
  std::vector<Hole> holes;
  if (const Entry* h = f.find("holes")) {
    for (const YAML::Node& item : section_list(*h, "[{at: A, radius: 5}]")) {
      if (holes.size() == kMaxHolesPerPlate) {
        fail(item, invalid + "a plate has at most " + std::to_string(kMaxHolesPerPlate) + " holes; this is one more");
      }
      holes.push_back(parse_hole(item));
    }
  }
  check_listed_holes(region, holes, invalid);
  for (const Hole& h : holes) add_hole(region, h);
  if (imported) {
    // The drawing's own holes were not checked one by one above.
    try {
      check_region(region);
    } catch (const Error& error) {
      fail(mark(outline), invalid + error.what());
    }
  }
  return to_si(std::move(region));
}

// `import: FILE`: a plate drawn in a DXF file (on one layer, if given), in the model's units.
Region Parser::import_plate(const Entry& e, const std::string& layer, const Entry* units) const {
  const std::string name = text_value(e, "`import`");
  if (!import_dir_) {
    fail(mark(e), "`import` reads a file, which only a model read from a file may do");
  }
  std::filesystem::path path(name);
  if (path.is_relative()) path = *import_dir_ / path;
  const std::optional<SketchFormat> format = sketch_format(path.string());
  if (!format) fail(mark(e), "`import` reads DXF (.dxf), SVG (.svg) or sketch CSV (.csv) drawings, not '" + name + "'");
  const FileText file = read_file_text(path);
  if (file.error) fail(mark(e), "cannot read " + path.string() + ": " + file.error.message());
  if (file.too_long) fail(mark(e), "cannot read " + path.string() + ": " + too_long_message());
  std::optional<double> stated;
  if (units) {
    stated = length_unit_scale(text_value(*units, "`units`"));
    if (!stated) fail(mark(*units), "the unit of the file read is one of mm, cm, m, in, ft");
  }
  const Sketch sketch = read_sketch(file.text, path.string(), *format, layer);
  return checked_plate_from_sketch(sketch, sketch_scale(sketch, stated, model_.units.length_scale), path.string());
}

Region Parser::parse_bar(const Entry& e, const Body& body, const std::string& name) const {
  if (!e.value.IsMap()) {
    fail(mark(e), "`bar` must be a mapping like {width: 20, margin: 10, hole: 5}, not " + describe(e.value));
  }
  const Fields f = fields(e.value, kBarKeys);
  std::array<int, 2> ends{};
  if (const Entry* between = f.find("between")) {
    ends = point_pair(*between, "[A, B]");
    if (ends[0] == ends[1]) fail(mark(*between), "a bar runs between two different points");
  } else if (body.points.size() < 2) {
    fail(e.key_node, name + " has a single point: say where its bar runs with `between: [P, Q]`");
  } else {
    ends = {body.points[0], body.points[1]};
  }
  const double width = non_negative(required(f, e.value, "width", "a bar"), "the width", true);
  double margin = width / 2;
  if (const Entry* m = f.find("margin")) margin = non_negative(*m, "the margin");
  std::array<double, 2> radii{0.0, 0.0};
  const Entry* hole = f.find("hole");
  const Entry* holes = f.find("holes");
  if (hole && holes) {
    const Entry* second = hole > holes ? hole : holes;  // entries are stored in file order
    fail(second->key_node, "give a bar either `hole` (both ends) or `holes: [r1, r2]`, not both");
  }
  if (hole) radii[0] = radii[1] = non_negative(*hole, "the hole radius");
  if (holes) {
    if (!holes->value.IsSequence() || holes->value.size() != 2) {
      fail(mark(*holes), "`holes` needs two radii [r1, r2], one per end (0 for none), not " + describe(holes->value));
    }
    for (std::size_t i = 0; i < 2; ++i) {
      radii[i] = number(holes->value[i], mark(holes->value[i]), "a hole radius");
      if (radii[i] < 0.0) fail(holes->value[i], "a hole radius must not be negative");
    }
  }
  try {
    return to_si(make_bar(drawn(ends[0]), drawn(ends[1]), width, margin, radii[0], radii[1]));
  } catch (const Error& error) {
    std::string_view reason = error.what();
    if (reason.rfind("make_bar: ", 0) == 0) reason.remove_prefix(10);
    fail(mark(e), "the bar of " + name + " is not valid: " + std::string(reason));
  }
}

}  // namespace nbar::io::model_file_detail
