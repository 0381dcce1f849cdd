// Reading model files (YAML, or JSON which is read by the same parser).
// Errors carry file:line:column so users can find the offending line.
#pragma once

#include <array>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "nbar/model/model.hpp"

namespace nbar::io {

using nbar::SourceMark;

// Where each entity of the model was written, so that errors found later (by validate()
// or by the kinematics stage) can be reported at the right line.
struct SourceMap {
  std::string file;
  SourceMark model;
  std::vector<SourceMark> points, bodies, sliders, slots, drivers;
  SourceMark sweep;
  std::vector<SourceMark> point_loads, torques, springs;  // the items of `forces`, `torques`, `springs`
  std::vector<SourceMark> frictions;                      // the items of `friction`
  // The `simulation:` section: [0] the section, [1] its `stop_when` (an unknown column is shown there)
  std::vector<SourceMark> simulation;
  // Where each entity's laws were written (EntityRef::law indexes the pair): a driver's `law`,
  // a torque's value, a force's fx and fy. An unmarked law is shown at its entity.
  std::vector<std::array<SourceMark, 2>> driver_laws, point_load_laws, torque_laws;

  SourceMark find(const EntityRef& ref) const;
  // Where a sweep that stopped early is reported: at the sweep's settings, or at the first
  // driver when the model has no `sweep:`: what asked for the motion that could not be followed.
  SourceMark sweep_stop() const;
};

// An error located in a source file (kind InvalidModel unless said otherwise).
class ModelFileError : public Error {
 public:
  // what() is "file:line:column: message" (or "file: message" without a position).
  ModelFileError(const std::string& file, SourceMark mark, const std::string& message,
                 ErrorKind kind = ErrorKind::InvalidModel)
      : Error(kind, message, {}, file, mark) {}
};

struct LoadedModel {
  Model model;
  SourceMap source;
  std::string text;  // what was parsed: Python pickles a model as its text
};

// Parses and validates (nbar::validate) a model; throws ModelFileError for any problem,
// including the ModelErrors of validate(), located with the source map.
LoadedModel parse_model(const std::string& text, const std::string& file_name = "<model>");
// The same, letting `shape: {import: FILE}` read files relative to `import_dir`, as a model file
// read from that folder does (load_model_file).
LoadedModel parse_model(const std::string& text, const std::string& file_name, const std::string& import_dir);
LoadedModel load_model_file(const std::string& path);

// A model being built, read as it is written: parsed as parse_model parses (a syntax error, an
// unknown name or a bad number still throws ModelFileError), but a model with no points yet, or
// one that validate() refuses (a point on no body, a single-point body with no slider), is
// returned with validate()'s complaint, located, in `problem`. The web app draws it while the
// user builds it; nothing may be solved from it.
struct DraftModel {
  LoadedModel loaded;
  std::optional<ModelFileError> problem;
};
DraftModel parse_draft_model(const std::string& text, const std::string& file_name = "<model>");

// "file:line:column: message" for an error the core reports about an entity.
std::string locate(const SourceMap& source, const ModelError& error);
// The error placed in the file at the entity it is about (a stop at a limit that names none: at
// the sweep, as a stopped sweep), unless it names none, already has a file or is about the call
// (BadInput) or time (Cancelled).
Error located(const SourceMap& source, const Error& error);

}  // namespace nbar::io
