#include "nbar/render/image_canvas.hpp"
#include "nbar/model/diagnostics.hpp"
#include "nbar/model/file_errors.hpp"

#include <cairo.h>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <vector>

// Under AddressSanitizer, cairo's and fontconfig's font caches are released at exit, or the
// leak checker reports them (they live as long as the process).
#if defined(__SANITIZE_ADDRESS__)
#define NBAR_RELEASE_FONT_CACHES 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define NBAR_RELEASE_FONT_CACHES 1
#endif
#endif
#ifdef NBAR_RELEASE_FONT_CACHES
#include <dlfcn.h>

#include <cstdlib>
#endif

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace nbar::render {

bool raster_pictures_available() { return true; }

struct ImageCanvas::Impl {
  cairo_surface_t* surface = nullptr;
  cairo_t* cr = nullptr;
  bool antialias = true;

  ~Impl() {
    if (cr) cairo_destroy(cr);
    if (surface) cairo_surface_destroy(surface);
  }
};

namespace {

void set_colour(cairo_t* cr, const Colour& c) {
  cairo_set_source_rgba(cr, c.r / 255.0, c.g / 255.0, c.b / 255.0, c.a / 255.0);
}

void trace_ring(cairo_t* cr, const std::vector<Eigen::Vector2d>& ring) {
  if (ring.empty()) return;
  cairo_move_to(cr, ring[0].x(), ring[0].y());
  for (std::size_t i = 1; i < ring.size(); ++i) cairo_line_to(cr, ring[i].x(), ring[i].y());
  cairo_close_path(cr);
}

void apply_stroke(cairo_t* cr, const Stroke& s) {
  set_colour(cr, s.colour);
  cairo_set_line_width(cr, s.width);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  cairo_set_dash(cr, s.dash.empty() ? nullptr : s.dash.data(), static_cast<int>(s.dash.size()), 0.0);
}

// Fills and then strokes the current path, as SVG paints it.
void paint_path(cairo_t* cr, const Paint& paint, cairo_fill_rule_t rule) {
  cairo_set_fill_rule(cr, rule);
  if (paint.fill) {
    set_colour(cr, *paint.fill);
    cairo_fill_preserve(cr);
  }
  if (paint.stroke) {
    apply_stroke(cr, *paint.stroke);
    cairo_stroke_preserve(cr);
  }
  cairo_new_path(cr);
}

std::string describe(cairo_status_t status) { return cairo_status_to_string(status); }

void release_caches_at_exit() {
#ifdef NBAR_RELEASE_FONT_CACHES
  static const bool registered = [] {
    std::atexit([] {
      cairo_debug_reset_static_data();
      // fontconfig is loaded by cairo; nbar does not link it itself.
      if (void* fini = ::dlsym(RTLD_DEFAULT, "FcFini")) reinterpret_cast<void (*)()>(fini)();
    });
    return true;
  }();
  (void)registered;
#endif
}

}  // namespace

ImageCanvas::ImageCanvas(int width, int height, const Colour& background)
    : Canvas(width, height), impl_(std::make_unique<Impl>()), background_(background) {
  if (width <= 0 || height <= 0) throw Error(ErrorKind::BadInput, "an image needs a positive width and height");
  impl_->surface = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width, height);
  if (cairo_surface_status(impl_->surface) != CAIRO_STATUS_SUCCESS)
    throw Error(ErrorKind::Internal, "cannot create a " + std::to_string(width) + "x" + std::to_string(height) +
                                         " image: " + describe(cairo_surface_status(impl_->surface)));
  impl_->cr = cairo_create(impl_->surface);
  release_caches_at_exit();
  // Explicit font options: with cairo's defaults, glyphs drawn after an unantialiased canvas
  // (a GIF frame) came out differently in the same process.
  set_antialias(true);
  clear();
}

ImageCanvas::~ImageCanvas() = default;
ImageCanvas::ImageCanvas(ImageCanvas&& other) noexcept
    : Canvas(other), impl_(std::move(other.impl_)), background_(other.background_) {}
ImageCanvas& ImageCanvas::operator=(ImageCanvas&& other) noexcept {
  Canvas::operator=(other);
  impl_ = std::move(other.impl_);
  background_ = other.background_;
  return *this;
}

void ImageCanvas::set_antialias(bool on) {
  impl_->antialias = on;
  cairo_set_antialias(impl_->cr, on ? CAIRO_ANTIALIAS_DEFAULT : CAIRO_ANTIALIAS_NONE);
  cairo_font_options_t* fo = cairo_font_options_create();
  cairo_font_options_set_antialias(fo, on ? CAIRO_ANTIALIAS_GRAY : CAIRO_ANTIALIAS_NONE);
  cairo_font_options_set_hint_style(fo, CAIRO_HINT_STYLE_NONE);
  cairo_font_options_set_hint_metrics(fo, CAIRO_HINT_METRICS_OFF);
  cairo_set_font_options(impl_->cr, fo);
  cairo_font_options_destroy(fo);
}

bool ImageCanvas::antialias() const { return impl_->antialias; }

void ImageCanvas::clear() {
  cairo_save(impl_->cr);
  cairo_set_operator(impl_->cr, CAIRO_OPERATOR_SOURCE);
  set_colour(impl_->cr, background_);
  cairo_paint(impl_->cr);
  cairo_restore(impl_->cr);
}

void ImageCanvas::begin_group(const std::string&, const std::string&) {}
void ImageCanvas::end_group() {}

