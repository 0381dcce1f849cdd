#include "request/answer_language.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>

#include "io/json_text.hpp"

namespace nbar::request {

namespace {

using Json = nlohmann::ordered_json;  // keeps the writer's order of keys

void translate_strings(Json& value, Language language) {
  if (value.is_string()) {
    value = translate(value.get_ref<const std::string&>(), language);
  } else if (value.is_array()) {
    for (Json& item : value)
      if (item.is_string()) translate_strings(item, language);
  }
}

void translate_tree(Json& node, Language language) {
  if (node.is_array()) {
    for (Json& item : node) translate_tree(item, language);
    return;
  }
  if (!node.is_object()) return;
  for (auto it = node.begin(); it != node.end(); ++it) {
    if (is_message_field(it.key())) translate_strings(it.value(), language);
    translate_tree(it.value(), language);
  }
}

}  // namespace

bool is_message_field(const std::string& key) {
  static const std::array<std::string_view, 9> kFields = {"message", "stop_reason", "label",    "start",      "joints",
                                                          "grashof", "immobile",    "warnings", "description"};
  return std::find(kFields.begin(), kFields.end(), key) != kFields.end();
}

std::string translate_json_answer(const std::string& json, Language language, int indent) {
  if (language == Language::English) return json;
  Json answer = Json::parse(json, nullptr, false);
  if (answer.is_discarded()) return json;
  translate_tree(answer, language);
  std::string out = io::json_text(answer, indent);
  if (!json.empty() && json.back() == '\n') out += '\n';
  return out;
}

int json_answer_indent(const std::string& json) {
  if (json.size() < 2 || json[1] != '\n') return -1;
  const std::size_t first = json.find_first_not_of(' ', 2);
  return first == std::string::npos ? -1 : static_cast<int>(first - 2);
}

}  // namespace nbar::request
