#include "nbar/render/drawing.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <optional>
#include <string>

#include "nbar/dynamics/inverse_dynamics.hpp"
#include "nbar/model/diagnostics.hpp"
#include "nbar/render/stress_map.hpp"

namespace nbar::render {

namespace {

constexpr double kJointRadius = 4.5;   // px
constexpr double kBarWidth = 9.0;      // px, bodies without a shape
constexpr double kBlockLength = 30.0;  // px, slider blocks
constexpr double kBlockWidth = 18.0;
constexpr double kPivotSize = 13.0;  // px, ground pivot triangles

const Colour kInk = Colour::rgb(0x222222);
const Colour kGround = Colour::rgb(0x555555);
const Colour kPaper = Colour::rgb(0xffffff);

Eigen::Vector2d perp(const Eigen::Vector2d& v) { return {-v.y(), v.x()}; }

Colour darker(const Colour& c) {
  return {static_cast<std::uint8_t>(c.r * 0.6), static_cast<std::uint8_t>(c.g * 0.6),
          static_cast<std::uint8_t>(c.b * 0.6), 255};
}

// Where a body-fixed point drawn at `drawn` is when the body's frame points are at `points`.
struct Placement {
  Eigen::Vector2d origin_drawn, direction_drawn, origin, direction;
  Eigen::Vector2d operator()(const Eigen::Vector2d& drawn) const {
    const double ll = direction_drawn.squaredNorm();
    if (ll == 0.0) return origin + (drawn - origin_drawn);
    const Eigen::Vector2d d = drawn - origin_drawn;
    const double a = d.dot(direction_drawn) / ll;
    const double b = (direction_drawn.x() * d.y() - direction_drawn.y() * d.x()) / ll;
    return origin + a * direction + b * perp(direction);
  }
};

Placement placement(const Model& m, int body, const std::vector<Eigen::Vector2d>& points) {
  const BodyFrame f = body_frame(m, body);
  Placement p;
  p.origin_drawn = m.points[f.origin].position;
  p.origin = points[f.origin];
  p.direction_drawn = p.direction = Eigen::Vector2d::Zero();
  if (f.from >= 0) {
    p.direction_drawn = m.points[f.to].position - m.points[f.from].position;
    p.direction = points[f.to] - points[f.from];
  }
  return p;
}

std::vector<int> links_at(const Model& m, int point) {
  std::vector<int> links;
  if (m.points[point].ground) links.push_back(-1);
  for (std::size_t b = 0; b < m.bodies.size(); ++b)
    for (int p : m.bodies[b].points)
      if (p == point) links.push_back(static_cast<int>(b));
  return links;
}

// Convex hull (monotone chain), for bodies of three or more points without a shape. A point within
// rounding of the line through its neighbours (a body's points drawn in line) is left out, so that
// the outline does not depend on the last bits of a solved pose.
std::vector<Eigen::Vector2d> hull(std::vector<Eigen::Vector2d> p) {
  std::sort(p.begin(), p.end(),
            [](const auto& a, const auto& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  if (p.size() < 3) return p;
  double extent = 0.0;
  for (const auto& q : p) extent = std::max(extent, (q - p.front()).lpNorm<Eigen::Infinity>());
  const double flat = 1e-9 * extent * extent;
  auto turn = [flat](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x() - flat;
  };
  std::vector<Eigen::Vector2d> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && turn(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && turn(h[k - 2], h[k - 1], p[i - 1]) <= 0) --k;
    h[k++] = p[i - 1];
  }
  h.resize(k - 1);
  return h;
}

std::vector<Eigen::Vector2d> rectangle(const Eigen::Vector2d& centre, const Eigen::Vector2d& along, double length,
                                       double width) {
  const Eigen::Vector2d e = along.norm() > 0 ? Eigen::Vector2d(along.normalized()) : Eigen::Vector2d(1, 0);
  const Eigen::Vector2d n = perp(e);
  return {centre - 0.5 * length * e - 0.5 * width * n, centre + 0.5 * length * e - 0.5 * width * n,
          centre + 0.5 * length * e + 0.5 * width * n, centre - 0.5 * length * e + 0.5 * width * n};
}

// A ground pivot: a triangle under the joint on a hatched base.
void draw_pivot(Canvas& c, const Eigen::Vector2d& at) {
  const double s = kPivotSize;
  const Eigen::Vector2d base(at.x(), at.y() + s);
  c.polygon({at, {at.x() - 0.6 * s, base.y()}, {at.x() + 0.6 * s, base.y()}},
            Paint{Colour::rgb(0xe6e6e6), Stroke{kGround, 1.4, {}}});
  c.polyline({{at.x() - s, base.y()}, {at.x() + s, base.y()}}, Stroke{kGround, 1.6, {}});
  for (int i = 0; i < 5; ++i) {
    const double x = at.x() - s + (i + 0.5) * (2 * s / 5);
    c.polyline({{x, base.y()}, {x - 5, base.y() + 6}}, Stroke{kGround, 1.0, {}});
  }
}

// A fixed guide line with hatching on the side `away` (a unit vector, px) points to.
void draw_ground_line(Canvas& c, const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& away) {
  c.polyline({a, b}, Stroke{kGround, 1.6, {}});
  const Eigen::Vector2d e = (b - a).normalized(), n = away;
  const double length = (b - a).norm();
  for (double s = 4; s < length; s += 10) {
    const Eigen::Vector2d p = a + s * e + 0.5 * kBlockWidth * n;
    c.polyline({p, p + 6 * n - 5 * e}, Stroke{kGround, 0.9, {}});
  }
}

double nice_length(double target) {
  const double p = std::pow(10.0, std::floor(std::log10(target)));
  for (double f : {5.0, 2.0, 1.0})
    if (f * p <= target) return f * p;
  return p;
}

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

}  // namespace

Colour body_colour(int index) {
  // Tableau's ten, then their light and dark companions: a machine of up to 30 bodies gets a
  // colour for each.
  static const std::uint32_t palette[] = {
      0x1f77b4, 0xff7f0e, 0x2ca02c, 0xd62728, 0x9467bd, 0x8c564b, 0xe377c2, 0x17becf, 0xbcbd22, 0x7f7f7f,
      0x9edae5, 0xffbb78, 0x98df8a, 0xff9896, 0xc5b0d5, 0xc49c94, 0xf7b6d2, 0xaec7e8, 0xdbdb8d, 0x393b79,
      0x637939, 0x8c6d31, 0x843c39, 0x7b4173, 0x3182bd, 0xe6550d, 0x31a354, 0x756bb1, 0x636363, 0xa55194};
  constexpr int count = static_cast<int>(sizeof palette / sizeof palette[0]);
  return Colour::rgb(palette[((index % count) + count) % count]);
}

std::vector<Eigen::Vector2d> sample_points(const Mechanism& mech, const Sample& sample) {
  return point_positions(mech, sample.taylor.col(0));
}

namespace {

bool is_slot_pin(const Model& m, int point) {
  return std::any_of(m.slots.begin(), m.slots.end(), [&](const Slot& s) { return s.point == point; });
}

// A joint: a point shared by two links, or a pin in a slot.
bool is_joint(const Model& m, int point) { return links_at(m, point).size() >= 2 || is_slot_pin(m, point); }

bool fixed_guide(const Model& m, const std::array<int, 2>& along) {
  return m.points[along[0]].ground && m.points[along[1]].ground;
}

// A ground point that no body holds and only guides use (a guide's far end, a slide's zero):
// where it is says nothing about where the mechanism moves.
bool guide_end_only(const Model& m, int point) {
  if (!m.points[point].ground || links_at(m, point).size() >= 2) return false;
  bool guide = false;
  for (const Slider& s : m.sliders) guide = guide || s.along[0] == point || s.along[1] == point;
  for (const Slot& s : m.slots) guide = guide || s.along[0] == point || s.along[1] == point;
  return guide;
}

// The two end points of a body whose points all lie on one line (a scissor arm with its middle
// pin), or nothing for a body with a real area.
std::optional<std::pair<int, int>> collinear_ends(const Model& m, const Body& body) {
  if (body.points.size() < 2) return std::nullopt;
  std::pair<int, int> ends{body.points[0], body.points[1]};
  double longest = -1;
  for (int i : body.points)
    for (int j : body.points) {
      const double d = (m.points[i].position - m.points[j].position).norm();
      if (d > longest) longest = d, ends = {i, j};
    }
  const Eigen::Vector2d a = m.points[ends.first].position;
  const Eigen::Vector2d e = (m.points[ends.second].position - a) / std::max(longest, 1e-300);
  for (int p : body.points) {
    const Eigen::Vector2d d = m.points[p].position - a;
    if (std::abs(e.x() * d.y() - e.y() * d.x()) > 1e-6 * longest) return std::nullopt;
  }
  return ends;
}

// Whether `body` holds both points of a guide (a shared end alone does not make it the guide's).
bool holds_guide(const Body& body, const std::array<int, 2>& along) {
  auto on = [&](int p) { return std::find(body.points.begin(), body.points.end(), p) != body.points.end(); };
  return on(along[0]) && on(along[1]);
}

bool carries_slot(const Model& m, const Body& body) {
  return std::any_of(m.slots.begin(), m.slots.end(),
                     [&](const Slot& s) { return !fixed_guide(m, s.along) && holds_guide(body, s.along); });
}

bool carries_guide(const Model& m, const Body& body) {
  return carries_slot(m, body) || std::any_of(m.sliders.begin(), m.sliders.end(), [&](const Slider& s) {
           return !fixed_guide(m, s.along) && holds_guide(body, s.along);
         });
}

// Plates first, then the bodies that carry guides and slots, then bars and blocks: whatever
// rides on or is pinned to a plate is drawn over it.
std::vector<int> drawing_order(const Model& m) {
  auto rank = [&](int b) {
    const Body& body = m.bodies[b];
    if (body.shape || (body.points.size() >= 3 && !collinear_ends(m, body))) return 0;
    return carries_guide(m, body) ? 1 : 2;
  };
  std::vector<int> order(m.bodies.size());
  for (std::size_t b = 0; b < order.size(); ++b) order[b] = static_cast<int>(b);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return rank(a) < rank(b); });
  return order;
}

constexpr double kSlotHalfWidth = kJointRadius + 2.0;  // px
constexpr double kSlottedBarWidth = 2 * kSlotHalfWidth + 6.0;

// A slot: a rounded outline from `a` to `b` (px).
std::vector<Eigen::Vector2d> stadium(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double radius) {
  const Eigen::Vector2d e = (b - a).norm() > 0 ? Eigen::Vector2d((b - a).normalized()) : Eigen::Vector2d(1, 0);
  const Eigen::Vector2d n = perp(e);
  std::vector<Eigen::Vector2d> out;
  constexpr int kArc = 8;
  for (int i = 0; i <= kArc; ++i) {
    const double t = std::numbers::pi * i / kArc;
    out.push_back(b + radius * (std::sin(t) * e - std::cos(t) * n));
  }
  for (int i = 0; i <= kArc; ++i) {
    const double t = std::numbers::pi * i / kArc;
    out.push_back(a + radius * (-std::sin(t) * e + std::cos(t) * n));
  }
  return out;
}

// The stretch (m, from along[0] towards along[1]) of a guide that `point` travels over the
// sweep, or where it is now when there is no sweep.
std::pair<double, double> travel(const Mechanism& mech, const SweepResult& sweep, int point,
                                 const std::array<int, 2>& along, const std::vector<Eigen::Vector2d>& now) {
  auto coordinate = [&](const std::vector<Eigen::Vector2d>& p) {
    const Eigen::Vector2d e = (p[along[1]] - p[along[0]]).normalized();
    return e.dot(p[point] - p[along[0]]);
  };
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Sample& s : sweep.samples) {
    const double t = coordinate(sample_points(mech, s));
    lo = std::min(lo, t);
    hi = std::max(hi, t);
  }
  if (sweep.samples.empty()) lo = hi = coordinate(now);
  return {lo, hi};
}

