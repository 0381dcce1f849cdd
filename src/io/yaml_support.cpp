#include "yaml_support.hpp"
#include "model/double_text.hpp"

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/eventhandler.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <sstream>
#include <system_error>
#include <unordered_map>

namespace nbar::io::yaml {

SourceMark mark(const YAML::Mark& m) {
  if (m.line < 0) return {};
  return {m.line + 1, m.column + 1};
}

SourceMark mark(const YAML::Node& node) { return mark(node.Mark()); }

SourceMark mark(const Entry& e) { return e.value.IsNull() ? mark(e.key_node) : mark(e.value); }

std::string describe(const YAML::Node& node) {
  if (node.IsMap()) return "a mapping";
  if (node.IsSequence()) return "a list";
  if (node.IsScalar()) return std::string("'").append(node.Scalar()).append("'");
  return "nothing";
}

int edit_distance(std::string_view a, std::string_view b, int cutoff) {
  const auto lower = [](char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); };
  if (a.size() < b.size()) std::swap(a, b);  // rows along the longer name, so a row costs min(n, m)
  const std::size_t n = a.size(), m = b.size();
  // The distance is at least the difference in length: no table needed when that is over the cut.
  if (n - m > static_cast<std::size_t>(cutoff)) return cutoff + 1;
  // Three rolling rows: the transposition looks two rows back.
  std::vector<int> before(m + 1), previous(m + 1), current(m + 1);
  for (std::size_t j = 0; j <= m; ++j) previous[j] = static_cast<int>(j);
  for (std::size_t i = 1; i <= n; ++i) {
    current[0] = static_cast<int>(i);
    int row_best = current[0];
    for (std::size_t j = 1; j <= m; ++j) {
      const int cost = lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1;
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, previous[j - 1] + cost});
      if (i > 1 && j > 1 && lower(a[i - 1]) == lower(b[j - 2]) && lower(a[i - 2]) == lower(b[j - 1])) {
        current[j] = std::min(current[j], before[j - 2] + 1);
      }
      row_best = std::min(row_best, current[j]);
    }
    // Every later row's cells are at least the smallest of this row's minus nothing: the
    // distance can only grow from here, so stop once it is past the cut.
    if (row_best > cutoff) return cutoff + 1;
    std::swap(before, previous);
    std::swap(previous, current);
  }
  return std::min(previous[m], cutoff + 1);
}

std::size_t utf8_character_length(std::string_view text, std::size_t at) {
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
  const unsigned char c = byte(at);
  std::size_t length = 0;
  unsigned char low = 0x80, high = 0xBF;  // the allowed range of the second byte
  if (c < 0x80) return 1;
  if (c >= 0xC2 && c <= 0xDF) {
    length = 2;
  } else if (c >= 0xE0 && c <= 0xEF) {
    length = 3;
    if (c == 0xE0) low = 0xA0;   // overlong
    if (c == 0xED) high = 0x9F;  // UTF-16 surrogates
  } else if (c >= 0xF0 && c <= 0xF4) {
    length = 4;
    if (c == 0xF0) low = 0x90;   // overlong
    if (c == 0xF4) high = 0x8F;  // past U+10FFFF
  } else {
    return 0;
  }
  if (at + length > text.size() || byte(at + 1) < low || byte(at + 1) > high) return 0;
  for (std::size_t k = 2; k < length; ++k)
    if ((byte(at + k) & 0xC0) != 0x80) return 0;
  return length;
}

std::optional<std::size_t> first_invalid_utf8(std::string_view text) {
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t length = utf8_character_length(text, i);
    if (length == 0) return i;
    i += length;
  }
  return std::nullopt;
}

