#include "nbar/io/sketch_model.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>

#include "drawing_rounding.hpp"
#include "model/box_index.hpp"
#include "nbar/model/diagnostics.hpp"
#include "nbar/model/geometry.hpp"

namespace nbar::io {

namespace {

using drawing_detail::Tidy;  // the coordinates written rounded relative to the drawing's size
using Eigen::Vector2d;

// The straight-edged polygon of a loop, for containment tests.
std::vector<Vector2d> chords(const SketchLoop& loop) {
  Region r;
  r.outline = loop.vertices;
  if (std::any_of(loop.bulges.begin(), loop.bulges.end(), [](double b) { return b != 0.0; })) {
    r.outline_bulges = loop.bulges;
  }
  return straight_edged(r).outline;
}

bool inside(const std::vector<Vector2d>& polygon, const Vector2d& p) {
  add_geometry_work(polygon.size());
  bool in = false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Vector2d& a = polygon[i];
    const Vector2d& b = polygon[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x()) {
      in = !in;
    }
  }
  return in;
}

// Whether `inner` lies wholly inside `outer`: a vertex inside is not enough, as two links
// drawn overlapping at their joint each have vertices inside the other.
Eigen::AlignedBox2d box_of(const std::vector<Vector2d>& p) {
  Eigen::AlignedBox2d b;
  for (const Vector2d& v : p) b.extend(v);
  return b;
}

bool wholly_inside(const std::vector<Vector2d>& inner, const std::vector<Vector2d>& outer) {
  add_geometry_work(1);
  if (!box_of(outer).contains(box_of(inner))) return false;  // the common case, without the edge pairs
  return std::all_of(inner.begin(), inner.end(), [&](const Vector2d& v) { return inside(outer, v); }) &&
         !polygons_meet(inner, outer);
}

std::string xy(const Vector2d& v, const Tidy& tidy) {
  return fmt::format("[{:.12g}, {:.12g}", tidy(v.x()), tidy(v.y()));
}

std::string ring_yaml(const SketchLoop& loop, double scale, const Tidy& tidy, const std::string& indent) {
  std::string out;
  for (std::size_t i = 0; i < loop.vertices.size(); ++i) {
    out += indent + "- " + xy(loop.vertices[i] * scale, tidy);
    if (loop.bulges[i] != 0.0) out += fmt::format(", {{bulge: {:.12g}}}", loop.bulges[i]);
    out += "]\n";
  }
  return out;
}

bool is_name(const std::string& s) {
  if (s.empty() || s == "0" || s.size() > 64 || !std::isalpha(static_cast<unsigned char>(s[0]))) return false;
  return std::all_of(s.begin(), s.end(),
                     [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-'; });
}

// A comment line counting the annotations the sketch left out by kind ("2 TEXT, 1 DIMENSION"),
// so that the user knows they were seen and not read; nothing when there were none.
std::string annotation_note(const std::vector<std::string>& annotations) {
  if (annotations.empty()) return {};
  std::map<std::string, int> count;
  for (const std::string& a : annotations) ++count[a];
  std::string list;
  for (const auto& [kind, n] : count) list += fmt::format("{}{} {}", list.empty() ? "" : ", ", n, kind);
  return "# Left out of the sketch, as notes that draw no link: " + list + ".\n";
}

struct Body {
  std::size_t loop;
  std::string name;
  std::vector<std::size_t> holes;           // loops
  std::vector<std::size_t> points;          // indices into the points
  std::map<std::size_t, double> pin_holes;  // point -> radius
};

// A point of the model: circle centres that coincide are one; then the marked points.
struct Joint {
  Vector2d at;
  double radius = 0;  // 0: a marked point, no hole
  int line = 0;       // the circle's (the smallest, where several are drawn at one place)
};

// The sketch's loops as straight-edged polygons, their areas and the box around them.
struct Outlines {
  std::vector<std::vector<Vector2d>> polygons;
  std::vector<double> areas;
  Vector2d lo = Vector2d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
};

Outlines outlines_of(const Sketch& sketch) {
  Outlines o;
  for (const SketchLoop& l : sketch.loops) {
    o.polygons.push_back(chords(l));
    o.areas.push_back(l.area());
    for (const Vector2d& v : o.polygons.back()) {
      o.lo = o.lo.cwiseMin(v);
      o.hi = o.hi.cwiseMax(v);
    }
  }
  return o;
}

// The plates (loops at an even depth of nesting), each with its holes (the loops at an odd
// depth whose smallest container it is).
std::vector<Body> plates_of(const Sketch& sketch, const Outlines& outlines, const SketchModelOptions& options) {
  const std::size_t n = sketch.loops.size();
  const auto& polygons = outlines.polygons;
  const auto& areas = outlines.areas;
  // Each loop's containers, wholly around it; they must nest in turn, or the outline lies in
  // two that cross and could be a hole of either. A container's box holds the loop's, so the
  // candidates are the loops whose boxes meet its box (not all n², which 50 000 squares were).
  const auto contains = [&](std::size_t j, std::size_t i) {
    return i != j && areas[j] > areas[i] && wholly_inside(polygons[i], polygons[j]);
  };
  std::vector<Eigen::AlignedBox2d> boxes;
  for (const auto& polygon : polygons) boxes.push_back(box_of(polygon));
  const BoxIndex index(boxes);
  const auto crossing = [&](std::size_t i, std::size_t a, std::size_t b) {
    return Error(ErrorKind::InvalidModel,
                 fmt::format("this outline lies inside two outlines that cross (at lines {} and {}); outlines must "
                             "nest, a plate holding holes, or stand apart",
                             sketch.loops[std::min(a, b)].lines.front(), sketch.loops[std::max(a, b)].lines.front()),
                 {}, options.source_name, {sketch.loops[i].lines.front(), 1});
  };
  std::vector<int> parent(n, -1);
  std::vector<int> depth(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<std::size_t> containers;  // ascending, as the scan of every loop met them
    for (std::size_t j : index.meeting(boxes[i])) {
      if (!contains(j, i)) continue;
      for (std::size_t k : containers) {
        if (!contains(j, k) && !contains(k, j)) throw crossing(i, k, j);
      }
      containers.push_back(j);
      ++depth[i];
      if (parent[i] < 0 || areas[j] < areas[static_cast<std::size_t>(parent[i])]) parent[i] = static_cast<int>(j);
    }
  }
  std::vector<Body> bodies;
  std::map<std::size_t, std::size_t> body_of_loop;
  for (std::size_t i = 0; i < n; ++i) {
    if (depth[i] % 2 != 0) continue;
    body_of_loop[i] = bodies.size();
    bodies.push_back({i, "", {}, {}, {}});
  }
  // Containers that nest alternate plate, hole, plate: an odd depth's smallest container is a
  // plate, unless rounding made containment disagree with itself.
  for (std::size_t i = 0; i < n; ++i) {
    if (depth[i] % 2 == 0) continue;
    const auto p = static_cast<std::size_t>(parent[i]);
    const auto body = body_of_loop.find(p);
    if (body == body_of_loop.end()) {
      throw Error(ErrorKind::InvalidModel,
                  fmt::format("this outline lies in the hole at line {}, which only outlines that cross make; "
                              "outlines must nest, a plate holding holes, or stand apart",
                              sketch.loops[p].lines.front()),
                  {}, options.source_name, {sketch.loops[i].lines.front(), 1});
    }
    bodies[body->second].holes.push_back(i);
  }
  return bodies;
}

// Names: the layer, when no other outline has it.
void name_bodies(const Sketch& sketch, std::vector<Body>& bodies) {
  std::map<std::string, int> layer_count;
  for (const Body& b : bodies) ++layer_count[sketch.loops[b.loop].layer];
  std::set<std::string> taken;
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    const std::string& layer = sketch.loops[bodies[k].loop].layer;
    std::string name = is_name(layer) && layer_count[layer] == 1 ? layer : "link" + std::to_string(k + 1);
    while (!taken.insert(name).second) name += "_";
    bodies[k].name = name;
  }
}

// The joints found so far in cells, so that finding the first one within `same`
// of a point looks at the joints around it, not at all of them (40 000 circles were 8e8 tests).
class JointCells {
 public:
  explicit JointCells(double same) : same_(same) {}
  // The first joint (in the order they were added) within `same` of p, as a scan of them all
  // would find it.
  std::optional<std::size_t> first_near(const std::vector<Joint>& joints, const Vector2d& p) const {
    std::optional<std::size_t> first;
    const auto [i, j] = cell(p);
    for (long long di = -1; di <= 1; ++di)
      for (long long dj = -1; dj <= 1; ++dj)
        if (const auto it = cells_.find({i + di, j + dj}); it != cells_.end())
          for (std::size_t k : it->second) {
            add_geometry_work(1);
            if ((!first || k < *first) && (joints[k].at - p).norm() <= same_) first = k;
          }
    return first;
  }
  void add(const Vector2d& p, std::size_t k) { cells_[cell(p)].push_back(k); }

 private:
  // Cells of twice `same` (so that rounding cannot put two points within `same` two cells
  // apart), or, when that is 0, of the exact point (only equal points are within 0);
  // beyond ±1e15 cells the coordinates share a cell, which only costs tests, never a joint.
  std::pair<long long, long long> cell(const Vector2d& p) const {
    const auto index = [&](double x) {
      const double c = same_ > 0 ? std::floor(x / (2 * same_)) : x;
      return static_cast<long long>(std::clamp(std::isnan(c) ? 0.0 : c, -1e15, 1e15));
    };
    return {index(p.x()), index(p.y())};
  }
  double same_;
  std::map<std::pair<long long, long long>, std::vector<std::size_t>> cells_;
};

// Points: circle centres that coincide (within `same`) are one; then the marked points.
std::vector<Joint> joints_of(const Sketch& sketch, double same) {
  std::vector<Joint> joints;
  JointCells cells(same);
  for (const SketchCircle& c : sketch.circles) {
    const std::optional<std::size_t> near = cells.first_near(joints, c.circle.centre);
    if (!near) {
      cells.add(c.circle.centre, joints.size());
      joints.push_back({c.circle.centre, c.circle.radius, c.line});
    } else if (Joint& it = joints[*near]; c.circle.radius < it.radius) {
      it.radius = c.circle.radius;
      it.line = c.line;
    }
  }
  for (const SketchPoint& p : sketch.points) {
    if (cells.first_near(joints, p.at)) continue;
    cells.add(p.at, joints.size());
    joints.push_back({p.at, 0.0, p.line});
  }
  return joints;
}

// A point belongs to every body whose plate holds it: inside the outline, outside its holes
// (a pin hole's own circle aside). Gives the number of bodies at each joint.
std::vector<int> place_joints(const Sketch& sketch, const Outlines& outlines, const std::vector<Joint>& joints,
                              std::vector<Body>& bodies, const SketchModelOptions& options) {
  const auto& polygons = outlines.polygons;
  std::vector<int> bodies_at(joints.size(), 0);
  // Only the joints in a plate's box can be in it, and only the holes whose box holds a joint
  // can hold it: the indexes keep a plate of 40 000 pin holes from testing every pair.
  std::vector<Eigen::AlignedBox2d> joint_boxes;
  for (const Joint& j : joints) joint_boxes.emplace_back(j.at);
  const BoxIndex joint_index(joint_boxes);
  for (Body& b : bodies) {
    std::vector<Eigen::AlignedBox2d> hole_boxes;
    for (std::size_t h : b.holes) hole_boxes.push_back(box_of(polygons[h]));
    const BoxIndex hole_index(hole_boxes);
    for (std::size_t j : joint_index.meeting(box_of(polygons[b.loop]))) {
      if (!inside(polygons[b.loop], joints[j].at)) continue;
      const std::vector<std::size_t> near = hole_index.meeting(Eigen::AlignedBox2d(joints[j].at));
      if (std::any_of(near.begin(), near.end(),
                      [&](std::size_t h) { return inside(polygons[b.holes[h]], joints[j].at); })) {
        continue;
      }
      b.points.push_back(j);
      if (joints[j].radius > 0) b.pin_holes[j] = joints[j].radius;
      ++bodies_at[j];
    }
    if (b.points.empty()) {
      throw Error(ErrorKind::InvalidModel,
                  "the outline here holds no pin hole (circle) or point: nbar cannot tell how it moves", {},
                  options.source_name, {sketch.loops[b.loop].lines.front(), 1});
    }
  }
  return bodies_at;
}

// A pin hole must stand clear of its plate's outline, its other holes and the other pin holes,
// as the model reader will ask of the model written: said here, at the circle's line.
void check_pin_holes(const Sketch& sketch, const Outlines& outlines, const std::vector<Joint>& joints,
                     const std::vector<Body>& bodies, const SketchModelOptions& options) {
  const auto& polygons = outlines.polygons;
  for (const Body& b : bodies) {
    // The other holes and pin holes near each pin hole, from indexes, in the order of a scan.
    std::vector<Eigen::AlignedBox2d> hole_boxes;
    for (std::size_t h : b.holes) hole_boxes.push_back(box_of(polygons[h]));
    const BoxIndex hole_index(hole_boxes);
    std::vector<std::pair<std::size_t, double>> pins(b.pin_holes.begin(), b.pin_holes.end());
    std::vector<Eigen::AlignedBox2d> pin_boxes;
    for (const auto& [point, radius] : pins) pin_boxes.push_back(circle_bounds({joints[point].at, radius}));
    const BoxIndex pin_index(pin_boxes);
    for (std::size_t p = 0; p < pins.size(); ++p) {
      const Joint& j = joints[pins[p].first];
      const double radius = pins[p].second;
      const auto refuse = [&](const std::string& what, int line) {
        throw Error(ErrorKind::InvalidModel,
                    fmt::format("this pin hole (centre ({:.6g}, {:.6g}), radius {:.6g}) {} at line {}: a plate "
                                "must hold its holes apart and inside its outline",
                                j.at.x(), j.at.y(), radius, what, line),
                    {}, options.source_name, {j.line, 1});
      };
      const Circle disc{j.at, radius};
      if (!circle_clear_of_edges(disc, polygons[b.loop]))
        refuse("meets the outline drawn", sketch.loops[b.loop].lines.front());
      for (std::size_t k : hole_index.meeting(pin_boxes[p])) {
        const std::size_t h = b.holes[k];
        if (inside(polygons[h], j.at) || !circle_clear_of_edges(disc, polygons[h]))
          refuse("meets the hole drawn", sketch.loops[h].lines.front());
      }
      for (std::size_t q : pin_index.meeting(pin_boxes[p])) {
        if (q >= p) break;
        add_geometry_work(1);
        const Joint& k = joints[pins[q].first];
        if ((k.at - j.at).norm() <= radius + pins[q].second) refuse("overlaps the pin hole drawn", k.line);
      }
    }
  }
}

// The model's name: the sketch file's, without folders and extension, and nothing YAML would escape.
std::string model_name(const std::string& source_name) {
  std::string name = source_name.substr(source_name.find_last_of("/\\") + 1);
  name = name.substr(0, name.rfind('.'));
  for (char& c : name) {
    if (c == '"' || c == '\\' || static_cast<unsigned char>(c) < 0x20) c = '_';
  }
  return name;
}

// The comment that opens the model: what was found, and what the user must still give.
std::string model_header(const std::vector<Joint>& joints, const std::vector<int>& bodies_at, std::size_t body_count,
                         const SketchModelOptions& options) {
  int joint_count = 0;
  for (std::size_t j = 0; j < joints.size(); ++j) {
    if (bodies_at[j] >= 2) ++joint_count;
  }
  return fmt::format(
      "# A model skeleton from {} (nbar import): {} link{}, {} joint{} between links.\n"
      "# Pin holes in a single link are taken as ground pivots: check `ground`, then add a driver\n"
      "# (see the end of the file) and set each plate's thickness and material.\n",
      options.source_name, body_count, body_count == 1 ? "" : "s", joint_count, joint_count == 1 ? "" : "s");
}

// A body's entry under `bodies:`: its points, its plate (outline and holes), thickness and material.
std::string body_yaml(const Sketch& sketch, const Body& b, const Tidy& tidy_model, const SketchModelOptions& options) {
  std::string out = "  " + b.name + ":\n    points: [";
  for (std::size_t k = 0; k < b.points.size(); ++k) out += fmt::format("{}P{}", k ? ", " : "", b.points[k] + 1);
  out += fmt::format("]   # outline at line {} of {}\n", sketch.loops[b.loop].lines.front(), options.source_name);
  out += "    shape:\n      outline:\n" + ring_yaml(sketch.loops[b.loop], options.scale, tidy_model, "        ");
  if (!b.holes.empty() || !b.pin_holes.empty()) out += "      holes:\n";
  for (const auto& [point, radius] : b.pin_holes) {
    out += fmt::format("        - {{at: P{}, radius: {:.10g}}}\n", point + 1, tidy_model(radius * options.scale));
  }
  for (std::size_t h : b.holes)
    out += "        - polygon:\n" + ring_yaml(sketch.loops[h], options.scale, tidy_model, "            ");
  out += fmt::format("    thickness: {:.10g}\n    material: {}\n", options.thickness, options.material);
  return out;
}

}  // namespace

std::string model_from_sketch(const Sketch& sketch, const SketchModelOptions& options) {
  const Outlines outlines = outlines_of(sketch);
  std::vector<Body> bodies = plates_of(sketch, outlines, options);
  name_bodies(sketch, bodies);
  // The drawing's size, the diagonal of its outlines' bounding box, which every length the
  // import compares or rounds to is relative to, so that the drawing's unit changes nothing
  // (hypot: the squares of a drawing 1e-100 across, the smallest read, underflow).
  const Vector2d lo = outlines.lo, hi = outlines.hi;
  const double size = std::hypot(hi.x() - lo.x(), hi.y() - lo.y());
  const std::vector<Joint> joints = joints_of(sketch, 1e-6 * size);
  const std::vector<int> bodies_at = place_joints(sketch, outlines, joints, bodies, options);
  if (bodies.empty()) throw Error(ErrorKind::InvalidModel, "the sketch has no outline", {}, options.source_name);
  check_pin_holes(sketch, outlines, joints, bodies, options);

  std::string ground;
  for (std::size_t j = 0; j < joints.size(); ++j) {
    if (bodies_at[j] == 1 && joints[j].radius > 0) ground += (ground.empty() ? "" : ", ") + fmt::format("P{}", j + 1);
  }
  std::string out = model_header(joints, bodies_at, bodies.size(), options);
  const std::string name = model_name(options.source_name);
  out += annotation_note(sketch.annotations);
  // Rounding of the drawing's coordinates (in the comments) and of the model's.
  const Tidy tidy(size), tidy_model(size * options.scale);
  // Circles and points on no link are left out, and the reader told so, not left to find it.
  for (std::size_t j = 0; j < joints.size(); ++j) {
    if (bodies_at[j] == 0)
      out += fmt::format("# Left out: the {} at line {} ({}, {}) lies on no link.\n",
                         joints[j].radius > 0 ? "circle" : "point", joints[j].line, tidy(joints[j].at.x()),
                         tidy(joints[j].at.y()));
  }
  out += fmt::format("name: \"{}\"\nunits: {{length: {}, angle: deg}}\npoints:\n", name, options.length_unit);
  for (std::size_t j = 0; j < joints.size(); ++j) {
    if (bodies_at[j] == 0) continue;  // a circle outside every outline
    out += fmt::format("  P{}: {}]\n", j + 1, xy(joints[j].at * options.scale, tidy_model));
  }
  out += "ground: [" + ground + "]\n";
  out += "gravity: standard\nbodies:\n";
  for (const Body& b : bodies) out += body_yaml(sketch, b, tidy_model, options);
  out += fmt::format("# drivers:\n#   - {{angle: {}, from: 0, to: 360, speed: 60 rpm}}\n", bodies.front().name);
  return out;
}

}  // namespace nbar::io