// What a label should not cover: lines (with their half widths) and filled areas.
struct Obstacles {
  struct Segment {
    Eigen::Vector2d a, b;
    double half_width;
  };
  std::vector<Segment> segments;
  std::vector<std::vector<Eigen::Vector2d>> blocks;  // slider blocks: never covered
  std::vector<std::vector<Eigen::Vector2d>> plates;  // plates: better not covered
  std::vector<std::pair<Eigen::Vector2d, double>> circles;
  std::vector<std::array<double, 4>> boxes;  // labels already placed: left, top, right, bottom

  void polyline(const std::vector<Eigen::Vector2d>& p, double half_width, bool closed) {
    for (std::size_t i = 0; i + 1 < p.size(); ++i) segments.push_back({p[i], p[i + 1], half_width});
    if (closed && p.size() > 2) segments.push_back({p.back(), p.front(), half_width});
  }
};

bool segments_cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                    const Eigen::Vector2d& d) {
  auto side = [](const Eigen::Vector2d& o, const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
    return (p - o).x() * (q - o).y() - (p - o).y() * (q - o).x();
  };
  return side(a, b, c) * side(a, b, d) < 0 && side(c, d, a) * side(c, d, b) < 0;
}

bool contains(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p) {
  bool in = false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++)
    if ((polygon[i].y() > p.y()) != (polygon[j].y() > p.y()) &&
        p.x() < (polygon[j].x() - polygon[i].x()) * (p.y() - polygon[i].y()) / (polygon[j].y() - polygon[i].y()) +
                    polygon[i].x())
      in = !in;
  return in;
}

