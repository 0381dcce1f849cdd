// JSON as text, the one way every writer and the server print it. The readers reject text that
// is not UTF-8, so invalid bytes should never get this far; should some (from a caller's own
// model or an option), they are written as U+FFFD instead of aborting the program.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "nbar/model/diagnostics.hpp"

namespace nbar::io {

// For nlohmann::json and nlohmann::ordered_json alike (a conversion would reorder the keys).
template <typename Json>
std::string json_text(const Json& j, int indent) {
  return j.dump(indent, ' ', false, Json::error_handler_t::replace);
}

// An answer's `warnings` as code and message, where it has any: an answer without any keeps its
// keys (a simulation's, an equilibrium's).
inline void put_warnings(nlohmann::ordered_json& j, const std::vector<Warning>& warnings) {
  if (warnings.empty()) return;
  nlohmann::ordered_json list = nlohmann::json::array();
  for (const Warning& w : warnings) list.push_back({{"code", w.code}, {"message", w.message}});
  j["warnings"] = list;
}

}  // namespace nbar::io
