// JSON as text, the one way every writer and the server print it. The readers reject text that
// is not UTF-8, so invalid bytes should never get this far; should some (from a caller's own
// model or an option), they are written as U+FFFD instead of aborting the program.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace nbar::io {

inline std::string json_text(const nlohmann::json& j, int indent) {
  return j.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace nbar::io
