#include "nbar/io/dxf_writer.hpp"

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <limits>
#include <set>
#include <string_view>
#include <utility>
#include <vector>

#include "drawing_rounding.hpp"
#include "nbar/dynamics/inverse_dynamics.hpp"
#include "nbar/model/diagnostics.hpp"
#include "nbar/model/geometry.hpp"

namespace nbar::io {

namespace {

using drawing_detail::Tidy;

// A DXF file is group-code/value pairs, each on its own line.
class DxfOut {
 public:
  // `tidy`: the rounding of the lengths written, relative to the drawing's size.
  explicit DxfOut(const Tidy& tidy) : tidy_(tidy) {}
  void pair(int code, std::string_view value) { out_ += fmt::format("{:>3}\n{}\n", code, value); }
  void pair(int code, int value) { pair(code, std::to_string(value)); }
  // A coordinate or a radius, to about 1e-12 of the drawing's size (1e-9 of the unit for a
  // drawing 100 to 1000 units across), far below any cutting tolerance: a pose solved to
  // rounding then writes 0, not 2.5e-11, and a plate 2 mm across drawn in metres keeps its 12
  // digits as one drawn in mm does.
  void length(int code, double value) { pair(code, fmt::format("{:.12g}", tidy_(value))); }
  // A bulge, a ratio the drawing's unit does not change: to 1e-9.
  void ratio(int code, double value) {
    double tidy = std::round(value * 1e9) / 1e9;
    if (tidy == 0.0) tidy = 0.0;  // no "-0"
    pair(code, fmt::format("{:.12g}", tidy));
  }
  void point(int x_code, const Eigen::Vector2d& v) {
    length(x_code, v.x());
    length(x_code + 10, v.y());
    length(x_code + 20, 0.0);
  }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
  Tidy tidy_;
};

// DXF drawing units ($INSUNITS) of the model's length units.
int insunits(const std::string& unit) {
  if (unit == "in") return 1;
  if (unit == "ft") return 2;
  if (unit == "mm") return 4;
  if (unit == "cm") return 5;
  if (unit == "m") return 6;
  return 0;  // unitless
}

// The rigid motion taking a body's plate from the drawn pose to the pose of `points`, like the
// drawing's (render/drawing.cpp): the frame's origin point, turned with its direction.
struct Placement {
  Eigen::Vector2d origin_drawn, origin;
  double angle = 0;  // rad
  Eigen::Vector2d operator()(const Eigen::Vector2d& drawn) const {
    const double c = std::cos(angle), s = std::sin(angle);
    const Eigen::Vector2d d = drawn - origin_drawn;
    return origin + Eigen::Vector2d(c * d.x() - s * d.y(), s * d.x() + c * d.y());
  }
};

Placement placement(const Model& m, int body, const std::vector<Eigen::Vector2d>& points) {
  const BodyFrame f = body_frame(m, body);
  Placement p;
  p.origin_drawn = m.points[f.origin].position;
  p.origin = points[f.origin];
  if (f.from >= 0) {
    const Eigen::Vector2d drawn = m.points[f.to].position - m.points[f.from].position;
    const Eigen::Vector2d now = points[f.to] - points[f.from];
    p.angle = std::atan2(now.y(), now.x()) - std::atan2(drawn.y(), drawn.x());
  }
  return p;
}

void header(DxfOut& dxf, const Model& m) {
  dxf.pair(0, "SECTION");
  dxf.pair(2, "HEADER");
  dxf.pair(9, "$ACADVER");
  dxf.pair(1, "AC1009");
  dxf.pair(9, "$INSUNITS");
  dxf.pair(70, insunits(m.units.length));
  dxf.pair(0, "ENDSEC");
}

void tables(DxfOut& dxf, const std::vector<std::string>& layers) {
  dxf.pair(0, "SECTION");
  dxf.pair(2, "TABLES");
  dxf.pair(0, "TABLE");
  dxf.pair(2, "LTYPE");
  dxf.pair(70, 1);
  dxf.pair(0, "LTYPE");
  dxf.pair(2, "CONTINUOUS");
  dxf.pair(70, 0);
  dxf.pair(3, "Solid line");
  dxf.pair(72, 65);
  dxf.pair(73, 0);
  dxf.length(40, 0.0);
  dxf.pair(0, "ENDTAB");
  dxf.pair(0, "TABLE");
  dxf.pair(2, "LAYER");
  dxf.pair(70, static_cast<int>(layers.size()));
  for (std::size_t i = 0; i < layers.size(); ++i) {
    dxf.pair(0, "LAYER");
    dxf.pair(2, layers[i]);
    dxf.pair(70, 0);
    dxf.pair(62, static_cast<int>(i % 6) + 1);  // the ACI colours red, yellow, green, cyan, blue, magenta
    dxf.pair(6, "CONTINUOUS");
  }
  dxf.pair(0, "ENDTAB");
  dxf.pair(0, "ENDSEC");
}

// A closed ring, bulges and all, as an R12 POLYLINE (flag 1: closed) with its VERTEXes.
void ring(DxfOut& dxf, const std::string& layer, const std::vector<Eigen::Vector2d>& vertices,
          const std::vector<double>& bulges, const Placement& place, double unit) {
  dxf.pair(0, "POLYLINE");
  dxf.pair(8, layer);
  dxf.pair(66, 1);  // vertices follow
  dxf.point(10, Eigen::Vector2d::Zero());
  dxf.pair(70, 1);
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    dxf.pair(0, "VERTEX");
    dxf.pair(8, layer);
    dxf.point(10, place(vertices[i]) / unit);
    const double bulge = bulges.empty() ? 0.0 : bulges[i];
    if (bulge != 0.0) dxf.ratio(42, bulge);  // a rigid motion keeps every arc's bulge
  }
  dxf.pair(0, "SEQEND");
  dxf.pair(8, layer);
}

void plate(DxfOut& dxf, const std::string& layer, const Region& r, const Placement& place, double unit) {
  ring(dxf, layer, r.outline, r.outline_bulges, place, unit);
  for (std::size_t i = 0; i < r.polygon_holes.size(); ++i) {
    const std::vector<double> none;
    ring(dxf, layer, r.polygon_holes[i], i < r.polygon_hole_bulges.size() ? r.polygon_hole_bulges[i] : none, place,
         unit);
  }
  for (const Circle& c : r.circle_holes) {
    dxf.pair(0, "CIRCLE");
    dxf.pair(8, layer);
    dxf.point(10, place(c.centre) / unit);
    dxf.length(40, c.radius / unit);
  }
}

// The SVG path of a closed ring in the pose: y turned down, each arc as an A command (a rigid
// motion keeps its radius and turn; the turn reverses with the y axis).
std::string svg_ring(const std::vector<Eigen::Vector2d>& vertices, const std::vector<double>& bulges,
                     const Placement& place, double unit, const Tidy& tidy) {
  const auto xy = [&tidy](const Eigen::Vector2d& v) {
    return fmt::format("{:.12g} {:.12g}", tidy(v.x()), tidy(-v.y()));
  };
  std::string d;
  const std::size_t n = vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d a = place(vertices[i]) / unit;
    if (i == 0) d += "M " + xy(a);
    const Eigen::Vector2d b = place(vertices[(i + 1) % n]) / unit;
    const double bulge = bulges.empty() ? 0.0 : bulges[i];
    if (bulge == 0.0) {
      if (i + 1 < n) d += " L " + xy(b);
      continue;
    }
    const double radius = (b - a).norm() * (1 + bulge * bulge) / (4 * std::abs(bulge));
    d += fmt::format(" A {:.12g} {:.12g} 0 {} {} ", radius, radius, std::abs(bulge) > 1 ? 1 : 0, bulge < 0 ? 1 : 0) +
         xy(b);
  }
  return d + " Z";
}

