// Internal to the sketch readers: what each format's reader gives the common chaining.
#pragma once

#include <Eigen/Core>

#include <string>
#include <utility>
#include <vector>

#include "nbar/io/sketch.hpp"
#include "nbar/model/curves.hpp"

namespace nbar::io::sketch_detail {

// An edge from a to b: straight, a circular arc (bulge != 0), or a curve running from
// curve(s0) = a to curve(s1) = b.
struct Segment {
  Segment(const Eigen::Vector2d& from, const Eigen::Vector2d& to, double arc_bulge = 0)
      : a(from), b(to), bulge(arc_bulge) {}
  Segment(const Eigen::Vector2d& from, const Eigen::Vector2d& to, double arc_bulge, CurveFunction f, double start,
          double end)
      : a(from), b(to), bulge(arc_bulge), curve(std::move(f)), s0(start), s1(end) {}
  Eigen::Vector2d a, b;
  double bulge = 0;
  CurveFunction curve;
  double s0 = 0, s1 = 0;
};

// Edges drawn one after the other by one entity; closed when it returns to its start.
struct Stroke {
  std::vector<Segment> segments;
  bool closed = false;
  int line = 0;
  std::string layer;
};

struct StrokeSet {
  std::vector<Stroke> strokes;
  std::vector<SketchCircle> circles;
  std::vector<SketchPoint> points;
  std::optional<double> metres_per_unit;
  std::vector<std::string> annotations;
};

// The most entities (strokes, circles and points together) a drawing may hold, and the most
// vertices an outline may have once its curves are cut into chords: the import is near-linear
// in them (docs/robustness.md), and past them it is refused at the line of the first entity
// over the count (or of the outline) instead of working for minutes.
inline constexpr std::size_t kMaxSketchEntities = 200000;
inline constexpr std::size_t kMaxLoopVertices = 1000000;

// Chains the strokes into loops, polygonises their curves, checks that no loop crosses
// itself; errors (ModelFileError) at `file`'s lines. `last_line` is where "nothing closed" is
// reported; `what` names what was read ("on the layer 'x'") for that message.
Sketch finish_sketch(StrokeSet set, const std::string& file, int last_line, const std::string& what);

[[noreturn]] void fail_at(const std::string& file, int line, const std::string& message);

StrokeSet read_dxf_strokes(const std::string& text, const std::string& file, const std::string& layer, int& last_line);
StrokeSet read_svg_strokes(const std::string& text, const std::string& file, const std::string& layer, int& last_line);
StrokeSet read_csv_strokes(const std::string& text, const std::string& file, int& last_line);

}  // namespace nbar::io::sketch_detail
