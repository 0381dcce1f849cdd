// The rocking sweep (`at_limits: reverse`): the kinematics engine's own, called by run_sweep.
#pragma once

#include "nbar/kinematics/limits.hpp"
#include "nbar/kinematics/sweep.hpp"

namespace nbar {

// The model's driver turns back at the mechanism's limits.
bool sweep_rocks(const Model& model);

// Sample::reciprocal_condition of the pose in `state`, solved and its Jacobian factorised (both
// sweeps' samples, when SweepOptions::condition asks).
double sample_condition(State& state);

// Samples a plan that reverses (plan.reverses): `options.steps` (or the model's steps) samples
// evenly spaced in time over the cycles asked for, or over the travel |to - from|.
SweepResult run_rocking_sweep(const Mechanism& mech, const RockingPlan& plan, const SweepOptions& options,
                              const RunControl& control, const SampleSink& sink);

}  // namespace nbar
