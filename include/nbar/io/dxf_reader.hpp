// A link plate read from a DXF drawing, for `shape: {import: FILE}`.
#pragma once

#include <string>

#include "nbar/model/geometry.hpp"

namespace nbar::io {

// Reads an ASCII DXF (release 12 or later) and makes a plate of its ENTITIES: LINE, ARC,
// CIRCLE, LWPOLYLINE and POLYLINE (with VERTEXes), arcs of polylines by their bulges. Lines,
// arcs and open polylines are chained end to end into closed loops (ends within 1e-6 of the
// drawing's size meet); closed polylines are loops by themselves. The loop of the largest
// area is the outline, the others are polygon holes; circles are round holes. Coordinates are
// converted from the drawing's $INSUNITS (in, ft, mm, cm, m) to the model's unit of
// `model_metres_per_unit`, or taken as the model's unit when the drawing states none.
// The result is not checked (check_region). Throws ModelFileError at file:line for a broken
// group-code pair, an entity nbar does not read, a bad number, an open loop or no loop at all.
// With a `layer`, only the entities on that layer (compared without case) are read.
Region read_dxf_plate(const std::string& text, const std::string& file_name, double model_metres_per_unit,
                      const std::string& layer = {});

}  // namespace nbar::io
