// Small builders of OptionRule for the requests' rule tables (requests.cpp,
// synthesis_request.cpp): one place that says which fields each kind of rule sets.
#pragma once

#include <climits>
#include <string>
#include <utility>
#include <vector>

#include "nbar/request/options.hpp"

namespace nbar::request::rule_builders {

inline constexpr double kIntMax = INT_MAX;

inline OptionRule rule(std::string key, OptionKind kind, std::string help) {
  OptionRule r;
  r.key = std::move(key);
  r.kind = kind;
  r.help = std::move(help);
  return r;
}

inline OptionRule integer_rule(std::string key, std::string help, double low, double high) {
  OptionRule r = rule(std::move(key), OptionKind::Integer, std::move(help));
  r.low = low;
  r.high = high;
  return r;
}

inline OptionRule positive_integer(std::string key, std::string help) {
  OptionRule r = rule(std::move(key), OptionKind::Integer, std::move(help));
  r.positive = true;
  r.high = kIntMax;
  return r;
}

inline OptionRule number_rule(std::string key, std::string help, double low, double high) {
  OptionRule r = rule(std::move(key), OptionKind::Number, std::move(help));
  r.low = low;
  r.high = high;
  return r;
}

inline OptionRule positive_number(std::string key, std::string help) {
  OptionRule r = rule(std::move(key), OptionKind::Number, std::move(help));
  r.positive = true;
  return r;
}

inline OptionRule flag(std::string key, std::string help) {
  return rule(std::move(key), OptionKind::Flag, std::move(help));
}
inline OptionRule text(std::string key, std::string help) {
  return rule(std::move(key), OptionKind::Text, std::move(help));
}
inline OptionRule names(std::string key, std::string help) {
  return rule(std::move(key), OptionKind::Names, std::move(help));
}

inline OptionRule choice(std::string key, std::string help, std::vector<std::string> choices) {
  OptionRule r = rule(std::move(key), OptionKind::Choice, std::move(help));
  r.choices = std::move(choices);
  return r;
}

}  // namespace nbar::request::rule_builders