bool box_meets_segment(const std::array<double, 4>& box, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                       double half_width) {
  const std::array<double, 4> grown = {box[0] - half_width, box[1] - half_width, box[2] + half_width,
                                       box[3] + half_width};
  auto inside = [&](const Eigen::Vector2d& p) {
    return p.x() >= grown[0] && p.x() <= grown[2] && p.y() >= grown[1] && p.y() <= grown[3];
  };
  if (inside(a) || inside(b)) return true;
  const Eigen::Vector2d corners[4] = {
      {grown[0], grown[1]}, {grown[2], grown[1]}, {grown[2], grown[3]}, {grown[0], grown[3]}};
  for (int i = 0; i < 4; ++i)
    if (segments_cross(a, b, corners[i], corners[(i + 1) % 4])) return true;
  return false;
}

std::array<double, 4> label_box(const Eigen::Vector2d& baseline_start, const std::string& text, double size) {
  const double width = 0.6 * size * static_cast<double>(text.size());
  return {baseline_start.x(), baseline_start.y() - 0.8 * size, baseline_start.x() + width,
          baseline_start.y() + 0.2 * size};
}

// How much a label's box at `box` covers: lines and blocks count fully, plates a little,
// other labels fully, leaving the canvas most.
double cover(const Obstacles& o, const std::array<double, 4>& box, const Canvas& canvas, double plate_weight) {
  double penalty = 0;
  for (const auto& s : o.segments)
    if (box_meets_segment(box, s.a, s.b, s.half_width)) penalty += 1;
  const Eigen::Vector2d centre(0.5 * (box[0] + box[2]), 0.5 * (box[1] + box[3]));
  const Eigen::Vector2d corners[5] = {centre, {box[0], box[1]}, {box[2], box[1]}, {box[2], box[3]}, {box[0], box[3]}};
  for (const auto& block : o.blocks)
    for (const auto& c : corners)
      if (contains(block, c)) penalty += 1;
  for (const auto& plate : o.plates)
    for (const auto& c : corners)
      if (contains(plate, c)) penalty += plate_weight / 5;
  for (const auto& [c, r] : o.circles) {
    const Eigen::Vector2d nearest(std::clamp(c.x(), box[0], box[2]), std::clamp(c.y(), box[1], box[3]));
    if ((nearest - c).norm() < r) penalty += 1;
  }
  for (const auto& b : o.boxes)
    if (box[0] < b[2] && b[0] < box[2] && box[1] < b[3] && b[1] < box[3]) penalty += 2;
  if (box[0] < 0 || box[1] < 0 || box[2] > canvas.width() || box[3] > canvas.height()) penalty += 4;
  return penalty;
}

