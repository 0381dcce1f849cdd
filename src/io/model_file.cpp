#include "nbar/io/model_file.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <numbers>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <string_view>
#include <system_error>
#include <utility>

#include "nbar/io/dxf_reader.hpp"
#include "nbar/io/sketch.hpp"
#include "nbar/io/yaml_support.hpp"
#include "nbar/model/curves.hpp"
#include "nbar/model/geometry.hpp"
#include "nbar/model/materials.hpp"

namespace nbar::io {

SourceMark SourceMap::sweep_stop() const {
  return sweep.line > 0 ? sweep : find({EntityRef::Kind::Driver, 0});
}

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
  }
  return model;
}

std::string locate(const SourceMap& source, const ModelError& error) {
  return compose_location(source.file, source.find(error.where()), error.message());
}

Error located(const SourceMap& source, const Error& error) {
  if (!error.file().empty() || error.kind() == ErrorKind::BadInput || error.kind() == ErrorKind::Cancelled ||
      error.where().kind == EntityRef::Kind::Model)
    return error;
  const SourceMark at = source.find(error.where());
  if (at.line == 0) return error;  // an entity the file does not name (made by the program)
  return Error(error.kind(), error.message(), error.where(), source.file, at);
}

namespace {

using yaml::AllowedKeys;
using yaml::describe;
using yaml::Entry;
using yaml::Fields;
using yaml::join;
using yaml::mark;
using yaml::NumberStatus;
using yaml::parse_number;
using yaml::suggestion;

// The keys each kind of mapping accepts, all in one place: new sections (shapes, loads,
// gravity, materials...) are declared here and then read in Parser::parse.
const AllowedKeys kTopLevelKeys{
    "at the top level",
    {"name", "description", "units", "points", "ground", "bodies", "lengths", "sliders", "slots", "drivers", "sweep",
     "gravity", "materials", "forces", "torques", "springs"}};
const AllowedKeys kUnitsKeys{"in `units`", {"length", "angle"}};
const AllowedKeys kSliderKeys{"in a slider", {"body", "point", "along"}};
const AllowedKeys kSlotKeys{"in a slot", {"point", "along"}};
const AllowedKeys kDriverKeys{
    "in a driver", {"name", "angle", "relative_to", "distance", "slide", "from", "to", "speed", "accel", "law"}};
const AllowedKeys kSweepKeys{"in `sweep`", {"steps", "duration", "step"}};
const AllowedKeys kBodyKeys{"in a body", {"points", "shape", "bar", "thickness", "material", "mass", "cg", "inertia"}};
const AllowedKeys kShapeKeys{"in a `shape`", {"outline", "upper", "lower", "import", "layer", "units", "holes"}};
const AllowedKeys kCurveKeys{"in a curve", {"x", "y", "s", "steps", "spline"}};
const AllowedKeys kArcKeys{"in an arc", {"centre", "radius", "angles"}};
const AllowedKeys kHoleKeys{"in a hole", {"at", "circle", "radius", "polygon"}};
const AllowedKeys kBarKeys{"in a `bar`", {"width", "margin", "hole", "holes", "between"}};
const AllowedKeys kMaterialKeys{"in a material", {"density", "yield", "youngs_modulus", "poisson_ratio"}};
const AllowedKeys kForceKeys{"in a force", {"point", "body", "force", "fx", "fy"}};
const AllowedKeys kTorqueKeys{"in a torque", {"body", "torque"}};
const AllowedKeys kSpringKeys{"in a spring", {"between", "stiffness", "free_length", "damping", "name"}};

// A unit a quantity may be written in, and its value in SI.
struct UnitScale {
  std::string_view unit;
  double scale;
};
constexpr double kPoundForce = 4.4482216152605;  // N
constexpr double kInch = 0.0254;                  // m
const std::vector<UnitScale> kStiffnessUnits{
    {"N/m", 1.0}, {"N/mm", 1e3}, {"kN/m", 1e3}, {"lbf/in", kPoundForce / kInch}};
const std::vector<UnitScale> kDampingUnits{{"N s/m", 1.0}, {"N s/mm", 1e3}};
constexpr double kPsi = kPoundForce / (kInch * kInch);  // Pa
const std::vector<UnitScale> kStressUnits{{"Pa", 1.0},  {"kPa", 1e3},       {"MPa", 1e6},
                                          {"GPa", 1e9}, {"psi", kPsi}, {"ksi", 1e3 * kPsi}};
constexpr double kStandardGravity = 9.80665;  // m/s^2

// The words of the model file's document-level errors.
const yaml::DocumentWording kModelDocument{
    "the file holds no model (it is empty or only comments): a model needs at least `points:`",
    "a model file holds a single YAML document; remove this one or the `---` before it",
    "a model file is a mapping of sections (points:, bodies:, drivers:, ...), not "};

class Parser : yaml::Reader {
 public:
  Parser(std::string text, std::string file) : Reader(std::move(text), file) { source_.file = std::move(file); }

  // Lets `shape: {import: FILE}` read files, relative to `dir` (the model file's folder). A
  // model parsed from text (the web server's) may not open files.
  void allow_imports(std::filesystem::path dir) { import_dir_ = std::move(dir); }

  LoadedModel parse() {
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

    try {
      validate(model_);
    } catch (const ModelError& error) {
      throw ModelFileError(source_.file, source_.find(error.where()), error.what());
    }
    return LoadedModel{std::move(model_), std::move(source_)};
  }

 private:
  Model model_;
  std::optional<std::filesystem::path> import_dir_;
  SourceMap source_;
  std::vector<Material> user_materials_;  // from `materials:`

  // ---- keys, mappings and lists (the generic readers are yaml::Reader's) ----

  // Keys are also the names of points, bodies and materials, hence "key or name".
  void check_key(const YAML::Node& key) const override {
    if (key.IsNull()) {
      fail(key, "a key or name cannot be empty or null (quote names such as 'null' or '~')");
    }
    if (!key.IsScalar()) fail(key, std::string("a key or name must be a single word, not ").append(describe(key)));
    if (key.Scalar().empty()) fail(key, "a key or name cannot be empty");
  }

  // The mapping under a section key; an empty value stands for an empty mapping.
  Fields section_fields(const Entry& e, const AllowedKeys& allowed, std::string_view example) const {
    if (e.value.IsNull()) return {};
    return mapping(e, allowed, example);
  }

  // A list section; an empty value stands for an empty list.
  std::vector<YAML::Node> section_list(const Entry& e, std::string_view example) const {
    if (e.value.IsNull()) return {};
    return list(e, example);
  }

  // ---- values ----

  int whole_number(const Entry& e, std::string_view what) const {
    const double v = number(e, what);
    if (v != std::floor(v)) fail(mark(e), std::string(what) + " must be a whole number");
    // Limits of their own (a sweep's samples, say) are checked where the value is used; past 1e9
    // it is no count a model means.
    if (std::abs(v) > 1e9) fail(mark(e), std::string(what) + " must be a whole number of at most a billion");
    return static_cast<int>(v);
  }

