// What can go wrong, said once for the whole library: one exception type with a kind, the
// entity it is about and, when the problem was read from a file, where in it; and structured
// warnings. Every front-end maps kinds in one place: the CLI to exit codes, the web server to
// HTTP statuses, Python to exception classes.
#pragma once

#include <stdexcept>
#include <string>

namespace nbar {

enum class ErrorKind {
  InvalidModel,    // syntax, unknown names, wrong geometry, drivers not matching the mobility
  BadInput,        // an option or argument out of range: a step that was not solved, an unknown column
  CannotAssemble,  // no pose meets the constraints at the start
  StoppedAtLimit,  // a sweep stopped at a limit (toggle) position before its end
  UndefinedLaw,    // a motion or load law has no value (or no derivative) where it is needed
  Cancelled,       // stopped by a cancellation token, a deadline or a progress callback
  Internal,        // a defect of nbar ("cannot happen"), or the system refused: a file that cannot be
                   // written, a program that cannot be started, a third-party library's failure
};

// "invalid_model", "bad_input", "cannot_assemble", "stopped_at_limit", "undefined_law",
// "cancelled", "internal": stable names for JSON and Python.
const char* to_string(ErrorKind kind);

// A place in a source text: 1-based line and column; 0 when unknown.
struct SourceMark {
  int line = 0;
  int column = 0;
};

// What a model error is about, so that front-ends can point at the right place (the parser
// maps it to file:line:column).
struct EntityRef {
  enum class Kind {
    Model,
    Point,
    Body,
    Slider,
    Slot,
    Driver,
    Sweep,
    PointLoad,
    Torque,
    Spring,
    Friction,
    Simulation
  } kind = Kind::Model;
  int index = -1;
  // Which law of the entity the error is about, so that it is shown at the law's text: 0 for a
  // driver's `law`, a torque or a force's fx, 1 for a force's fy; -1 for the entity as a whole.
  int law = -1;
};

// "model", "point", "body", "slider", "slot", "driver", "sweep", "force", "torque", "spring":
// stable names of the kinds of entity for JSON and Python.
const char* to_string(EntityRef::Kind kind);

class Error : public std::runtime_error {
 public:
  // what() is "file:line:column: message", "file: message" without a line, or the message alone
  // without a file.
  Error(ErrorKind kind, const std::string& message, EntityRef where = {}, const std::string& file = {},
        SourceMark mark = {});

  ErrorKind kind() const { return kind_; }
  const std::string& message() const { return message_; }  // without the location
  const EntityRef& where() const { return where_; }
  const std::string& file() const { return file_; }
  SourceMark mark() const { return mark_; }

 private:
  ErrorKind kind_;
  std::string message_;
  EntityRef where_;
  std::string file_;
  SourceMark mark_;
};

// "file:line:column: message" (or shorter, as Error::what() says).
std::string compose_location(const std::string& file, SourceMark mark, const std::string& message);

// An invalid model, found by validate() or by compiling the model (the kind is InvalidModel).
class ModelError : public Error {
 public:
  ModelError(EntityRef where, const std::string& message) : Error(ErrorKind::InvalidModel, message, where) {}
};

// Something a result should be read with: a change point passed, a loop that changed branch,
// forces that are not unique. `code` is a stable identifier, `step` the sample it happened
// before (-1 when it concerns the whole run).
struct Warning {
  std::string code;
  int step = -1;
  std::string message;
};

}  // namespace nbar
