#include "nbar/render/scene.hpp"

#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "nbar/model/diagnostics.hpp"
#include "nbar/render/canvas.hpp"

namespace nbar::render {

namespace {

// Built by appending: g++ 12 warns falsely (-Wrestrict) on "literal" + std::string.
std::string cat(std::initializer_list<std::string_view> parts) {
  std::string out;
  for (std::string_view p : parts) out.append(p);
  return out;
}

// 0.01 px, as the SVG canvas writes them.
std::string coordinate_text(double v) {
  if (!std::isfinite(v)) return "0";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v + 0.0);
  std::string s(buf);
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  return s == "-0" ? "0" : s;
}

std::string precise(double v) {
  if (!std::isfinite(v)) return "0";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

std::string json_string(const std::string& text) {
  std::string out = "\"";
  for (unsigned char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += static_cast<char>(c);
    }
  }
  out += '"';
  return out;
}

std::string flat_points(const std::vector<Eigen::Vector2d>& points) {
  std::string s = "[";
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (i) s += ',';
    s += cat({coordinate_text(points[i].x()), ",", coordinate_text(points[i].y())});
  }
  s += "]";
  return s;
}

std::string paint_fields(const Paint& p) {
  std::string s;
  if (p.fill) {
    s += cat({",\"fill\":", json_string(p.fill->hex())});
    if (p.fill->a != 255) s += cat({",\"fill_opacity\":", coordinate_text(p.fill->opacity())});
  }
  if (p.stroke) {
    s += cat(
        {",\"stroke\":", json_string(p.stroke->colour.hex()), ",\"stroke_width\":", coordinate_text(p.stroke->width)});
    if (p.stroke->colour.a != 255) s += cat({",\"stroke_opacity\":", coordinate_text(p.stroke->colour.opacity())});
    if (!p.stroke->dash.empty()) {
      s += ",\"dash\":[";
      for (std::size_t i = 0; i < p.stroke->dash.size(); ++i)
        s += cat({i ? "," : "", coordinate_text(p.stroke->dash[i])});
      s += "]";
    }
  }
  return s;
}

// Records what is drawn as the scene's JSON items, groups nested as drawn.
class SceneCanvas : public Canvas {
 public:
  SceneCanvas(int width, int height) : Canvas(width, height) { open_.push_back(true); }

  void begin_group(const std::string& id, const std::string& css_class) override {
    item(cat({"{\"type\":\"group\",\"id\":", json_string(id), ",\"class\":", json_string(css_class), ",\"items\":["}));
    open_.push_back(true);
  }
  void end_group() override {
    out_ += "]}";
    open_.pop_back();
  }
  void polygon(const std::vector<Eigen::Vector2d>& points, const Paint& paint) override {
    item(cat({"{\"type\":\"polygon\",\"points\":", flat_points(points), paint_fields(paint), "}"}));
  }
  void polyline(const std::vector<Eigen::Vector2d>& points, const Stroke& stroke) override {
    item(cat(
        {"{\"type\":\"polyline\",\"points\":", flat_points(points), paint_fields(Paint{std::nullopt, stroke}), "}"}));
  }
  void circle(const Eigen::Vector2d& centre, double radius, const Paint& paint) override {
    item(cat({"{\"type\":\"circle\",\"cx\":", coordinate_text(centre.x()), ",\"cy\":", coordinate_text(centre.y()),
              ",\"r\":", coordinate_text(radius), paint_fields(paint), "}"}));
  }
  void outline(const Outline& shape, const Paint& paint) override {
    std::string rings = cat({"[", flat_points(shape.outer)});
    for (const auto& hole : shape.polygon_holes) rings += cat({",", flat_points(hole)});
    std::string circles = "[";
    for (std::size_t i = 0; i < shape.circle_holes.size(); ++i) {
      const auto& [c, r] = shape.circle_holes[i];
      circles +=
          cat({i ? ",[" : "[", coordinate_text(c.x()), ",", coordinate_text(c.y()), ",", coordinate_text(r), "]"});
    }
    item(cat({"{\"type\":\"outline\",\"rings\":", rings, "],\"circles\":", circles, "]", paint_fields(paint), "}"}));
  }
  void text(const Eigen::Vector2d& at, const std::string& text, double size, Anchor anchor,
            const Colour& colour) override {
    const char* a = anchor == Anchor::Start ? "start" : anchor == Anchor::Middle ? "middle" : "end";
    item(cat({"{\"type\":\"text\",\"x\":", coordinate_text(at.x()), ",\"y\":", coordinate_text(at.y()),
              ",\"text\":", json_string(text), ",\"size\":", coordinate_text(size), ",\"anchor\":\"", a,
              "\",\"color\":", json_string(colour.hex()), "}"}));
  }

