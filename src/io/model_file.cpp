#include "io/model_file.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string_view>
#include <system_error>
#include <utility>

namespace nbar::io {

namespace {

std::string compose(const std::string& file, SourceMark mark, const std::string& message) {
  if (mark.line <= 0) return file + ": " + message;
  return file + ":" + std::to_string(mark.line) + ":" + std::to_string(mark.column) + ": " + message;
}

}  // namespace

SourceMark SourceMap::find(const EntityRef& ref) const {
  const auto pick = [&](const std::vector<SourceMark>& marks) {
    if (ref.index >= 0 && ref.index < static_cast<int>(marks.size()) && marks[ref.index].line > 0) {
      return marks[ref.index];
    }
    return model;
  };
  switch (ref.kind) {
    case EntityRef::Kind::Model: return model;
    case EntityRef::Kind::Point: return pick(points);
    case EntityRef::Kind::Body: return pick(bodies);
    case EntityRef::Kind::Slider: return pick(sliders);
    case EntityRef::Kind::Slot: return pick(slots);
    case EntityRef::Kind::Driver: return pick(drivers);
    case EntityRef::Kind::Sweep: return sweep.line > 0 ? sweep : model;
  }
  return model;
}

ModelFileError::ModelFileError(const std::string& file, SourceMark mark, const std::string& message)
    : std::runtime_error(compose(file, mark, message)), file_(file), mark_(mark), message_(message) {}

std::string locate(const SourceMap& source, const ModelError& error) {
  return compose(source.file, source.find(error.where()), error.what());
}

namespace {

// The keys each kind of mapping accepts, all in one place: new sections (shapes, loads,
// gravity, materials...) are declared here and then read in Parser::parse.
struct AllowedKeys {
  std::string_view context;  // completes "unknown key 'x' ..."
  std::vector<std::string_view> keys;
};
const AllowedKeys kTopLevelKeys{
    "at the top level",
    {"name", "description", "units", "points", "ground", "bodies", "lengths", "sliders", "slots", "drivers", "sweep"}};
const AllowedKeys kUnitsKeys{"in `units`", {"length", "angle"}};
const AllowedKeys kSliderKeys{"in a slider", {"body", "point", "along"}};
const AllowedKeys kSlotKeys{"in a slot", {"point", "along"}};
const AllowedKeys kDriverKeys{
    "in a driver", {"name", "angle", "relative_to", "distance", "slide", "from", "to", "speed", "accel", "law"}};
const AllowedKeys kSweepKeys{"in `sweep`", {"steps", "duration", "step"}};

// Optimal string alignment distance (Levenshtein plus adjacent transpositions, the most
// common typo), ignoring case so that "o2" finds "O2".
int edit_distance(std::string_view a, std::string_view b) {
  const auto lower = [](char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); };
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::vector<int>> d(n + 1, std::vector<int>(m + 1, 0));
  for (std::size_t i = 0; i <= n; ++i) d[i][0] = static_cast<int>(i);
  for (std::size_t j = 0; j <= m; ++j) d[0][j] = static_cast<int>(j);
  for (std::size_t i = 1; i <= n; ++i) {
    for (std::size_t j = 1; j <= m; ++j) {
      const int cost = lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && lower(a[i - 1]) == lower(b[j - 2]) && lower(a[i - 2]) == lower(b[j - 1])) {
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
      }
    }
  }
  return d[n][m];
}

// The closest candidate, if it is close enough to be a plausible typo. One-letter names
// are all one edit apart, so a distance equal to the length suggests nothing.
template <typename Names>
std::optional<std::string> suggestion(std::string_view wrong, const Names& candidates) {
  const int limit = std::max<int>(1, static_cast<int>(wrong.size()) / 3);
  std::optional<std::string> best;
  int best_distance = std::numeric_limits<int>::max();
  for (const auto& candidate : candidates) {
    const int d = edit_distance(wrong, candidate);
    if (d < best_distance && d <= limit && d < static_cast<int>(wrong.size())) {
      best = std::string(candidate);
      best_distance = d;
    }
  }
  return best;
}

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

