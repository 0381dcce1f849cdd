// Writing models as nbar YAML model files (docs/model-format.md) that parse_model reads back
// to the same model: numbers in the model's units, written to the last bit.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "nbar/model/model.hpp"
#include "nbar/synthesis/fourbar_design.hpp"

namespace nbar::io {

// The kinematic model: name, units, points, ground, bodies, lengths, sliders, slots, drivers
// and sweep, after `comments` (one "# " line each). Throws Error(ErrorKind::BadInput) for a model
// with kinetics (masses, shapes, loads, springs, gravity), which are not written yet.
void write_model_yaml(std::ostream& out, const Model& model, const std::vector<std::string>& comments = {});
std::string model_yaml(const Model& model, const std::vector<std::string>& comments = {});

// What a check found, as comment lines for a model file: link lengths and Grashof class,
// defects, transmission angles and each target's input angle, in `units`.
std::vector<std::string> design_comments(const synthesis::DesignCheck& check, const Units& units = {});

// Where the design's angles are measured from, as comment lines: none when they are the links'
// own directions, otherwise which pointer (Ip, Op) carries the input or output angle.
std::vector<std::string> design_angle_comments(const synthesis::FourBarDesign& design);

// A synthesised four-bar as a model file: make_fourbar_model with the check's motion, its
// coordinates in `units`, `comments`, design_comments then design_angle_comments.
std::string design_yaml(const synthesis::FourBarDesign& design, const synthesis::DesignCheck& check,
                        const std::string& name, const Units& units = {},
                        const std::vector<std::string>& comments = {});

}  // namespace nbar::io
