// Overflow in the dynamics and stress stages: a result that is not a finite number becomes an
// error about the input that made it so, for every front-end alike.
#pragma once

#include <vector>

#include "nbar/dynamics/inverse_dynamics.hpp"
#include "nbar/stress/link_stress.hpp"

namespace nbar::detail {

// Throws Error(InvalidModel) about the largest load of the model (a mass, a force, a torque, a
// spring) when a sample's forces, efforts or energies are not all finite.
void check_finite_dynamics(const Model& model, const Sample& sample, const DynamicsResult& result);
// The same for the stress peaks, at the samples of `samples`.
void check_finite_stress(const Model& model, const std::vector<Sample>& samples, const std::vector<StressPeak>& peaks);

}  // namespace nbar::detail
