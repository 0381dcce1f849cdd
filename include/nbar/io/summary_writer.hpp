// The model summary as text for a terminal (`nbar check`).
#pragma once

#include <ostream>
#include <string>

#include "nbar/analysis/summary.hpp"
#include "nbar/io/model_file.hpp"

namespace nbar::io {

// Points, bodies, joints, degrees of freedom, redundant constraints, drivers, mass properties
// and loads, then the assembly at the start (or "FAILED") and every four-bar loop there.
// `source` is the model file's name, shown after the model's name.
void write_summary_text(std::ostream& out, const Mechanism& mechanism, const ModelSummary& summary,
                        const std::string& source);

// The same summary as a JSON document (indented by 2, with a final newline), in the model's
// units: `nbar check --format json` and the web server's /api/check. `source` names the file
// and places an assembly failure at its line and column.
std::string summary_json(const Mechanism& mechanism, const ModelSummary& summary, const SourceMap& source);

}  // namespace nbar::io