// Where a label of `text` next to `at` covers least (up right when nothing is in the way).
Eigen::Vector2d place_label(Obstacles& o, const Canvas& canvas, const Eigen::Vector2d& at, const std::string& text,
                            double size, double plate_weight, const std::vector<double>& distances) {
  const double width = 0.6 * size * static_cast<double>(text.size());
  Eigen::Vector2d best = at + Eigen::Vector2d(distances.front(), -distances.front());
  double least = std::numeric_limits<double>::infinity();
  for (double d : distances)
    for (double degrees : {45.0, 135.0, -45.0, -135.0, 0.0, 180.0, 90.0, -90.0}) {  // up right first
      const double angle = degrees * std::numbers::pi / 180.0;
      const Eigen::Vector2d dir(std::cos(angle), -std::sin(angle));
      // The box's nearest corner or edge at distance d from the point.
      const Eigen::Vector2d anchor = at + d * dir;
      const Eigen::Vector2d start(dir.x() < -0.3  ? anchor.x() - width
                                  : dir.x() > 0.3 ? anchor.x()
                                                  : anchor.x() - 0.5 * width,
                                  dir.y() < -0.3  ? anchor.y()
                                  : dir.y() > 0.3 ? anchor.y() + 0.8 * size
                                                  : anchor.y() + 0.3 * size);
      const double penalty = cover(o, label_box(start, text, size), canvas, plate_weight);
      if (penalty < least - 1e-9) least = penalty, best = start;
    }
  o.boxes.push_back(label_box(best, text, size));
  return best;
}

}  // namespace

View fit_view(const Mechanism& mech, const SweepResult& sweep, const DrawOptions& options) {
  const Model& m = mech.model();
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  auto include = [&](const Eigen::Vector2d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  };
  std::vector<std::vector<Eigen::Vector2d>> poses;
  for (const Sample& s : sweep.samples) poses.push_back(sample_points(mech, s));
  if (poses.empty()) {
    std::vector<Eigen::Vector2d> drawn;
    for (const Point& p : m.points) drawn.push_back(p.position);
    poses.push_back(drawn);
  }
  // Far guide ends would stretch the view: the guides are drawn over their used length only.
  for (const auto& points : poses) {
    for (std::size_t p = 0; p < points.size(); ++p)
      if (!guide_end_only(m, static_cast<int>(p))) include(points[p]);
    for (std::size_t b = 0; b < m.bodies.size(); ++b) {
      if (!m.bodies[b].shape) continue;
      const Placement place = placement(m, static_cast<int>(b), points);
      for (const auto& v : straight_edged(*m.bodies[b].shape).outline) include(place(v));
    }
  }
  // Room for pivots, blocks and labels around the outermost points.
  const double room = 30.0;
  // A stress legend takes the right edge: the mechanism is centred in what is left.
  const int legend = options.stress_maps.empty() ? 0 : kStressLegendWidth;
  // The margin is fixed in pixels, for labels and pivots of a fixed size; on a short or narrow
  // picture (a phone turned sideways: 808 x 176) two of them would leave the mechanism a quarter
  // of the height, so neither takes more than 22% of its side (which leaves sides of 300 px and
  // more, and so every picture drawn before, as they were).
  const double margin = options.margin + room;
  const int width = options.width - legend;
  return View(lo, hi, width, options.height, std::min(margin, 0.22 * width), std::min(margin, 0.22 * options.height));
}

