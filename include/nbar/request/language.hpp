// The language of an answer's messages. The core writes its messages (errors, the sweep's stop
// and warnings, the check's joints and Grashof classes, explain's row labels and Newton start)
// in English, the same text in the CLI, Python and the API; one catalogue here knows each by its
// English template and says it again in another language, so that every front-end that takes a
// language (the web API's `lang`, Accept-Language) answers in it. A message no template matches
// is kept as the core wrote it: English is the fallback, never a blank.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace nbar::request {

enum class Language { English, Spanish };

// "en" or "es" (case-insensitive, a region such as "es-ES" allowed); anything else is an
// OptionError naming the option `lang`.
Language read_language(std::string_view code);

// The first language of an HTTP Accept-Language header that the catalogue speaks, by the order
// given (weights are not weighed: browsers list by preference); English when none is.
Language accept_language(std::string_view header);

// "en", "es".
std::string language_code(Language language);

// The message in `language`: its catalogue template with its parameters put back (those that are
// themselves messages translated in turn), or the message unchanged when no template matches.
std::string translate(std::string_view message, Language language);

// One catalogue entry: a stable code, the core's English with {name} for each parameter
// ({name:msg} a nested message, {name:word} a word of the catalogue, {name:list} a list whose
// last "or" is said in the language) and the same message in Spanish.
struct MessageTemplate {
  std::string_view code, english, spanish;
};
const std::vector<MessageTemplate>& message_catalogue();

// The codes of the templates a message matches, its own first, then those of its nested
// messages; empty when no template matches. For tests that hold the catalogue to the core.
std::vector<std::string> message_codes(std::string_view message);

}  // namespace nbar::request