NumberStatus parse_number(std::string_view text, double& value) {
  std::string lower(text);
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (std::string_view special : {".nan", ".inf", "+.inf", "-.inf"}) {
    if (lower == special) return NumberStatus::NotFinite;
  }
  std::string_view s = text;
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);  // from_chars does not take it
  if (s.empty()) return NumberStatus::NotNumber;
  const auto [end, ec] = parse_double(s.data(), s.data() + s.size(), value);
  if (end != s.data() + s.size()) return NumberStatus::NotNumber;
  if (ec == std::errc::result_out_of_range) return NumberStatus::NotFinite;
  if (ec != std::errc()) return NumberStatus::NotNumber;
  return std::isfinite(value) ? NumberStatus::Ok : NumberStatus::NotFinite;
}

namespace {

// Calls visit(bracket, mark) for each [ { ] } of `text` outside comments, in order, until visit
// returns false. A '#' after a space starts a comment; quotes are not followed, so this only
// places an error the YAML parser has already found.
template <class Visit>
void for_each_flow_bracket(std::string_view text, Visit visit) {
  int line = 1;
  std::size_t line_start = 0;
  bool comment = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      line_start = i + 1;
      comment = false;
    } else if (comment) {
      continue;
    } else if (c == '#' && (i == 0 || text[i - 1] == ' ' || text[i - 1] == '\t')) {
      comment = true;
    } else if (c == '[' || c == '{' || c == ']' || c == '}') {
      if (!visit(c, SourceMark{line, static_cast<int>(i - line_start) + 1})) return;
    }
  }
}

bool opens(char bracket) { return bracket == '[' || bracket == '{'; }

// Where the flow collections ([ and {) of `text` first reach `depth` levels, or no mark.
// The deepest nesting of [ and { in `text`, and the bracket that first reaches it (no mark
// when there are none).
struct FlowDepth {
  int levels = 0;
  SourceMark at;
};
FlowDepth deepest_flow_nesting(std::string_view text) {
  int level = 0;
  FlowDepth deepest;
  for_each_flow_bracket(text, [&](char c, SourceMark at) {
    if (opens(c)) {
      if (++level > deepest.levels) deepest = {level, at};
    } else if (level > 0) {
      --level;
    }
    return true;
  });
  return deepest;
}

// The first ']' or '}' of `text` that closes nothing, or no mark.
SourceMark stray_closing_bracket(std::string_view text, char& bracket) {
  int level = 0;
  SourceMark found;
  for_each_flow_bracket(text, [&](char c, SourceMark at) {
    if (opens(c)) {
      ++level;
    } else if (level > 0) {
      --level;
    } else {
      bracket = c;
      found = at;
      return false;
    }
    return true;
  });
  return found;
}

// YAML reads a key of at most 1024 characters and, past it, reports some structure it cannot
// close, at the key's end. The first key of `text` longer than that, with its `length`, or no mark.
SourceMark overlong_key(std::string_view text, std::size_t& length) {
  constexpr std::size_t kYamlKeyLimit = 1024;
  constexpr std::size_t kNone = std::string_view::npos;
  std::size_t token = kNone;  // where the current token's text starts, after spaces and a '- '
  int line = 1;
  std::size_t line_start = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n' || c == '{' || c == '[' || c == ',') {
      if (c == '\n') {
        ++line;
        line_start = i + 1;
      }
      token = kNone;
    } else if (c == ':' &&
               (i + 1 == text.size() || text[i + 1] == ' ' || text[i + 1] == '\n' || (i > 0 && text[i - 1] == '"'))) {
      if (token != kNone && i - token > kYamlKeyLimit) {
        length = i - token - (text[token] == '"' || text[token] == '\'' ? 2 : 0);
        return SourceMark{line, static_cast<int>(token - line_start) + 1};
      }
      token = kNone;
    } else if (token == kNone && c != ' ' && c != '-') {
      token = i;
      if (c == '"' || c == '\'') {
        // A quoted scalar: a value's colons are not keys. One left open ends the search.
        const std::size_t close = text.find(c, i + 1);
        if (close == kNone || text.substr(i, close - i).find('\n') != kNone) return SourceMark{};
        i = close;
      }
    }
  }
  return SourceMark{};
}

