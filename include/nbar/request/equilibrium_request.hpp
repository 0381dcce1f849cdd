// nbar equilibrium: the static equilibrium of the free drivers under the model's loads
// (docs/dynamics.md#static-equilibrium-nbar-equilibrium), as every front-end asks for it.
#pragma once

#include <string>
#include <vector>

#include "nbar/dynamics/equilibrium.hpp"
#include "nbar/request/options.hpp"

namespace nbar::request {

struct EquilibriumRequest {
  std::string format = "table";      // table, csv or json
  std::vector<std::string> columns;  // of the pose; empty: every column
  int max_iterations = 50;

  static const std::vector<OptionRule>& rules();
  static EquilibriumRequest read(const Options& options);
  EquilibriumOptions equilibrium_options() const;
  // The pose's columns asked for, or an OptionError at `columns` naming the columns there are.
  ResultTable table(const Mechanism& mechanism, const Equilibrium& equilibrium) const;
};

}  // namespace nbar::request
