// The step-by-step explanation as JSON (for the web API): every section of an Explanation,
// numbers in the model's units, never null or NaN.
#pragma once

#include <nlohmann/json.hpp>

#include "nbar/analysis/explain.hpp"

namespace nbar::io {

nlohmann::json explanation_json(const Explanation& explanation);

}  // namespace nbar::io