// The bodies with a plate and each one's DXF layer, which is also its SVG group's id, so that
// `layer:` picks the same plate from either file. Layer names are case-insensitive in DXF (and
// `layer:` matches without case): two bodies that differ only in case or in replaced
// characters get a numbered suffix.
std::vector<std::pair<int, std::string>> plate_layers(const Model& m) {
  std::vector<std::pair<int, std::string>> plates;
  std::set<std::string> taken;
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    if (!m.bodies[b].shape) continue;
    std::string layer = dxf_layer_name(m.bodies[b].name), key;
    for (int n = 2;; ++n) {
      key.clear();
      for (char c : layer) key += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
      if (taken.insert(key).second) break;
      layer = dxf_layer_name(m.bodies[b].name) + "_" + std::to_string(n);
    }
    plates.emplace_back(static_cast<int>(b), layer);
  }
  if (plates.empty()) throw Error(ErrorKind::BadInput, "no body has a `shape` or a `bar`: there is nothing to cut");
  return plates;
}

// The bounding box of the plates' outlines (arcs by their chords) in the pose, in the model's
// length unit: the SVG's viewBox, and the size (its diagonal) that the rounding of the lengths
// written, in either file, is relative to.
struct Extent {
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  double size() const { return std::hypot(hi.x() - lo.x(), hi.y() - lo.y()); }
};

