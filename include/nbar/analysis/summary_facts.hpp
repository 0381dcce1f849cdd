// The slider-cranks and quick-returns of a model, found from its topology, with their stroke,
// dead centres, swing and time ratio (summary.hpp's SliderCrankSummary, QuickReturnSummary).
#pragma once

#include "nbar/analysis/summary.hpp"

namespace nbar {

// Fills out.slider_cranks and out.quick_returns from the model's geometry (its lengths).
void summarize_crank_mechanisms(const Model& model, ModelSummary& out);

// Fills l.rocker for a crank-rocker on the ground, from its pose `points` (the assembled start).
void add_rocker_swing(const Mechanism& mechanism, const std::vector<Eigen::Vector2d>& points, LoopSummary& l);

}  // namespace nbar
