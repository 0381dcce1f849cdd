// JSON as text, the one way every writer and the server print it. The readers reject text that
// is not UTF-8, so invalid bytes should never get this far; should some (from a caller's own
// model or an option), they are written as U+FFFD instead of aborting the program.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace nbar::io {

// For nlohmann::json and nlohmann::ordered_json alike (a conversion would reorder the keys).
template <typename Json>
std::string json_text(const Json& j, int indent) {
  return j.dump(indent, ' ', false, Json::error_handler_t::replace);
}

}  // namespace nbar::io
