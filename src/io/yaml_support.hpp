// What the YAML readers of nbar_io (model files, synthesis task files) share, so that both
// kinds of file report the same mistakes with the same words, lines and columns.
// Internal to nbar_io: it exposes yaml-cpp, which the library links privately.
#pragma once

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "nbar/io/file_text.hpp"
#include "nbar/io/model_file.hpp"
#include "nbar/model/units.hpp"

namespace nbar::io::yaml {

// One key: value pair of a mapping whose keys have been checked.
struct Entry {
  std::string key;
  YAML::Node key_node;
  YAML::Node value;
};

// The pairs of a mapping, in file order.
struct Fields {
  std::vector<Entry> entries;
  const Entry* find(std::string_view key) const {
    for (const Entry& e : entries) {
      if (e.key == key) return &e;
    }
    return nullptr;
  }
};

// The keys a kind of mapping accepts; `context` completes "unknown key 'x' ...", as in
// "in a slider" or "in `units`".
struct AllowedKeys {
  std::string context;
  std::vector<std::string_view> keys;
};

// yaml-cpp counts lines and columns from 0 (and -1 when unknown); messages count from 1.
SourceMark mark(const YAML::Mark& m);
SourceMark mark(const YAML::Node& node);
// An empty value ("key:" and nothing) is marked at the next token, possibly lines
// below, so errors about it are better shown at its key.
SourceMark mark(const Entry& e);

// What a node is, to end messages such as "... must be a number, not 'abc'".
std::string describe(const YAML::Node& node);

// Optimal string alignment distance (Levenshtein plus adjacent transpositions, the most
// common typo), ignoring case so that "o2" finds "O2". Memory grows with the shorter name
// only; a distance over `cutoff` is returned as cutoff + 1 as soon as it is certain, so a
// suggestion among long names costs little.
int edit_distance(std::string_view a, std::string_view b, int cutoff = std::numeric_limits<int>::max() - 1);

// Names longer than this are not names: the readers reject them (where they are read) before
// any suggestion compares them.
inline constexpr std::size_t kMaxNameLength = 256;
// The largest model or task file the readers take.
inline constexpr std::size_t kMaxFileBytes = kMaxInputFileBytes;

// The offset of the first byte that does not begin a well-formed UTF-8 character (overlong
// forms, surrogates and code points past U+10FFFF are not), or nothing for valid text.
std::optional<std::size_t> first_invalid_utf8(std::string_view text);
// The length in bytes of the well-formed UTF-8 character at `at` (< text.size()), or 0.
std::size_t utf8_character_length(std::string_view text, std::size_t at);

// The closest candidate, if it is close enough to be a plausible typo. One-letter names
// are all one edit apart, so a distance equal to the length suggests nothing.
template <typename Names>
std::optional<std::string> suggestion(std::string_view wrong, const Names& candidates) {
  if (wrong.size() > kMaxNameLength) return std::nullopt;
  const int limit = std::max<int>(1, static_cast<int>(wrong.size()) / 3);
  std::optional<std::string> best;
  int best_distance = std::numeric_limits<int>::max();
  for (const auto& candidate : candidates) {
    const int d = edit_distance(wrong, candidate, limit);
    if (d < best_distance && d <= limit && d < static_cast<int>(wrong.size())) {
      best = std::string(candidate);
      best_distance = d;
    }
  }
  return best;
}

// "a, b, c", cut short with ", ..." after `at_most` names.
template <typename Names>
std::string join(const Names& names, std::size_t at_most = 12) {
  std::string out;
  std::size_t count = 0;
  for (const auto& name : names) {
    if (count == at_most) {
      out += ", ...";
      break;
    }
    if (count++ > 0) out += ", ";
    out += name;
  }
  return out;
}

enum class NumberStatus { Ok, NotFinite, NotNumber };

// A plain number, as YAML writes it: a leading '+' is allowed, and YAML's .nan and .inf
// (which yaml-cpp would read as numbers) are NotFinite, like values out of double's range.
NumberStatus parse_number(std::string_view text, double& value);

// How a kind of file words the problems of its document as a whole.
struct DocumentWording {
  std::string_view empty;        // the file has no document (empty or only comments)
  std::string_view several;      // at a second document
  std::string_view not_mapping;  // the document is not a mapping; describe(document) follows
};

// The base of a parser: the text and name of the file, and the readers of generic values
// that report mistakes (ModelFileError) at their line and column.
class Reader {
 protected:
  Reader(std::string text, std::string file) : text_(std::move(text)), file_(std::move(file)) {}
  ~Reader() = default;

  const std::string text_;
  const std::string file_;

  [[noreturn]] void fail(SourceMark at, const std::string& message) const;
  [[noreturn]] void fail(const YAML::Node& at, const std::string& message) const;

  // Rejects a key or a reference longer than kMaxNameLength, at its place.
  void check_name_length(const YAML::Node& name) const;
  // Rejects a file too long to be a model or not UTF-8 text, at the first bad byte.
  void check_text() const;
  // The single document of the file (checked by check_text), which must be a mapping.
  YAML::Node load(const DocumentWording& wording) const;

  // Rejects a key that is not a name. Each kind of file words this itself: model files
  // also use keys as the names of points and bodies.
  virtual void check_key(const YAML::Node& key) const = 0;

  // Reads the pairs of a mapping in file order, reporting keys that are not names and
  // keys given twice (yaml-cpp keeps both pairs but lookups only ever see the first).
  // `entity` words the duplicate error for mappings of user names ("point", "body").
  std::vector<Entry> entries(const YAML::Node& map, std::string_view entity) const;
  // Reports the first key that is not allowed, suggesting the allowed key it is a typo of.
  void check_keys(const Fields& fields, const AllowedKeys& allowed) const;
  Fields fields(const YAML::Node& map, const AllowedKeys& allowed) const;
  // The mapping under a key, `example` showing one.
  Fields mapping(const Entry& e, const AllowedKeys& allowed, std::string_view example) const;
  const Entry& required(const Fields& f, const YAML::Node& owner, std::string_view key, std::string_view what) const;
  // The list under a key, `example` showing one.
  std::vector<YAML::Node> list(const Entry& e, std::string_view example) const;

  // Text; an empty value is empty text.
  std::string text_value(const Entry& e, std::string_view what) const;
  double number(const YAML::Node& node, SourceMark at, std::string_view what) const;
  double number(const Entry& e, std::string_view what) const;
  // A number that must not be negative (or, with `positive`, must be above zero).
  double non_negative(const Entry& e, std::string_view what, bool positive = false) const;
  // The `length` and `angle` of a `units` mapping; those not given keep their value in `units`.
  Units units_of(const Fields& f, const Units& units) const;
};

}  // namespace nbar::io::yaml
