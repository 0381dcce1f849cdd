// One call from a pose to a picture's bytes, for front-ends that send pictures rather than
// write files (the CLI's `nbar draw`, Python's Model.draw(), the web server).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "nbar/analysis/explain.hpp"
#include "nbar/render/drawing.hpp"

namespace nbar::render {

// The mechanism at `points` (m) on a view fitted to every pose of `sweep`, as SVG text or PNG
// bytes.
std::string drawing_svg(const Mechanism& mech, const SweepResult& sweep, const std::vector<Eigen::Vector2d>& points,
                        const DrawOptions& options);
std::vector<std::uint8_t> drawing_png(const Mechanism& mech, const SweepResult& sweep,
                                      const std::vector<Eigen::Vector2d>& points, const DrawOptions& options);

// The pose of an explanation with its finite instant centres marked, labelled as textbooks
// number the links (1 the ground, then the bodies: I23 is the centre of links 2 and 3), on a
// view that takes in the centres not too far from the mechanism; `off_picture` (when given)
// counts the centres left out for lying too far.
std::string instant_centres_svg(const Explanation& explanation, int* off_picture = nullptr);
std::vector<std::uint8_t> instant_centres_png(const Explanation& explanation, int* off_picture = nullptr);

}  // namespace nbar::render