void ImageCanvas::polygon(const std::vector<Eigen::Vector2d>& points, const Paint& paint) {
  if (points.size() < 2) return;
  trace_ring(impl_->cr, points);
  paint_path(impl_->cr, paint, CAIRO_FILL_RULE_WINDING);
}

void ImageCanvas::polyline(const std::vector<Eigen::Vector2d>& points, const Stroke& stroke) {
  if (points.size() < 2) return;
  cairo_t* cr = impl_->cr;
  cairo_move_to(cr, points[0].x(), points[0].y());
  for (std::size_t i = 1; i < points.size(); ++i) cairo_line_to(cr, points[i].x(), points[i].y());
  apply_stroke(cr, stroke);
  cairo_stroke(cr);
}

void ImageCanvas::circle(const Eigen::Vector2d& centre, double radius, const Paint& paint) {
  if (!(radius > 0)) return;
  cairo_new_sub_path(impl_->cr);
  cairo_arc(impl_->cr, centre.x(), centre.y(), radius, 0.0, 2 * std::numbers::pi);
  cairo_close_path(impl_->cr);
  paint_path(impl_->cr, paint, CAIRO_FILL_RULE_WINDING);
}

void ImageCanvas::outline(const Outline& shape, const Paint& paint) {
  cairo_t* cr = impl_->cr;
  trace_ring(cr, shape.outer);
  for (const auto& hole : shape.polygon_holes) trace_ring(cr, hole);
  for (const auto& [c, r] : shape.circle_holes) {
    if (!(r > 0)) continue;
    cairo_new_sub_path(cr);
    cairo_arc(cr, c.x(), c.y(), r, 0.0, 2 * std::numbers::pi);
    cairo_close_path(cr);
  }
  paint_path(cr, paint, CAIRO_FILL_RULE_EVEN_ODD);
}

void ImageCanvas::text(const Eigen::Vector2d& at, const std::string& text, double size, Anchor anchor,
                       const Colour& colour) {
  if (text.empty()) return;
  cairo_t* cr = impl_->cr;
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
  double x = at.x();
  if (anchor != Anchor::Start) {
    cairo_text_extents_t ext;
    cairo_text_extents(cr, text.c_str(), &ext);
    x -= anchor == Anchor::Middle ? 0.5 * ext.x_advance : ext.x_advance;
  }
  set_colour(cr, colour);
  cairo_move_to(cr, x, at.y());
  cairo_show_text(cr, text.c_str());
  cairo_new_path(cr);
}

namespace {

cairo_status_t append_png(void* closure, const unsigned char* data, unsigned int length) {
  auto* out = static_cast<std::vector<std::uint8_t>*>(closure);
  out->insert(out->end(), data, data + length);
  return CAIRO_STATUS_SUCCESS;
}

}  // namespace

std::vector<std::uint8_t> ImageCanvas::png_bytes() const {
  cairo_surface_flush(impl_->surface);
  std::vector<std::uint8_t> bytes;
  const cairo_status_t status = cairo_surface_write_to_png_stream(impl_->surface, &append_png, &bytes);
  if (status != CAIRO_STATUS_SUCCESS)
    throw Error(ErrorKind::Internal, std::string("cannot encode the PNG: ") + describe(status));
  return bytes;
}

void ImageCanvas::write_png(const std::string& path) const {
  const std::vector<std::uint8_t> bytes = png_bytes();
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (out) out.close();  // a full disk fails here, after the bytes were taken
  if (!out) throw Error(ErrorKind::Internal, cannot_write_message(path));
}

ImageCanvas ImageCanvas::read_png(const std::string& path) {
  cairo_surface_t* png = cairo_image_surface_create_from_png(path.c_str());
  const cairo_status_t status = cairo_surface_status(png);
  if (status != CAIRO_STATUS_SUCCESS) {
    cairo_surface_destroy(png);
    std::string message = "cannot read PNG ";
    message += path;
    message += ": ";
    message += describe(status);
    throw Error(ErrorKind::Internal, message);
  }
  ImageCanvas image(cairo_image_surface_get_width(png), cairo_image_surface_get_height(png), Colour{0, 0, 0, 0});
  cairo_t* cr = image.impl_->cr;
  cairo_save(cr);
  cairo_set_operator(cr, CAIRO_OPERATOR_SOURCE);
  cairo_set_source_surface(cr, png, 0, 0);
  cairo_paint(cr);
  cairo_restore(cr);
  cairo_surface_destroy(png);
  image.background_ = Colour::rgb(0xffffff);
  return image;
}

int ImageCanvas::stride() const { return cairo_image_surface_get_stride(impl_->surface); }

const std::uint8_t* ImageCanvas::data() const {
  cairo_surface_flush(impl_->surface);
  return cairo_image_surface_get_data(impl_->surface);
}

Colour ImageCanvas::pixel(int x, int y) const {
  if (x < 0 || y < 0 || x >= width() || y >= height()) throw Error(ErrorKind::BadInput, "pixel outside the image");
  const std::uint8_t* p = data() + static_cast<std::ptrdiff_t>(y) * stride() + 4 * x;
  const std::uint8_t a = p[3];
  auto unpremultiply = [a](std::uint8_t v) {
    return a == 0 ? std::uint8_t{0} : static_cast<std::uint8_t>(std::lround(std::min(255.0, v * 255.0 / a)));
  };
  return {unpremultiply(p[2]), unpremultiply(p[1]), unpremultiply(p[0]), a};
}

}  // namespace nbar::render
