#include "nbar/io/model_file.hpp"

#include <yaml-cpp/yaml.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "model_file_parser.hpp"
#include "nbar/io/file_text.hpp"
#include "yaml_support.hpp"

namespace nbar::io {

SourceMark SourceMap::sweep_stop() const { return sweep.line > 0 ? sweep : find({EntityRef::Kind::Driver, 0}); }

SourceMark SourceMap::find(const EntityRef& ref) const {
  const auto law_mark = [&](const std::vector<std::array<SourceMark, 2>>& laws) {
    if (ref.law < 0 || ref.law > 1 || ref.index < 0 || ref.index >= static_cast<int>(laws.size())) return SourceMark{};
    return laws[ref.index][ref.law];
  };
  SourceMark law_at;
  if (ref.kind == EntityRef::Kind::Driver) law_at = law_mark(driver_laws);
  if (ref.kind == EntityRef::Kind::PointLoad) law_at = law_mark(point_load_laws);
  if (ref.kind == EntityRef::Kind::Torque) law_at = law_mark(torque_laws);
  if (law_at.line > 0) return law_at;
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
    case EntityRef::Kind::PointLoad: return pick(point_loads);
    case EntityRef::Kind::Torque: return pick(torques);
    case EntityRef::Kind::Spring: return pick(springs);
    case EntityRef::Kind::Friction: return pick(frictions);
    case EntityRef::Kind::Simulation: return pick(simulation);
  }
  return model;
}

std::string locate(const SourceMap& source, const ModelError& error) {
  return compose_location(source.file, source.find(error.where()), error.message());
}

Error located(const SourceMap& source, const Error& error) {
  if (!error.file().empty() || error.kind() == ErrorKind::BadInput || error.kind() == ErrorKind::Cancelled ||
      error.kind() == ErrorKind::Internal)
    return error;
  // A stop at a limit about no entity in particular (draw at a value, explain a step the sweep
  // does not reach) is placed where a stopped sweep is: the sweep's line, or the first driver's.
  const bool sweep_stop = error.kind() == ErrorKind::StoppedAtLimit && error.where().kind == EntityRef::Kind::Model;
  if (error.where().kind == EntityRef::Kind::Model && !sweep_stop) return error;
  const SourceMark at = sweep_stop ? source.sweep_stop() : source.find(error.where());
  if (at.line == 0) return error;  // an entity the file does not name (made by the program)
  return Error(error.kind(), error.message(), error.where(), source.file, at);
}