NumberStatus parse_number(std::string_view text, double& value) {
  std::string lower(text);
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (std::string_view special : {".nan", ".inf", "+.inf", "-.inf"}) {
    if (lower == special) return NumberStatus::NotFinite;
  }
  std::string_view s = text;
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return NumberStatus::NotNumber;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (end != s.data() + s.size()) return NumberStatus::NotNumber;
  if (ec == std::errc::result_out_of_range) return NumberStatus::NotFinite;
  if (ec != std::errc()) return NumberStatus::NotNumber;
  return std::isfinite(value) ? NumberStatus::Ok : NumberStatus::NotFinite;
}

std::string describe(const YAML::Node& node) {
  if (node.IsMap()) return "a mapping";
  if (node.IsSequence()) return "a list";
  if (node.IsScalar()) return "'" + node.Scalar() + "'";
  return "nothing";
}

// One key: value pair of a mapping whose keys have been checked.
struct Entry {
  std::string key;
  YAML::Node key_node;
  YAML::Node value;
};

struct Fields {
  std::vector<Entry> entries;
  const Entry* find(std::string_view key) const {
    for (const Entry& e : entries) {
      if (e.key == key) return &e;
    }
    return nullptr;
  }
};

class Parser {
 public:
  Parser(std::string text, std::string file) : text_(std::move(text)) { source_.file = std::move(file); }

  LoadedModel parse() {
    const YAML::Node root = load();
    source_.model = mark(root);
    const Fields top = fields(root, kTopLevelKeys);

    if (const Entry* e = top.find("name")) model_.name = text_value(*e, "the model name");
    if (const Entry* e = top.find("description")) text_value(*e, "the description");
    if (const Entry* e = top.find("units")) parse_units(*e);
    parse_points(top.find("points"));
    if (const Entry* e = top.find("ground")) parse_ground(*e);
    if (const Entry* e = top.find("bodies")) parse_bodies(*e);
    if (const Entry* e = top.find("lengths")) parse_lengths(*e);
    if (const Entry* e = top.find("sliders")) parse_sliders(*e);
    if (const Entry* e = top.find("slots")) parse_slots(*e);
    if (const Entry* e = top.find("drivers")) parse_drivers(*e);
    if (const Entry* e = top.find("sweep")) parse_sweep(*e);

    try {
      validate(model_);
    } catch (const ModelError& error) {
      throw ModelFileError(source_.file, source_.find(error.where()), error.what());
    }
    return LoadedModel{std::move(model_), std::move(source_)};
  }

 private:
  std::string text_;
  Model model_;
  SourceMap source_;

  // ---- locations and errors ----

  static SourceMark mark(const YAML::Node& node) {
    const YAML::Mark m = node.Mark();
    if (m.line < 0) return {};
    return {m.line + 1, m.column + 1};
  }
  // An empty value ("key:" and nothing) is marked at the next token, possibly lines
  // below, so errors about it are better shown at its key.
  static SourceMark mark(const Entry& e) { return e.value.IsNull() ? mark(e.key_node) : mark(e.value); }

  [[noreturn]] void fail(SourceMark at, const std::string& message) const {
    throw ModelFileError(source_.file, at, message);
  }
  [[noreturn]] void fail(const YAML::Node& at, const std::string& message) const { fail(mark(at), message); }

  YAML::Node load() {
    std::vector<YAML::Node> documents;
    try {
      documents = YAML::LoadAll(text_);
    } catch (const YAML::Exception& e) {
      const SourceMark at = e.mark.line < 0 ? SourceMark{} : SourceMark{e.mark.line + 1, e.mark.column + 1};
      fail(at, "invalid YAML: " + e.msg);
    }
    if (documents.empty() || (documents.size() == 1 && documents[0].IsNull())) {
      fail(SourceMark{1, 1},
           "the file holds no model (it is empty or only comments): a model needs at least `points:`");
    }
    if (documents.size() > 1) {
      fail(documents[1], "a model file holds a single YAML document; remove this one or the `---` before it");
    }
    const YAML::Node root = documents[0];
    if (!root.IsMap()) {
      fail(root, "a model file is a mapping of sections (points:, bodies:, drivers:, ...), not " + describe(root));
    }
    return root;
  }

