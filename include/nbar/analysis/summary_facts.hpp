// The slider-cranks and quick-returns of a model, found from its topology, with their stroke,
// dead centres, swing and time ratio (summary.hpp's SliderCrankSummary, QuickReturnSummary).
#pragma once

#include "nbar/analysis/summary.hpp"

namespace nbar {

// Fills out.slider_cranks and out.quick_returns from the model's geometry (its lengths).
void summarize_crank_mechanisms(const Model& model, ModelSummary& out);

}  // namespace nbar