int default_drawn_step(const Mechanism& mech, const SweepResult& sweep) {
  const Model& m = mech.model();
  auto spread = [&](const Sample& s) {
    std::vector<Eigen::Vector2d> points;
    const auto at = sample_points(mech, s);
    for (std::size_t p = 0; p < at.size(); ++p)
      if (!guide_end_only(m, static_cast<int>(p))) points.push_back(at[p]);
    const auto h = hull(points);
    double area = 0;
    for (std::size_t i = 0; h.size() >= 3 && i < h.size(); ++i) {
      const auto& a = h[i];
      const auto& b = h[(i + 1) % h.size()];
      area += 0.5 * (a.x() * b.y() - a.y() * b.x());
    }
    Eigen::Vector2d lo = points.empty() ? Eigen::Vector2d::Zero() : points[0], hi = lo;
    for (const auto& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    return std::pair{std::abs(area), (hi - lo).squaredNorm()};
  };
  if (sweep.samples.empty()) return 0;
  const auto [area, size] = spread(sweep.samples[0]);
  if (area > 0.01 * size) return 0;
  // The first of the widest: samples whose areas differ only by rounding (mirror images of each
  // other in a symmetric mechanism) count as equal, so that the choice does not turn on last bits.
  int best = 0;
  double widest = area;
  for (std::size_t k = 1; k < sweep.samples.size(); ++k) {
    const double a = spread(sweep.samples[k]).first;
    if (a > widest * (1 + 1e-9) + 1e-12 * size) widest = a, best = static_cast<int>(k);
  }
  return best;
}

std::vector<std::vector<Eigen::Vector2d>> trace_paths(const Mechanism& mech, const SweepResult& sweep,
                                                      const std::vector<int>& points) {
  std::vector<std::vector<Eigen::Vector2d>> paths(points.size());
  if (points.empty() || sweep.samples.empty()) return paths;
  const SweepResult* source = &sweep;
  SweepResult finer;
  if (sweep.complete && sweep.samples.size() > 1 && sweep.samples.size() < static_cast<std::size_t>(kTraceSamples)) {
    try {
      SweepOptions options;
      options.steps = kTraceSamples;
      options.order = 0;
      finer = run_sweep(mech, options);
      if (finer.complete) source = &finer;
    } catch (const Error&) {
      // the sweep's own samples then
    }
  }
  for (const Sample& s : source->samples) {
    const auto at = sample_points(mech, s);
    for (std::size_t i = 0; i < points.size(); ++i) paths[i].push_back(at[points[i]]);
  }
  return paths;
}

namespace {

// Where the moving points are on average over the sweep (px), or at `points` without a sweep;
// false when nothing moves.
bool moving_centroid(const Mechanism& mech, const SweepResult& sweep, const View& view,
                     const std::vector<Eigen::Vector2d>& points, Eigen::Vector2d& centroid) {
  const Model& m = mech.model();
  centroid = Eigen::Vector2d::Zero();
  int count = 0;
  auto add = [&](const std::vector<Eigen::Vector2d>& at) {
    for (std::size_t p = 0; p < m.points.size(); ++p)
      if (!m.points[p].ground) centroid += view.to_pixels(at[p]), ++count;
  };
  if (sweep.samples.empty()) add(points);
  for (const Sample& s : sweep.samples) add(sample_points(mech, s));
  if (count) centroid /= count;
  return count > 0;
}

// Fixed guides: the stretch the point travels plus a block's length, hatched on the side away
// from the moving parts over the whole sweep (the mechanism stands on it, or hangs under it), so
// that the hatching stays on its side in every pose and every frame of an animation.
void draw_fixed_guides(Canvas& canvas, const View& view, const Mechanism& mech, const SweepResult& sweep,
                       const std::vector<Eigen::Vector2d>& points, Obstacles& obstacles) {
  const Model& m = mech.model();
  auto px = [&](const Eigen::Vector2d& w) { return view.to_pixels(w); };
  Eigen::Vector2d centroid;
  const bool moving = moving_centroid(mech, sweep, view, points, centroid);
  auto span = [&](int point, const std::array<int, 2>& along) {
    const auto [lo, hi] = travel(mech, sweep, point, along, points);
    const Eigen::Vector2d a = points[along[0]], e = (points[along[1]] - a).normalized();
    const double pad = kBlockLength / view.pixels_per_metre();
    return std::pair{px(a + (lo - pad) * e), px(a + (hi + pad) * e)};
  };
  for (const Slider& s : m.sliders)
    if (fixed_guide(m, s.along)) {
      const auto [a, b] = span(s.point, s.along);
      Eigen::Vector2d away = perp((b - a).normalized());
      // A guide the moving parts straddle evenly (an in-line slider-crank) is hatched below, or
      // on the right when it stands upright: a choice that does not change from pose to pose.
      const double side = moving ? away.dot(centroid - a) : 0.0;
      if (std::abs(side) < 1.0 ? (std::abs(away.y()) > 1e-9 ? away.y() < 0 : away.x() < 0) : side > 0) away = -away;
      canvas.begin_group("guide-" + m.points[s.point].name, "guide");
      draw_ground_line(canvas, a, b, away);
      canvas.end_group();
      obstacles.segments.push_back({a, b, 1.0});
      obstacles.segments.push_back({a + 0.5 * kBlockWidth * away, b + (0.5 * kBlockWidth + 6) * away, 1.0});
    }
  for (const Slot& s : m.slots)
    if (fixed_guide(m, s.along)) {
      const auto [a, b] = span(s.point, s.along);
      const Eigen::Vector2d n = perp((b - a).normalized()) * kSlotHalfWidth;
      canvas.polyline({a + n, b + n}, Stroke{kGround, 1.4, {}});
      canvas.polyline({a - n, b - n}, Stroke{kGround, 1.4, {}});
      obstacles.segments.push_back({a + n, b + n, 1.0});
      obstacles.segments.push_back({a - n, b - n, 1.0});
    }
}

// A guide's end outside the fitted view (or at its very edge): left out with its label, since
// the guide is drawn where it is used.
bool far_guide_end(const Model& m, int point, const Eigen::Vector2d& at, const Canvas& canvas) {
  const double inset = 20;
  return guide_end_only(m, point) &&
         (at.x() < inset || at.y() < inset || at.x() > canvas.width() - inset || at.y() > canvas.height() - inset);
}

void draw_ground(Canvas& canvas, const View& view, const Mechanism& mech, const SweepResult& sweep,
                 const std::vector<Eigen::Vector2d>& points, Obstacles& obstacles) {
  const Model& m = mech.model();
  canvas.begin_group("ground", "ground");
  draw_fixed_guides(canvas, view, mech, sweep, points, obstacles);
  for (std::size_t p = 0; p < m.points.size(); ++p) {
    if (!m.points[p].ground) continue;
    const Eigen::Vector2d c = view.to_pixels(points[p]);
    if (links_at(m, static_cast<int>(p)).size() >= 2) {
      draw_pivot(canvas, c);
      obstacles.blocks.push_back(
          {c, {c.x() - 0.6 * kPivotSize, c.y() + kPivotSize}, {c.x() + 0.6 * kPivotSize, c.y() + kPivotSize}});
      obstacles.segments.push_back(
          {{c.x() - kPivotSize, c.y() + kPivotSize + 3}, {c.x() + kPivotSize, c.y() + kPivotSize + 3}, 3.0});
    } else if (!far_guide_end(m, static_cast<int>(p), c, canvas)) {  // a guide's end, a spring's anchor
      canvas.polygon(rectangle(c, {1, 0}, 7, 7), Paint{Colour::rgb(0x9a9a9a), Stroke{kGround, 1.0, {}}});
    }
  }
  canvas.end_group();
}

// The slots a moving body carries: a rounded outline over the stretch its pin travels.
void draw_body_slots(Canvas& canvas, const View& view, const Mechanism& mech, const SweepResult& sweep,
                     const std::vector<Eigen::Vector2d>& points, const Body& body, const Colour& colour) {
  const Model& m = mech.model();
  for (const Slot& s : m.slots) {
    if (fixed_guide(m, s.along) || !holds_guide(body, s.along)) continue;
    const auto [lo, hi] = travel(mech, sweep, s.point, s.along, points);
    const Eigen::Vector2d a = points[s.along[0]], e = (points[s.along[1]] - a).normalized();
    canvas.polygon(stadium(view.to_pixels(a + lo * e), view.to_pixels(a + hi * e), kSlotHalfWidth),
                   Paint{kPaper, Stroke{darker(colour), 1.2, {}}});
  }
}

void draw_body(Canvas& canvas, const View& view, const Mechanism& mech, const SweepResult& sweep,
               const std::vector<Eigen::Vector2d>& points, int b, const std::vector<int>& joint_owner,
               const DrawOptions& options, Obstacles& obstacles) {
  const Model& m = mech.model();
  const Body& body = m.bodies[b];
  auto px = [&](const Eigen::Vector2d& w) { return view.to_pixels(w); };
  const double scale = view.pixels_per_metre();
  const Colour colour = body_colour(b);
  const Paint plate{Colour{colour.r, colour.g, colour.b, 150}, Stroke{darker(colour), 1.4, {}}};
  // A body with a slot or a guide (a slotted lever, a cylinder's barrel) is wider than what
  // rides in it.
  const double bar_width = carries_guide(m, body) ? kSlottedBarWidth : kBarWidth;
  canvas.begin_group("body-" + body.name, "body");
  const Placement place = placement(m, b, points);
  const auto ends = collinear_ends(m, body);
  if (body.shape) {
    Outline o;
    const Region shape = straight_edged(*body.shape);  // arcs as chords within 1e-5 of the plate's size
    for (const auto& v : shape.outline) o.outer.push_back(px(place(v)));
    for (const auto& hole : shape.polygon_holes) {
      o.polygon_holes.emplace_back();
      for (const auto& v : hole) o.polygon_holes.back().push_back(px(place(v)));
    }
    for (const Circle& c : body.shape->circle_holes) o.circle_holes.push_back({px(place(c.centre)), c.radius * scale});
    canvas.outline(o, plate);
    for (const StressMap& map : options.stress_maps) {
      if (map.body != b) continue;
      draw_stress_plate(canvas, map, stress_scale(options), [&](const Eigen::Vector2d& v) { return px(place(v)); });
      canvas.outline(o, Paint{std::nullopt, plate.stroke});  // the edge over the colours
    }
    obstacles.plates.push_back(o.outer);
    obstacles.polyline(o.outer, 1.0, true);
  } else if (body.points.size() == 1) {
    const Eigen::Vector2d along = px(place(place.origin_drawn + place.direction_drawn)) - px(place.origin);
    const auto block = rectangle(px(points[body.points[0]]), along, kBlockLength, kBlockWidth);
    canvas.polygon(block, plate);
    obstacles.blocks.push_back(block);
  } else if (ends) {  // two points, or more on one line: a bar
    const Eigen::Vector2d a = px(points[ends->first]), c = px(points[ends->second]);
    canvas.polyline({a, c}, Stroke{colour, bar_width, {}});
    obstacles.segments.push_back({a, c, 0.5 * bar_width});
  } else {
    std::vector<Eigen::Vector2d> corners;
    for (int p : body.points) corners.push_back(px(points[p]));
    const auto outline = hull(corners);
    canvas.polygon(outline, plate);
    obstacles.plates.push_back(outline);
    obstacles.polyline(outline, 1.0, true);
  }
  // Guides and slots that ride on this body.
  for (const Slider& s : m.sliders)
    if (!fixed_guide(m, s.along) && holds_guide(body, s.along))
      canvas.polyline({px(points[s.along[0]]), px(points[s.along[1]])}, Stroke{darker(colour), 2.0, {6, 3}});
  draw_body_slots(canvas, view, mech, sweep, points, body, colour);
  for (int p : body.points) {
    if (joint_owner[p] != b) continue;
    if (is_joint(m, p))
      canvas.circle(px(points[p]), kJointRadius, Paint{kPaper, Stroke{kInk, 1.5, {}}});
    else
      canvas.circle(px(points[p]), 2.5, Paint{kInk, std::nullopt});
    obstacles.circles.push_back({px(points[p]), kJointRadius + 1});
  }
  canvas.end_group();
}

// The paths of the traced points.
void draw_traces(Canvas& canvas, const View& view, const Mechanism& mech, const SweepResult& sweep,
                 const DrawOptions& options) {
  auto px = [&](const Eigen::Vector2d& w) { return view.to_pixels(w); };
  const auto paths = options.trace_paths.size() == options.traces.size() ? options.trace_paths
                                                                         : trace_paths(mech, sweep, options.traces);
  canvas.begin_group("traces", "traces");
  for (const auto& path : paths) {
    std::vector<Eigen::Vector2d> drawn;
    for (const auto& p : path) drawn.push_back(px(p));
    canvas.polyline(drawn, Stroke{Colour::rgb(0x444444, 200), 1.3, {5, 3}});
  }
  canvas.end_group();
}

// Every point's name, placed clear of what is drawn.
void draw_labels(Canvas& canvas, const View& view, const Model& m, const std::vector<Eigen::Vector2d>& points,
                 Obstacles& obstacles) {
  auto px = [&](const Eigen::Vector2d& w) { return view.to_pixels(w); };
  canvas.begin_group("labels", "labels");
  for (std::size_t p = 0; p < m.points.size(); ++p) {
    // One text per point, in order (animations find a point's label by its place), empty
    // for a far guide end and for the point that only gives a guide its direction.
    if (m.points[p].guide_direction || far_guide_end(m, static_cast<int>(p), px(points[p]), canvas)) {
      canvas.text(px(points[p]), "", 12, Anchor::Start, kInk);
      continue;
    }
    const Eigen::Vector2d at =
        place_label(obstacles, canvas, px(points[p]), m.points[p].name, 12, 1.0, {8.0, 13.0, 20.0});
    canvas.text(at, m.points[p].name, 12, Anchor::Start, kInk);
  }
  canvas.end_group();
}

// Markers on bodies (a ring and a dot, with their labels outside plates).
void draw_markers(Canvas& canvas, const View& view, const Model& m, const std::vector<Eigen::Vector2d>& points,
                  const DrawOptions& options, Obstacles& obstacles) {
  auto px = [&](const Eigen::Vector2d& w) { return view.to_pixels(w); };
  canvas.begin_group("markers", "markers");
  for (const Marker& mk : options.markers) {
    const Body& body = m.bodies[mk.body];
    const Eigen::Vector2d o = points[body.points[0]];
    const Eigen::Vector2d e =
        body.points.size() >= 2 ? Eigen::Vector2d((points[body.points[1]] - o).normalized()) : Eigen::Vector2d(1, 0);
    const Eigen::Vector2d at = px(o + mk.local.x() * e + mk.local.y() * perp(e));
    canvas.circle(at, 7, Paint{std::nullopt, Stroke{Colour::rgb(0xd00000), 2.2, {}}});
    canvas.circle(at, 2, Paint{Colour::rgb(0xd00000), std::nullopt});
    obstacles.circles.push_back({at, 8});
    if (!mk.label.empty()) {
      // Outside plates, where it can be read.
      const Eigen::Vector2d where = place_label(obstacles, canvas, at, mk.label, 12, 5.0, {10.0, 24.0, 40.0, 60.0});
      canvas.text(where, mk.label, 12, Anchor::Start, Colour::rgb(0xb00000));
    }
  }
  canvas.end_group();
}

// Points marked in the plane (a ring and a cross).
void draw_marked_points(Canvas& canvas, const View& view, const DrawOptions& options) {
  auto px = [&](const Eigen::Vector2d& w) { return view.to_pixels(w); };
  const Colour mark = Colour::rgb(0x1f5fbf);
  canvas.begin_group("marked-points", "marked-points");
  for (const MarkedPoint& mp : options.marked_points) {
    const Eigen::Vector2d at = px(mp.position);
    canvas.circle(at, 5, Paint{std::nullopt, Stroke{mark, 1.6, {}}});
    canvas.polyline({at + Eigen::Vector2d(-7, 0), at + Eigen::Vector2d(7, 0)}, Stroke{mark, 1.2, {}});
    canvas.polyline({at + Eigen::Vector2d(0, -7), at + Eigen::Vector2d(0, 7)}, Stroke{mark, 1.2, {}});
    if (!mp.label.empty()) canvas.text(at + Eigen::Vector2d(8, 14), mp.label, 11, Anchor::Start, mark);
  }
  canvas.end_group();
}

// A scale bar of a round length, about a fifth of the width, at the bottom left.
void draw_scale_bar(Canvas& canvas, const View& view, const Model& m) {
  const double scale = view.pixels_per_metre();
  const double unit = m.units.length_scale;
  const double length = nice_length(0.2 * canvas.width() / scale / unit);  // model units
  const double bar = length * unit * scale;
  const Eigen::Vector2d a(14, canvas.height() - 14.0), b(14 + bar, canvas.height() - 14.0);
  canvas.begin_group("scale-bar", "scale-bar");
  canvas.polyline({a, b}, Stroke{kInk, 2, {}});
  canvas.polyline({a + Eigen::Vector2d(0, -5), a + Eigen::Vector2d(0, 3)}, Stroke{kInk, 1.5, {}});
  canvas.polyline({b + Eigen::Vector2d(0, -5), b + Eigen::Vector2d(0, 3)}, Stroke{kInk, 1.5, {}});
  canvas.text(0.5 * (a + b) + Eigen::Vector2d(0, -7), number(length) + " " + m.units.length, 12, Anchor::Middle, kInk);
  canvas.end_group();
}

}  // namespace

void draw_mechanism(Canvas& canvas, const View& view, const Mechanism& mech, const SweepResult& sweep,
                    const std::vector<Eigen::Vector2d>& points, const DrawOptions& options) {
  const Model& m = mech.model();
  Obstacles obstacles;

  draw_ground(canvas, view, mech, sweep, points, obstacles);
  if (!options.traces.empty()) draw_traces(canvas, view, mech, sweep, options);

  // Bodies, each with the joints it is the last drawn body of: drawn after every body that
  // meets there, a joint stays visible.
  const std::vector<int> order = drawing_order(m);
  std::vector<int> joint_owner(m.points.size(), -1);
  for (int b : order)
    for (int p : m.bodies[b].points) joint_owner[p] = b;
  for (int b : order) draw_body(canvas, view, mech, sweep, points, b, joint_owner, options, obstacles);
  if (!options.stress_maps.empty()) draw_stress_legend(canvas, stress_scale(options));

  if (options.labels) draw_labels(canvas, view, m, points, obstacles);
  if (!options.markers.empty()) draw_markers(canvas, view, m, points, options, obstacles);
  if (!options.marked_points.empty()) draw_marked_points(canvas, view, options);
  if (options.scale_bar) draw_scale_bar(canvas, view, m);
  if (!options.title.empty()) canvas.text({14, 22}, options.title, 15, Anchor::Start, kInk);
}

void draw_sample(Canvas& canvas, const Mechanism& mech, const SweepResult& sweep, int step,
                 const DrawOptions& options) {
  if (step < 0 || static_cast<std::size_t>(step) >= sweep.samples.size())
    throw Error(ErrorKind::BadInput, "step " + std::to_string(step) + " is not one of the sweep's " +
                                         std::to_string(sweep.samples.size()) + " samples");
  const View view = fit_view(mech, sweep, options);
  draw_mechanism(canvas, view, mech, sweep, sample_points(mech, sweep.samples[static_cast<std::size_t>(step)]),
                 options);
}

std::vector<PixelTransform> body_transforms(const Mechanism& mech, const View& view,
                                            const std::vector<Eigen::Vector2d>& reference,
                                            const std::vector<Eigen::Vector2d>& points) {
  const Model& m = mech.model();
  std::vector<PixelTransform> out;
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const Placement from = placement(m, static_cast<int>(b), reference);
    const Placement to = placement(m, static_cast<int>(b), points);
    PixelTransform t;
    double turn = 0.0;
    if (from.direction.squaredNorm() > 0.0)
      turn = std::atan2(to.direction.y(), to.direction.x()) - std::atan2(from.direction.y(), from.direction.x());
    t.angle_deg = -turn * 180.0 / std::numbers::pi;  // y points down on screen
    t.pivot = view.to_pixels(from.origin);
    t.shift = view.to_pixels(to.origin) - t.pivot;
    out.push_back(t);
  }
  return out;
}

std::vector<int> trace_points(const Model& model, const std::vector<std::string>& names) {
  std::vector<int> points;
  for (const std::string& name : names) {
    const int p = model.find_point(name);
    if (p < 0) {
      std::string known;
      for (const Point& point : model.points) known += (known.empty() ? "" : ", ") + point.name;
      throw Error(ErrorKind::BadInput, "'" + name + "' is not a point of the model; the points are: " + known);
    }
    points.push_back(p);
  }
  return points;
}

}  // namespace nbar::render