  // Reads the pairs of a mapping in file order, reporting keys that are not names and
  // keys given twice (yaml-cpp keeps both pairs but lookups only ever see the first).
  // `entity` words the duplicate error for mappings of user names ("point", "body").
  std::vector<Entry> entries(const YAML::Node& map, std::string_view entity) const {
    std::vector<Entry> out;
    for (auto it = map.begin(); it != map.end(); ++it) {
      const YAML::Node key = it->first;
      if (key.IsNull()) {
        fail(key, "a key or name cannot be empty or null (quote names such as 'null' or '~')");
      }
      if (!key.IsScalar()) fail(key, "a key or name must be a single word, not " + describe(key));
      const std::string name = key.Scalar();
      if (name.empty()) fail(key, "a key or name cannot be empty");
      for (const Entry& previous : out) {
        if (previous.key != name) continue;
        const std::string first = " (first given on line " + std::to_string(mark(previous.key_node).line) + ")";
        if (entity.empty()) fail(key, "duplicate key '" + name + "'" + first);
        fail(key, std::string(entity) + " '" + name + "' is defined twice" + first);
      }
      out.push_back(Entry{name, key, it->second});
    }
    return out;
  }

  Fields fields(const YAML::Node& map, const AllowedKeys& allowed) const {
    Fields f{entries(map, "")};
    for (const Entry& e : f.entries) {
      if (std::find(allowed.keys.begin(), allowed.keys.end(), e.key) != allowed.keys.end()) continue;
      std::string message = "unknown key '" + e.key + "' " + std::string(allowed.context);
      if (auto close = suggestion(e.key, allowed.keys)) {
        message += "; did you mean '" + *close + "'?";
      } else {
        message += " (allowed: " + join(allowed.keys, allowed.keys.size()) + ")";
      }
      fail(e.key_node, message);
    }
    return f;
  }

  // The mapping under a section key; an empty value stands for an empty mapping.
  Fields section_fields(const Entry& e, const AllowedKeys& allowed, std::string_view example) const {
    if (e.value.IsNull()) return {};
    if (!e.value.IsMap()) {
      fail(mark(e), "`" + e.key + "` must be a mapping like " + std::string(example) + ", not " + describe(e.value));
    }
    return fields(e.value, allowed);
  }

  // ---- values ----

  std::string text_value(const Entry& e, std::string_view what) const {
    if (e.value.IsNull()) return {};
    if (!e.value.IsScalar()) fail(mark(e), std::string(what) + " must be text, not " + describe(e.value));
    return e.value.Scalar();
  }

  double number(const YAML::Node& node, SourceMark at, std::string_view what) const {
    if (!node.IsScalar()) fail(at, std::string(what) + " must be a number, not " + describe(node));
    double value = 0.0;
    switch (parse_number(node.Scalar(), value)) {
      case NumberStatus::Ok: return value;
      case NumberStatus::NotFinite:
        fail(at, std::string(what) + " must be a finite number, not '" + node.Scalar() + "'");
      case NumberStatus::NotNumber: break;
    }
    fail(at, std::string(what) + " must be a number, not '" + node.Scalar() + "'");
  }
  double number(const Entry& e, std::string_view what) const { return number(e.value, mark(e), what); }

  int whole_number(const Entry& e, std::string_view what) const {
    const double v = number(e, what);
    if (v != std::floor(v) || std::abs(v) > 1e9) fail(mark(e), std::string(what) + " must be a whole number");
    return static_cast<int>(v);
  }

  std::string name_of(const YAML::Node& node, std::string_view what) const {
    if (!node.IsScalar() || node.Scalar().empty()) {
      fail(node, std::string(what) + " must be a name, not " + describe(node));
    }
    return node.Scalar();
  }

  template <typename Items, typename NameOf>
  [[noreturn]] void fail_unknown(const YAML::Node& at, std::string_view kind, std::string_view plural,
                                 const std::string& name, const Items& items, NameOf name_of_item) const {
    std::vector<std::string> names;
    for (const auto& item : items) names.push_back(name_of_item(item));
    std::string message = "unknown " + std::string(kind) + " '" + name + "'";
    if (names.empty()) {
      message += " (there are no " + std::string(plural) + ")";
    } else if (auto close = suggestion(name, names)) {
      message += "; did you mean '" + *close + "'?";
    } else {
      message += " (" + std::string(plural) + " are: " + join(names) + ")";
    }
    fail(at, message);
  }

