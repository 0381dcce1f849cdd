// A model being built, as the web app draws it while the user adds points, links and guides with
// its tools: what the text says (points in the model's units, ground, bodies, guides, joints), how
// free its joints leave it (the Gruebler-Kutzbach count, and the rank's mobility once the model
// is valid) and what still keeps it from being solved. Every rule is the core's (the reader's,
// validate()'s, the Mechanism's mobility analysis); the app only draws the answer.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "nbar/kinematics/mechanism.hpp"
#include "nbar/model/diagnostics.hpp"

namespace nbar::request {

struct OutlinePoint {
  std::string name;
  double x = 0.0, y = 0.0;  // in the model's length unit, as written
  bool ground = false;
};

struct OutlineBody {
  std::string name;
  std::vector<std::string> points;
};

// A slider's or slot's guide: the line through two points (model units) and what slides on it.
struct OutlineGuide {
  std::string kind;  // "slider" | "slot"
  std::string body;  // a slider's body; empty for a slot
  std::string point;
  std::array<double, 4> line{};  // x0, y0, x1, y1
};

struct Outline {
  std::string name;  // the model's `name:`, empty when it has none
  Units units;
  std::vector<OutlinePoint> points;
  std::vector<OutlineBody> bodies;
  std::vector<OutlineGuide> guides;
  std::vector<std::string> joints;         // as `nbar check` lists them: "revolute A (crank/rod)"
  PairCount count;                         // Gruebler-Kutzbach
  std::optional<MobilityReport> mobility;  // the joints' true mobility, when the model is valid
  int drivers = 0;
  // What keeps the model from being solved (validate()'s complaint, or the Mechanism's about its
  // drivers), located in the text; empty when nothing does.
  std::string problem;
  SourceMark problem_at;
  // Set when the joints leave nothing free to move (a slider on the connecting rod, say): the
  // reason, said with the counts. An edit that leads here is refused by the app's tools.
  std::string immobile;
};

// Throws as io::parse_model does for what cannot be read at all (syntax, unknown names, numbers).
Outline outline_model(const std::string& text, const std::string& file_name);

}  // namespace nbar::request
