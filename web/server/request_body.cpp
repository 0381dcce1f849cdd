#include "request_body.hpp"

#include <unordered_set>

#include "io/json_text.hpp"
#include "io/yaml_support.hpp"

namespace nbar::web {

// Line and column (1-based) of a byte offset in a text.
std::pair<int, int> line_column(const std::string& text, std::size_t offset) {
  int line = 1, column = 1;
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return {line, column};
}

// A model or task sent as a JSON object is read as the indented JSON text it makes. Its depth,
// and a bound on that text's size, are checked before it is written: the writer recurses once a
// level (a 200 kB body nested 100 000 deep overflowed the stack), and every level indents every
// line below it (20 000 levels in 40 kB made 800 MB of text).
void check_document_shape(const nlohmann::json& document, const char* key) {
  constexpr int kMaxDepth = 64;
  constexpr std::size_t kPerValue = 40;  // a number's digits, punctuation, a line end
  std::vector<std::pair<const nlohmann::json*, int>> stack{{&document, 1}};
  std::size_t bound = 0;
  while (!stack.empty()) {
    const auto [node, depth] = stack.back();
    stack.pop_back();
    if (depth > kMaxDepth) bad_input(fmt::format("'{}' nests deeper than {} levels", key, kMaxDepth));
    bound += 2 * static_cast<std::size_t>(depth) + kPerValue;
    if (node->is_string()) bound += 6 * node->get_ref<const std::string&>().size();  // \uXXXX at worst
    if (node->is_object()) {
      for (auto it = node->begin(); it != node->end(); ++it) {
        bound += 6 * it.key().size();
        stack.emplace_back(&*it, depth + 1);
      }
    } else if (node->is_array()) {
      for (const nlohmann::json& child : *node) stack.emplace_back(&child, depth + 1);
    }
  }
  check_limit("model_bytes", static_cast<double>(bound), static_cast<double>(io::yaml::kMaxFileBytes),
              fmt::format("the size of '{}' written out as indented JSON (a bound, in bytes)", key));
}

// The request's JSON, with every object's keys told apart: nlohmann keeps the last of a key given
// twice ({"steps": 5, "steps": 500}), silently. The parser's events are followed with a set of
// the keys seen in each open object (only while parsing); the first key given twice is a 400
// naming it and where it is ("model.points"), before anything else is read.
nlohmann::json parse_request(const std::string& text) {
  struct Open {
    std::unordered_set<std::string> keys;
    std::string name;  // this object's own key in its parent, "[]" inside a list
  };
  std::vector<Open> open;
  std::string key;  // the last key read: the name of an object that starts next
  return nlohmann::json::parse(text, [&](int, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    using Event = nlohmann::json::parse_event_t;
    switch (event) {
      case Event::object_start:
      case Event::array_start:
        open.push_back({{}, open.empty() ? std::string() : key});
        key = "[]";  // a list's items have no key of their own
        break;
      case Event::object_end:
      case Event::array_end:
        if (!open.empty()) open.pop_back();
        key = "[]";
        break;
      case Event::key:
        key = parsed.get<std::string>();
        if (!open.empty() && !open.back().keys.insert(key).second) {
          std::string where;
          for (const Open& o : open)
            if (!o.name.empty()) where += (where.empty() || o.name == "[]" ? "" : ".") + o.name;
          throw ApiError(ApiErrorKind::BadJson,
                         where.empty() ? fmt::format("the body gives '{}' twice; give each option once", key)
                                       : fmt::format("the body gives the key '{}' twice in '{}'", key, where),
                         Json{{"key", key}});
        }
        break;
      case Event::value: break;
    }
    return true;
  });
}

RequestBody::RequestBody(const std::string& text, const std::vector<request::OptionRule>& rules,
                         const std::vector<std::string>& documents) {
  try {
    json_ = parse_request(text);
  } catch (const nlohmann::json::parse_error& e) {
    const auto [line, column] = line_column(text, e.byte > 0 ? e.byte - 1 : 0);
    throw ApiError(ApiErrorKind::BadJson, std::string("the body is not valid JSON: ") + e.what(),
                   Json{{"line", line}, {"column", column}});
  } catch (const nlohmann::json::exception& e) {
    // A number beyond a double's range (1e400): the parser gives no place for it.
    throw ApiError(ApiErrorKind::BadJson, std::string("the body is not valid JSON: ") + e.what());
  }
  if (!json_.is_object())
    throw ApiError(ApiErrorKind::BadJson, "the body must be a JSON object, e.g. {\"model\": \"...\"}");
  std::vector<std::string> given;
  // "lang", the language of the answer's messages, is every endpoint's and read by handle_api.
  for (const auto& [key, value] : json_.items())
    if (key != "lang") given.push_back(key);
  if (const std::optional<std::string> key = request::unknown_key(given, rules, documents)) {
    std::string list;
    for (const std::string& k : request::known_keys(rules, documents)) list += (list.empty() ? "" : ", ") + k;
    bad_input("unknown option '" + *key + "'; this endpoint takes: " + list);
  }
}

request::Options RequestBody::options(const std::vector<std::string>& documents) const {
  request::Options options;
  for (const auto& [key, value] : json_.items()) {
    if (value.is_null() || key == "lang" || std::find(documents.begin(), documents.end(), key) != documents.end())
      continue;
    if (value.is_boolean()) {
      options.set(key, value.get<bool>());
    } else if (value.is_number_integer() && !value.is_number_unsigned()) {
      options.set(key, value.get<long long>());
    } else if (value.is_number()) {  // a float, or an unsigned integer that may not fit a long long
      options.set(key, value.get<double>());
    } else if (value.is_string()) {
      options.set(key, value.get<std::string>());
    } else if (value.is_array() &&
               std::all_of(value.begin(), value.end(), [](const auto& v) { return v.is_string(); })) {
      options.set(key, value.get<std::vector<std::string>>());  // an empty list too
    } else if (value.is_array() &&
               std::all_of(value.begin(), value.end(), [](const auto& v) { return v.is_number(); })) {
      std::vector<double> numbers;
      for (const auto& v : value) numbers.push_back(v.get<double>());
      options.set(key, numbers);
    } else {
      // An object or a mixed list: its JSON text, which no rule but a text's accepts.
      options.set(key, value.dump());
    }
  }
  return options;
}

}  // namespace nbar::web
