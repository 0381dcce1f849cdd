#include "nbar/io/dxf_writer.hpp"

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <set>
#include <string_view>

#include "nbar/dynamics/inverse_dynamics.hpp"
#include "nbar/model/diagnostics.hpp"
#include "nbar/model/geometry.hpp"

namespace nbar::io {

namespace {

// A DXF file is group-code/value pairs, each on its own line.
class DxfOut {
 public:
  void pair(int code, std::string_view value) { out_ += fmt::format("{:>3}\n{}\n", code, value); }
  void pair(int code, int value) { pair(code, std::to_string(value)); }
  void number(int code, double value) {
    // To 1e-9 of the unit, far below any cutting tolerance: a pose solved to rounding then
    // writes 0, not 2.5e-11, and 12 digits keep a coordinate in mm to well below a micrometre.
    double tidy = std::round(value * 1e9) / 1e9;
    if (tidy == 0.0) tidy = 0.0;  // no "-0"
    pair(code, fmt::format("{:.12g}", tidy));
  }
  void point(int x_code, const Eigen::Vector2d& v) {
    number(x_code, v.x());
    number(x_code + 10, v.y());
    number(x_code + 20, 0.0);
  }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
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
  dxf.number(40, 0.0);
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
    if (bulge != 0.0) dxf.number(42, bulge);  // a rigid motion keeps every arc's bulge
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
    dxf.number(40, c.radius / unit);
  }
}

}  // namespace

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
  std::vector<int> plates;
  std::vector<std::string> layers;
  std::set<std::string> taken;
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    if (!m.bodies[b].shape) continue;
    plates.push_back(static_cast<int>(b));
    // Layer names are case-insensitive in DXF: two bodies that differ only in case or in
    // replaced characters get a numbered suffix.
    std::string layer = dxf_layer_name(m.bodies[b].name), key;
    for (int n = 2;; ++n) {
      key.clear();
      for (char c : layer) key += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
      if (taken.insert(key).second) break;
      layer = dxf_layer_name(m.bodies[b].name) + "_" + std::to_string(n);
    }
    layers.push_back(layer);
  }
  if (plates.empty()) {
    throw Error(ErrorKind::BadInput, "no body has a `shape` or a `bar`: there is nothing to cut");
  }
  DxfOut dxf;
  header(dxf, m);
  tables(dxf, layers);
  dxf.pair(0, "SECTION");
  dxf.pair(2, "ENTITIES");
  for (std::size_t i = 0; i < plates.size(); ++i) {
    plate(dxf, layers[i], *m.bodies[plates[i]].shape, placement(m, plates[i], points), m.units.length_scale);
  }
  dxf.pair(0, "ENDSEC");
  dxf.pair(0, "EOF");
  return dxf.take();
}

}  // namespace nbar::io