bool before(SourceMark a, SourceMark b) { return a.line < b.line || (a.line == b.line && a.column < b.column); }

// The innermost [ or { before `at` (where yaml-cpp gave up) that no ']' or '}' of the whole text
// closes, or no mark. yaml-cpp says "end of sequence flow not found" where it next looked for the
// ']' (the line after the mistake, or further): the student's mistake is the bracket left open.
// When every bracket is closed somewhere (a comma missing: "[0, 0] [1, 1]"), yaml-cpp's mark is
// the right place and stays.
SourceMark unclosed_flow_bracket(std::string_view text, SourceMark at, char& bracket) {
  std::vector<std::pair<char, SourceMark>> open;
  for_each_flow_bracket(text, [&](char c, SourceMark where) {
    if (opens(c))
      open.emplace_back(c, where);
    else if (!open.empty())
      open.pop_back();
    return true;
  });
  while (!open.empty() && !before(open.back().second, at)) open.pop_back();
  if (open.empty()) return {};
  bracket = open.back().first;
  return open.back().second;
}

// The last quote of `text` before `at` that opens a quoted scalar and is not closed on its own
// line, when that scalar ends on `at`'s line or its line before (or not at all): an unclosed
// quote makes yaml-cpp read on into the next lines and fail there. Quoted scalars may span lines
// in YAML, so this only places an error the parser has already found.
SourceMark unclosed_quote(std::string_view text, SourceMark at, char& quote) {
  SourceMark opened;  // where the quote still open began
  SourceMark found;   // the last scalar that spanned lines and ended near `at`, or is still open
  char in = 0;
  int line = 1;
  std::size_t line_start = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const SourceMark here{line, static_cast<int>(i - line_start) + 1};
    if (!before(here, at)) break;
    const char c = text[i];
    if (c == '\n') {
      ++line;
      line_start = i + 1;
      continue;
    }
    if (in) {
      if (in == '"' && c == '\\') {
        ++i;
        continue;
      }
      if (in == '\'' && c == '\'' && i + 1 < text.size() && text[i + 1] == '\'') {
        ++i;
        continue;
      }
      if (c != in) continue;
      in = 0;
      if (opened.line < line && line >= at.line - 1) {
        found = opened;
        quote = c;
      }
      continue;
    }
    const char prev = i == line_start ? ' ' : text[i - 1];
    if (c == '#' && (prev == ' ' || prev == '\t')) {  // a comment: to the line's end
      while (i + 1 < text.size() && text[i + 1] != '\n') ++i;
      continue;
    }
    const bool starts_scalar = prev == ' ' || prev == '\t' || prev == '[' || prev == '{' || prev == ',' || prev == ':';
    if ((c == '"' || c == '\'') && starts_scalar) {
      in = c;
      opened = here;
    }
  }
  if (in && opened.line < at.line) {
    found = opened;
    quote = in;
  }
  return found;
}

// Where a YAML syntax error really is, when yaml-cpp's mark lies after it: at the bracket or
// quote left open. Leaves `at` and `message` as they are otherwise.
void place_unclosed(std::string_view text, SourceMark& at, std::string& message) {
  if (at.line <= 0) return;
  char c = ' ';
  if (message.find("flow not found") != std::string::npos) {
    const SourceMark open = unclosed_flow_bracket(text, at, c);
    if (open.line <= 0) return;
    at = open;
    message = std::string("this '") + c + "' is never closed by a '" + (c == '[' ? ']' : '}') + "' (" + message + ")";
    return;
  }
  const SourceMark quote = unclosed_quote(text, at, c);
  if (quote.line <= 0) return;
  message = std::string("this ") + c + " is not closed on its line (the reader found \"" + message + "\" on line " +
            std::to_string(at.line) + ")";
  at = quote;
}

