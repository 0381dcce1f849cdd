#include "nbar/render/pictures.hpp"

#include <algorithm>

#include "nbar/render/image_canvas.hpp"

namespace nbar::render {

namespace {

struct CentresPicture {
  DrawOptions options;
  std::vector<Eigen::Vector2d> points;
  Eigen::Vector2d lo{0, 0}, hi{0, 0};
  int off_picture = 0;
};

CentresPicture centres_picture(const Explanation& ex) {
  const Mechanism& mech = *ex.mechanism;
  const Model& m = mech.model();
  const double lu = m.units.length_scale;
  CentresPicture pic;
  pic.points = point_positions(mech, ex.q * lu);
  Eigen::Vector2d lo = pic.points.front(), hi = lo;
  for (const auto& p : pic.points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Eigen::Vector2d centre = 0.5 * (lo + hi);
  const double reach = 2.0 * std::max(mech.characteristic_length(), (hi - lo).norm());
  // Links numbered as textbooks do: 1 the ground, then the bodies; I23 is the centre of links 2, 3.
  std::vector<int> number(m.bodies.size() + 1, 0);  // by body index + 1
  std::string legend = "1 ground";
  number[0] = 1;
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    number[b + 1] = static_cast<int>(b) + 2;
    legend += ", " + std::to_string(b + 2) + " " + m.bodies[b].name;
  }
  const bool short_labels = m.bodies.size() + 1 < 10;
  pic.options.labels = true;
  pic.options.title = "Instant centres at step " + std::to_string(ex.step) + " (links: " + legend + ")";
  for (const InstantCentre& c : ex.centres) {
    if (c.at_infinity || c.indeterminate) continue;
    const Eigen::Vector2d at = c.position * lu;
    if ((at - centre).norm() > reach) {
      ++pic.off_picture;
      continue;
    }
    lo = lo.cwiseMin(at);
    hi = hi.cwiseMax(at);
    const int a = number[c.body_a + 1], b = number[c.body_b + 1];
    std::string label(1, 'I');
    label +=
        short_labels ? std::to_string(a) + std::to_string(b) : '(' + std::to_string(a) + ',' + std::to_string(b) + ')';
    pic.options.marked_points.push_back({at, label});
  }
  pic.lo = lo;
  pic.hi = hi;
  return pic;
}

template <class Canvas>
void draw_centres(Canvas& canvas, const Explanation& ex, const CentresPicture& pic) {
  const View view(pic.lo, pic.hi, pic.options.width, pic.options.height, pic.options.margin + 30.0);
  const SweepResult none;  // no traces, no guide spans from a sweep: the pose alone
  draw_mechanism(canvas, view, *ex.mechanism, none, pic.points, pic.options);
}

}  // namespace

std::string instant_centres_svg(const Explanation& explanation, int* off_picture) {
  const CentresPicture pic = centres_picture(explanation);
  SvgCanvas canvas(pic.options.width, pic.options.height);
  draw_centres(canvas, explanation, pic);
  if (off_picture) *off_picture = pic.off_picture;
  return canvas.document();
}

std::vector<std::uint8_t> instant_centres_png(const Explanation& explanation, int* off_picture) {
  const CentresPicture pic = centres_picture(explanation);
  ImageCanvas canvas(pic.options.width, pic.options.height);
  draw_centres(canvas, explanation, pic);
  if (off_picture) *off_picture = pic.off_picture;
  return canvas.png_bytes();
}

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
