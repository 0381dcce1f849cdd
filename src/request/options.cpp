#include "nbar/request/options.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace nbar::request {

namespace {

// A range's top this large is no limit a person means (INT_MAX of a step): messages leave it out.
constexpr double kNoTop = 2147483647.0;

std::string joined(const std::vector<std::string>& items, const char* separator) {
  std::string out;
  for (const std::string& item : items) out += (out.empty() ? "" : separator) + item;
  return out;
}

// A number and how the user wrote it (the text as given, so that a message quotes it).
struct GivenNumber {
  double value;
  std::string shown;
};

GivenNumber given_number(const OptionRule& rule, const Value& value, bool text_values) {
  if (const auto* i = std::get_if<long long>(&value)) return {static_cast<double>(*i), std::to_string(*i)};
  if (const auto* d = std::get_if<double>(&value)) {
    if (!std::isfinite(*d)) throw OptionError(rule.key, "must be a finite number, not " + number_text(*d));
    return {*d, number_text(*d)};
  }
  if (const auto* text = std::get_if<std::string>(&value)) {
    if (!text_values)
      throw OptionError(rule.key, literal((rule.kind == OptionKind::Integer ? "must be a whole number, not the text '"
                                                                            : "must be a number, not the text '") +
                                          *text + "'"));
    const std::optional<double> x = finite_number(*text);
    if (!x) throw OptionError(rule.key, literal("'" + *text + "' is not a finite number"));
    return {*x, *text};
  }
  throw OptionError(rule.key, rule.kind == OptionKind::Integer ? "must be a whole number" : "must be a number");
}

void check_range(const OptionRule& rule, const GivenNumber& x) {
  if (rule.positive) {
    if (!(x.value > 0.0)) throw OptionError(rule.key, "must be a positive number, not " + x.shown);
    if (x.value > rule.high)
      throw OptionError(rule.key, "must be a positive number up to " + number_text(rule.high) + ", not " + x.shown);
    return;
  }
  if (x.value >= rule.low && x.value <= rule.high) return;
  const bool bounded_below = std::isfinite(rule.low);
  const bool bounded_above = std::isfinite(rule.high) && (rule.high < kNoTop || x.value > rule.high);
  if (bounded_below && bounded_above)
    throw OptionError(rule.key,
                      "must be from " + number_text(rule.low) + " to " + number_text(rule.high) + ", not " + x.shown);
  if (bounded_below) throw OptionError(rule.key, "must be " + number_text(rule.low) + " or more, not " + x.shown);
  throw OptionError(rule.key, "must be at most " + number_text(rule.high) + ", not " + x.shown);
}

}  // namespace

std::string number_text(double x) {
  if (std::floor(x) == x && std::abs(x) < 1e15) return std::to_string(static_cast<long long>(x));
  std::ostringstream s;
  s << x;
  return s.str();
}

std::optional<double> finite_number(const std::string& text) {
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const double x = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(x)) return std::nullopt;
  return x;
}

const Value* Options::find(std::string_view key) const {
  const auto it = values_.find(key);
  return it == values_.end() ? nullptr : &it->second;
}

std::string spell_keys(const std::string& text, const std::function<std::string(std::string_view)>& spell) {
  std::string out;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t open = text.find('{', at);
    if (open != std::string::npos && open + 1 < text.size() && text[open + 1] == '{') {  // "{{": a brace
      out += text.substr(at, open + 1 - at);
      at = open + 2;
      continue;
    }
    const std::size_t close = open == std::string::npos ? open : text.find('}', open);
    const bool is_key = close != std::string::npos && close > open + 1 &&
                        std::all_of(text.begin() + static_cast<std::ptrdiff_t>(open) + 1,
                                    text.begin() + static_cast<std::ptrdiff_t>(close),
                                    [](char c) { return (c >= 'a' && c <= 'z') || c == '_'; });
    if (!is_key) {
      out += text.substr(at, open == std::string::npos ? std::string::npos : open + 1 - at);
      at = open == std::string::npos ? text.size() : open + 1;
      continue;
    }
    out += text.substr(at, open - at) + spell(std::string_view(text).substr(open + 1, close - open - 1));
    at = close + 1;
  }
  return out;
}

OptionError::OptionError(std::string option, std::string problem, bool reads_on)
    : Error(ErrorKind::BadInput, option + (reads_on ? " " : ": ") + spell_keys(problem, key_name)),
      option_(std::move(option)),
      problem_(std::move(problem)),
      reads_on_(reads_on) {}

std::string OptionError::problem(const std::function<std::string(std::string_view)>& spell) const {
  return spell_keys(problem_, spell);
}

std::string OptionError::spelled(const std::function<std::string(std::string_view)>& spell) const {
  return spell(option_) + (reads_on_ ? " " : ": ") + problem(spell);
}

std::string key_name(std::string_view key) { return std::string(key); }

std::string literal(std::string_view text) {
  std::string out;
  for (const char c : text) out += c == '{' ? std::string("{{") : std::string(1, c);
  return out;
}