// Counts a text's documents without building them, and keeps where the second starts: at its
// first node, or at its marker when it has none.
class DocumentCounter : public YAML::EventHandler {
 public:
  int documents = 0;
  YAML::Mark second;
  void OnDocumentStart(const YAML::Mark& at) override {
    if (++documents == 2) second = at;
  }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& at, YAML::anchor_t) override { node(at); }
  void OnAlias(const YAML::Mark& at, YAML::anchor_t) override { node(at); }
  void OnScalar(const YAML::Mark& at, const std::string&, YAML::anchor_t, const std::string&) override { node(at); }
  void OnSequenceStart(const YAML::Mark& at, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    node(at);
  }
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark& at, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    node(at);
  }
  void OnMapEnd() override {}

 private:
  bool second_has_node_ = false;
  void node(const YAML::Mark& at) {
    if (documents != 2 || second_has_node_) return;
    second_has_node_ = true;
    second = at;
  }
};

}  // namespace

void Reader::fail(SourceMark at, const std::string& message) const { throw ModelFileError(file_, at, message); }

void Reader::fail(const YAML::Node& at, const std::string& message) const { fail(mark(at), message); }

void Reader::check_name_length(const YAML::Node& name) const {
  if (name.IsScalar() && name.Scalar().size() > kMaxNameLength)
    fail(name, "a key or name may have at most " + std::to_string(kMaxNameLength) + " characters (this one has " +
                   std::to_string(name.Scalar().size()) + ")");
}

void Reader::check_text() const {
  if (text_.size() > kMaxFileBytes)
    fail(SourceMark{1, 1}, "the file is " + std::to_string(text_.size()) + " bytes long; nbar reads at most " +
                               std::to_string(kMaxFileBytes) + " bytes");
  // YAML text has no control characters but tab and line ends. A NUL also makes yaml-cpp guess
  // UTF-16 or UTF-32, and then read the file as garbled text.
  const auto control = std::find_if(text_.begin(), text_.end(), [](char ch) {
    const auto c = static_cast<unsigned char>(ch);
    return (c < 0x20 && c != '\t' && c != '\n' && c != '\r') || c == 0x7F;
  });
  const std::optional<std::size_t> invalid = first_invalid_utf8(text_);
  const std::size_t at_control = static_cast<std::size_t>(control - text_.begin());
  const bool is_control = control != text_.end() && (!invalid || at_control < *invalid);
  if (!is_control && !invalid) return;
  const std::size_t bad = is_control ? at_control : *invalid;
  const std::size_t line_start = text_.rfind('\n', bad == 0 ? 0 : bad - 1);
  const std::size_t column_start = line_start == std::string::npos || text_[line_start] != '\n' ? 0 : line_start + 1;
  const int line = 1 + static_cast<int>(std::count(text_.begin(), text_.begin() + static_cast<long>(bad), '\n'));
  static constexpr char kHex[] = "0123456789ABCDEF";
  const unsigned char c = static_cast<unsigned char>(text_[bad]);
  const std::string byte = std::string("byte 0x").append(1, kHex[c >> 4]).append(1, kHex[c & 15]);
  fail(SourceMark{line, static_cast<int>(bad - column_start) + 1},
       is_control ? "the file is not text: " + byte +
                        " here is a control character (UTF-16 or a binary file?); save it as UTF-8"
                  : "the file is not valid UTF-8 text: " + byte + " here is not a character; save the file as UTF-8");
}

