// The language nbar speaks its messages in: --lang, else $NBAR_LANG, else English. Only these
// two are read, never LANG or LC_*: a script or a test gets English unless it asks. The words are
// the request layer's catalogue (nbar/request/language.hpp), the same as the web API's, so the
// command line only chooses the language and hands each of the core's messages to it.
#pragma once

#include <cstdlib>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>

#include "nbar/request/language.hpp"
#include "nbar/request/options.hpp"
#include "request/answer_language.hpp"

namespace nbar::cli {

// Set once, after the command line is parsed, before a command runs.
inline request::Language& spoken_language() {
  static request::Language language = request::Language::English;
  return language;
}

// One of the core's messages in the language asked (as it is when the catalogue does not know it).
inline std::string say(std::string_view message) { return request::translate(message, spoken_language()); }

// A JSON answer with its message fields in the language asked, as the web API translates it.
inline std::string say_json(const std::string& json) {
  return request::translate_json_answer(json, spoken_language());
}

// Chooses the language from --lang's text (when given) or $NBAR_LANG. False, after saying why as a
// bad option is said (naming --lang, or NBAR_LANG when the value came from there), when nbar does
// not speak it.
inline bool choose_language(const std::optional<std::string>& flag) {
  const char* environment = std::getenv("NBAR_LANG");
  const bool from_flag = flag.has_value();
  if (!from_flag && (!environment || !*environment)) return true;
  try {
    spoken_language() = request::read_language(from_flag ? *flag : std::string(environment));
  } catch (const request::OptionError& e) {
    std::cerr << e.spelled([from_flag](std::string_view) { return from_flag ? "--lang" : "NBAR_LANG"; })
              << "\nRun with --help for more information.\n";
    return false;
  }
  return true;
}

}  // namespace nbar::cli
