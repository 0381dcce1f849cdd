// Whether the four-bar loops of a model can close at all, from its link lengths.
#pragma once

#include <string>
#include <vector>

#include "nbar/kinematics/loops.hpp"
#include "nbar/model/model.hpp"

namespace nbar {

// The length of `link` (a body index, or -1 for the ground) between two of its points, as the
// solver holds it: a body's `lengths:` value scales the whole body (its other points are held
// in the frame of its first two).
double link_length(const Model& model, int link, int from_point, int to_point);

// Why a four-bar loop cannot be closed in any pose: its longest link is longer than the other
// three together, e.g. "crank 40 + coupler 50 + rocker 50 < frame 200 mm: loop
// crank-coupler-rocker cannot close". Lengths as link_length; empty when every loop can close.
std::string loop_closure_failure(const Model& model, const std::vector<FourBarLoop>& loops);

}  // namespace nbar