YAML::Node Reader::load(const DocumentWording& wording) const {
  check_text();
  // Not YAML::LoadAll: after a stray '}' or ']' (", a: 1}") yaml-cpp 0.7 makes empty
  // documents forever, and LoadAll never returns (a fuzzer's finding). Counting the documents,
  // and stopping at the second, reads every text in one pass.
  std::vector<YAML::Node> documents;
  try {
    std::istringstream in(text_);
    YAML::Parser parser(in);
    DocumentCounter counter;
    while (counter.documents < 2 && parser.HandleNextDocument(counter)) {
    }
    if (counter.documents > 1) {
      // Without a document marker, the second document is the parser's way of skipping a
      // bracket that closes nothing.
      char bracket = ' ';
      const SourceMark stray = stray_closing_bracket(text_, bracket);
      const bool markers = text_.rfind("---", 0) == 0 || text_.find("\n---") != std::string::npos ||
                           text_.rfind("...", 0) == 0 || text_.find("\n...") != std::string::npos;
      if (!markers && stray.line > 0) {
        fail(stray,
             std::string("invalid YAML: a '") + bracket + "' that closes no '" + (bracket == '}' ? '{' : '[') + "'");
      }
      fail(mark(counter.second), std::string(wording.several));
    }
    if (counter.documents == 1) documents.push_back(YAML::Load(text_));
  } catch (const YAML::DeepRecursion& e) {
    // yaml-cpp stops at a depth of its own calls, which is not a number of levels (four calls
    // for a level in some contexts, one in others), with "bad file" at some later place: say
    // how deep the file goes and where, at the bracket that goes deepest.
    const FlowDepth deepest = deepest_flow_nesting(text_);
    if (deepest.levels == 0)
      fail(mark(e.mark),
           "invalid YAML: lists and mappings nested deeper than the reader follows (a model or task "
           "needs a handful of levels)");
    fail(deepest.at, "invalid YAML: lists and mappings nested " + std::to_string(deepest.levels) +
                         " levels deep here, deeper than the reader follows (a model or task needs a handful)");
  } catch (const YAML::Exception& e) {
    // yaml-cpp reports a tab in the indentation as some structure it could not close, at some
    // later place: name the tab, at its line and column, when one comes before the error.
    const SourceMark at = mark(e.mark);
    int line = 1;
    for (std::size_t start = 0; start < text_.size() && (at.line == 0 || line <= at.line); ++line) {
      const std::size_t end = std::min(text_.find('\n', start), text_.size());
      const std::string_view row = std::string_view(text_).substr(start, end - start);
      const std::size_t content = row.find_first_not_of(" \t\r");
      const std::size_t tab = row.find('\t');
      if (content != std::string_view::npos && tab < content && row[content] != '#')
        fail(SourceMark{line, static_cast<int>(tab) + 1},
             "invalid YAML: tab characters are not allowed in YAML "
             "indentation; indent with spaces");
      start = end + 1;
    }
    std::size_t key_length = 0;
    if (const SourceMark key = overlong_key(text_, key_length); key.line > 0 && !before(at, key))
      fail(key, "a key or name may have at most " + std::to_string(kMaxNameLength) + " characters (this one has " +
                    std::to_string(key_length) + ")");
    SourceMark where = at;
    std::string message = e.msg;
    place_unclosed(text_, where, message);
    fail(where, "invalid YAML: " + message);
  }
  if (documents.empty() || (documents.size() == 1 && documents[0].IsNull())) {
    fail(SourceMark{1, 1}, std::string(wording.empty));
  }
  const YAML::Node root = documents[0];
  if (!root.IsMap()) fail(root, std::string(wording.not_mapping).append(describe(root)));
  return root;
}

std::vector<Entry> Reader::entries(const YAML::Node& map, std::string_view entity) const {
  std::vector<Entry> out;
  // Keys seen so far, to their entry: a mapping of thousands of bodies is read in linear time.
  std::unordered_map<std::string, std::size_t> seen;
  for (auto it = map.begin(); it != map.end(); ++it) {
    const YAML::Node key = it->first;
    check_key(key);
    check_name_length(key);
    const std::string name = key.Scalar();
    if (const auto [at, inserted] = seen.emplace(name, out.size()); !inserted) {
      const Entry& previous = out[at->second];
      const std::string first =
          std::string(" (first given on line ").append(std::to_string(mark(previous.key_node).line)).append(")");
      if (entity.empty()) fail(key, std::string("duplicate key '").append(name).append("'").append(first));
      fail(key, std::string(entity).append(" '").append(name).append("' is defined twice").append(first));
    }
    out.push_back(Entry{name, key, it->second});
  }
  return out;
}

