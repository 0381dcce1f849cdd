// One pose along the sweep: where the first driver has a given value, reached from the sweep's
// start along the sweep's own path, so that it lies on the branch drawn (a pose solved from the
// drawing alone could land on another branch).
#pragma once

#include "nbar/kinematics/mechanism.hpp"
#include "nbar/kinematics/sweep.hpp"
#include "nbar/model/run_control.hpp"

namespace nbar {

// `value` is in the model's units (the first driver's angle or length unit), or a time in s for
// models driven by time laws; the other drivers move as the sweep moves them. The Sample holds
// Taylor coefficients to `order`. Throws Error: BadInput for a model without drivers,
// StoppedAtLimit when a limit (toggle) position lies between the start and `value`,
// CannotAssemble when the start cannot be assembled. A rocking driver (`at_limits: reverse`) takes
// most values more than once: the pose is where its motion first has `value` (rocking_sample_at),
// and a value outside the range it rocks over is StoppedAtLimit.
Sample pose_at(const Mechanism& mechanism, double value, int order = 0, const RunControl& control = {});

}  // namespace nbar