  std::string items() const { return cat({"[", out_, "]"}); }

 private:
  void item(const std::string& json) {
    if (!open_.back()) out_ += ',';
    open_.back() = false;
    out_ += json;
  }
  std::string out_;
  std::vector<bool> open_;  // per open group: no item written yet
};

std::string step_motion(const Mechanism& mech, const View& view, const std::vector<Eigen::Vector2d>& reference,
                        const std::vector<Eigen::Vector2d>& points) {
  std::string s = "{\"bodies\":[";
  const std::vector<PixelTransform> moves = body_transforms(mech, view, reference, points);
  for (std::size_t b = 0; b < moves.size(); ++b)
    s += cat({b ? ",[" : "[", precise(moves[b].angle_deg), ",", coordinate_text(moves[b].shift.x()), ",",
              coordinate_text(moves[b].shift.y()), "]"});
  s += "],\"labels\":[";
  for (std::size_t p = 0; p < points.size(); ++p) {
    const Eigen::Vector2d d = view.to_pixels(points[p]) - view.to_pixels(reference[p]);
    s += cat({p ? ",[" : "[", coordinate_text(d.x()), ",", coordinate_text(d.y()), "]"});
  }
  s += "]}";
  return s;
}

}  // namespace

std::string drawing_scene_json(const Mechanism& mech, const SweepResult& sweep, const DrawOptions& options,
                               int reference_step) {
  const Model& m = mech.model();
  const View view = fit_view(mech, sweep, options);
  std::vector<Eigen::Vector2d> reference;
  if (sweep.samples.empty()) {
    for (const Point& p : m.points) reference.push_back(p.position);
    reference_step = 0;
  } else {
    if (reference_step < 0) reference_step = default_drawn_step(mech, sweep);
    if (static_cast<std::size_t>(reference_step) >= sweep.samples.size())
      throw Error(ErrorKind::BadInput, "step " + std::to_string(reference_step) + " is past the sweep's " +
                                           std::to_string(sweep.samples.size()) + " samples");
    reference = sample_points(mech, sweep.samples[static_cast<std::size_t>(reference_step)]);
  }
  SceneCanvas canvas(options.width, options.height);
  draw_mechanism(canvas, view, mech, sweep, reference, options);

  // Pixels to model length units, y down: the model's x and -y.
  const double unit = m.units.length_scale;
  const Eigen::Vector2d origin = view.to_world({0, 0});
  std::string s =
      cat({"{\"width\":", std::to_string(options.width), ",\"height\":", std::to_string(options.height),
           ",\"to_model\":[", precise(1.0 / (view.pixels_per_metre() * unit)), ",", precise(origin.x() / unit), ",",
           precise(-origin.y() / unit), "],\"reference_step\":", std::to_string(reference_step),
           ",\"items\":", canvas.items(), ",\"bodies\":["});
  const std::vector<PixelTransform> still = body_transforms(mech, view, reference, reference);
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const Eigen::Vector2d pivot = still[b].pivot;
    s += cat({b ? "," : "", "{\"name\":", json_string(m.bodies[b].name),
              ",\"group\":", json_string(cat({"body-", m.bodies[b].name})), ",\"pivot\":[", coordinate_text(pivot.x()),
              ",", coordinate_text(pivot.y()), "]}"});
  }
  s += "],\"steps\":[";
  for (std::size_t k = 0; k < sweep.samples.size(); ++k)
    s += cat({k ? "," : "", step_motion(mech, view, reference, sample_points(mech, sweep.samples[k]))});
  s += "]}";
  return s;
}

}  // namespace nbar::render