  std::string name_of(const YAML::Node& node, std::string_view what) const {
    if (!node.IsScalar() || node.Scalar().empty()) {
      fail(node, std::string(what) + " must be a name, not " + describe(node));
    }
    check_name_length(node);
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

  // ---- sections ----

  void parse_units(const Entry& e) {
    model_.units = units_of(section_fields(e, kUnitsKeys, "{length: mm, angle: deg}"), model_.units);
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
    for (const YAML::Node& item : section_list(e, "[O2, O4]")) {
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
      Body body;
      body.name = b.key;
      if (b.value.IsSequence()) {
        for (const YAML::Node& item : b.value) body.points.push_back(point_ref(item));
      } else if (b.value.IsMap()) {
        parse_body_details(b, body);
      } else {
        fail(mark(b), "body '" + b.key +
                          "' needs a list of its points, like [A, B], or a mapping with `points:`, not " +
                          describe(b.value));
      }
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
    for (const YAML::Node& item : section_list(e, "[{body: piston, point: C, along: [O2, X]}]")) {
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
    for (const YAML::Node& item : section_list(e, "[{point: D, along: [E, F]}]")) {
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
    for (const YAML::Node& item : section_list(e, "[{angle: crank, from: 0, to: 360}]")) parse_driver(item);
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
    // Without a speed, one driver unit a second towards `to`: time runs forward either way.
    d.speed = d.from && d.to && *d.to < *d.from ? -scale : scale;
    if (const Entry* speed = f.find("speed")) d.speed = rate(*speed, 1, d, scale);
    if (const Entry* accel = f.find("accel")) d.accel = rate(*accel, 2, d, scale);
    std::array<SourceMark, 2> law_marks{};
    if (const Entry* law = f.find("law")) {
      law_marks[0] = mark(*law);
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
    source_.driver_laws.push_back(law_marks);
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
    return law_of(e.value, mark(e), e.value.Scalar(), scale);
  }

  // `text` parsed as a law; syntax errors are reported at their character in `node`,
  // followed by `hint` when there is one.
  Law law_of(const YAML::Node& node, SourceMark at, const std::string& text, double scale,
             const std::string& hint = {}) const {
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
      if (sweep.steps < 1) fail(mark(*steps), "the sweep needs at least 1 step (1: the start pose alone)");
    }
    if (duration) {
      sweep.duration = number(*duration, "`duration` (s)");
      if (sweep.duration <= 0.0) fail(mark(*duration), "the sweep duration must be positive");
    }
    if (step) {
      sweep.time_step = number(*step, "`step` (s)");
      if (*sweep.time_step <= 0.0) fail(mark(*step), "the sweep `step` must be positive");
      if (*sweep.time_step > sweep.duration) fail(mark(*step), "the sweep `step` is longer than its duration");
    } else if (steps && time_sweep && sweep.steps > 1) {
      sweep.time_step = sweep.duration / (sweep.steps - 1);
    }
  }

  // ---- kinetics: materials, bodies' mass and shape, gravity, loads ----

  // A number (in the first of `units`) or "<number> <unit>" with one of `units` (`example`
  // shows one); in SI. Spaces and `*` inside the unit are ignored, so "N s/m", "N*s/m" and
  // "Ns/m" are the same; case is not ("mPa" is not "MPa").
  double quantity(const Entry& e, const std::string& what, const std::vector<UnitScale>& units,
                  std::string_view example) const {
    if (!e.value.IsScalar()) {
      fail(mark(e),
           what + " must be a number or a quantity like '" + std::string(example) + "', not " + describe(e.value));
    }
    const std::string text = e.value.Scalar();
    double value = 0.0;
    switch (parse_number(text, value)) {
      case NumberStatus::Ok: return value * units[0].scale;
      case NumberStatus::NotFinite: fail(mark(e), what + " must be a finite number, not '" + text + "'");
      case NumberStatus::NotNumber: break;
    }
    std::string_view rest = text;
    while (!rest.empty() && std::isspace(static_cast<unsigned char>(rest.front()))) rest.remove_prefix(1);
    if (!rest.empty() && rest.front() == '+') rest.remove_prefix(1);
    const auto [end, ec] = std::from_chars(rest.data(), rest.data() + rest.size(), value);
    if (ec == std::errc::invalid_argument || end == rest.data()) {
      fail(mark(e), what + " must be a number or a quantity like '" + std::string(example) + "', not '" + text +
                        "'");
    }
    if (ec == std::errc::result_out_of_range || !std::isfinite(value)) {
      fail(mark(e), what + " must be a finite number, not '" + text + "'");
    }
    const auto squeeze = [](std::string_view u) {
      std::string out;
      for (std::size_t i = 0; i < u.size(); ++i) {
        if (u[i] == ' ' || u[i] == '\t' || u[i] == '*') continue;
        if (u.substr(i, 2) == "\u00b7") {  // middle dot, "N·s/m"
          ++i;
          continue;
        }
        out += u[i];
      }
      return out;
    };
    const std::string unit = squeeze(rest.substr(static_cast<std::size_t>(end - rest.data())));
    for (const UnitScale& u : units) {
      if (squeeze(u.unit) == unit) return value * u.scale;
    }
    std::vector<std::string_view> names;
    for (const UnitScale& u : units) names.push_back(u.unit);
    const std::string known = join(names, names.size());
    if (unit.empty()) fail(mark(e), what + " '" + text + "' needs a unit: " + known);
    fail(mark(e), "unknown unit in " + what + " '" + text + "' (use " + known + ")");
  }

  // [x, y] in model units, as written (not converted).
  Eigen::Vector2d coordinates(const YAML::Node& node, std::string_view what) const {
    if (!node.IsSequence() || node.size() != 2) {
      fail(node, std::string(what) + " needs [x, y], not " + describe(node));
    }
    return {number(node[0], mark(node[0]), "x"), number(node[1], mark(node[1]), "y")};
  }

  // An outline or polygon hole: vertices [x, y], each optionally [x, y, {bulge: b}] or
  // [x, y, {through: [x, y]}] to make the edge to the next vertex a circular arc, and curves
  // (parametric, function profiles, splines) that add their polygonised vertices.
  struct Ring {
    std::vector<Eigen::Vector2d> vertices;
    std::vector<double> bulges;  // empty when every edge is straight
    std::vector<YAML::Node> origin;  // the item each vertex came from
    bool curves = false;
  };

  // A curve item of a ring, sampled once the ring's size (and so the tolerance) is known.
  struct CurveItem {
    YAML::Node node;
    CurveFunction point;
    double from = 0, to = 0;
    int steps = 0;  // 0: adaptive
    std::shared_ptr<const CubicSpline> spline;
  };

  // One item of a ring as written: a vertex (possibly starting an arc) or a curve.
  struct RingItem {
    YAML::Node node;
    std::optional<Eigen::Vector2d> vertex;
    double bulge = 0;
    std::optional<std::pair<YAML::Node, Eigen::Vector2d>> through;
    std::optional<CurveItem> curve;
    std::optional<Eigen::Vector2d> arc_end;  // an arc by centre, radius and angles: vertex to arc_end, with `bulge`
  };

  // An expression in `variable` (model length units, angles of sin and cos in radians), its
  // syntax errors reported at their character.
  Law curve_law(const YAML::Node& node, const std::string& text, std::string_view variable) const {
    try {
      return Law::parse(text, 1.0, variable);
    } catch (const LawSyntaxError& error) {
      const std::optional<SourceMark> where = column_in_scalar(node, error.column());
      fail(where.value_or(mark(node)), "in the expression '" + text + "': " + error.what());
    }
  }

  static std::string_view trimmed(std::string_view s) {
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
    return s;
  }

  // A number, or an expression of numbers such as "2*pi", written in `node`.
  double constant_text(const YAML::Node& node, std::string_view written, std::string_view what) const {
    const std::string text(trimmed(written));
    double value = 0;
    if (yaml::parse_number(text, value) == yaml::NumberStatus::Ok) return value;
    Law law;
    try {
      law = Law::parse(text, 1.0, "nothing");
    } catch (const LawSyntaxError& error) {
      fail(node, std::string(what) + " '" + text + "': " + error.what());
    }
    try {
      return law.value(0.0);
    } catch (const Error& error) {
      fail(node, std::string(what) + ": " + error.what());
    }
  }

  double curve_constant(const YAML::Node& node, std::string_view what) const {
    if (!node.IsScalar()) fail(node, std::string(what) + " must be a number, not " + describe(node));
    return constant_text(node, node.Scalar(), what);
  }

  std::pair<double, double> curve_interval(const YAML::Node& node, std::string_view what) const {
    if (!node.IsSequence() || node.size() != 2) fail(node, std::string(what) + " must be [from, to], not " + describe(node));
    const double a = curve_constant(node[0], "the start"), b = curve_constant(node[1], "the end");
    if (a == b) fail(node, std::string(what) + " is empty: [" + node[0].Scalar() + ", " + node[1].Scalar() + "]");
    return {a, b};
  }

  int curve_steps(const YAML::Node& node) const {
    const double n = number(node, mark(node), "`steps`");
    if (n != std::floor(n) || n < 1 || n > kMaxCurveSteps) {
      fail(node, "`steps` must be a whole number from 1 to " + std::to_string(kMaxCurveSteps));
    }
    return static_cast<int>(n);
  }

  // A function profile: `expression` of `variable` (x or y), over [a, b], giving the other
  // coordinate. The thesis tool's "f{a, b, steps}" gives the interval and steps inline.
  CurveItem profile(const YAML::Node& node, const YAML::Node& function, std::string_view variable,
                    const YAML::Node* interval, const YAML::Node* steps) const {
    if (!function.IsScalar()) fail(function, "a profile is an expression like \"x^2\", not " + describe(function));
    std::string text = function.Scalar();
    CurveItem c;
    c.node = node;
    const std::size_t brace = text.rfind('{');
    const bool inline_interval = brace != std::string::npos && !text.empty() && text.back() == '}';
    if (inline_interval) {
      if (interval) fail(*interval, "this profile gives its interval in braces already ('" + text + "')");
      std::vector<std::string> parts{""};
      for (char ch : text.substr(brace + 1, text.size() - brace - 2)) {
        if (ch == ',') {
          parts.emplace_back();
        } else {
          parts.back() += ch;
        }
      }
      if (parts.size() != 3) {
        fail(function, "a profile's braces hold {from, to, steps}, as in \"x^2{0, 2, 15}\", not '" +
                           text.substr(brace) + "'");
      }
      c.from = constant_text(function, parts[0], "the start in the braces");
      c.to = constant_text(function, parts[1], "the end in the braces");
      if (c.from == c.to) fail(function, "the profile's interval " + text.substr(brace) + " is empty");
      double n = 0;
      if (yaml::parse_number(std::string(trimmed(parts[2])), n) != yaml::NumberStatus::Ok || n != std::floor(n) ||
          n < 1 || n > kMaxCurveSteps) {
        fail(function, "the steps in a profile's braces must be a whole number from 1 to " +
                           std::to_string(kMaxCurveSteps) + ", not '" + parts[2] + "'");
      }
      c.steps = static_cast<int>(n);
      text.resize(brace);
    } else {
      if (!interval) {
        fail(node, "a profile " + std::string(variable == "x" ? "y" : "x") + " = f(" + std::string(variable) +
                       ") needs its interval: `" + std::string(variable) + ": [from, to]`, or \"f{from, to, steps}\"");
      }
      std::tie(c.from, c.to) = curve_interval(*interval, "the interval");
    }
    if (steps) {
      if (inline_interval) fail(*steps, "this profile gives its steps in braces already");
      c.steps = curve_steps(*steps);
    }
    const Law law = curve_law(function, text, variable);
    const bool of_x = variable == "x";
    c.point = [law, of_x](double v) {
      const double w = law.value(v);
      return of_x ? Eigen::Vector2d(v, w) : Eigen::Vector2d(w, v);
    };
    return c;
  }

  CurveItem curve_item(const YAML::Node& node) const {
    const Fields f = fields(node, kCurveKeys);
    const Entry* x = f.find("x");
    const Entry* y = f.find("y");
    const Entry* s = f.find("s");
    const Entry* steps = f.find("steps");
    const YAML::Node* steps_node = steps ? &steps->value : nullptr;
    if (const Entry* spline = f.find("spline")) {
      for (const Entry* other : {x, y, s, steps}) {
        if (other) fail(other->key_node, "a spline is {spline: [[x, y], ...]} alone, without `" + other->key + "`");
      }
      if (!spline->value.IsSequence()) fail(mark(*spline), "`spline` is a list of points [[x, y], ...]");
      std::vector<Eigen::Vector2d> points;
      for (const YAML::Node& p : spline->value) points.push_back(coordinates(p, "a spline point"));
      CurveItem c;
      c.node = node;
      try {
        c.spline = std::make_shared<const CubicSpline>(std::move(points), false);
      } catch (const std::invalid_argument& error) {
        fail(mark(*spline), error.what());
      }
      return c;
    }
    if (s) {
      if (!x || !y || !x->value.IsScalar() || !y->value.IsScalar()) {
        fail(node, "a parametric curve is {x: \"expression in s\", y: \"expression in s\", s: [from, to]}");
      }
      CurveItem c;
      c.node = node;
      std::tie(c.from, c.to) = curve_interval(s->value, "`s`");
      if (steps) c.steps = curve_steps(steps->value);
      const Law lx = curve_law(x->value, x->value.Scalar(), "s"), ly = curve_law(y->value, y->value.Scalar(), "s");
      c.point = [lx, ly](double v) { return Eigen::Vector2d(lx.value(v), ly.value(v)); };
      return c;
    }
    // A function profile: the expression is the scalar of x and y, the other (if any) its interval.
    if (y && y->value.IsScalar() && (!x || x->value.IsSequence())) {
      return profile(node, y->value, "x", x ? &x->value : nullptr, steps_node);
    }
    if (x && x->value.IsScalar() && (!y || y->value.IsSequence())) {
      return profile(node, x->value, "y", y ? &y->value : nullptr, steps_node);
    }
    fail(node, "a curve is {x: \"f(s)\", y: \"g(s)\", s: [a, b]}, {y: \"f(x)\", x: [a, b]}, {x: \"f(y)\", y: [a, b]} "
               "or {spline: [[x, y], ...]}, not " + describe(node));
  }

  // {centre: [x, y], radius: r, angles: [from, to]}: the arc from angle `from` to `to` (the
  // model's angle unit, counterclockwise when to > from), as its two ends and the bulge between.
  RingItem arc_item(const YAML::Node& node) const {
    const Fields f = fields(node, kArcKeys);
    const Entry* centre = f.find("centre");
    const Entry* radius = f.find("radius");
    const Entry* angles = f.find("angles");
    if (!centre || !radius || !angles) fail(node, "an arc is {centre: [x, y], radius: r, angles: [from, to]}");
    const Eigen::Vector2d c = coordinates(centre->value, "`centre`");
    const double r = number(radius->value, mark(*radius), "the radius");
    if (!(r > 0)) fail(mark(*radius), "an arc's radius must be > 0, not " + describe(radius->value));
    if (!angles->value.IsSequence() || angles->value.size() != 2) {
      fail(mark(*angles), "`angles` is [from, to] in the model's angle unit, not " + describe(angles->value));
    }
    const double scale = model_.units.angle_scale;
    const double from = scale * number(angles->value[0], mark(angles->value[0]), "the start angle");
    const double to = scale * number(angles->value[1], mark(angles->value[1]), "the end angle");
    const double sweep = to - from;
    if (!(std::abs(sweep) > 1e-9) || !(std::abs(sweep) < 2 * std::numbers::pi - 1e-9)) {
      fail(mark(*angles), "an arc sweeps more than 0 and less than a full turn; use a circle hole for a whole circle");
    }
    RingItem item;
    item.node = node;
    item.vertex = c + r * Eigen::Vector2d(std::cos(from), std::sin(from));
    item.arc_end = c + r * Eigen::Vector2d(std::cos(to), std::sin(to));
    item.bulge = std::tan(sweep / 4);
    return item;
  }

  RingItem ring_item(const YAML::Node& v) const {
    RingItem item;
    item.node = v;
    if (v.IsMap() && v["centre"]) return arc_item(v);
    if (v.IsMap()) {
      item.curve = curve_item(v);
      return item;
    }
    const bool with_arc = v.IsSequence() && v.size() == 3;
    if (!v.IsSequence() || (v.size() != 2 && !with_arc)) {
      fail(v, "a vertex needs [x, y], not " + describe(v) +
                  " (or [x, y, {bulge: b}] for an arc to the next vertex, or a curve {x: ..., y: ...})");
    }
    item.vertex = Eigen::Vector2d(number(v[0], mark(v[0]), "x"), number(v[1], mark(v[1]), "y"));
    if (!with_arc) return item;
    const YAML::Node arc = v[2];
    if (!arc.IsMap() || arc.size() != 1 || !(arc["bulge"] || arc["through"])) {
      fail(arc, "an arc on a vertex is {bulge: b} or {through: [x, y]}, not " + describe(arc));
    }
    if (arc["bulge"]) {
      item.bulge = number(arc["bulge"], mark(arc["bulge"]), "the bulge");
    } else {
      item.through = std::make_pair(arc["through"], coordinates(arc["through"], "`through`"));
    }
    return item;
  }

  // The vertices of a curve item, at the ring's tolerance (or its fixed steps).
  std::vector<Eigen::Vector2d> curve_vertices(const CurveItem& c, double tolerance) const {
    try {
      if (c.spline) return sample_spline(*c.spline, tolerance);
      if (c.steps > 0) return sample_curve_uniform(c.point, c.from, c.to, c.steps);
      return sample_curve(c.point, c.from, c.to, tolerance);
    } catch (const Error& error) {
      fail(c.node, std::string("this curve: ") + error.what());
    } catch (const std::invalid_argument& error) {
      fail(c.node, std::string("this curve: ") + error.what());
    }
  }

  // The tolerance of a ring's curves: kRelativeCurveTolerance of the diagonal of the box
  // around its vertices and a first coarse sampling of its curves.
  double ring_tolerance(const std::vector<RingItem>& items) const {
    Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    const auto grow = [&](const Eigen::Vector2d& p) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    };
    for (const RingItem& item : items) {
      if (item.vertex) grow(*item.vertex);
      if (!item.curve) continue;
      CurveItem coarse = *item.curve;
      coarse.steps = 64;
      if (coarse.spline) {
        for (double k = 0; k <= 64; ++k) grow((*coarse.spline)(coarse.spline->end() * k / 64));
      } else {
        for (const Eigen::Vector2d& p : curve_vertices(coarse, 1.0)) grow(p);
      }
    }
    const double diagonal = (hi - lo).norm();
    return diagonal > 0 && std::isfinite(diagonal) ? kRelativeCurveTolerance * diagonal : 1.0;
  }

  Ring ring_of(const std::vector<RingItem>& items, SourceMark where, std::string_view what) const {
    Ring ring;
    const double tolerance = ring_tolerance(items);
    // Where a curve ends on the next item's start, up to its rounding (cos(2 pi) is not 1).
    const double same = 1e-9 * tolerance / kRelativeCurveTolerance;
    bool after_curve = false;
    std::vector<double> bulges;
    std::vector<std::optional<std::pair<YAML::Node, Eigen::Vector2d>>> through;
    bool arcs = false;
    for (const RingItem& item : items) {
      std::vector<Eigen::Vector2d> added;
      if (item.curve) {
        added = curve_vertices(*item.curve, tolerance);
        ring.curves = true;
      } else {
        added.push_back(*item.vertex);
      }
      for (const Eigen::Vector2d& p : added) {
        // A curve that starts where the previous item ended shares that vertex.
        if ((item.curve || item.arc_end || after_curve) && !ring.vertices.empty() && (p - ring.vertices.back()).norm() <= same &&
            bulges.back() == 0 && !through.back()) {
          continue;
        }
        ring.vertices.push_back(p);
        ring.origin.push_back(item.node);
        bulges.push_back(0.0);
        through.emplace_back();
      }
      after_curve = item.curve.has_value() || item.arc_end.has_value();
      if (item.vertex && (item.bulge != 0 || item.through || item.node.size() == 3 || item.arc_end)) {
        arcs = true;
        bulges.back() = item.bulge;
        through.back() = item.through;
      }
      if (item.arc_end) {
        ring.vertices.push_back(*item.arc_end);
        ring.origin.push_back(item.node);
        bulges.push_back(0.0);
        through.emplace_back();
      }
    }
    // A closed curve (or an arc) ends where the ring starts.
    const bool ends_with_arc = !items.empty() && items.back().arc_end.has_value();
    while ((ring.curves || ends_with_arc) && ring.vertices.size() > 1 &&
           (ring.vertices.back() - ring.vertices.front()).norm() <= same && bulges.back() == 0) {
      ring.vertices.pop_back();
      ring.origin.pop_back();
      bulges.pop_back();
      through.pop_back();
    }
    const std::size_t n = ring.vertices.size();
    if (ring.curves && n > 2 * static_cast<std::size_t>(kMaxCurveSteps)) {
      fail(where, std::string(what) + " has " + std::to_string(n) + " vertices with its curves, more than " +
                      std::to_string(2 * kMaxCurveSteps) + ": give its curves fewer `steps`");
    }
    if (n < (arcs ? 2u : 3u)) {
      fail(where, std::string(what) + " needs at least " + (arcs ? "2 vertices with an arc" : "3 vertices") +
                      ", not " + std::to_string(n));
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (!through[i]) continue;
      try {
        bulges[i] = bulge_through(ring.vertices[i], ring.vertices[(i + 1) % n], through[i]->second);
      } catch (const std::invalid_argument& error) {
        fail(through[i]->first, std::string("`through`: ") + error.what());
      }
    }
    if (arcs) ring.bulges = std::move(bulges);
    return ring;
  }

  Ring polygon(const Entry& e, std::string_view what) const {
    if (!e.value.IsSequence()) {
      fail(mark(e), "`" + e.key + "` must be a list of vertices like [[0, 0], [100, 0], [100, 20]], not " +
                        describe(e.value));
    }
    std::vector<RingItem> items;
    for (const YAML::Node& v : e.value) items.push_back(ring_item(v));
    // A ring that is one spline through points that close on themselves is a periodic spline.
    if (items.size() == 1 && items[0].curve && items[0].curve->spline) {
      const YAML::Node points = e.value[0]["spline"];
      std::vector<Eigen::Vector2d> p;
      for (const YAML::Node& q : points) p.push_back(coordinates(q, "a spline point"));
      if (p.size() > 3 && p.front() == p.back()) {
        p.pop_back();
        items[0].curve->spline = std::make_shared<const CubicSpline>(std::move(p), true);
      }
    }
    return ring_of(items, mark(e), what);
  }

  // The outline between a lower and an upper profile, as the thesis tool builds a link: the
  // lower profiles from left to right, then the upper ones from right to left, joined by
  // straight edges.
  Ring profiles_ring(const Entry* lower, const Entry* upper, const YAML::Node& shape) const {
    if (!lower || !upper) {
      fail(shape, "a shape by profiles needs both `lower` and `upper` (each like \"x^2{0, 2, 15}\" or "
                  "{y: \"x^2\", x: [0, 2]})");
    }
    const auto profiles = [&](const Entry& e) {
      std::vector<RingItem> items;
      const auto one = [&](const YAML::Node& p) {
        RingItem item;
        item.node = p;
        if (p.IsScalar()) {
          item.curve = profile(p, p, "x", nullptr, nullptr);
        } else if (p.IsMap()) {
          item.curve = curve_item(p);
          if (item.curve->spline || !p["y"] || !p["y"].IsScalar()) {
            fail(p, "an upper or lower profile is y = f(x): \"f{from, to, steps}\" or {y: \"f\", x: [from, to]}");
          }
        } else {
          fail(p, "an upper or lower profile is \"f{from, to, steps}\" or {y: \"f\", x: [from, to]}, not " +
                      describe(p));
        }
        if (item.curve->from > item.curve->to) std::swap(item.curve->from, item.curve->to);
        items.push_back(std::move(item));
      };
      if (e.value.IsSequence()) {
        for (const YAML::Node& p : e.value) one(p);
      } else {
        one(e.value);
      }
      std::vector<double> starts;
      for (const RingItem& item : items) starts.push_back(item.curve->from);
      std::vector<std::size_t> order(items.size());
      for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
      std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return starts[a] < starts[b]; });
      std::vector<RingItem> sorted;
      for (std::size_t i : order) sorted.push_back(items[i]);
      return sorted;
    };
    std::vector<RingItem> items = profiles(*lower);
    std::vector<RingItem> top = profiles(*upper);
    for (auto it = top.rbegin(); it != top.rend(); ++it) {
      std::swap(it->curve->from, it->curve->to);
      items.push_back(std::move(*it));
    }
    return ring_of(items, mark(shape), "an outline by profiles");
  }

  // check_region names vertices of the polygonised ring; with curves, say where they came from.
  static std::string with_origins(std::string message, const Ring& ring) {
    if (!ring.curves) return message;
    std::string out;
    std::size_t last = 0;
    for (const EdgeMention& edge : edge_mentions(message)) {
      out.append(message, last, edge.end - last);
      if (edge.from < ring.origin.size()) out += " (of the item at line " + std::to_string(mark(ring.origin[edge.from]).line) + ")";
      last = edge.end;
    }
    out.append(message, last, std::string::npos);
    return out;
  }

  // The position of a point in model units, for geometry written in model units.
  Eigen::Vector2d drawn(int point) const { return model_.points[point].position / model_.units.length_scale; }

  Region to_si(Region r) const {
    const double s = model_.units.length_scale;
    for (Eigen::Vector2d& v : r.outline) v *= s;
    for (auto& hole : r.polygon_holes) {
      for (Eigen::Vector2d& v : hole) v *= s;
    }
    for (Circle& c : r.circle_holes) {
      c.centre *= s;
      c.radius *= s;
    }
    return r;
  }

  void parse_materials(const Entry& e) {
    if (e.value.IsNull()) return;
    if (!e.value.IsMap()) {
      fail(mark(e), "`materials` must be a mapping like {my-alloy: {density: 2800, yield: 250 MPa}}, not " +
                        describe(e.value));
    }
    for (const Entry& m : entries(e.value, "material")) {
      if (builtin_material(m.key)) {
        fail(m.key_node, "'" + m.key + "' is a built-in material; give yours another name");
      }
      if (!m.value.IsMap()) {
        fail(mark(m), "material '" + m.key + "' needs a mapping like {density: 2800, yield: 250 MPa}, not " +
                          describe(m.value));
      }
      user_materials_.push_back(material_fields(m.value, m.key));
    }
  }

  Material material_fields(const YAML::Node& map, const std::string& name) const {
    const Fields f = fields(map, kMaterialKeys);
    Material m;
    m.name = name;
    m.density = non_negative(required(f, map, "density", "a material"), "the density (kg/m^3)", true);
    if (const Entry* y = f.find("yield")) {
      m.yield_strength = quantity(*y, "the yield strength", kStressUnits, "250 MPa");
      if (*m.yield_strength <= 0.0) {
        fail(mark(*y), "the yield strength must be positive (leave `yield` out for a brittle material)");
      }
    }
    if (const Entry* e = f.find("youngs_modulus")) {
      m.youngs_modulus = quantity(*e, "Young's modulus", kStressUnits, "200 GPa");
      if (*m.youngs_modulus <= 0.0) fail(mark(*e), "Young's modulus must be positive, like 200 GPa for steel");
    }
    if (const Entry* nu = f.find("poisson_ratio")) {
      m.poisson_ratio = number(*nu, "Poisson's ratio");
      // 0.5 is an incompressible solid, which plane-stress elements cannot take; a negative
      // ratio (auxetic foams) is left out of a linkage tool's materials on purpose.
      if (*m.poisson_ratio < 0.0 || *m.poisson_ratio >= 0.5)
        fail(mark(*nu), "Poisson's ratio must be at least 0 and less than 0.5 (0.3 for steel), not " +
                            nu->value.Scalar());
    }
    return m;
  }

  Material material_of(const Entry& e) const {
    if (e.value.IsMap()) return material_fields(e.value, "");
    if (!e.value.IsScalar() || e.value.Scalar().empty()) {
      fail(mark(e), "`material` must be a material name like steel, or a mapping like {density: 7850, yield: 250 MPa}, "
                    "not " + describe(e.value));
    }
    const std::string name = e.value.Scalar();
    for (const Material& m : user_materials_) {
      if (m.name == name) return m;
    }
    if (auto m = builtin_material(name)) return *m;
    std::vector<std::string> names;
    for (const Material& m : user_materials_) names.push_back(m.name);
    for (const std::string& n : builtin_material_names()) names.push_back(n);
    std::string message = "unknown material '" + name + "'";
    if (auto close = suggestion(name, names)) message += "; did you mean '" + *close + "'?";
    message += " (known materials: " + join(names, names.size()) + "; or define it under `materials:`)";
    fail(mark(e), message);
  }

  // The long form of a body: {points: [...], shape or bar, thickness, material, mass, cg, inertia}.
  void parse_body_details(const Entry& b, Body& body) {
    const Fields f = fields(b.value, kBodyKeys);
    const std::string name = "body '" + b.key + "'";
    const Entry& points = required(f, b.key_node, "points", name);
    if (!points.value.IsSequence()) {
      fail(mark(points), "`points` must be a list of point names like [A, B], not " + describe(points.value));
    }
    for (const YAML::Node& item : points.value) body.points.push_back(point_ref(item));

    const Entry* plate = nullptr;  // `shape` or `bar`, whichever comes first
    for (const Entry& field : f.entries) {
      if (field.key != "shape" && field.key != "bar") continue;
      if (plate) fail(field.key_node, name + " has either a `shape` or a `bar`, not both");
      plate = &field;
    }
    if (plate) body.shape = plate->key == "shape" ? parse_shape(*plate, name) : parse_bar(*plate, body, name);

    const Entry* thickness = f.find("thickness");
    if (plate && !thickness) fail(plate->key_node, name + " has a " + plate->key + " but no `thickness`");
    if (thickness && !plate) {
      fail(thickness->key_node, "`thickness` applies only to a body with a `shape` or a `bar`");
    }
    if (thickness) {
      body.thickness = non_negative(*thickness, "the thickness", true) * model_.units.length_scale;
    }

    const Entry* material = f.find("material");
    if (material) body.material = material_of(*material);

    const Entry* mass = f.find("mass");
    for (std::string_view key : {"cg", "inertia"}) {
      const Entry* given = f.find(key);
      if (given && !mass) {
        fail(given->key_node, "`" + given->key + "` applies only with `mass`" +
                                  (plate ? " (otherwise the shape and material give the mass properties)" : ""));
      }
    }
    if (mass) {
      GivenInertia given;
      given.mass = non_negative(*mass, "the mass (kg)");
      if (const Entry* cg = f.find("cg")) {
        if (cg->value.IsScalar()) {
          given.cg = model_.points[point_ref(cg->value)].position;
        } else if (cg->value.IsSequence()) {
          given.cg = model_.units.length_scale * coordinates(cg->value, "`cg`");
        } else {
          fail(mark(*cg), "`cg` must be a point name or [x, y], not " + describe(cg->value));
        }
      } else if (body.shape) {
        given.cg = area_properties(*body.shape).centroid;
      } else if (!body.points.empty()) {
        given.cg = model_.points[body.points.front()].position;
      }
      if (const Entry* inertia = f.find("inertia")) given.inertia = non_negative(*inertia, "the inertia (kg m^2)");
      body.inertia = given;
    }

    if (plate && !material && !mass) {
      fail(plate->key_node, name + " has a " + plate->key + " but no material: give `material:` or `mass:`");
    }
    if (material && !plate && !mass) {
      fail(material->key_node, name + " has a material but nothing to weigh: give it a `shape` or a `bar` (with " +
                                   "`thickness`), or its `mass:`");
    }
  }

  // One hole of a shape, in model units, before it is checked.
  struct Hole {
    YAML::Node node;
    std::optional<Circle> circle;
    Ring polygon;
  };

  // Every polygon hole gets its list of bulges, empty when straight, so the lists stay aligned.
  static void add_hole(Region& r, const Hole& h) {
    if (h.circle) {
      r.circle_holes.push_back(*h.circle);
    } else {
      r.polygon_holes.push_back(h.polygon.vertices);
      r.polygon_hole_bulges.push_back(h.polygon.bulges);
    }
  }

  Hole parse_hole(const YAML::Node& item) const {
    if (!item.IsMap()) {
      fail(item, "a hole is a mapping like {at: A, radius: 5}, {circle: [50, 10], radius: 4} or "
                 "{polygon: [[x, y], ...]}, not " + describe(item));
    }
    const Fields f = fields(item, kHoleKeys);
    const Entry* kind = nullptr;
    for (const Entry& field : f.entries) {
      if (field.key != "at" && field.key != "circle" && field.key != "polygon") continue;
      if (kind) {
        fail(field.key_node, "a hole has exactly one of `at`, `circle` or `polygon`; this one already has `" +
                                 kind->key + "`");
      }
      kind = &field;
    }
    if (!kind) fail(item, "a hole needs one of `at: <point>`, `circle: [x, y]` or `polygon: [[x, y], ...]`");
    Hole hole;
    hole.node = item;
    const Entry* radius = f.find("radius");
    if (kind->key == "polygon") {
      if (radius) fail(radius->key_node, "`radius` applies only to a round hole (`at` or `circle`)");
      hole.polygon = polygon(*kind, "a polygon hole");
      return hole;
    }
    if (!radius) fail(item, "a round hole needs `radius`");
    const Eigen::Vector2d centre =
        kind->key == "at" ? drawn(point_ref(kind->value)) : coordinates(kind->value, "`circle`");
    hole.circle = Circle{centre, non_negative(*radius, "the radius", true)};
    return hole;
  }

  // Checked piece by piece so that an error points at the outline or at the hole concerned.
  Region parse_shape(const Entry& e, const std::string& body) const {
    if (!e.value.IsMap()) {
      fail(mark(e), "`shape` must be a mapping like {outline: [[0, 0], [100, 0], [100, 20], [0, 20]]}, not " +
                        describe(e.value));
    }
    const Fields f = fields(e.value, kShapeKeys);
    const std::string invalid = "the shape of " + body + " is not valid: ";
    const Entry* imported = f.find("import");
    const Entry* lower = f.find("lower");
    const Entry* upper = f.find("upper");
    const Entry* written = f.find("outline");
    {
      int ways = 0;
      const Entry* second = nullptr;
      for (const Entry* way : {written, imported, lower ? lower : upper}) {
        if (way && ++ways == 2) second = way;
      }
      if (second) fail(second->key_node, "a shape has one of `outline`, `import` or `lower` and `upper`");
    }
    if (!imported && !lower && !upper) required(f, e.value, "outline", "a shape");
    const Entry& outline = imported ? *imported : written ? *written : lower ? *lower : *upper;
    Region region;
    const Entry* layer = f.find("layer");
    if (layer && !imported) fail(layer->key_node, "`layer` goes with `import`: the layer (DXF) or group (SVG) of the drawing to read");
    const Entry* units = f.find("units");
    if (units && !imported) fail(units->key_node, "`units` goes with `import`: the length unit of the file read");
    Ring outer;
    if (imported) {
      region = import_plate(*imported, layer ? text_value(*layer, "`layer`") : std::string(), units);
    } else {
      outer = written ? polygon(*written, "an outline") : profiles_ring(lower, upper, e.value);
      region.outline = outer.vertices;
      region.outline_bulges = outer.bulges;
    }
    try {
      check_region(region);
    } catch (const std::invalid_argument& error) {
      fail(mark(outline), invalid + with_origins(error.what(), outer));
    }
    std::vector<Hole> holes;
    if (const Entry* h = f.find("holes")) {
      for (const YAML::Node& item : section_list(*h, "[{at: A, radius: 5}]")) holes.push_back(parse_hole(item));
    }
    for (std::size_t k = 0; k < holes.size(); ++k) {
      Region alone{region.outline, {}, {}, region.outline_bulges, {}};
      add_hole(alone, holes[k]);
      try {
        check_region(alone);
      } catch (const std::invalid_argument& error) {
        // The hole is the only one checked, so it is "hole 0" to check_region.
        std::string reason = error.what();
        for (std::string_view name : {"circle hole 0", "polygon hole 0"}) {
          if (reason.rfind(name, 0) == 0) reason = "the hole" + reason.substr(name.size());
        }
        fail(holes[k].node, invalid + reason);
      }
      for (std::size_t j = 0; j < k; ++j) {
        Region pair{region.outline, {}, {}, region.outline_bulges, {}};
        add_hole(pair, holes[j]);
        add_hole(pair, holes[k]);
        try {
          check_region(pair);
        } catch (const std::invalid_argument&) {
          fail(holes[k].node, invalid + "this hole overlaps or touches hole " + std::to_string(j + 1) + " (line " +
                                  std::to_string(mark(holes[j].node).line) + ")");
        }
      }
    }
    for (const Hole& h : holes) add_hole(region, h);
    if (imported) {
      // The drawing's own holes were not checked one by one above.
      try {
        check_region(region);
      } catch (const std::invalid_argument& error) {
        fail(mark(outline), invalid + error.what());
      }
    }
    return to_si(std::move(region));
  }

  // `import: FILE`: a plate drawn in a DXF file (on one layer, if given), in the model's units.
  Region import_plate(const Entry& e, const std::string& layer, const Entry* units) const {
    const std::string name = text_value(e, "`import`");
    if (!import_dir_) {
      fail(mark(e), "`import` reads a file, which only a model read from a file may do");
    }
    std::filesystem::path path(name);
    if (path.is_relative()) path = *import_dir_ / path;
    const std::optional<SketchFormat> format = sketch_format(path.string());
    if (!format) fail(mark(e), "`import` reads DXF (.dxf), SVG (.svg) or sketch CSV (.csv) drawings, not '" + name + "'");
    const FileText file = read_file_text(path);
    if (file.error) fail(mark(e), "cannot read " + path.string() + ": " + file.error.message());
    if (file.too_long) fail(mark(e), "cannot read " + path.string() + ": " + too_long_message());
    std::optional<double> stated;
    if (units) {
      stated = length_unit_scale(text_value(*units, "`units`"));
      if (!stated) fail(mark(*units), "the unit of the file read is one of mm, cm, m, in, ft");
    }
    const Sketch sketch = read_sketch(file.text, path.string(), *format, layer);
    return checked_plate_from_sketch(sketch, sketch_scale(sketch, stated, model_.units.length_scale), path.string());
  }

  Region parse_bar(const Entry& e, const Body& body, const std::string& name) const {
    if (!e.value.IsMap()) {
      fail(mark(e), "`bar` must be a mapping like {width: 20, margin: 10, hole: 5}, not " + describe(e.value));
    }
    const Fields f = fields(e.value, kBarKeys);
    std::array<int, 2> ends{};
    if (const Entry* between = f.find("between")) {
      ends = point_pair(*between, "[A, B]");
      if (ends[0] == ends[1]) fail(mark(*between), "a bar runs between two different points");
    } else if (body.points.size() < 2) {
      fail(e.key_node, name + " has a single point: say where its bar runs with `between: [P, Q]`");
    } else {
      ends = {body.points[0], body.points[1]};
    }
    const double width = non_negative(required(f, e.value, "width", "a bar"), "the width", true);
    double margin = width / 2;
    if (const Entry* m = f.find("margin")) margin = non_negative(*m, "the margin");
    std::array<double, 2> radii{0.0, 0.0};
    const Entry* hole = f.find("hole");
    const Entry* holes = f.find("holes");
    if (hole && holes) {
      const Entry* second = hole > holes ? hole : holes;  // entries are stored in file order
      fail(second->key_node, "give a bar either `hole` (both ends) or `holes: [r1, r2]`, not both");
    }
    if (hole) radii[0] = radii[1] = non_negative(*hole, "the hole radius");
    if (holes) {
      if (!holes->value.IsSequence() || holes->value.size() != 2) {
        fail(mark(*holes), "`holes` needs two radii [r1, r2], one per end (0 for none), not " +
                               describe(holes->value));
      }
      for (std::size_t i = 0; i < 2; ++i) {
        radii[i] = number(holes->value[i], mark(holes->value[i]), "a hole radius");
        if (radii[i] < 0.0) fail(holes->value[i], "a hole radius must not be negative");
      }
    }
    try {
      return to_si(make_bar(drawn(ends[0]), drawn(ends[1]), width, margin, radii[0], radii[1]));
    } catch (const std::invalid_argument& error) {
      std::string_view reason = error.what();
      if (reason.rfind("make_bar: ", 0) == 0) reason.remove_prefix(10);
      fail(mark(e), "the bar of " + name + " is not valid: " + std::string(reason));
    }
  }

  void parse_gravity(const Entry& e) {
    if (e.value.IsNull()) return;
    if (e.value.IsScalar() && e.value.Scalar() == "standard") {
      model_.gravity = Eigen::Vector2d(0.0, -kStandardGravity);
      return;
    }
    if (e.value.IsSequence() && e.value.size() == 2) {
      model_.gravity = Eigen::Vector2d(number(e.value[0], mark(e.value[0]), "gx (m/s^2)"),
                                       number(e.value[1], mark(e.value[1]), "gy (m/s^2)"));
      return;
    }
    std::string message = "`gravity` must be [gx, gy] in m/s^2 or `standard`, not " + describe(e.value);
    double value = 0.0;
    if (e.value.IsScalar() && parse_number(e.value.Scalar(), value) == NumberStatus::Ok) {
      std::string down = e.value.Scalar();
      if (!down.empty() && (down.front() == '-' || down.front() == '+')) down.erase(0, 1);
      message += " (write [0, -" + down + "] for " + down + " m/s^2 downwards)";
    }
    fail(mark(e), message);
  }

  // A force or torque component: a number, or a law in t (text), in SI: `unit` is N or N m.
  Law load_law(const YAML::Node& node, SourceMark at, const std::string& what, std::string_view unit) const {
    if (!node.IsScalar()) {
      fail(at, what + " must be a number or an expression in t like \"100*sin(2*pi*t)\", not " + describe(node));
    }
    const std::string text = node.Scalar();
    double value = 0.0;
    switch (parse_number(text, value)) {
      case NumberStatus::Ok:
        try {
          return Law::parse(text.front() == '+' ? text.substr(1) : text);
        } catch (const LawSyntaxError&) {
          std::ostringstream canonical;  // a spelling of the number the law grammar does not read
          canonical.precision(17);
          canonical << value;
          return Law::parse(canonical.str());
        }
      case NumberStatus::NotFinite: fail(at, what + " must be a finite number, not '" + text + "'");
      case NumberStatus::NotNumber: break;
    }
    // "5 N" reads as a number with a unit, which laws do not take.
    std::string hint;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec == std::errc() && end != text.data() && end != text.data() + text.size() && *end == ' ') {
      hint = what + " is in " + std::string(unit) + ": write a number without its unit, or an expression in t";
    }
    return law_of(node, at, text, 1.0, hint);
  }

