// The model summary as text for a terminal (`nbar check`).
#pragma once

#include <ostream>
#include <string>

#include "nbar/analysis/summary.hpp"

namespace nbar::io {

// Points, bodies, joints, degrees of freedom, redundant constraints, drivers, mass properties
// and loads, then the assembly at the start (or "FAILED") and every four-bar loop there.
// `source` is the model file's name, shown after the model's name.
void write_summary_text(std::ostream& out, const Mechanism& mechanism, const ModelSummary& summary,
                        const std::string& source);

}  // namespace nbar::io