std::string flag_name(std::string_view key) {
  std::string flag = "--";
  for (const char c : key) flag += c == '_' ? '-' : c;
  return flag;
}

std::vector<std::string> known_keys(const std::vector<OptionRule>& rules, const std::vector<std::string>& documents) {
  std::vector<std::string> keys = documents;
  for (const OptionRule& r : rules) keys.push_back(r.key);
  return keys;
}

std::optional<std::string> unknown_key(const std::vector<std::string>& given, const std::vector<OptionRule>& rules,
                                       const std::vector<std::string>& documents) {
  const std::vector<std::string> keys = known_keys(rules, documents);
  for (const std::string& key : given)
    if (std::find(keys.begin(), keys.end(), key) == keys.end()) return key;
  return std::nullopt;
}

void check_known(const Options& options, const std::vector<OptionRule>& rules, const std::string& request_name) {
  std::vector<std::string> given;
  for (const auto& [key, value] : options.values()) given.push_back(key);
  if (const std::optional<std::string> key = unknown_key(given, rules)) {
    std::vector<std::string> marked;  // each spelled by the front-end
    for (const std::string& k : known_keys(rules)) marked.push_back("{" + k + "}");
    throw OptionError(*key, "unknown option of " + literal(request_name) + "; it takes: " + joined(marked, ", "));
  }
}

const OptionRule& rule_of(const std::vector<OptionRule>& rules, std::string_view key) {
  for (const OptionRule& r : rules)
    if (r.key == key) return r;
  throw Error(ErrorKind::BadInput, "no option '" + std::string(key) + "'");
}

std::optional<long long> read_integer(const Options& options, const OptionRule& rule) {
  const Value* value = options.find(rule.key);
  if (!value) return std::nullopt;
  const GivenNumber x = given_number(rule, *value, options.text_values());
  if (std::floor(x.value) != x.value) throw OptionError(rule.key, "must be a whole number, not " + x.shown);
  check_range(rule, x);
  // Ranges of whole numbers end within long long (a rule's high is at most INT_MAX or so).
  return static_cast<long long>(x.value);
}

std::optional<double> read_number(const Options& options, const OptionRule& rule) {
  const Value* value = options.find(rule.key);
  if (!value) return std::nullopt;
  const GivenNumber x = given_number(rule, *value, options.text_values());
  check_range(rule, x);
  return x.value;
}

bool read_flag(const Options& options, const OptionRule& rule) {
  const Value* value = options.find(rule.key);
  if (!value) return false;
  if (const auto* b = std::get_if<bool>(value)) return *b;
  throw OptionError(rule.key, "must be true or false");
}

std::optional<std::string> read_text(const Options& options, const OptionRule& rule) {
  const Value* value = options.find(rule.key);
  if (!value) return std::nullopt;
  const auto* text = std::get_if<std::string>(value);
  if (!text)
    throw OptionError(rule.key, rule.kind == OptionKind::Choice ? "must be one of " + joined(rule.choices, ", ")
                                                                : std::string("must be a text"));
  if (rule.kind == OptionKind::Choice &&
      std::find(rule.choices.begin(), rule.choices.end(), *text) == rule.choices.end())
    throw OptionError(rule.key, "must be one of " + joined(rule.choices, ", ") + ", not '" + literal(*text) + "'");
  return *text;
}

std::vector<std::string> read_names(const Options& options, const OptionRule& rule) {
  const Value* value = options.find(rule.key);
  if (!value) return {};
  std::vector<std::string> names;
  const auto add_split = [&](const std::string& text) {
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ',');)
      if (!item.empty()) names.push_back(item);
  };
  if (const auto* text = std::get_if<std::string>(value)) {
    add_split(*text);
  } else if (const auto* list = std::get_if<std::vector<std::string>>(value)) {
    for (const std::string& item : *list) add_split(item);
  } else {
    throw OptionError(rule.key, "must be a list of names or a comma-separated text");
  }
  return names;
}

std::vector<double> read_numbers(const Options& options, const OptionRule& rule) {
  const Value* value = options.find(rule.key);
  if (!value) return {};
  std::vector<double> numbers;
  if (const auto* list = std::get_if<std::vector<double>>(value)) {
    numbers = *list;
  } else if (const auto* texts = std::get_if<std::vector<std::string>>(value);
             texts && (options.text_values() || texts->empty())) {
    for (const std::string& text : *texts) {
      const std::optional<double> x = finite_number(text);
      if (!x) throw OptionError(rule.key, literal("'" + text + "' is not a finite number"));
      numbers.push_back(*x);
    }
  } else {
    throw OptionError(rule.key, "must be a list of numbers");
  }
  for (const double x : numbers)
    if (!std::isfinite(x)) throw OptionError(rule.key, "must be a list of finite numbers");
  if (rule.count > 0 && numbers.size() != rule.count)
    throw OptionError(rule.key,
                      "must be " + std::to_string(rule.count) + " numbers, not " + std::to_string(numbers.size()));
  return numbers;
}

}  // namespace nbar::request
