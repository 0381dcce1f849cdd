// One call from a pose to a picture's bytes, for front-ends that send pictures rather than
// write files (the CLI's `nbar draw`, Python's Model.draw(), the web server).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "nbar/render/drawing.hpp"

namespace nbar::render {

// The mechanism at `points` (m) on a view fitted to every pose of `sweep`, as SVG text or PNG
// bytes.
std::string drawing_svg(const Mechanism& mech, const SweepResult& sweep, const std::vector<Eigen::Vector2d>& points,
                        const DrawOptions& options);
std::vector<std::uint8_t> drawing_png(const Mechanism& mech, const SweepResult& sweep,
                                      const std::vector<Eigen::Vector2d>& points, const DrawOptions& options);

}  // namespace nbar::render
