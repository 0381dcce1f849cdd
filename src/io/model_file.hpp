// Reading model files (YAML, or JSON which is read by the same parser).
// Errors carry file:line:column so users can find the offending line.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "model/model.hpp"

namespace nbar::io {

struct SourceMark {
  int line = 0;    // 1-based; 0 = unknown
  int column = 0;  // 1-based
};

// Where each entity of the model was written, so that errors found later (by validate()
// or by the kinematics stage) can be reported at the right line.
struct SourceMap {
  std::string file;
  SourceMark model;
  std::vector<SourceMark> points, bodies, sliders, slots, drivers;
  SourceMark sweep;
  std::vector<SourceMark> point_loads, torques, springs;  // the items of `forces`, `torques`, `springs`

  SourceMark find(const EntityRef& ref) const;
};

class ModelFileError : public std::runtime_error {
 public:
  // what() is "file:line:column: message" (or "file: message" without a position).
  ModelFileError(const std::string& file, SourceMark mark, const std::string& message);
  const std::string& file() const { return file_; }
  SourceMark mark() const { return mark_; }
  const std::string& message() const { return message_; }

 private:
  std::string file_;
  SourceMark mark_;
  std::string message_;
};

struct LoadedModel {
  Model model;
  SourceMap source;
};

// Parses and validates (nbar::validate) a model; throws ModelFileError for any problem,
// including the ModelErrors of validate(), located with the source map.
LoadedModel parse_model(const std::string& text, const std::string& file_name = "<model>");
LoadedModel load_model_file(const std::string& path);

// "file:line:column: message" for an error the core reports about an entity.
std::string locate(const SourceMap& source, const ModelError& error);

}  // namespace nbar::io
