// The links' plates as a DXF drawing for cutting: every body with a shape (or a bar), placed
// in one pose, on a layer of its own.
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

#include "nbar/kinematics/mechanism.hpp"

namespace nbar::io {

// An ASCII DXF of AutoCAD release 12 (AC1009), which LibreCAD, AutoCAD and laser-cutting
// software all read: a HEADER (version, drawing units), a TABLES section with the line type
// CONTINUOUS and one layer per plate (the body's name, with characters DXF does not allow in a
// layer name replaced by '_'), and the ENTITIES: each outline and polygon hole as a closed
// POLYLINE whose VERTEXes carry the arcs' bulges (group 42), each round hole as a CIRCLE.
// Coordinates are in the model's length unit. `points` are the world positions (m) of the
// model's points in the pose wanted, as point_positions gives them; each plate moves rigidly
// with its body's frame from the drawn pose. Throws Error (BadInput) when no body has a plate.
std::string cutting_dxf(const Mechanism& mechanism, const std::vector<Eigen::Vector2d>& points);

// The same plates as an SVG for the web app and for vector editors: one <g id="layer name">
// per plate holding a <path> of its outline and polygon holes (arcs as A commands) and a
// <circle> per round hole; coordinates in the model's length unit with y turned down (SVG's
// way), width and height in mm so that the drawing has its true size and reads back
// (`shape: {import: F.svg}`) in the right unit. Throws Error (BadInput) when no body has a
// plate.
std::string cutting_svg(const Mechanism& mechanism, const std::vector<Eigen::Vector2d>& points);

// The layer name a body's plate gets.
std::string dxf_layer_name(const std::string& body_name);

}  // namespace nbar::io
