// The raster pictures of a build without cairo and cgif (the WebAssembly engine, whose browser
// draws PNG and GIF from the SVG or its own canvas): every raster picture is refused when it is
// asked for, with a message that says where it can be had. No ImageCanvas is ever constructed,
// so its other members are never reached; they exist for the linker (and the vtable).
#include "nbar/model/diagnostics.hpp"
#include "nbar/render/animation.hpp"
#include "nbar/render/image_canvas.hpp"

namespace nbar::render {

namespace {

[[noreturn]] void refuse() {
  throw Error(ErrorKind::BadInput,
              "this build of nbar draws no PNG or GIF (it has no cairo or cgif): ask the native nbar program, "
              "or draw SVG");
}

}  // namespace

bool raster_pictures_available() { return false; }

struct ImageCanvas::Impl {};

ImageCanvas::ImageCanvas(int width, int height, const Colour& background)
    : Canvas(width, height), background_(background) {
  refuse();
}
ImageCanvas::~ImageCanvas() = default;
ImageCanvas::ImageCanvas(ImageCanvas&& other) noexcept : Canvas(other), background_(other.background_) {}
ImageCanvas& ImageCanvas::operator=(ImageCanvas&& other) noexcept {
  Canvas::operator=(other);
  background_ = other.background_;
  return *this;
}
void ImageCanvas::set_antialias(bool) {}
bool ImageCanvas::antialias() const { return false; }
void ImageCanvas::clear() {}
void ImageCanvas::begin_group(const std::string&, const std::string&) {}
void ImageCanvas::end_group() {}
void ImageCanvas::polygon(const std::vector<Eigen::Vector2d>&, const Paint&) {}
void ImageCanvas::polyline(const std::vector<Eigen::Vector2d>&, const Stroke&) {}
void ImageCanvas::circle(const Eigen::Vector2d&, double, const Paint&) {}
void ImageCanvas::outline(const Outline&, const Paint&) {}
void ImageCanvas::text(const Eigen::Vector2d&, const std::string&, double, Anchor, const Colour&) {}
void ImageCanvas::write_png(const std::string&) const { refuse(); }
std::vector<std::uint8_t> ImageCanvas::png_bytes() const { refuse(); }
ImageCanvas ImageCanvas::read_png(const std::string&) { refuse(); }
int ImageCanvas::stride() const { return 0; }
const std::uint8_t* ImageCanvas::data() const { return nullptr; }
Colour ImageCanvas::pixel(int, int) const { return background_; }

std::vector<std::uint8_t> Animation::gif_bytes() const { refuse(); }

}  // namespace nbar::render
