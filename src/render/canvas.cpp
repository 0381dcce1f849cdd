#include "nbar/render/canvas.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <string_view>

namespace nbar::render {

namespace {

// Short, exact enough coordinates: 0.01 px.
std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v + 0.0);
  std::string s(buf);
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  return s == "-0" ? "0" : s;
}

// Built by appending: g++ 12 warns falsely (-Wrestrict) on "literal" + std::string.
void append(std::string& out, std::initializer_list<std::string_view> parts) {
  for (std::string_view p : parts) out.append(p);
}

std::string paint_attributes(const Paint& p) {
  std::string s;
  if (p.fill) {
    append(s, {" fill=\"", p.fill->hex(), "\""});
    if (p.fill->a != 255) append(s, {" fill-opacity=\"", num(p.fill->opacity()), "\""});
  } else {
    s += " fill=\"none\"";
  }
  if (p.stroke) {
    append(s, {" stroke=\"", p.stroke->colour.hex(), "\" stroke-width=\"", num(p.stroke->width), "\""});
    if (p.stroke->colour.a != 255) append(s, {" stroke-opacity=\"", num(p.stroke->colour.opacity()), "\""});
    if (!p.stroke->dash.empty()) {
      s += " stroke-dasharray=\"";
      for (std::size_t i = 0; i < p.stroke->dash.size(); ++i) append(s, {i ? "," : "", num(p.stroke->dash[i])});
      s += "\"";
    }
    s += " stroke-linejoin=\"round\" stroke-linecap=\"round\"";
  }
  return s;
}

std::string points_attribute(const std::vector<Eigen::Vector2d>& points) {
  std::string s;
  for (std::size_t i = 0; i < points.size(); ++i)
    append(s, {i ? " " : "", num(points[i].x()), ",", num(points[i].y())});
  return s;
}

void append_ring(std::string& d, const std::vector<Eigen::Vector2d>& ring) {
  for (std::size_t i = 0; i < ring.size(); ++i) append(d, {i ? " L" : "M", num(ring[i].x()), " ", num(ring[i].y())});
  d += " Z ";
}

}  // namespace

std::string Colour::hex() const {
  char buf[8];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", r, g, b);
  return buf;
}

std::string xml_escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

View::View(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, int width, int height, double margin_x_px,
           double margin_y_px) {
  const Eigen::Vector2d size = (hi - lo).cwiseMax(Eigen::Vector2d::Constant(1e-12));
  const double w = std::max(1.0, width - 2 * margin_x_px), h = std::max(1.0, height - 2 * margin_y_px);
  scale_ = std::min(w / size.x(), h / size.y());
  world_centre_ = 0.5 * (lo + hi);
  pixel_centre_ = {0.5 * width, 0.5 * height};
}

Eigen::Vector2d View::to_pixels(const Eigen::Vector2d& world) const {
  const Eigen::Vector2d d = (world - world_centre_) * scale_;
  return {pixel_centre_.x() + d.x(), pixel_centre_.y() - d.y()};
}

Eigen::Vector2d View::to_world(const Eigen::Vector2d& pixels) const {
  const Eigen::Vector2d d(pixels.x() - pixel_centre_.x(), pixel_centre_.y() - pixels.y());
  return world_centre_ + d / scale_;
}

SvgCanvas::SvgCanvas(int width, int height, const std::string& background)
    : Canvas(width, height), background_(background) {}

void SvgCanvas::begin_group(const std::string& id, const std::string& css_class) {
  body_ += "<g";
  if (!id.empty()) append(body_, {" id=\"", xml_escape(id), "\""});
  if (!css_class.empty()) append(body_, {" class=\"", xml_escape(css_class), "\""});
  body_ += ">\n";
}

void SvgCanvas::end_group() { body_ += "</g>\n"; }

void SvgCanvas::polygon(const std::vector<Eigen::Vector2d>& points, const Paint& paint) {
  append(body_, {"<polygon points=\"", points_attribute(points), "\"", paint_attributes(paint), "/>\n"});
}

void SvgCanvas::polyline(const std::vector<Eigen::Vector2d>& points, const Stroke& stroke) {
  append(body_, {"<polyline points=\"", points_attribute(points), "\"", paint_attributes(Paint{std::nullopt, stroke}),
                 "/>\n"});
}

void SvgCanvas::circle(const Eigen::Vector2d& centre, double radius, const Paint& paint) {
  append(body_, {"<circle cx=\"", num(centre.x()), "\" cy=\"", num(centre.y()), "\" r=\"", num(radius), "\"",
                 paint_attributes(paint), "/>\n"});
}

void SvgCanvas::outline(const Outline& shape, const Paint& paint) {
  std::string d;
  append_ring(d, shape.outer);
  for (const auto& hole : shape.polygon_holes) append_ring(d, hole);
  for (const auto& [c, r] : shape.circle_holes) {
    const std::string rr = num(r), y = num(c.y()), right = num(c.x() + r), left = num(c.x() - r);
    append(d, {"M", right, " ", y,   " A", rr,        " ",   rr,  " 0 1 0 ", left, " ",
               y,   " A",  rr,  " ", rr,   " 0 1 0 ", right, " ", y,         " Z "});
  }
  append(body_, {"<path fill-rule=\"evenodd\" d=\"", d, "\"", paint_attributes(paint), "/>\n"});
}

void SvgCanvas::text(const Eigen::Vector2d& at, const std::string& text, double size, Anchor anchor,
                     const Colour& colour) {
  const char* a = anchor == Anchor::Start ? "start" : anchor == Anchor::Middle ? "middle" : "end";
  append(body_, {"<text x=\"", num(at.x()), "\" y=\"", num(at.y()), "\" font-size=\"", num(size),
                 "\" font-family=\"sans-serif\" text-anchor=\"", a, "\" fill=\"", colour.hex(), "\">", xml_escape(text),
                 "</text>\n"});
}

void SvgCanvas::raw(const std::string& markup) { body_ += markup; }

std::string SvgCanvas::element() const {
  const std::string w = std::to_string(width()), h = std::to_string(height());
  std::string svg;
  append(svg, {"<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"", w, "\" height=\"", h, "\" viewBox=\"0 0 ", w, " ",
               h, "\">\n<rect width=\"100%\" height=\"100%\" fill=\"", background_, "\"/>\n", body_, "</svg>\n"});
  return svg;
}

std::string SvgCanvas::document() const {
  std::string doc = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  doc += element();
  return doc;
}

}  // namespace nbar::render
