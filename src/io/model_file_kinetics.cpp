// The model file's kinetics: materials, gravity, forces, torques and springs
// (model_file_parser.hpp).
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "model/double_text.hpp"
#include "model_file_parser.hpp"

namespace nbar::io::model_file_detail {

namespace {

constexpr double kPoundForce = 4.4482216152605;  // N
constexpr double kInch = 0.0254;                 // m
const std::vector<UnitScale> kStiffnessUnits{
    {"N/m", 1.0}, {"N/mm", 1e3}, {"kN/m", 1e3}, {"lbf/in", kPoundForce / kInch}};
const std::vector<UnitScale> kDampingUnits{{"N s/m", 1.0}, {"N s/mm", 1e3}};
constexpr double kPsi = kPoundForce / (kInch * kInch);  // Pa
const std::vector<UnitScale> kStressUnits{{"Pa", 1.0},  {"kPa", 1e3},  {"MPa", 1e6},
                                          {"GPa", 1e9}, {"psi", kPsi}, {"ksi", 1e3 * kPsi}};
constexpr double kStandardGravity = 9.80665;  // m/s^2

}  // namespace

// A number (in the first of `units`) or "<number> <unit>" with one of `units` (`example`
// shows one); in SI. Spaces and `*` inside the unit are ignored, so "N s/m", "N*s/m" and
// "Ns/m" are the same; case is not ("mPa" is not "MPa").
double Parser::quantity(const Entry& e, const std::string& what, const std::vector<UnitScale>& units,
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
  const auto [end, ec] = parse_double(rest.data(), rest.data() + rest.size(), value);
  if (ec == std::errc::invalid_argument || end == rest.data()) {
    fail(mark(e), what + " must be a number or a quantity like '" + std::string(example) + "', not '" + text + "'");
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

void Parser::parse_materials(const Entry& e) {
  if (e.value.IsNull()) return;
  if (!e.value.IsMap()) {
    fail(mark(e),
         "`materials` must be a mapping like {my-alloy: {density: 2800, yield: 250 MPa}}, not " + describe(e.value));
  }
  for (const Entry& m : entries(e.value, "material")) {
    if (builtin_material(m.key)) {
      fail(m.key_node, "'" + m.key + "' is a built-in material; give yours another name");
    }
    if (!m.value.IsMap()) {
      fail(mark(m),
           "material '" + m.key + "' needs a mapping like {density: 2800, yield: 250 MPa}, not " + describe(m.value));
    }
    user_materials_.push_back(material_fields(m.value, m.key));
  }
}

Material Parser::material_fields(const YAML::Node& map, const std::string& name) const {
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
      fail(mark(*nu),
           "Poisson's ratio must be at least 0 and less than 0.5 (0.3 for steel), not " + nu->value.Scalar());
  }
  return m;
}

Material Parser::material_of(const Entry& e) const {
  if (e.value.IsMap()) return material_fields(e.value, "");
  if (!e.value.IsScalar() || e.value.Scalar().empty()) {
    fail(mark(e),
         "`material` must be a material name like steel, or a mapping like {density: 7850, yield: 250 MPa}, "
         "not " +
             describe(e.value));
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

void Parser::parse_gravity(const Entry& e) {
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
Law Parser::load_law(const YAML::Node& node, SourceMark at, const std::string& what, std::string_view unit) const {
  if (!node.IsScalar()) {
    fail(at, what + " must be a number or an expression in t like \"100*sin(2*pi*t)\", not " + describe(node));
  }
  const std::string text = node.Scalar();
  double value = 0.0;
  switch (parse_number(text, value)) {
    case NumberStatus::Ok: try { return Law::parse(text.front() == '+' ? text.substr(1) : text);
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
  const auto [end, ec] = parse_double(text.data(), text.data() + text.size(), value);
  if (ec == std::errc() && end != text.data() && end != text.data() + text.size() && *end == ' ') {
    hint = what + " is in " + std::string(unit) + ": write a number without its unit, or an expression in t";
  }
  return law_of(node, at, text, 1.0, hint);
}

void Parser::parse_forces(const Entry& e) {
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

void Parser::parse_torques(const Entry& e) {
  for (const YAML::Node& item : section_list(e, "[{body: crank, torque: -5}]")) {
    if (!item.IsMap()) fail(item, "a torque is a mapping like {body: crank, torque: -5}, not " + describe(item));
    const Fields f = fields(item, kTorqueKeys);
    BodyTorque torque;
    torque.body = body_ref(required(f, item, "body", "a torque").value);
    const Entry& value = required(f, item, "torque", "a torque");
    torque.torque = load_law(value.value, mark(value), "the torque", "N m");
    if (const Entry* line = f.find("no_load_speed")) {
      // A motor's line: rad/s, or a quantity with an angular unit (300 rpm).
      Driver angular;
      angular.name = "the motor of body '" + model_.bodies[torque.body].name + "'";
      torque.no_load_speed = rate(*line, 1, angular, model_.units.angle_scale);
      if (*torque.no_load_speed == 0.0) fail(mark(*line), "the no-load speed of a motor cannot be zero");
    }
    model_.torques.push_back(std::move(torque));
    source_.torques.push_back(mark(item));
    source_.torque_laws.push_back({mark(value), SourceMark{}});
  }
}

void Parser::parse_springs(const Entry& e) {
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
      fail(mark(between),
           "a spring joins two different points, not point '" + model_.points[s.points[0]].name + "' to itself");
    }
    const Entry* stiffness = f.find("stiffness");
    const Entry* damping = f.find("damping");
    if (!stiffness && !damping) fail(item, "a spring needs `stiffness` (N/m), `damping` (N s/m) or both");
    if (stiffness) {
      s.stiffness = quantity(*stiffness, "the stiffness", kStiffnessUnits, "2 N/mm");
      if (s.stiffness < 0.0) fail(mark(*stiffness), "the stiffness must not be negative");
      if (s.stiffness > kMaxLoadCoefficient)
        fail(mark(*stiffness),
             "the stiffness is out of range (at most 1e12 N/m): the motion it gives is faster "
             "than any integration step");
    }
    if (damping) {
      s.damping = quantity(*damping, "the damping", kDampingUnits, "0.5 N s/mm");
      if (s.damping < 0.0) fail(mark(*damping), "the damping must not be negative");
      if (s.damping > kMaxLoadCoefficient)
        fail(mark(*damping),
             "the damping is out of range (at most 1e12 N s/m): the motion it gives is faster "
             "than any integration step");
    }
    if (const Entry* preload = f.find("preload")) s.preload = number(*preload, "the preload (N)");
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
          fail(mark(*n),
               "two springs are named '" + s.name + "' (first on line " + std::to_string(name_marks[i].line) + ")");
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

}  // namespace nbar::io::model_file_detail
