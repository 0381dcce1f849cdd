// An answer's messages in a language (nbar/request/language.hpp), for the front-ends that answer
// in JSON (the web API, the WebAssembly engine). Only the fields that hold the core's prose are
// said again; names, numbers and an error's place (line, column, entity, option) stay as they are.
#pragma once

#include <string>

#include "nbar/request/language.hpp"

namespace nbar::request {

// The fields whose strings are the core's messages: an error's or a warning's "message", a
// sweep's "stop_reason", explain's "label" and Newton "start", the check's "joints" and
// "grashof", the check's "description" of a loop, a rocker, a slider-crank or a quick-return,
// an outline's "immobile", and a list of "warnings" given as plain strings. A "description" the
// core did not write (a model's own) matches no template and stays as it is.
bool is_message_field(const std::string& key);

// A JSON answer's text with those fields in `language`, laid out as it was (indented by
// `indent` spaces, or on one line when -1). The text as it is for English, or when it is not JSON.
std::string translate_json_answer(const std::string& json, Language language, int indent);

// The indentation of a JSON answer as the writers lay it out: the spaces before its first key
// when it starts "{\n", else -1 (one line). Every front-end keeps an answer's layout with it.
int json_answer_indent(const std::string& json);

}  // namespace nbar::request
