// A request's options as a front-end received them, and the rules that read them.
//
// Every front-end fills the same `Options`: the command line with the text after each flag, the
// web server with the JSON body's values, Python with its keyword arguments. The request types
// (request/requests.hpp) read them with one rule per option, so a limit, a default or a message
// is written once and every front-end gives the same answer or the same error. What a front-end
// adds is only its spelling of an option's name: `--mesh-size` on the command line, `mesh_size`
// in JSON and in Python (OptionError::option() is the key; each front-end spells it).
#pragma once

#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "nbar/model/diagnostics.hpp"

namespace nbar::request {

// One option's value as it arrived: the command line gives text (a list option a list of
// texts), JSON and Python give typed values. A number given as text is read by the rule.
using Value = std::variant<bool, long long, double, std::string, std::vector<std::string>, std::vector<double>>;

// The options of one request, by key. Keys are snake_case: the web API's key and Python's
// keyword; the command line spells them in kebab-case (`--max-steps`).
class Options {
 public:
  // `text_values`: every value is the text a person typed (the command line), so a number given
  // as text is read as a number; JSON and Python have numbers of their own, and a text there
  // where a number belongs is refused.
  explicit Options(bool text_values = false) : text_values_(text_values) {}
  void set(const std::string& key, Value value) { values_[key] = std::move(value); }
  const Value* find(std::string_view key) const;
  bool has(std::string_view key) const { return find(key) != nullptr; }
  const std::map<std::string, Value, std::less<>>& values() const { return values_; }
  bool text_values() const { return text_values_; }

 private:
  std::map<std::string, Value, std::less<>> values_;
  bool text_values_;
};

// An option given a value its rule refuses: an Error of kind BadInput that names the option.
// message() is "key: problem" (or "key problem" when the problem reads on from the option's name,
// as in "step 999 is not a solved step (0 to 12)"). A problem that names other options writes
// them as {key}; message() shows them as keys, and spelled() as a front-end spells them.
class OptionError : public Error {
 public:
  OptionError(std::string option, std::string problem, bool reads_on = false);
  const std::string& option() const { return option_; }
  // Whether the problem continues the option's name ("--step 999 is not ...") rather than
  // following it after a colon ("--order: must be from 0 to 5, not 9").
  bool reads_on() const { return reads_on_; }
  // The problem alone, and the whole message, with every key spelled by `spell`.
  std::string problem(const std::function<std::string(std::string_view)>& spell) const;
  std::string spelled(const std::function<std::string(std::string_view)>& spell) const;

 private:
  std::string option_;
  std::string problem_;  // with {key} marks
  bool reads_on_;
};

// `text` with every {key} mark replaced by spell(key) ("{{" is a brace): how a message or a help
// text that names options reads in a front-end.
std::string spell_keys(const std::string& text, const std::function<std::string(std::string_view)>& spell);

// A key as it is: the spelling of JSON and Python.
std::string key_name(std::string_view key);

// Text from elsewhere (a name, another error's message) put in a problem as it is: its braces
// marked as braces, not keys.
std::string literal(std::string_view text);

// The whole text as a finite number ("1.5x", "nan", "1e999" are not), or nothing.
std::optional<double> finite_number(const std::string& text);

// A number as messages and help texts write it: whole numbers in full (9, 2147483647), others to
// six significant digits (0.1, 1.5e+20).
std::string number_text(double x);

// The command line's spelling of a key: "max_steps" -> "--max-steps".
std::string flag_name(std::string_view key);

enum class OptionKind {
  Integer,  // a whole number within [low, high] (above low when `positive`)
  Number,   // a finite number within [low, high] (above low when `positive`)
  Flag,     // true or false
  Text,     // any text
  Choice,   // one of `choices`
  Names,    // a list of names: a list, or one comma-separated text
  Numbers,  // a list of finite numbers
};

// How one option is read and described, the same for every front-end.
struct OptionRule {
  std::string key;
  OptionKind kind = OptionKind::Text;
  std::string help;  // one line: the command line's --help, the API's and Python's docs
  double low = -std::numeric_limits<double>::infinity();
  double high = std::numeric_limits<double>::infinity();
  bool positive = false;             // the range is (0, high]: "must be a positive number"
  std::vector<std::string> choices;  // Choice
  std::size_t count = 0;             // Numbers: exactly this many (0: any)
};

// The keys a request takes: `documents` first (what a front-end reads itself, such as the model's
// text in a JSON body), then every rule's key.
std::vector<std::string> known_keys(const std::vector<OptionRule>& rules,
                                    const std::vector<std::string>& documents = {});

// The first of `given` that neither a rule nor `documents` names, or nothing.
std::optional<std::string> unknown_key(const std::vector<std::string>& given, const std::vector<OptionRule>& rules,
                                       const std::vector<std::string>& documents = {});

// Refuses a key no rule names, with the list of the keys the request takes.
void check_known(const Options& options, const std::vector<OptionRule>& rules, const std::string& request_name);

// The rule of `key` among `rules` (a programming error if there is none: Error of kind BadInput).
const OptionRule& rule_of(const std::vector<OptionRule>& rules, std::string_view key);

// Each reads one option by its rule; an absent option gives nullopt (or false, or an empty list).
// Throws OptionError when the value breaks the rule.
std::optional<long long> read_integer(const Options& options, const OptionRule& rule);
std::optional<double> read_number(const Options& options, const OptionRule& rule);
bool read_flag(const Options& options, const OptionRule& rule);
std::optional<std::string> read_text(const Options& options, const OptionRule& rule);
std::vector<std::string> read_names(const Options& options, const OptionRule& rule);
std::vector<double> read_numbers(const Options& options, const OptionRule& rule);

}  // namespace nbar::request