  int point_ref(const YAML::Node& node) const {
    const std::string name = name_of(node, "a point reference");
    const int index = model_.find_point(name);
    if (index < 0) fail_unknown(node, "point", "points", name, model_.points, [](const Point& p) { return p.name; });
    return index;
  }

  int body_ref(const YAML::Node& node) const {
    const std::string name = name_of(node, "a body reference");
    const int index = model_.find_body(name);
    if (index < 0) fail_unknown(node, "body", "bodies", name, model_.bodies, [](const Body& b) { return b.name; });
    return index;
  }

  std::array<int, 2> point_pair(const Entry& e, std::string_view example) const {
    if (!e.value.IsSequence() || e.value.size() != 2) {
      fail(mark(e),
           "`" + e.key + "` needs two point names, like " + std::string(example) + ", not " + describe(e.value));
    }
    return {point_ref(e.value[0]), point_ref(e.value[1])};
  }

  const Entry& required(const Fields& f, const YAML::Node& owner, std::string_view key, std::string_view what) const {
    const Entry* e = f.find(key);
    if (!e) fail(owner, std::string(what) + " needs `" + std::string(key) + "`");
    return *e;
  }

  // A list section; an empty value stands for an empty list.
  std::vector<YAML::Node> list(const Entry& e, std::string_view example) const {
    if (e.value.IsNull()) return {};
    if (!e.value.IsSequence()) {
      fail(mark(e), "`" + e.key + "` must be a list like " + std::string(example) + ", not " + describe(e.value));
    }
    std::vector<YAML::Node> items;
    for (const YAML::Node& item : e.value) items.push_back(item);
    return items;
  }

  // ---- sections ----

  void parse_units(const Entry& e) {
    const Fields f = section_fields(e, kUnitsKeys, "{length: mm, angle: deg}");
    std::string length = model_.units.length, angle = model_.units.angle;
    if (const Entry* l = f.find("length")) {
      length = text_value(*l, "the length unit");
      if (!length_unit_scale(length)) fail(mark(*l), "unknown length unit '" + length + "' (use m, mm, cm, in or ft)");
    }
    if (const Entry* a = f.find("angle")) {
      angle = text_value(*a, "the angle unit");
      if (!angle_unit_scale(angle)) fail(mark(*a), "unknown angle unit '" + angle + "' (use deg or rad)");
    }
    model_.units = *Units::make(length, angle);
  }

  void parse_points(const Entry* e) {
    if (!e) fail(source_.model, "the model has no `points:` section");
    if (e->value.IsNull() || (e->value.IsMap() && e->value.size() == 0)) {
      fail(mark(e->key_node), "`points` is empty: a model needs at least one point");
    }
    if (!e->value.IsMap()) {
      fail(mark(*e), "`points` must be a mapping of point names to [x, y], not " + describe(e->value));
    }
    for (const Entry& p : entries(e->value, "point")) {
      if (!p.value.IsSequence() || p.value.size() != 2) {
        fail(mark(p), "a point needs [x, y]: point '" + p.key + "' has " + describe(p.value));
      }
      const double x = number(p.value[0], mark(p.value[0]), "x");
      const double y = number(p.value[1], mark(p.value[1]), "y");
      model_.points.push_back(Point{p.key, model_.units.length_scale * Eigen::Vector2d(x, y), false});
      source_.points.push_back(mark(p.key_node));
    }
  }

  void parse_ground(const Entry& e) {
    for (const YAML::Node& item : list(e, "[O2, O4]")) {
      const int p = point_ref(item);
      if (model_.points[p].ground) fail(item, "point '" + model_.points[p].name + "' is listed twice under `ground`");
      model_.points[p].ground = true;
    }
  }

