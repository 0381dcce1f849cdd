#include "nbar/render/drawing.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <cmath>
#include <numbers>
#include <string>

#include "nbar/dynamics/inverse_dynamics.hpp"

namespace nbar::render {

namespace {

constexpr double kJointRadius = 4.5;   // px
constexpr double kBarWidth = 9.0;      // px, bodies without a shape
constexpr double kBlockLength = 30.0;  // px, slider blocks
constexpr double kBlockWidth = 18.0;
constexpr double kPivotSize = 13.0;    // px, ground pivot triangles

const Color kInk = Color::rgb(0x222222);
const Color kGround = Color::rgb(0x555555);
const Color kPaper = Color::rgb(0xffffff);

Eigen::Vector2d perp(const Eigen::Vector2d& v) { return {-v.y(), v.x()}; }

Color darker(const Color& c) {
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

// Convex hull (monotone chain), for bodies of three or more points without a shape.
std::vector<Eigen::Vector2d> hull(std::vector<Eigen::Vector2d> p) {
  std::sort(p.begin(), p.end(), [](const auto& a, const auto& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  if (p.size() < 3) return p;
  auto turn = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
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
            Paint{Color::rgb(0xe6e6e6), Stroke{kGround, 1.4, {}}});
  c.polyline({{at.x() - s, base.y()}, {at.x() + s, base.y()}}, Stroke{kGround, 1.6, {}});
  for (int i = 0; i < 5; ++i) {
    const double x = at.x() - s + (i + 0.5) * (2 * s / 5);
    c.polyline({{x, base.y()}, {x - 5, base.y() + 6}}, Stroke{kGround, 1.0, {}});
  }
}

// A fixed guide line with hatching on one side.
void draw_ground_line(Canvas& c, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  c.polyline({a, b}, Stroke{kGround, 1.6, {}});
  const Eigen::Vector2d e = (b - a).normalized(), n = perp(e);
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

Color body_color(int index) {
  static const std::uint32_t palette[] = {0x1f77b4, 0xff7f0e, 0x2ca02c, 0xd62728, 0x9467bd,
                                          0x8c564b, 0xe377c2, 0x17becf, 0xbcbd22, 0x7f7f7f};
  return Color::rgb(palette[index % 10]);
}

std::vector<Eigen::Vector2d> sample_points(const Mechanism& mech, const Sample& sample) {
  return point_positions(mech, sample.taylor.col(0));
}

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
  for (const auto& points : poses) {
    for (const auto& p : points) include(p);
    for (std::size_t b = 0; b < m.bodies.size(); ++b) {
      if (!m.bodies[b].shape) continue;
      const Placement place = placement(m, static_cast<int>(b), points);
      for (const auto& v : straight_edged(*m.bodies[b].shape).outline) include(place(v));
    }
  }
  // Room for pivots, blocks and labels around the outermost points.
  const double room = 30.0;
  return View(lo, hi, options.width, options.height, options.margin + room);
}

void draw_mechanism(Canvas& canvas, const View& view, const Mechanism& mech, const SweepResult& sweep,
                    const std::vector<Eigen::Vector2d>& points, const DrawOptions& options) {
  const Model& m = mech.model();
  auto px = [&](const Eigen::Vector2d& w) { return view.to_pixels(w); };
  const double scale = view.pixels_per_metre();

  // Ground: guides of sliders and slots fixed to the frame, then pivots.
  canvas.begin_group("ground", "ground");
  auto guide_span = [&](int point, const std::array<int, 2>& along) {
    // The stretch of the guide line the point travels, plus a block's length.
    const Eigen::Vector2d a = m.points[along[0]].position, e = (m.points[along[1]].position - a).normalized();
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const Sample& s : sweep.samples) {
      const double t = e.dot(sample_points(mech, s)[point] - a);
      lo = std::min(lo, t);
      hi = std::max(hi, t);
    }
    if (sweep.samples.empty()) lo = hi = e.dot(points[point] - a);
    const double pad = kBlockLength / scale;
    return std::pair{px(a + (lo - pad) * e), px(a + (hi + pad) * e)};
  };
  for (const Slider& s : m.sliders)
    if (m.points[s.along[0]].ground && m.points[s.along[1]].ground) {
      const auto [a, b] = guide_span(s.point, s.along);
      draw_ground_line(canvas, a, b);
    }
  for (const Slot& s : m.slots)
    if (m.points[s.along[0]].ground && m.points[s.along[1]].ground) {
      const auto [a, b] = guide_span(s.point, s.along);
      const Eigen::Vector2d n = perp((b - a).normalized()) * (kJointRadius + 2);
      canvas.polyline({a + n, b + n}, Stroke{kGround, 1.4, {}});
      canvas.polyline({a - n, b - n}, Stroke{kGround, 1.4, {}});
    }
  for (std::size_t p = 0; p < m.points.size(); ++p) {
    if (!m.points[p].ground) continue;
    if (links_at(m, static_cast<int>(p)).size() >= 2) {
      draw_pivot(canvas, px(points[p]));
    } else {  // a fixed point of no body: a guide's end, a spring's anchor
      const Eigen::Vector2d c = px(points[p]);
      canvas.polygon(rectangle(c, {1, 0}, 7, 7), Paint{Color::rgb(0x9a9a9a), Stroke{kGround, 1.0, {}}});
    }
  }
  canvas.end_group();

  if (!options.traces.empty()) {
    canvas.begin_group("traces", "traces");
    for (int t : options.traces) {
      std::vector<Eigen::Vector2d> path;
      for (const Sample& s : sweep.samples) path.push_back(px(sample_points(mech, s)[t]));
      canvas.polyline(path, Stroke{Color::rgb(0x444444, 200), 1.3, {5, 3}});
    }
    canvas.end_group();
  }

  // Bodies, each with the joints it is the last moving body of: drawn after every body that
  // meets there, a joint stays visible.
  std::vector<int> joint_owner(m.points.size(), -1);
  for (std::size_t bi = 0; bi < m.bodies.size(); ++bi)
    for (int p : m.bodies[bi].points) joint_owner[p] = static_cast<int>(bi);
  for (std::size_t bi = 0; bi < m.bodies.size(); ++bi) {
    const Body& body = m.bodies[bi];
    const int b = static_cast<int>(bi);
    const Color color = body_color(b);
    const Paint plate{Color{color.r, color.g, color.b, 150}, Stroke{darker(color), 1.4, {}}};
    canvas.begin_group("body-" + body.name, "body");
    const Placement place = placement(m, b, points);
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
    } else if (body.points.size() == 1) {
      const Eigen::Vector2d along = px(place(place.origin_drawn + place.direction_drawn)) - px(place.origin);
      canvas.polygon(rectangle(px(points[body.points[0]]), along, kBlockLength, kBlockWidth), plate);
    } else if (body.points.size() == 2) {
      canvas.polyline({px(points[body.points[0]]), px(points[body.points[1]])}, Stroke{color, kBarWidth, {}});
    } else {
      std::vector<Eigen::Vector2d> corners;
      for (int p : body.points) corners.push_back(px(points[p]));
      canvas.polygon(hull(corners), plate);
    }
    // Guides and slots that ride on this body.
    for (const Slider& s : m.sliders)
      if (!(m.points[s.along[0]].ground && m.points[s.along[1]].ground) &&
          std::find(body.points.begin(), body.points.end(), s.along[0]) != body.points.end())
        canvas.polyline({px(points[s.along[0]]), px(points[s.along[1]])}, Stroke{darker(color), 2.0, {6, 3}});
    for (const Slot& s : m.slots)
      if (std::find(body.points.begin(), body.points.end(), s.along[0]) != body.points.end() &&
          !(m.points[s.along[0]].ground && m.points[s.along[1]].ground)) {
        const Eigen::Vector2d a = px(points[s.along[0]]), c = px(points[s.along[1]]);
        canvas.polygon(rectangle(0.5 * (a + c), c - a, (c - a).norm() + 2 * kJointRadius, 2 * kJointRadius + 3),
                       Paint{kPaper, Stroke{darker(color), 1.2, {}}});
      }
    for (int p : body.points) {
      if (joint_owner[p] != b) continue;
      const bool joint = links_at(m, p).size() >= 2;
      if (joint)
        canvas.circle(px(points[p]), kJointRadius, Paint{kPaper, Stroke{kInk, 1.5, {}}});
      else
        canvas.circle(px(points[p]), 2.5, Paint{kInk, std::nullopt});
    }
    canvas.end_group();
  }

  if (options.labels) {
    canvas.begin_group("labels", "labels");
    for (std::size_t p = 0; p < m.points.size(); ++p)
      canvas.text(px(points[p]) + Eigen::Vector2d(7, -7), m.points[p].name, 12, Anchor::Start, kInk);
    canvas.end_group();
  }

  if (!options.markers.empty()) {
    canvas.begin_group("markers", "markers");
    for (const Marker& mk : options.markers) {
      const Body& body = m.bodies[mk.body];
      const Eigen::Vector2d o = points[body.points[0]];
      const Eigen::Vector2d e = body.points.size() >= 2 ? Eigen::Vector2d((points[body.points[1]] - o).normalized())
                                                        : Eigen::Vector2d(1, 0);
      const Eigen::Vector2d at = px(o + mk.local.x() * e + mk.local.y() * perp(e));
      canvas.circle(at, 7, Paint{std::nullopt, Stroke{Color::rgb(0xd00000), 2.2, {}}});
      canvas.circle(at, 2, Paint{Color::rgb(0xd00000), std::nullopt});
      if (!mk.label.empty()) canvas.text(at + Eigen::Vector2d(10, -10), mk.label, 12, Anchor::Start, Color::rgb(0xb00000));
    }
    canvas.end_group();
  }

  if (!options.marked_points.empty()) {
    const Color mark = Color::rgb(0x1f5fbf);
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

  if (options.scale_bar) {
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
  if (!options.title.empty()) canvas.text({14, 22}, options.title, 15, Anchor::Start, kInk);
}

void draw_sample(Canvas& canvas, const Mechanism& mech, const SweepResult& sweep, int step,
                 const DrawOptions& options) {
  const View view = fit_view(mech, sweep, options);
  draw_mechanism(canvas, view, mech, sweep, sample_points(mech, sweep.samples.at(step)), options);
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