  void parse_forces(const Entry& e) {
    for (const YAML::Node& item : section_list(e, "[{point: P, force: [0, -100]}]")) {
      if (!item.IsMap()) fail(item, "a force is a mapping like {point: P, force: [0, -100]}, not " + describe(item));
      const Fields f = fields(item, kForceKeys);
      PointLoad load;
      load.point = point_ref(required(f, item, "point", "a force").value);
      if (const Entry* body = f.find("body")) {
        load.body = body_ref(body->value);
        const Body& b = model_.bodies[load.body];
        if (std::find(b.points.begin(), b.points.end(), load.point) == b.points.end()) {
          std::vector<std::string> names;
          for (int p : b.points) names.push_back(model_.points[p].name);
          fail(body->value, "point '" + model_.points[load.point].name + "' is not a point of body '" + b.name +
                                "' (its points are: " + join(names) + ")");
        }
      }
      const Entry* force = f.find("force");
      const Entry* fx = f.find("fx");
      const Entry* fy = f.find("fy");
      if (force && (fx || fy)) {
        fail((fx ? fx : fy)->key_node, "give a force either as `force: [fx, fy]` or as `fx` and `fy`, not both");
      }
      std::array<SourceMark, 2> law_marks{};
      if (force) {
        if (!force->value.IsSequence() || force->value.size() != 2) {
          fail(mark(*force), "`force` needs two components [fx, fy] in N, not " + describe(force->value));
        }
        law_marks = {mark(force->value[0]), mark(force->value[1])};
        load.fx = load_law(force->value[0], law_marks[0], "fx", "N");
        load.fy = load_law(force->value[1], law_marks[1], "fy", "N");
      } else if (fx || fy) {
        if (fx) law_marks[0] = mark(*fx);
        if (fy) law_marks[1] = mark(*fy);
        load.fx = fx ? load_law(fx->value, mark(*fx), "fx", "N") : Law::parse("0");
        load.fy = fy ? load_law(fy->value, mark(*fy), "fy", "N") : Law::parse("0");
      } else {
        fail(item, "a force needs `force: [fx, fy]`, or `fx` and/or `fy` (N)");
      }
      model_.point_loads.push_back(std::move(load));
      source_.point_loads.push_back(mark(item));
      source_.point_load_laws.push_back(law_marks);
    }
  }