  void parse_bodies(const Entry& e) {
    if (e.value.IsNull()) return;
    if (!e.value.IsMap()) {
      fail(mark(e), "`bodies` must be a mapping of body names to lists of points, not " + describe(e.value));
    }
    for (const Entry& b : entries(e.value, "body")) {
      if (!b.value.IsSequence()) {
        fail(mark(b), "body '" + b.key + "' needs a list of its points, like [A, B], not " + describe(b.value));
      }
      Body body;
      body.name = b.key;
      for (const YAML::Node& item : b.value) body.points.push_back(point_ref(item));
      model_.bodies.push_back(std::move(body));
      source_.bodies.push_back(mark(b.key_node));
    }
  }

  // Checked here as well as in validate() so that the error points into `lengths:`
  // rather than at the body.
  void parse_lengths(const Entry& e) {
    if (e.value.IsNull()) return;
    if (!e.value.IsMap()) fail(mark(e), "`lengths` must be a mapping like {crank: 80}, not " + describe(e.value));
    for (const Entry& l : entries(e.value, "the length of body")) {
      const int b = body_ref(l.key_node);
      Body& body = model_.bodies[b];
      if (body.points.size() != 2) {
        fail(l.key_node, "body '" + body.name + "' has " + std::to_string(body.points.size()) +
                             " points: `lengths` applies only to bodies with two points");
      }
      const double v = number(l, "a length");
      if (v <= 0.0) fail(mark(l), "the length of body '" + body.name + "' must be positive");
      body.length = v * model_.units.length_scale;
    }
  }

  void parse_sliders(const Entry& e) {
    for (const YAML::Node& item : list(e, "[{body: piston, point: C, along: [O2, X]}]")) {
      if (!item.IsMap()) {
        fail(item, "a slider is a mapping like {body: piston, point: C, along: [O2, X]}, not " + describe(item));
      }
      const Fields f = fields(item, kSliderKeys);
      Slider s;
      s.body = body_ref(required(f, item, "body", "a slider").value);
      s.point = point_ref(required(f, item, "point", "a slider").value);
      s.along = point_pair(required(f, item, "along", "a slider"), "[O2, X]");
      model_.sliders.push_back(s);
      source_.sliders.push_back(mark(item));
    }
  }

  void parse_slots(const Entry& e) {
    for (const YAML::Node& item : list(e, "[{point: D, along: [E, F]}]")) {
      if (!item.IsMap()) fail(item, "a slot is a mapping like {point: D, along: [E, F]}, not " + describe(item));
      const Fields f = fields(item, kSlotKeys);
      Slot s;
      s.point = point_ref(required(f, item, "point", "a slot").value);
      s.along = point_pair(required(f, item, "along", "a slot"), "[E, F]");
      model_.slots.push_back(s);
      source_.slots.push_back(mark(item));
    }
  }

  void parse_drivers(const Entry& e) {
    for (const YAML::Node& item : list(e, "[{angle: crank, from: 0, to: 360}]")) parse_driver(item);
  }

