// nbar equilibrium's answer as text (after the pose's table) and as JSON.
#pragma once

#include <ostream>

#include "nbar/dynamics/equilibrium.hpp"
#include "nbar/kinematics/table.hpp"

namespace nbar::io {

// "Equilibrium: stable ...", the free drivers' values, the residual and the stiffness's
// eigenvalues, one line each, in the model's units.
void write_equilibrium_summary(std::ostream& out, const Mechanism& mechanism, const Equilibrium& equilibrium);

// {"model", "units", "free_drivers": {name: value}, "stability", "stiffness_eigenvalues",
// "stiffness", "residual", "forces", "iterations", "columns", "column_units", "row"}.
void write_equilibrium_json(std::ostream& out, const Mechanism& mechanism, const Equilibrium& equilibrium,
                            const ResultTable& table);

}  // namespace nbar::io
