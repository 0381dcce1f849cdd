#include "nbar/model/diagnostics.hpp"
#include "nbar/model/file_errors.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

namespace nbar {

const char* to_string(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::InvalidModel: return "invalid_model";
    case ErrorKind::BadInput: return "bad_input";
    case ErrorKind::CannotAssemble: return "cannot_assemble";
    case ErrorKind::StoppedAtLimit: return "stopped_at_limit";
    case ErrorKind::UndefinedLaw: return "undefined_law";
    case ErrorKind::Cancelled: return "cancelled";
    case ErrorKind::Internal: return "internal";
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
    case EntityRef::Kind::Friction: return "friction";
    case EntityRef::Kind::Simulation: return "simulation";
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

std::string output_path_problem(const std::string& path) {
  namespace fs = std::filesystem;
  const std::string message = "cannot write " + path;
  const fs::path folder = fs::path(path).parent_path();
  std::error_code ec;
  if (!folder.empty() && !fs::exists(folder, ec))
    return message + ": the folder '" + folder.string() + "' does not exist";
  if (!folder.empty() && !fs::is_directory(folder, ec))
    return message + ": '" + folder.string() + "' is a file, not a folder";
  if (fs::is_directory(path, ec)) return message + ": it is a folder";
  return "";
}

std::string cannot_write_message(const std::string& path) {
  const int error = errno;
  if (std::string problem = output_path_problem(path); !problem.empty()) return problem;
  if (error != 0) return "cannot write " + path + ": " + std::strerror(error);
  return "cannot write " + path;
}

}  // namespace nbar
