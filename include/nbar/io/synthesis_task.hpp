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

// Whether the reader may open the CSV a path task's `curve: FILE.csv` names.
enum class CurveFiles {
  refused,  // a client's text (the web server's): `curve` is an error at its value
  read,     // the user's own: a task file (a relative name is read beside it), nbar synth's
            // options and Python's task() (from the current directory)
};

// Throws ModelFileError for any problem, at the offending key or value. A task parsed from
// text opens no file unless `curve_files` says so; a task loaded from a file reads its curve
// beside it.
SynthesisTask parse_synthesis_task(const std::string& text, const std::string& file_name = "<task>",
                                   CurveFiles curve_files = CurveFiles::refused);
SynthesisTask load_synthesis_task(const std::string& path);

}  // namespace nbar::io
