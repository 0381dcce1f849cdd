// Writing a sweep's results as CSV or JSON.
#pragma once

#include <ostream>

#include "kinematics/table.hpp"

namespace nbar::io {

// Header line of column names, then one line per sample; values in the model's units.
void write_csv(std::ostream& out, const ResultTable& table);

// Aligned columns for people reading a terminal, with a units line under the names.
void write_text_table(std::ostream& out, const ResultTable& table);

// The same columns and rows, plus units per column, the degrees of freedom, the assembly
// branch of every four-bar loop, the residuals and every warning.
void write_json(std::ostream& out, const Mechanism& mech, const SweepResult& sweep, const ResultTable& table);

}  // namespace nbar::io
