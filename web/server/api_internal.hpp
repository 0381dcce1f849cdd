// Inside the API (api.cpp, errors.cpp, limits.cpp): its kinds of error, their HTTP statuses,
// and the checks of a request against the limits.
#pragma once

#include <nlohmann/json.hpp>

#include <optional>
#include <stdexcept>
#include <string>

#include "nbar/io/model_file.hpp"
#include "nbar/model/diagnostics.hpp"
#include "nbar/model/model.hpp"
#include "nbar/web/api.hpp"

namespace nbar::web {

using Json = nlohmann::ordered_json;

// The library's kinds (nbar::ErrorKind) and the server's own.
enum class ApiErrorKind {
  BadJson,           // the body is not a JSON object
  BadInput,          // an option of the wrong type or out of range
  InvalidModel,      // the model or task text: syntax, names, geometry, drivers
  UndefinedLaw,      // a motion or load law with no value where it is needed
  CannotAssemble,    // no pose at the start
  StoppedAtLimit,    // the explanation of a step the sweep never reached
  TimeBudget,        // the computation ran past the time budget and was cancelled
  BodyTooLarge,      // the request body is over the limit
  LimitExceeded,     // the request asks for more than a limit allows
  TooManyJobs,       // every job slot is taken
  NotFound,          // no such endpoint or file
  MethodNotAllowed,  // the endpoint exists, not for this method
  NotImplemented,    // the server cannot do it here (MP4 without ffmpeg)
  Internal,          // a bug
};

// The one place where kinds of error become HTTP statuses.
int http_status(ApiErrorKind kind);
const char* to_string(ApiErrorKind kind);
ApiErrorKind api_kind(ErrorKind kind);

// An error the API answers; `details` go into the error object beside kind and message.
class ApiError : public std::runtime_error {
 public:
  ApiError(ApiErrorKind kind, const std::string& message, Json details = Json::object())
      : std::runtime_error(message), kind_(kind), details_(std::move(details)) {}
  ApiErrorKind kind() const { return kind_; }
  const Json& details() const { return details_; }

 private:
  ApiErrorKind kind_;
  Json details_;
};

// {"error": {"kind", "message", ...details}} with its status.
ApiResponse error_answer(ApiErrorKind kind, const std::string& message, const Json& details = Json::object());
// A library error: its line and column (from the error, or from `source` for an error about a
// model entity) and the entity, named when `model` is known.
ApiResponse error_answer(const Error& error, const Model* model = nullptr, const io::SourceMap* source = nullptr);

// A number for a JSON answer: an integer when it is whole (2000, not 2000.0), so that a limit
// reads as the count it is; otherwise the double.
Json json_number(double v);

// 413 limit_exceeded unless value <= max: "`what` is <value>; this server allows at most <max>".
void check_limit(const char* limit, double value, double max, const std::string& what);

}  // namespace nbar::web