Extent plates_extent(const Model& m, const std::vector<std::pair<int, std::string>>& plates,
                     const std::vector<Eigen::Vector2d>& points) {
  const double unit = m.units.length_scale;
  Extent e;
  for (const auto& plate : plates) {
    const Placement place = placement(m, plate.first, points);
    for (const Eigen::Vector2d& v : straight_edged(*m.bodies[static_cast<std::size_t>(plate.first)].shape).outline) {
      const Eigen::Vector2d p = place(v) / unit;
      e.lo = e.lo.cwiseMin(p);
      e.hi = e.hi.cwiseMax(p);
    }
  }
  return e;
}

}  // namespace

std::string cutting_svg(const Mechanism& mechanism, const std::vector<Eigen::Vector2d>& points) {
  const Model& m = mechanism.model();
  const double unit = m.units.length_scale;
  const std::vector<std::pair<int, std::string>> plates = plate_layers(m);
  const Extent extent = plates_extent(m, plates, points);
  const Eigen::Vector2d lo = extent.lo, hi = extent.hi;
  const Tidy tidy(extent.size());
  std::string groups;
  for (const auto& [b, id] : plates) {
    const Region& r = *m.bodies[static_cast<std::size_t>(b)].shape;
    const Placement place = placement(m, b, points);
    std::string d = svg_ring(r.outline, r.outline_bulges, place, unit, tidy);
    for (std::size_t i = 0; i < r.polygon_holes.size(); ++i) {
      const std::vector<double> none;
      d.push_back(' ');
      d.append(svg_ring(r.polygon_holes[i], i < r.polygon_hole_bulges.size() ? r.polygon_hole_bulges[i] : none, place,
                        unit, tidy));
    }
    groups += fmt::format("  <g id=\"{}\">\n    <path d=\"{}\"/>\n", id, d);
    for (const Circle& c : r.circle_holes) {
      const Eigen::Vector2d centre = place(c.centre) / unit;
      groups += fmt::format("    <circle cx=\"{:.12g}\" cy=\"{:.12g}\" r=\"{:.12g}\"/>\n", tidy(centre.x()),
                            tidy(-centre.y()), c.radius / unit);
    }
    groups += "  </g>\n";
  }
  const Eigen::Vector2d size = hi - lo;
  const double margin = 0.02 * std::max(size.x(), size.y());
  const double x0 = lo.x() - margin, y0 = -hi.y() - margin;
  const double width = size.x() + 2 * margin, height = size.y() + 2 * margin;
  const double mm_per_unit = unit * 1e3;
  return fmt::format(
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<!-- Plates written by nbar export: outlines and holes in the model's unit ({}), y downwards as SVG has it. "
      "-->\n"
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{:.12g}mm\" height=\"{:.12g}mm\" viewBox=\"{:.12g} {:.12g} "
      "{:.12g} {:.12g}\">\n"
      "<g fill=\"none\" stroke=\"#000\" stroke-width=\"{:.6g}\" fill-rule=\"evenodd\">\n{}</g>\n</svg>\n",
      m.units.length, width * mm_per_unit, height * mm_per_unit, x0, y0, width, height, 0.1 / mm_per_unit, groups);
}

std::string dxf_layer_name(const std::string& body_name) {
  std::string name;
  for (char c : body_name) {
    const bool allowed = std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '$';
    name += allowed ? c : '_';
  }
  return name.empty() ? "_" : name;
}

std::string cutting_dxf(const Mechanism& mechanism, const std::vector<Eigen::Vector2d>& points) {
  const Model& m = mechanism.model();
  const std::vector<std::pair<int, std::string>> plates = plate_layers(m);
  std::vector<std::string> layers;
  for (const auto& plate : plates) layers.push_back(plate.second);
  DxfOut dxf(Tidy(plates_extent(m, plates, points).size()));
  header(dxf, m);
  tables(dxf, layers);
  dxf.pair(0, "SECTION");
  dxf.pair(2, "ENTITIES");
  for (const auto& [b, layer] : plates) {
    plate(dxf, layer, *m.bodies[static_cast<std::size_t>(b)].shape, placement(m, b, points), m.units.length_scale);
  }
  dxf.pair(0, "ENDSEC");
  dxf.pair(0, "EOF");
  return dxf.take();
}

}  // namespace nbar::io