namespace model_file_detail {
namespace {

// The words of the model file's document-level errors.
const yaml::DocumentWording kModelDocument{
    "the file holds no model (it is empty or only comments): a model needs at least `points:`",
    "a model file holds a single YAML document; remove this one or the `---` before it",
    "a model file is a mapping of sections (points:, bodies:, drivers:, ...), not "};

}  // namespace

LoadedModel Parser::parse() {
  const YAML::Node root = load(kModelDocument);
  source_.model = mark(root);
  const Fields top = fields(root, kTopLevelKeys);

  if (const Entry* e = top.find("name")) model_.name = text_value(*e, "the model name");
  if (const Entry* e = top.find("description")) text_value(*e, "the description");
  if (const Entry* e = top.find("units")) parse_units(*e);
  parse_points(top.find("points"));
  if (const Entry* e = top.find("ground")) parse_ground(*e);
  if (const Entry* e = top.find("materials")) parse_materials(*e);
  if (const Entry* e = top.find("bodies")) parse_bodies(*e);
  if (const Entry* e = top.find("lengths")) parse_lengths(*e);
  if (const Entry* e = top.find("sliders")) parse_sliders(*e);
  if (const Entry* e = top.find("slots")) parse_slots(*e);
  if (const Entry* e = top.find("drivers")) parse_drivers(*e);
  if (const Entry* e = top.find("sweep")) parse_sweep(*e);
  if (const Entry* e = top.find("gravity")) parse_gravity(*e);
  if (const Entry* e = top.find("forces")) parse_forces(*e);
  if (const Entry* e = top.find("torques")) parse_torques(*e);
  if (const Entry* e = top.find("springs")) parse_springs(*e);
  if (const Entry* e = top.find("friction")) parse_friction(*e);
  if (const Entry* e = top.find("simulation")) parse_simulation(*e);

  try {
    validate(model_);
  } catch (const ModelError& error) {
    ModelFileError located(source_.file, source_.find(error.where()), error.what());
    if (!draft_) throw located;
    draft_problem = located;
  }
  return LoadedModel{std::move(model_), std::move(source_), {}};
}

// Keys are also the names of points, bodies and materials, hence "key or name".
void Parser::check_key(const YAML::Node& key) const {
  if (key.IsNull()) {
    fail(key, "a key or name cannot be empty or null (quote names such as 'null' or '~')");
  }
  if (!key.IsScalar()) fail(key, std::string("a key or name must be a single word, not ").append(describe(key)));
  if (key.Scalar().empty()) fail(key, "a key or name cannot be empty");
}

// The mapping under a section key; an empty value stands for an empty mapping.
Fields Parser::section_fields(const Entry& e, const AllowedKeys& allowed, std::string_view example) const {
  if (e.value.IsNull()) return {};
  return mapping(e, allowed, example);
}

// A list section; an empty value stands for an empty list.
std::vector<YAML::Node> Parser::section_list(const Entry& e, std::string_view example) const {
  if (e.value.IsNull()) return {};
  return list(e, example);
}

int Parser::whole_number(const Entry& e, std::string_view what) const {
  const double v = number(e, what);
  if (v != std::floor(v)) fail(mark(e), std::string(what) + " must be a whole number");
  // Limits of their own (a sweep's samples, say) are checked where the value is used; past 1e9
  // it is no count a model means.
  if (std::abs(v) > 1e9) fail(mark(e), std::string(what) + " must be a whole number of at most a billion");
  return static_cast<int>(v);
}

std::string Parser::name_of(const YAML::Node& node, std::string_view what) const {
  if (!node.IsScalar() || node.Scalar().empty()) {
    fail(node, std::string(what) + " must be a name, not " + describe(node));
  }
  check_name_length(node);
  return node.Scalar();
}

int Parser::point_ref(const YAML::Node& node) const {
  const std::string name = name_of(node, "a point reference");
  const int index = model_.find_point(name);
  if (index < 0) fail_unknown(node, "point", "points", name, model_.points, [](const Point& p) { return p.name; });
  return index;
}

int Parser::body_ref(const YAML::Node& node) const {
  const std::string name = name_of(node, "a body reference");
  const int index = model_.find_body(name);
  if (index < 0) fail_unknown(node, "body", "bodies", name, model_.bodies, [](const Body& b) { return b.name; });
  return index;
}

std::array<int, 2> Parser::point_pair(const Entry& e, std::string_view example) const {
  if (!e.value.IsSequence() || e.value.size() != 2) {
    fail(mark(e), "`" + e.key + "` needs two point names, like " + std::string(example) + ", not " + describe(e.value));
  }
  return {point_ref(e.value[0]), point_ref(e.value[1])};
}

// Where the character at `offset` of a scalar's value sits in the file. Quoted scalars
// start one column after their quote and escapes take several characters in the file;
// block scalars and values folded over lines are not mapped (nullopt).
std::optional<SourceMark> Parser::column_in_scalar(const YAML::Node& node, int offset) const {
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

// `text` parsed as a law; syntax errors are reported at their character in `node`,
// followed by `hint` when there is one.
Law Parser::law_of(const YAML::Node& node, SourceMark at, const std::string& text, double scale,
                   const std::string& hint) const {
  try {
    return Law::parse(text, scale);
  } catch (const LawSyntaxError& error) {
    const std::optional<SourceMark> where = column_in_scalar(node, error.column());
    std::string message = "in the law '" + text + "': " + error.what();
    if (!where) message += " (at character " + std::to_string(error.column() + 1) + " of the law)";
    if (!hint.empty()) message += " (" + hint + ")";
    fail(where.value_or(at), message);
  }
}

void Parser::parse_units(const Entry& e) {
  model_.units = units_of(section_fields(e, kUnitsKeys, "{length: mm, angle: deg}"), model_.units);
}

}  // namespace model_file_detail

using model_file_detail::Parser;

LoadedModel parse_model(const std::string& text, const std::string& file_name) {
  LoadedModel loaded = Parser(text, file_name).parse();
  loaded.text = text;
  return loaded;
}

LoadedModel parse_model(const std::string& text, const std::string& file_name, const std::string& import_dir) {
  Parser parser(text, file_name);
  parser.allow_imports(import_dir);
  LoadedModel loaded = parser.parse();
  loaded.text = text;
  return loaded;
}

DraftModel parse_draft_model(const std::string& text, const std::string& file_name) {
  Parser parser(text, file_name);
  parser.allow_drafts();
  DraftModel draft{parser.parse(), parser.draft_problem};
  draft.loaded.text = text;
  return draft;
}

LoadedModel load_model_file(const std::string& path) {
  const FileText file = read_file_text(path);
  if (file.error) throw ModelFileError(path, SourceMark{}, "cannot read: " + file.error.message());
  if (file.too_long) throw ModelFileError(path, SourceMark{1, 1}, too_long_message());
  return parse_model(file.text, path, std::filesystem::path(path).parent_path().string());
}

}  // namespace nbar::io
