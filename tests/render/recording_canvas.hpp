// A canvas that keeps what is drawn, in order, with the group it is drawn in: for tests that
// assert geometry (where a circle is, how wide a line is, what a label's box covers).
#pragma once

#include <string>
#include <vector>

#include "nbar/render/canvas.hpp"

namespace nbar::render::test_support {

struct Drawn {
  enum Kind { Polygon, Polyline, Circle, Outline, Text } kind;
  std::string group;                    // the innermost group's id
  std::vector<Eigen::Vector2d> points;  // vertices; a circle's centre; a text's baseline start
  double size = 0;                      // stroke width (polylines), radius (circles), font size (texts)
  std::string text;
  Paint paint;
};

class RecordingCanvas : public Canvas {
 public:
  RecordingCanvas(int width, int height) : Canvas(width, height) {}
  std::vector<Drawn> drawn;

  void begin_group(const std::string& id, const std::string&) override { groups_.push_back(id); }
  void end_group() override { groups_.pop_back(); }
  void polygon(const std::vector<Eigen::Vector2d>& points, const Paint& paint) override {
    drawn.push_back({Drawn::Polygon, group(), points, 0, "", paint});
  }
  void polyline(const std::vector<Eigen::Vector2d>& points, const Stroke& stroke) override {
    drawn.push_back({Drawn::Polyline, group(), points, stroke.width, "", Paint{std::nullopt, stroke}});
  }
  void circle(const Eigen::Vector2d& centre, double radius, const Paint& paint) override {
    drawn.push_back({Drawn::Circle, group(), {centre}, radius, "", paint});
  }
  void outline(const Outline& shape, const Paint& paint) override {
    drawn.push_back({Drawn::Outline, group(), shape.outer, 0, "", paint});
  }
  void text(const Eigen::Vector2d& at, const std::string& text, double size, Anchor, const Colour&) override {
    drawn.push_back({Drawn::Text, group(), {at}, size, text, {}});
  }

  std::vector<const Drawn*> in(const std::string& group_id, Drawn::Kind kind) const {
    std::vector<const Drawn*> out;
    for (const Drawn& d : drawn)
      if (d.group == group_id && d.kind == kind) out.push_back(&d);
    return out;
  }

 private:
  std::string group() const { return groups_.empty() ? "" : groups_.back(); }
  std::vector<std::string> groups_;
};

}  // namespace nbar::render::test_support
