// 2-D sketches read from drawing files — DXF (R12 and R2000+), SVG path data, and the sketch
// CSV of the thesis tool of Ksam — as closed loops, circles and points, for plates
// (`shape: {import: FILE}`) and model skeletons (`nbar import`).
#pragma once

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

#include "nbar/model/geometry.hpp"

namespace nbar::io {

// A closed loop of the sketch: vertices with the bulges of the edges they start (as in Region),
// the line of the file each vertex's entity starts on, and the entity's layer (DXF) or group
// (SVG) or entity name (CSV).
struct SketchLoop {
  std::vector<Eigen::Vector2d> vertices;
  std::vector<double> bulges;
  std::vector<int> lines;
  std::string layer;
  double area() const;  // enclosed, > 0, exact for arcs
};

struct SketchCircle {
  Circle circle;
  int line = 0;
  std::string layer;
};

// A point marked in the drawing (a DXF POINT, a CSV `Point`): a joint.
struct SketchPoint {
  Eigen::Vector2d at;
  int line = 0;
};

// Everything in the file's own unit; `metres_per_unit` when the file states its unit.
// `annotations`: the kind of each note left out (DXF TEXT, DIMENSION..., SVG <text>), which
// draw no part, so that a reader can say what it did not read.
struct Sketch {
  std::vector<SketchLoop> loops;
  std::vector<SketchCircle> circles;
  std::vector<SketchPoint> points;
  std::optional<double> metres_per_unit;
  std::vector<std::string> annotations;
};

enum class SketchFormat { kDxf, kSvg, kCsv };

// The format of a file by its extension (.dxf, .svg, .csv or .txt), without regard to case.
std::optional<SketchFormat> sketch_format(const std::string& file_name);

// Reads a sketch. Lines, arcs, open polylines and curves (splines, ellipses, Béziers) are
// chained end to end into closed loops, ends within 1e-6 of the drawing's size meeting; curves
// are polygonised within kRelativeCurveTolerance of the drawing's size (curves.hpp), arcs stay
// bulges. With a `layer`, only that DXF layer (compared without case) or SVG group (id or
// Inkscape label) is read. Throws ModelFileError at file:line for what the file cannot mean: a
// broken DXF group-code pair, an entity or element nbar does not read, a bad number, an open
// loop, a loop that crosses itself, nothing closed at all.
Sketch read_sketch(const std::string& text, const std::string& file_name, SketchFormat format,
                   const std::string& layer = {});

// The plate of a sketch of one link, each coordinate multiplied by `scale`: the loop of the
// largest area is the outline, the other loops polygon holes, the circles round (pin) holes.
// Not checked (check_region).
Region plate_from_sketch(const Sketch& sketch, double scale);
// The same, checked as a plate (check_region): a hole that meets the outline or another hole,
// or lies outside the outline, is an error at the line of `file` where that hole is drawn.
Region checked_plate_from_sketch(const Sketch& sketch, double scale, const std::string& file);

// The scale from a sketch's unit to the model's: `stated_metres_per_unit` when given, else the
// file's own, else 1 (the file is taken in the model's unit).
double sketch_scale(const Sketch& sketch, std::optional<double> stated_metres_per_unit, double model_metres_per_unit);

}  // namespace nbar::io
