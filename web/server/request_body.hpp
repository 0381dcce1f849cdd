// Request bodies: the JSON object an endpoint is sent, its duplicate keys refused, its model or
// task read as a document, its options handed to the request layer (nbar/request).
#pragma once

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "api_internal.hpp"
#include "io/json_text.hpp"
#include "nbar/request/options.hpp"

namespace nbar::web {

[[noreturn]] inline void bad_input(const std::string& message) { throw ApiError(ApiErrorKind::BadInput, message); }

// Line and column (1-based) of a byte offset in a text.
std::pair<int, int> line_column(const std::string& text, std::size_t offset);

// A model or task sent as a JSON object is read as the indented JSON text it makes; its depth and
// the size of that text are bounded first.
void check_document_shape(const nlohmann::json& document, const char* key);

// The request's JSON, with a key given twice in one object refused (nlohmann keeps the last).
nlohmann::json parse_request(const std::string& text);

// The request's JSON object: every key one the endpoint knows; the options handed to the endpoint's
// request (nbar/request) by options(), the documents (a model's or a task's text) read here.
class RequestBody {
 public:
  // A body whose options are a request's (`rules`, read by the request layer) beside the
  // `documents` the endpoint reads itself (the model's text, the render's kind); any other key is
  // refused by the request layer's rule (request::unknown_key), listing the keys it takes.
  RequestBody(const std::string& text, const std::vector<request::OptionRule>& rules,
              const std::vector<std::string>& documents);
  // A body of documents only (a check's model).
  RequestBody(const std::string& text, const std::vector<std::string>& documents) : RequestBody(text, {}, documents) {}

  bool has(const char* key) const { return json_.contains(key) && !json_[key].is_null(); }

  // A text (or, for `model` and `task`, a JSON object, read as the same document).
  std::string text(const char* key, bool document = false) const {
    if (!has(key)) bad_input(std::string("missing '") + key + "'");
    const nlohmann::json& v = json_[key];
    if (v.is_string()) return v.get<std::string>();
    if (document && v.is_object()) {
      check_document_shape(v, key);
      return io::json_text(v, 2) + "\n";
    }
    bad_input(std::string("'") + key + "' must be " + (document ? "the text of a YAML or JSON document" : "a string"));
  }
  bool flag(const char* key) const {
    if (!has(key)) return false;
    if (!json_[key].is_boolean()) bad_input(std::string("'") + key + "' must be true or false");
    return json_[key].get<bool>();
  }

  // Every option but the `documents` (the model's or task's text), as the request layer reads them:
  // JSON's values as they are, null as absent.
  request::Options options(const std::vector<std::string>& documents) const;

 private:
  nlohmann::json json_;
};

}  // namespace nbar::web
