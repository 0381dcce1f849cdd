// Where pictures are drawn: a small set of primitives in pixel coordinates (x right, y down),
// written as SVG text or rasterised by cairo. Drawings and plots are built once against this
// interface and come out in every format.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace nbar::render {

struct Colour {
  std::uint8_t r = 0, g = 0, b = 0, a = 255;
  static Colour rgb(std::uint32_t hex, std::uint8_t alpha = 255) {
    return {static_cast<std::uint8_t>(hex >> 16), static_cast<std::uint8_t>(hex >> 8), static_cast<std::uint8_t>(hex),
            alpha};
  }
  std::string hex() const;  // "#rrggbb"
  double opacity() const { return a / 255.0; }
};

struct Stroke {
  Colour colour;
  double width = 1.5;        // px
  std::vector<double> dash;  // px on, px off...; empty = solid
};

struct Paint {
  std::optional<Colour> fill;
  std::optional<Stroke> stroke;
};

enum class Anchor { Start, Middle, End };

// A closed outline with holes (polygons and circles), filled even-odd: a link plate.
struct Outline {
  std::vector<Eigen::Vector2d> outer;
  std::vector<std::vector<Eigen::Vector2d>> polygon_holes;
  std::vector<std::pair<Eigen::Vector2d, double>> circle_holes;  // centre, radius (px)
};

class Canvas {
 public:
  Canvas(int width, int height) : width_(width), height_(height) {}
  virtual ~Canvas() = default;
  int width() const { return width_; }
  int height() const { return height_; }

  // Groups name what they hold (SVG: <g id=... class=...>); raster canvases ignore them.
  virtual void begin_group(const std::string& id, const std::string& css_class) = 0;
  virtual void end_group() = 0;
  virtual void polygon(const std::vector<Eigen::Vector2d>& points, const Paint& paint) = 0;  // closed
  virtual void polyline(const std::vector<Eigen::Vector2d>& points, const Stroke& stroke) = 0;
  virtual void circle(const Eigen::Vector2d& centre, double radius, const Paint& paint) = 0;
  virtual void outline(const Outline& shape, const Paint& paint) = 0;
  // `size` in px; the text's baseline starts, centres or ends at `at`.
  virtual void text(const Eigen::Vector2d& at, const std::string& text, double size, Anchor anchor,
                    const Colour& colour) = 0;

 private:
  int width_, height_;
};

// Maps model coordinates (m, y up) to pixels (y down) with equal scales on both axes, fitting a
// box with a margin.
class View {
 public:
  View(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, int width, int height, double margin_px)
      : View(lo, hi, width, height, margin_px, margin_px) {}
  // With margins of their own at the sides (x) and at the top and bottom (y).
  View(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, int width, int height, double margin_x_px,
       double margin_y_px);
  Eigen::Vector2d to_pixels(const Eigen::Vector2d& world) const;
  Eigen::Vector2d to_world(const Eigen::Vector2d& pixels) const;
  double pixels_per_metre() const { return scale_; }

 private:
  double scale_ = 1.0;
  Eigen::Vector2d world_centre_{0, 0}, pixel_centre_{0, 0};
};

// A picture as SVG text.
class SvgCanvas : public Canvas {
 public:
  SvgCanvas(int width, int height, const std::string& background = "#ffffff");
  void begin_group(const std::string& id, const std::string& css_class) override;
  void end_group() override;
  void polygon(const std::vector<Eigen::Vector2d>& points, const Paint& paint) override;
  void polyline(const std::vector<Eigen::Vector2d>& points, const Stroke& stroke) override;
  void circle(const Eigen::Vector2d& centre, double radius, const Paint& paint) override;
  void outline(const Outline& shape, const Paint& paint) override;
  void text(const Eigen::Vector2d& at, const std::string& text, double size, Anchor anchor,
            const Colour& colour) override;
  // Raw SVG markup to insert (animation elements, titles).
  void raw(const std::string& markup);
  // The whole document (with the XML declaration) or only the <svg> element, for HTML.
  std::string document() const;
  std::string element() const;

 private:
  std::string body_;
  std::string background_;
};

std::string xml_escape(const std::string& text);

}  // namespace nbar::render
