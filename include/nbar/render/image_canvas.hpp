// A Canvas that rasterises with cairo into an image in memory (32-bit pixels on an opaque
// background), for PNG files and for the frames of GIF and MP4 animations.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "nbar/render/canvas.hpp"

namespace nbar::render {

class ImageCanvas : public Canvas {
 public:
  ImageCanvas(int width, int height, const Colour& background = Colour::rgb(0xffffff));
  ~ImageCanvas() override;
  ImageCanvas(ImageCanvas&&) noexcept;
  ImageCanvas& operator=(ImageCanvas&&) noexcept;
  ImageCanvas(const ImageCanvas&) = delete;
  ImageCanvas& operator=(const ImageCanvas&) = delete;

  // Smooth edges (default). Off, every pixel is one of the colours drawn (or a blend of
  // translucent ones), which keeps GIF palettes small.
  void set_antialias(bool on);
  bool antialias() const;
  // Paints the whole image with the background colour again.
  void clear();

  // Groups mean nothing to a raster image.
  void begin_group(const std::string& id, const std::string& css_class) override;
  void end_group() override;
  void polygon(const std::vector<Eigen::Vector2d>& points, const Paint& paint) override;
  void polyline(const std::vector<Eigen::Vector2d>& points, const Stroke& stroke) override;
  void circle(const Eigen::Vector2d& centre, double radius, const Paint& paint) override;
  void outline(const Outline& shape, const Paint& paint) override;
  void text(const Eigen::Vector2d& at, const std::string& text, double size, Anchor anchor,
            const Colour& colour) override;

  // Throws Error(ErrorKind::Internal) naming the path when the file cannot be written.
  void write_png(const std::string& path) const;
  // The PNG file's bytes, for a front-end that sends them without touching the disk.
  std::vector<std::uint8_t> png_bytes() const;
  // Reads any PNG into a canvas of its size (transparent pixels come out as premultiplied
  // black). Throws Error(ErrorKind::Internal) naming the path when it cannot.
  static ImageCanvas read_png(const std::string& path);

  // The pixels: `height` rows of `stride` bytes, each pixel 4 bytes B, G, R, A (cairo's
  // ARGB32 on a little-endian machine; colours are premultiplied by alpha, which changes
  // nothing while the background is opaque). Valid until the next drawing call.
  int stride() const;
  const std::uint8_t* data() const;
  // The colour of one pixel (alpha undone); (0,0) is the top left.
  Colour pixel(int x, int y) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  Colour background_;
};

// Whether this build draws raster pictures (PNG, and the frames of GIF and MP4): not the
// WebAssembly engine's, which has no cairo or cgif (its browser draws them itself).
bool raster_pictures_available();

}  // namespace nbar::render
