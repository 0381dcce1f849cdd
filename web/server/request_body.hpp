// Request bodies: the JSON object an endpoint is sent, its duplicate keys refused, its model or
// task read as a document, its options handed to the request layer (nbar/request) or read one by
// one for the endpoints that have no request type yet.
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
// request (nbar/request) by options(), the documents (a model's or a task's text) and the
// options of the endpoints without a request type read here.
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
  std::optional<std::string> optional_text(const char* key) const {
    if (!has(key)) return std::nullopt;
    return text(key);
  }
  // An integer in [lo, hi] (the CLI's range); larger values than `limit` are over the server's
  // limit (413), other values outside the range are bad input (400).
  // `shown_hi`, when given, is the top of the range the message names: the server's limit
  // (checked after, with its own answer) when it is lower than what the option could ever be.
  std::optional<long long> integer(const char* key, long long lo, long long hi, long long shown_hi = -1) const {
    if (!has(key)) return std::nullopt;
    const nlohmann::json& v = json_[key];
    const auto out_of_range = [&](const std::string& shown) {
      bad_input(fmt::format("'{}' must be from {} to {}; it is {}", key, lo, shown_hi >= lo ? shown_hi : hi, shown));
    };
    if (v.is_number_unsigned()) {
      const unsigned long long u = v.get<unsigned long long>();
      if (u > static_cast<unsigned long long>(hi) || (lo > 0 && u < static_cast<unsigned long long>(lo)))
        out_of_range(std::to_string(u));
      return static_cast<long long>(u);
    }
    if (v.is_number_integer()) {
      const long long i = v.get<long long>();
      if (i < lo || i > hi) out_of_range(std::to_string(i));
      return i;
    }
    if (v.is_number_float()) {
      const double d = v.get<double>();
      if (!(std::isfinite(d) && std::floor(d) == d)) bad_input(std::string("'") + key + "' must be a whole number");
      if (d < static_cast<double>(lo) || d > static_cast<double>(hi)) out_of_range(fmt::format("{}", d));
      return static_cast<long long>(d);
    }
    bad_input(std::string("'") + key + "' must be a whole number");
  }
  std::optional<double> number(const char* key) const {
    if (!has(key)) return std::nullopt;
    const nlohmann::json& v = json_[key];
    if (!v.is_number() || !std::isfinite(v.get<double>())) bad_input(std::string("'") + key + "' must be a number");
    return v.get<double>();
  }
  bool flag(const char* key) const {
    if (!has(key)) return false;
    if (!json_[key].is_boolean()) bad_input(std::string("'") + key + "' must be true or false");
    return json_[key].get<bool>();
  }
  // A list of names: an array of strings, or one comma-separated string (as on the command line).
  std::vector<std::string> list(const char* key) const {
    std::vector<std::string> out;
    if (!has(key)) return out;
    const nlohmann::json& v = json_[key];
    if (v.is_string()) {
      std::stringstream in(v.get<std::string>());
      for (std::string item; std::getline(in, item, ',');)
        if (!item.empty()) out.push_back(item);
      return out;
    }
    if (v.is_array()) {
      for (const auto& item : v) {
        if (!item.is_string()) bad_input(std::string("'") + key + "' must be a list of names");
        out.push_back(item.get<std::string>());
      }
      return out;
    }
    bad_input(std::string("'") + key + "' must be a list of names or a comma-separated string");
  }
  std::vector<double> numbers(const char* key) const {
    std::vector<double> out;
    if (!has(key)) return out;
    const nlohmann::json& v = json_[key];
    if (!v.is_array()) bad_input(std::string("'") + key + "' must be a list of numbers");
    for (const auto& item : v) {
      if (!item.is_number() || !std::isfinite(item.get<double>()))
        bad_input(std::string("'") + key + "' must be a list of numbers");
      out.push_back(item.get<double>());
    }
    return out;
  }
  std::string choice(const char* key, const std::vector<std::string>& choices, const std::string& otherwise) const {
    if (!has(key)) return otherwise;
    const std::string value = text(key);
    if (std::find(choices.begin(), choices.end(), value) != choices.end()) return value;
    std::string list;
    for (const std::string& c : choices) list += (list.empty() ? "" : ", ") + c;
    bad_input(std::string("'") + key + "' must be one of: " + list + "; it is '" + value + "'");
  }

  // Every option but the `documents` (the model's or task's text), as the request layer reads them:
  // JSON's values as they are, null as absent.
  request::Options options(const std::vector<std::string>& documents) const;

 private:
  nlohmann::json json_;
};

}  // namespace nbar::web