  void parse_driver(const YAML::Node& item) {
    if (!item.IsMap()) {
      fail(item, "a driver is a mapping like {angle: crank, from: 0, to: 360}, not " + describe(item));
    }
    const Fields f = fields(item, kDriverKeys);
    const Entry* kind_entry = nullptr;
    for (const Entry& field : f.entries) {
      if (field.key != "angle" && field.key != "distance" && field.key != "slide") continue;
      if (kind_entry) {
        fail(field.key_node, "a driver has exactly one of `angle`, `distance` or `slide`; this one already has `" +
                                 kind_entry->key + "`");
      }
      kind_entry = &field;
    }
    if (!kind_entry) fail(item, "a driver needs one of `angle: <body>`, `distance: [P, Q]` or `slide: <body>`");

    Driver d;
    const Entry* relative = f.find("relative_to");
    if (relative && kind_entry->key != "angle") {
      fail(relative->key_node, "`relative_to` applies only to `angle` drivers");
    }
    if (kind_entry->key == "angle") {
      d.kind = DriverKind::Angle;
      d.body = body_ref(kind_entry->value);
      d.name = model_.bodies[d.body].name;
      if (relative) {
        d.relative_to = body_ref(relative->value);
        d.name += "/" + model_.bodies[d.relative_to].name;
      }
    } else if (kind_entry->key == "distance") {
      d.kind = DriverKind::Distance;
      d.points = point_pair(*kind_entry, "[P, Q]");
      d.name = model_.points[d.points[0]].name + "-" + model_.points[d.points[1]].name;
    } else {
      d.kind = DriverKind::Slide;
      const int body = body_ref(kind_entry->value);
      const auto it =
          std::find_if(model_.sliders.begin(), model_.sliders.end(), [&](const Slider& s) { return s.body == body; });
      if (it == model_.sliders.end()) {
        fail(kind_entry->value,
             "body '" + model_.bodies[body].name + "' has no slider (`slide` names the body of a slider)");
      }
      d.slider = static_cast<int>(it - model_.sliders.begin());
      d.name = model_.bodies[body].name;
    }
    if (const Entry* n = f.find("name")) {
      d.name = text_value(*n, "a driver name");
      if (d.name.empty()) fail(mark(*n), "a driver name cannot be empty");
    }

    const double scale = d.is_angular() ? model_.units.angle_scale : model_.units.length_scale;
    const std::string unit = d.is_angular() ? model_.units.angle : model_.units.length;
    if (const Entry* from = f.find("from")) d.from = scale * number(*from, "`from` (" + unit + ")");
    if (const Entry* to = f.find("to")) d.to = scale * number(*to, "`to` (" + unit + ")");
    d.speed = scale;
    if (const Entry* speed = f.find("speed")) d.speed = rate(*speed, 1, d, scale);
    if (const Entry* accel = f.find("accel")) d.accel = rate(*accel, 2, d, scale);
    if (const Entry* law = f.find("law")) {
      for (std::string_view key : {"from", "to", "speed", "accel"}) {
        if (const Entry* other = f.find(key)) {
          fail(other->key_node, "driver '" + d.name + "' follows a `law`, which sets its motion, so it takes no `" +
                                    std::string(key) + "`");
        }
      }
      d.law = parse_law(*law, scale);
    }
    model_.drivers.push_back(std::move(d));
    source_.drivers.push_back(mark(item));
  }

  // A bare number is in driver units (angle or length unit) per second, or per second
  // squared; text carries its own unit, which must be of the driver's kind.
  double rate(const Entry& e, int order, const Driver& d, double scale) const {
    const std::string what = order == 1 ? "the speed" : "the acceleration";
    if (!e.value.IsScalar()) {
      fail(mark(e), what + " must be a number or a quantity like '1750 rpm', not " + describe(e.value));
    }
    const std::string text = e.value.Scalar();
    double value = 0.0;
    switch (parse_number(text, value)) {
      case NumberStatus::Ok: return value * scale;
      case NumberStatus::NotFinite: fail(mark(e), what + " must be a finite number, not '" + text + "'");
      case NumberStatus::NotNumber: break;
    }
    Quantity q;
    try {
      q = parse_rate(text, order);
    } catch (const std::invalid_argument& error) {
      fail(mark(e), error.what());
    }
    if (q.angular != d.is_angular()) {
      const std::string examples = order == 1 ? (d.is_angular() ? "rpm, deg/s or rad/s" : "m/s, mm/s or in/s")
                                              : (d.is_angular() ? "deg/s^2 or rad/s^2" : "m/s^2 or mm/s^2");
      fail(mark(e), "'" + text + "' is " + (q.angular ? "an angular" : "a linear") + " " +
                        (order == 1 ? "speed" : "acceleration") + " but driver '" + d.name + "' is " +
                        (d.is_angular() ? "an angle" : "a length") + ": use a unit such as " + examples);
    }
    return q.value_si;
  }

  Law parse_law(const Entry& e, double scale) const {
    if (!e.value.IsScalar()) {
      fail(mark(e), "a law must be an expression in t like \"30*sin(2*pi*t)\", not " + describe(e.value));
    }
    const std::string text = e.value.Scalar();
    try {
      return Law::parse(text, scale);
    } catch (const LawSyntaxError& error) {
      const std::optional<SourceMark> at = column_in_scalar(e.value, error.column());
      std::string message = "in the law '" + text + "': " + error.what();
      if (!at) message += " (at character " + std::to_string(error.column() + 1) + " of the law)";
      fail(at.value_or(mark(e)), message);
    }
  }

