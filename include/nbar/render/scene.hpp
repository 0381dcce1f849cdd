// The drawing of a sweep as data, for front-ends that draw it themselves (the web app): the
// primitives `draw_mechanism` gives a canvas at one reference pose, recorded as JSON, and for
// every sample the rigid motion of each body group and the shift of each point label from that
// pose. Drawn with those motions, each sample is the picture `nbar draw --step` makes of it, so
// the front-end needs no drawing decision of its own and moves the picture without asking again.
#pragma once

#include <string>

#include "nbar/render/drawing.hpp"

namespace nbar::render {

// JSON (docs/web-api.md, "scene"):
//   width, height       the canvas (px) the primitives are drawn on
//   to_model            [k, tx, ty]: a pixel (px, py) is at (k px + tx, k py + ty) in model
//                       length units with y pointing down (x, -y of the model)
//   reference_step      the sample drawn (default_drawn_step, or the one asked for)
//   items               the primitives in drawing order: {"type": "group", "id", "class",
//                       "items"}, "polygon"/"polyline" {points: [x0, y0, x1, y1, ...]},
//                       "circle" {cx, cy, r}, "outline" {rings: [[...]...], circles: [[cx, cy,
//                       r]...]} (even-odd), "text" {x, y, text, size, anchor, color}; paints as
//                       fill, fill_opacity, stroke, stroke_width, stroke_opacity, dash
//   bodies              per body {name, group, pivot: [x, y]}
//   steps               per sample {bodies: [[angle_deg, dx, dy]...], labels: [[dx, dy]...]}:
//                       body b at the sample is its group rotated by angle_deg about its pivot
//                       (clockwise on screen) then moved by (dx, dy); label i (the i-th text
//                       of the "labels" group, one per point) moved by (dx, dy)
// reference_step < 0: default_drawn_step. Throws Error(ErrorKind::BadInput) for a step past the sweep.
std::string drawing_scene_json(const Mechanism& mech, const SweepResult& sweep, const DrawOptions& options,
                               int reference_step = -1);

}  // namespace nbar::render
