#include "nbar/render/pictures.hpp"

#include "nbar/render/image_canvas.hpp"

namespace nbar::render {

std::string drawing_svg(const Mechanism& mech, const SweepResult& sweep, const std::vector<Eigen::Vector2d>& points,
                        const DrawOptions& options) {
  SvgCanvas canvas(options.width, options.height);
  draw_mechanism(canvas, fit_view(mech, sweep, options), mech, sweep, points, options);
  return canvas.document();
}

std::vector<std::uint8_t> drawing_png(const Mechanism& mech, const SweepResult& sweep,
                                      const std::vector<Eigen::Vector2d>& points, const DrawOptions& options) {
  ImageCanvas canvas(options.width, options.height);
  draw_mechanism(canvas, fit_view(mech, sweep, options), mech, sweep, points, options);
  return canvas.png_bytes();
}

}  // namespace nbar::render
