// Errors as JSON, and the one mapping of kinds of error to HTTP statuses.
#include <fmt/format.h>

#include <cmath>

#include "api_internal.hpp"
#include "io/json_text.hpp"
#include "nbar/request/options.hpp"

namespace nbar::web {

int http_status(ApiErrorKind kind) {
  switch (kind) {
    case ApiErrorKind::BadJson: return 400;
    case ApiErrorKind::BadInput: return 400;
    case ApiErrorKind::InvalidModel: return 422;
    case ApiErrorKind::UndefinedLaw: return 422;
    case ApiErrorKind::CannotAssemble: return 422;
    case ApiErrorKind::StoppedAtLimit: return 422;
    case ApiErrorKind::TimeBudget: return 504;
    case ApiErrorKind::BodyTooLarge: return 413;
    case ApiErrorKind::LimitExceeded: return 413;
    case ApiErrorKind::TooManyJobs: return 503;
    case ApiErrorKind::NotFound: return 404;
    case ApiErrorKind::MethodNotAllowed: return 405;
    case ApiErrorKind::NotImplemented: return 501;
    case ApiErrorKind::Internal: return 500;
  }
  return 500;
}

const char* to_string(ApiErrorKind kind) {
  switch (kind) {
    case ApiErrorKind::BadJson: return "bad_json";
    case ApiErrorKind::BadInput: return "bad_input";
    case ApiErrorKind::InvalidModel: return "invalid_model";
    case ApiErrorKind::UndefinedLaw: return "undefined_law";
    case ApiErrorKind::CannotAssemble: return "cannot_assemble";
    case ApiErrorKind::StoppedAtLimit: return "stopped_at_limit";
    case ApiErrorKind::TimeBudget: return "time_budget_exceeded";
    case ApiErrorKind::BodyTooLarge: return "body_too_large";
    case ApiErrorKind::LimitExceeded: return "limit_exceeded";
    case ApiErrorKind::TooManyJobs: return "too_many_jobs";
    case ApiErrorKind::NotFound: return "not_found";
    case ApiErrorKind::MethodNotAllowed: return "method_not_allowed";
    case ApiErrorKind::NotImplemented: return "not_implemented";
    case ApiErrorKind::Internal: return "internal";
  }
  return "internal";
}

ApiErrorKind api_kind(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::InvalidModel: return ApiErrorKind::InvalidModel;
    case ErrorKind::BadInput: return ApiErrorKind::BadInput;
    case ErrorKind::CannotAssemble: return ApiErrorKind::CannotAssemble;
    case ErrorKind::StoppedAtLimit: return ApiErrorKind::StoppedAtLimit;
    case ErrorKind::UndefinedLaw: return ApiErrorKind::UndefinedLaw;
    case ErrorKind::Cancelled: return ApiErrorKind::TimeBudget;  // the server cancels only by its deadline
    case ErrorKind::Internal: return ApiErrorKind::Internal;
  }
  return ApiErrorKind::Internal;
}

ApiResponse error_answer(ApiErrorKind kind, const std::string& message, const Json& details) {
  Json error;
  error["kind"] = to_string(kind);
  error["message"] = message;
  for (const auto& [key, value] : details.items()) error[key] = value;
  ApiResponse r;
  r.status = http_status(kind);
  r.body = io::json_text(Json{{"error", error}}, 2) + '\n';
  return r;
}

namespace {

// The entity's name in the model, when it has one.
std::string entity_name(const Model& m, const EntityRef& ref) {
  const auto at = [&](const auto& items) -> std::string {
    return ref.index >= 0 && ref.index < static_cast<int>(items.size()) ? items[ref.index].name : std::string();
  };
  switch (ref.kind) {
    case EntityRef::Kind::Point: return at(m.points);
    case EntityRef::Kind::Body: return at(m.bodies);
    case EntityRef::Kind::Driver: return at(m.drivers);
    case EntityRef::Kind::Spring: return at(m.springs);
    default: return {};
  }
}

}  // namespace

ApiResponse error_answer(const Error& error, const Model* model, const io::SourceMap* source) {
  Json details = Json::object();
  // Placed in the model's text by the rule the command line uses (io::located).
  const Error placed = source ? io::located(*source, error) : error;
  const SourceMark mark = placed.mark();
  const std::string& file = placed.file();
  if (!file.empty()) details["file"] = file;
  if (mark.line > 0) {
    details["line"] = mark.line;
    details["column"] = mark.column;
  }
  const EntityRef& where = error.where();
  if (where.kind != EntityRef::Kind::Model && where.index >= 0) {
    Json entity = {{"kind", to_string(where.kind)}, {"index", where.index}};
    if (model) {
      const std::string name = entity_name(*model, where);
      if (!name.empty()) entity["name"] = name;
    }
    details["entity"] = entity;
  }
  if (const auto* option = dynamic_cast<const request::OptionError*>(&error)) details["option"] = option->option();
  const ApiErrorKind kind = api_kind(error.kind());
  const std::string message = kind == ApiErrorKind::TimeBudget
                                  ? "the computation took longer than this server's time budget and was stopped"
                                  : error.message();
  return error_answer(kind, message, details);
}

Json json_number(double v) {
  // Beyond 2^53 a double no longer holds every integer: those stay doubles.
  constexpr double kExact = 9007199254740992.0;
  if (std::isfinite(v) && std::floor(v) == v && std::abs(v) <= kExact) return static_cast<long long>(v);
  return v;
}

void check_limit(const char* limit, double value, double max, const std::string& what) {
  if (value <= max) return;
  throw ApiError(ApiErrorKind::LimitExceeded, fmt::format("{} is {}; this server allows at most {}", what, value, max),
                 Json{{"limit", limit}, {"max", json_number(max)}, {"value", json_number(value)}});
}

}  // namespace nbar::web