void Reader::check_keys(const Fields& fields, const AllowedKeys& allowed) const {
  for (const Entry& e : fields.entries) {
    if (std::find(allowed.keys.begin(), allowed.keys.end(), e.key) != allowed.keys.end()) continue;
    std::string message = std::string("unknown key '").append(e.key).append("' ").append(allowed.context);
    if (auto close = suggestion(e.key, allowed.keys)) {
      message.append("; did you mean '").append(*close).append("'?");
    } else {
      message.append(" (allowed: ").append(join(allowed.keys, allowed.keys.size())).append(")");
    }
    fail(e.key_node, message);
  }
}

Fields Reader::fields(const YAML::Node& map, const AllowedKeys& allowed) const {
  Fields f{entries(map, "")};
  check_keys(f, allowed);
  return f;
}

Fields Reader::mapping(const Entry& e, const AllowedKeys& allowed, std::string_view example) const {
  if (!e.value.IsMap()) {
    fail(mark(e), std::string("`")
                      .append(e.key)
                      .append("` must be a mapping like ")
                      .append(example)
                      .append(", not ")
                      .append(describe(e.value)));
  }
  return fields(e.value, allowed);
}

const Entry& Reader::required(const Fields& f, const YAML::Node& owner, std::string_view key,
                              std::string_view what) const {
  const Entry* e = f.find(key);
  if (!e) fail(owner, std::string(what).append(" needs `").append(key).append("`"));
  return *e;
}

std::vector<YAML::Node> Reader::list(const Entry& e, std::string_view example) const {
  if (!e.value.IsSequence()) {
    fail(mark(e), std::string("`")
                      .append(e.key)
                      .append("` must be a list like ")
                      .append(example)
                      .append(", not ")
                      .append(describe(e.value)));
  }
  return {e.value.begin(), e.value.end()};
}

std::string Reader::text_value(const Entry& e, std::string_view what) const {
  if (e.value.IsNull()) return {};
  if (!e.value.IsScalar()) fail(mark(e), std::string(what).append(" must be text, not ").append(describe(e.value)));
  return e.value.Scalar();
}

double Reader::number(const YAML::Node& node, SourceMark at, std::string_view what) const {
  if (!node.IsScalar()) fail(at, std::string(what).append(" must be a number, not ").append(describe(node)));
  double value = 0.0;
  switch (parse_number(node.Scalar(), value)) {
    case NumberStatus::Ok: return value;
    case NumberStatus::NotFinite:
      fail(at, std::string(what).append(" must be a finite number, not '").append(node.Scalar()).append("'"));
    case NumberStatus::NotNumber: break;
  }
  fail(at, std::string(what).append(" must be a number, not '").append(node.Scalar()).append("'"));
}

double Reader::number(const Entry& e, std::string_view what) const { return number(e.value, mark(e), what); }

double Reader::non_negative(const Entry& e, std::string_view what, bool positive) const {
  const double v = number(e, what);
  if (positive && v <= 0.0) fail(mark(e), std::string(what).append(" must be positive"));
  if (v < 0.0) fail(mark(e), std::string(what).append(" must not be negative"));
  return v;
}

Units Reader::units_of(const Fields& f, const Units& units) const {
  std::string length = units.length, angle = units.angle;
  if (const Entry* l = f.find("length")) {
    length = text_value(*l, "the length unit");
    if (!length_unit_scale(length)) {
      fail(mark(*l), std::string("unknown length unit '").append(length).append("' (use m, mm, cm, in or ft)"));
    }
  }
  if (const Entry* a = f.find("angle")) {
    angle = text_value(*a, "the angle unit");
    if (!angle_unit_scale(angle)) {
      fail(mark(*a), std::string("unknown angle unit '").append(angle).append("' (use deg or rad)"));
    }
  }
  return *Units::make(length, angle);
}

}  // namespace nbar::io::yaml