  // Where the character at `offset` of a scalar's value sits in the file. Quoted scalars
  // start one column after their quote and escapes take several characters in the file;
  // block scalars and values folded over lines are not mapped (nullopt).
  std::optional<SourceMark> column_in_scalar(const YAML::Node& node, int offset) const {
    const YAML::Mark m = node.Mark();
    if (m.pos < 0 || m.line < 0 || offset < 0 || static_cast<std::size_t>(m.pos) >= text_.size()) return std::nullopt;
    std::size_t pos = static_cast<std::size_t>(m.pos);
    const char quote = text_[pos];
    if (quote == '|' || quote == '>') return std::nullopt;
    const bool quoted = quote == '"' || quote == '\'';
    if (quoted) ++pos;
    for (int i = 0; i < offset; ++i) {
      if (pos >= text_.size() || text_[pos] == '\n' || text_[pos] == '\r') return std::nullopt;
      std::size_t width = 1;
      if (quote == '\'' && text_[pos] == '\'') {
        width = 2;  // '' stands for '
      } else if (quote == '"' && text_[pos] == '\\' && pos + 1 < text_.size()) {
        const char kind = text_[pos + 1];
        width = kind == 'x' ? 4 : kind == 'u' ? 6 : kind == 'U' ? 10 : 2;
      }
      pos += width;
    }
    if (pos > text_.size()) return std::nullopt;
    return SourceMark{m.line + 1, m.column + 1 + static_cast<int>(pos - static_cast<std::size_t>(m.pos))};
  }

  void parse_sweep(const Entry& e) {
    source_.sweep = mark(e.key_node);
    const Fields f = section_fields(e, kSweepKeys, "{steps: 361} or {duration: 0.1, step: 0.001}");
    const Entry* steps = f.find("steps");
    const Entry* duration = f.find("duration");
    const Entry* step = f.find("step");
    if (steps && step) fail(step->key_node, "give the sweep either `steps` or `step`, not both");
    const bool time_sweep = model_.has_time_law();
    for (const Entry* timed : {duration, step}) {
      if (timed && !time_sweep) {
        fail(timed->key_node, "`" + timed->key +
                                  "` applies only when a driver follows a `law` in time; a from/to sweep is "
                                  "sampled with `steps`");
      }
    }
    SweepSpec& sweep = model_.sweep;
    if (steps) {
      sweep.steps = whole_number(*steps, "`steps`");
      if (sweep.steps < 2) fail(mark(*steps), "the sweep needs at least 2 steps (ends included)");
    }
    if (duration) {
      sweep.duration = number(*duration, "`duration` (s)");
      if (sweep.duration <= 0.0) fail(mark(*duration), "the sweep duration must be positive");
    }
    if (step) {
      sweep.time_step = number(*step, "`step` (s)");
      if (*sweep.time_step <= 0.0) fail(mark(*step), "the sweep `step` must be positive");
      if (*sweep.time_step > sweep.duration) fail(mark(*step), "the sweep `step` is longer than its duration");
    } else if (steps && time_sweep) {
      sweep.time_step = sweep.duration / (sweep.steps - 1);
    }
  }
};

}  // namespace

LoadedModel parse_model(const std::string& text, const std::string& file_name) {
  return Parser(text, file_name).parse();
}

LoadedModel load_model_file(const std::string& path) {
  // A directory opens without error on Linux and then reads as empty, which would be
  // reported as an empty model.
  std::error_code status_error;
  if (std::filesystem::is_directory(path, status_error)) {
    throw ModelFileError(path, SourceMark{},
                         "cannot read: " + std::make_error_code(std::errc::is_a_directory).message());
  }
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    const std::error_code error(errno != 0 ? errno : EIO, std::generic_category());
    throw ModelFileError(path, SourceMark{}, "cannot read: " + error.message());
  }
  std::ostringstream contents;
  contents << in.rdbuf();
  if (in.bad()) throw ModelFileError(path, SourceMark{}, "cannot read: input error");
  return parse_model(contents.str(), path);
}

}  // namespace nbar::io
