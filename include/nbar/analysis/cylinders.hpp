// Hydraulic cylinders described as two bodies, a barrel and a rod with a slider between them:
// whether the rod stays in its barrel over the sweep.
#pragma once

#include <vector>

#include "nbar/kinematics/mechanism.hpp"
#include "nbar/kinematics/sweep.hpp"
#include "nbar/model/diagnostics.hpp"

namespace nbar {

// One warning "rod_leaves_barrel" per rod point that starts inside its barrel and leaves it
// during `sweep`. A cylinder is a slider whose guide points are exactly the two points of a
// moving body (the barrel, from the guide's first point, its base, to its second, its mouth)
// and whose body (the rod) has two or more points; the rod's points lying on the barrel's
// segment at the start (the piston end) must stay on it. The sweep's step is in the warning.
// Whether the model has such a cylinder, so that checking it is worth a sweep.
bool has_cylinder(const Model& model);

// The same over the model's own sweep (positions only, at most kCylinderCheckSamples samples),
// as `nbar check` says it; nothing when the sweep cannot be run (the summary says why).
constexpr int kCylinderCheckSamples = 1001;
std::vector<Warning> cylinder_warnings(const Mechanism& mech);

std::vector<Warning> cylinder_warnings(const Mechanism& mech, const SweepResult& sweep);

}  // namespace nbar
