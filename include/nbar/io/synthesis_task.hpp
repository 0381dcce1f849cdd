// Reading synthesis task files (docs/synthesis.md): small YAML files that say what a four-bar
// should do. Errors are ModelFileErrors, "file:line:column: message", like model files.
#pragma once

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

#include "nbar/io/model_file.hpp"
#include "nbar/synthesis/task.hpp"

namespace nbar::io {

using synthesis::SynthesisKind;
using synthesis::SynthesisTask;
using synthesis::to_string;

// Throws ModelFileError for any problem, at the offending key or value. A task parsed from
// text reads no file: a path task's `curve: FILE.csv` is an error there (the web server parses
// its clients' tasks so); a task loaded from a file reads its curve beside it.
SynthesisTask parse_synthesis_task(const std::string& text, const std::string& file_name = "<task>");
SynthesisTask load_synthesis_task(const std::string& path);

}  // namespace nbar::io
