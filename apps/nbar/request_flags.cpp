#include "request_flags.hpp"

#include <cmath>

namespace nbar::cli {

namespace {

// The type CLI11's help shows after the flag, as it showed for the typed options before
// ("INT:POSITIVE", "INT:[0 to 5]", "TEXT:{csv,json,table}").
std::string type_name(const request::OptionRule& rule) {
  using request::OptionKind;
  const bool is_integer = rule.kind == OptionKind::Integer;
  if (is_integer || rule.kind == OptionKind::Number) {
    std::string name = is_integer ? "INT" : "FLOAT";
    if (rule.positive) return name + ":POSITIVE";
    if (std::isfinite(rule.low) && std::isfinite(rule.high) && rule.high < 2147483647.0)
      return name + ":[" + request::number_text(rule.low) + " to " + request::number_text(rule.high) + "]";
    return name;
  }
  if (rule.kind == OptionKind::Choice) {
    std::string name = "TEXT:{";
    for (std::size_t i = 0; i < rule.choices.size(); ++i) name += (i ? "," : "") + rule.choices[i];
    return name + "}";
  }
  if (rule.kind == OptionKind::Numbers) return "FLOAT";
  return "TEXT";
}

}  // namespace

RequestFlags& RequestFlags::add(std::initializer_list<std::string_view> keys) {
  using request::OptionKind;
  for (const std::string_view key : keys) {
    const request::OptionRule& rule = request::rule_of(rules_, key);
    auto given = std::make_unique<Given>();
    given->kind = rule.kind;
    const std::string flag = spell_flag(key);
    const std::string help = request::spell_keys(rule.help, spell_flag);
    if (rule.kind == OptionKind::Flag) {
      given->option = command_.add_flag(flag, given->on, help);
    } else if (rule.kind == OptionKind::Names || rule.kind == OptionKind::Numbers) {
      given->option = command_.add_option(flag, given->list, help)->delimiter(',')->type_name(type_name(rule));
      if (rule.count > 0) given->option->expected(static_cast<int>(rule.count));
    } else {
      given->option = command_.add_option(flag, given->text, help)->type_name(type_name(rule));
    }
    given_.emplace(std::string(key), std::move(given));
  }
  return *this;
}

Option* RequestFlags::option(std::string_view key) const {
  const auto it = given_.find(key);
  return it == given_.end() ? nullptr : it->second->option;
}

request::Options RequestFlags::options() const {
  request::Options options(true);  // what was typed
  for (const auto& [key, given] : given_) {
    if (given->option->count() == 0) continue;
    switch (given->kind) {
      case request::OptionKind::Flag: options.set(key, given->on); break;
      case request::OptionKind::Names:
      case request::OptionKind::Numbers: options.set(key, given->list); break;
      default: options.set(key, given->text); break;
    }
  }
  return options;
}

}  // namespace nbar::cli