  void parse_torques(const Entry& e) {
    for (const YAML::Node& item : section_list(e, "[{body: crank, torque: -5}]")) {
      if (!item.IsMap()) fail(item, "a torque is a mapping like {body: crank, torque: -5}, not " + describe(item));
      const Fields f = fields(item, kTorqueKeys);
      BodyTorque torque;
      torque.body = body_ref(required(f, item, "body", "a torque").value);
      const Entry& value = required(f, item, "torque", "a torque");
      torque.torque = load_law(value.value, mark(value), "the torque", "N m");
      model_.torques.push_back(std::move(torque));
      source_.torques.push_back(mark(item));
      source_.torque_laws.push_back({mark(value), SourceMark{}});
    }
  }

  void parse_springs(const Entry& e) {
    std::vector<std::size_t> unnamed;
    std::vector<SourceMark> name_marks;
    for (const YAML::Node& item : section_list(e, "[{between: [P, Q], stiffness: 2000}]")) {
      if (!item.IsMap()) {
        fail(item, "a spring is a mapping like {between: [P, Q], stiffness: 2000}, not " + describe(item));
      }
      const Fields f = fields(item, kSpringKeys);
      Spring s;
      const Entry& between = required(f, item, "between", "a spring");
      s.points = point_pair(between, "[P, Q]");
      if (s.points[0] == s.points[1]) {
        fail(mark(between), "a spring joins two different points, not point '" + model_.points[s.points[0]].name +
                                "' to itself");
      }
      const Entry* stiffness = f.find("stiffness");
      const Entry* damping = f.find("damping");
      if (!stiffness && !damping) fail(item, "a spring needs `stiffness` (N/m), `damping` (N s/m) or both");
      if (stiffness) {
        s.stiffness = quantity(*stiffness, "the stiffness", kStiffnessUnits, "2 N/mm");
        if (s.stiffness < 0.0) fail(mark(*stiffness), "the stiffness must not be negative");
      }
      if (damping) {
        s.damping = quantity(*damping, "the damping", kDampingUnits, "0.5 N s/mm");
        if (s.damping < 0.0) fail(mark(*damping), "the damping must not be negative");
      }
      if (const Entry* free = f.find("free_length")) {
        s.free_length = non_negative(*free, "the free length") * model_.units.length_scale;
      } else {
        s.free_length = (model_.points[s.points[1]].position - model_.points[s.points[0]].position).norm();
      }
      if (const Entry* n = f.find("name")) {
        s.name = text_value(*n, "a spring name");
        if (s.name.empty()) fail(mark(*n), "a spring name cannot be empty");
        for (std::size_t i = 0; i < model_.springs.size(); ++i) {
          if (model_.springs[i].name == s.name) {
            fail(mark(*n), "two springs are named '" + s.name + "' (first on line " +
                               std::to_string(name_marks[i].line) + ")");
          }
        }
        name_marks.push_back(mark(*n));
      } else {
        unnamed.push_back(model_.springs.size());
        name_marks.push_back(mark(item));
      }
      model_.springs.push_back(std::move(s));
      source_.springs.push_back(mark(item));
    }
    // spring1, spring2... in order, skipping names given explicitly.
    int counter = 0;
    for (std::size_t i : unnamed) {
      std::string candidate;
      do {
        candidate = "spring" + std::to_string(++counter);
      } while (std::any_of(model_.springs.begin(), model_.springs.end(),
                           [&](const Spring& other) { return other.name == candidate; }));
      model_.springs[i].name = candidate;
    }
  }
};

}  // namespace

LoadedModel parse_model(const std::string& text, const std::string& file_name) {
  return Parser(text, file_name).parse();
}

LoadedModel load_model_file(const std::string& path) {
  const FileText file = read_file_text(path);
  if (file.error) throw ModelFileError(path, SourceMark{}, "cannot read: " + file.error.message());
  if (file.too_long) throw ModelFileError(path, SourceMark{1, 1}, too_long_message());
  Parser parser(file.text, path);
  parser.allow_imports(std::filesystem::path(path).parent_path());
  return parser.parse();
}

}  // namespace nbar::io
