#include "nbar/model/diagnostics.hpp"

namespace nbar {

const char* to_string(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::InvalidModel: return "invalid_model";
    case ErrorKind::BadInput: return "bad_input";
    case ErrorKind::CannotAssemble: return "cannot_assemble";
    case ErrorKind::StoppedAtLimit: return "stopped_at_limit";
    case ErrorKind::UndefinedLaw: return "undefined_law";
    case ErrorKind::Cancelled: return "cancelled";
  }
  return "error";
}

const char* to_string(EntityRef::Kind kind) {
  switch (kind) {
    case EntityRef::Kind::Model: return "model";
    case EntityRef::Kind::Point: return "point";
    case EntityRef::Kind::Body: return "body";
    case EntityRef::Kind::Slider: return "slider";
    case EntityRef::Kind::Slot: return "slot";
    case EntityRef::Kind::Driver: return "driver";
    case EntityRef::Kind::Sweep: return "sweep";
    case EntityRef::Kind::PointLoad: return "force";
    case EntityRef::Kind::Torque: return "torque";
    case EntityRef::Kind::Spring: return "spring";
  }
  return "model";
}

std::string compose_location(const std::string& file, SourceMark mark, const std::string& message) {
  if (file.empty()) return message;
  if (mark.line <= 0) return file + ": " + message;
  return file + ":" + std::to_string(mark.line) + ":" + std::to_string(mark.column) + ": " + message;
}

Error::Error(ErrorKind kind, const std::string& message, EntityRef where, const std::string& file, SourceMark mark)
    : std::runtime_error(compose_location(file, mark, message)),
      kind_(kind),
      message_(message),
      where_(where),
      file_(file),
      mark_(mark) {}

}  // namespace nbar
