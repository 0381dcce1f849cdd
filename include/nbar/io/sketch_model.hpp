// A model skeleton from a sketch of several links (`nbar import`): every closed outline a body
// cut from a plate, coinciding pin holes the joints between them.
#pragma once

#include <string>

#include "nbar/io/sketch.hpp"

namespace nbar::io {

struct SketchModelOptions {
  std::string source_name;  // the sketch file, for the comments
  std::string length_unit;  // the model's unit: mm, cm, m, in or ft
  double scale = 1;         // sketch coordinates to the model's unit
  double thickness = 5;     // plates' thickness, in the model's unit
  std::string material = "steel";
};

// The model file (YAML) of a sketch. Loops not inside another are outlines, each a body named
// after its layer or group when that is a name no other outline has (otherwise link1,
// link2...); loops inside an outline are its holes. Circles whose centres coincide (within
// 1e-6 of the drawing's size) are one point, P1, P2...; each body containing a point has it
// (a pin hole of that radius); a point in two or more bodies is a joint; a pin hole in a single
// body is taken as a ground pivot. Marked points (DXF POINT, CSV Point) become points of the
// bodies containing them, without holes. Throws Error (InvalidModel) when an outline contains
// no point, or no loop is an outline. Every tolerance is relative to the drawing's size (the
// diagonal of its outlines' bounding box), so a drawing in another unit gives the same model,
// scaled; coordinates are written rounded to 10^(ceil(log10 size) - 12) (1e-9 for a drawing
// 100 to 1000 units across), with 12 significant digits.
std::string model_from_sketch(const Sketch& sketch, const SketchModelOptions& options);

}  // namespace nbar::io
