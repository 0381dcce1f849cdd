// Stress maps: a link's plate coloured by the von Mises stress of its finite elements, with a
// colour legend and each link's peak marked. Used by `nbar draw --stress`, the animations (the
// colours change along the sweep) and the HTML report.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "nbar/analysis/analysis.hpp"
#include "nbar/render/canvas.hpp"
#include "nbar/render/drawing.hpp"

namespace nbar::render {

// The colour of a stress at `fraction` of the scale (clamped to 0..1): blue, cyan, green,
// yellow, red, as FE packages colour.
Colour stress_colour(double fraction);

// "246 kPa", "1.25 MPa": three significant digits in the unit that reads best.
std::string stress_text(double pascals);

// The plate of `map` coloured on `canvas`: each 6-node triangle cut into four at its mid-side
// nodes, each quarter filled with the colour of its nodes' mean value. `to_pixels` takes a
// plate-frame point to the canvas.
void draw_stress_plate(Canvas& canvas, const StressMap& map, double scale,
                       const std::function<Eigen::Vector2d(const Eigen::Vector2d&)>& to_pixels);

// The width the legend takes at the right edge of a drawing, px (fit_view leaves it free).
constexpr int kStressLegendWidth = 84;

// The colour legend, a vertical bar from 0 to `scale` (Pa) at the top right of the canvas.
void draw_stress_legend(Canvas& canvas, double scale);

// The top of the colour scale of `options`: its stress_scale, or the largest value of its maps.
double stress_scale(const DrawOptions& options);

// The maps of every link the analysis's finite-element stage analysed, at sample `sample` (an
// index into analysis.sweep.samples). Throws Error(BadInput) when the analysis has no
// finite-element stresses.
std::vector<StressMap> stress_maps(const Analysis& analysis, int sample);

// Adds to `options` the maps at `sample`, a marker at each link's largest stress there, and
// the colour scale: from 0 to `scale` (Pa), or to the largest value drawn when scale is 0.
void add_stress_maps(DrawOptions& options, const Analysis& analysis, int sample, double scale = 0.0);

// The largest stress of the finite-element stage's peaks over the sweep, Pa: the scale that
// keeps colours comparable between the frames of an animation.
double sweep_stress_scale(const Analysis& analysis);

}  // namespace nbar::render
