// The step-by-step explanation as JSON (for the web API), and the equations of motion at a time: every section of an
// Explanation, numbers in the model's units, never null or NaN.
#pragma once

#include <nlohmann/json.hpp>

#include "nbar/analysis/explain.hpp"
#include "nbar/dynamics/equations_of_motion.hpp"

namespace nbar::io {

nlohmann::json explanation_json(const Explanation& explanation);

// The equations of motion at one time of a simulation (`nbar explain --simulate --format json`):
// the state, M, Phi_q with its rows' labels, Q by origin, gamma and the solution, in SI.
nlohmann::json equations_of_motion_json(const Mechanism& mechanism, const EquationsOfMotionAt& equations);

}  // namespace nbar::io
