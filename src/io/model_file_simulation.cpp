// The model file's simulation settings: joint friction (`friction:`) and the run's own settings
// (`simulation:`), both read only by `nbar simulate` (docs/dynamics.md).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "model_file_parser.hpp"
#include "nbar/dynamics/forward_dynamics.hpp"

namespace nbar::io::model_file_detail {

namespace {

// The default creep speed of Coulomb friction at a pin, rad/s (docs/model-format.md#friction).
constexpr double kDefaultAngularCreep = 1e-3;
// ... and along a guide, as a fraction of the drawing's size per second.
constexpr double kDefaultLinearCreep = 1e-3;

}  // namespace

// A friction coefficient: a finite number, >= 0 and at most kMaxLoadCoefficient (SI).
double Parser::load_coefficient(const Entry& e, const std::string& what, const std::string& unit) const {
  const double value = number(e, what + " (" + unit + ")");
  if (value < 0.0) fail(mark(e), what + " must not be negative");
  if (value > kMaxLoadCoefficient)
    fail(mark(e), what + " of " + e.value.Scalar() + " " + unit + " is out of range (at most 1e12 " + unit +
                      "): the motion it gives is faster than any integration step");
  return value;
}

// The links meeting at a pin: the bodies that have the point, and the ground when it is ground.
std::vector<int> Parser::links_at(int point) const {
  std::vector<int> links;
  if (model_.points[point].ground) links.push_back(-1);
  for (std::size_t b = 0; b < model_.bodies.size(); ++b) {
    const std::vector<int>& points = model_.bodies[b].points;
    if (std::find(points.begin(), points.end(), point) != points.end()) links.push_back(static_cast<int>(b));
  }
  return links;
}

// `joint: A` (with `links: [crank, coupler]` where more than two links meet): which two links.
std::array<int, 2> Parser::friction_links(const Fields& f, const Entry& joint, int point) const {
  const std::vector<int> at = links_at(point);
  const std::string& name = model_.points[point].name;
  const auto link_name = [&](int link) { return link < 0 ? std::string("ground") : model_.bodies[link].name; };
  std::vector<std::string> names;
  for (int link : at) names.push_back(link_name(link));
  const Entry* given = f.find("links");
  if (!given) {
    if (at.size() != 2)
      fail(mark(joint), "at point '" + name + "' " + std::to_string(at.size()) +
                            (at.size() == 1 ? " link meets (" : " links meet (") + join(names) +
                            "): a joint's friction acts between two links; " +
                            (at.size() < 2 ? "this point is not a joint" : "name them with `links: [a, b]`"));
    return {at[0], at[1]};
  }
  if (!given->value.IsSequence() || given->value.size() != 2)
    fail(mark(*given),
         "`links` names the two links the friction acts between, like [crank, coupler], not " + describe(given->value));
  std::array<int, 2> links{};
  for (int i = 0; i < 2; ++i) {
    const YAML::Node& item = given->value[i];
    const std::string text = item.IsScalar() ? item.Scalar() : std::string();
    links[i] = text == "ground" && model_.find_body("ground") < 0 ? -1 : body_ref(item);
    if (std::find(at.begin(), at.end(), links[i]) == at.end())
      fail(item, "'" + link_name(links[i]) + "' does not meet at point '" + name +
                     "' (the links there: " + join(names) + ")");
  }
  if (links[0] == links[1]) fail(mark(*given), "`links` names two different links");
  return links;
}

void Parser::parse_friction(const Entry& e) {
  for (const YAML::Node& item : section_list(e, "[{joint: A, viscous: 0.01}]")) {
    if (!item.IsMap())
      fail(item,
           "a joint's friction is a mapping like {joint: A, viscous: 0.01} or {slider: piston, coulomb: 5}, "
           "not " +
               describe(item));
    const Fields f = fields(item, kFrictionKeys);
    JointFriction friction;
    const Entry* joint = f.find("joint");
    const Entry* slider = f.find("slider");
    const Entry* slot = f.find("slot");
    if ((joint ? 1 : 0) + (slider ? 1 : 0) + (slot ? 1 : 0) != 1)
      fail(item, "a joint's friction names one joint: `joint: POINT` (a pin), `slider: BODY` or `slot: POINT`");
    if (f.find("links") && !joint) fail(f.find("links")->key_node, "`links` applies only to `joint:` (a pin)");
    bool sliding = true;
    if (joint) {
      friction.joint = JointFriction::Joint::Revolute;
      friction.index = point_ref(joint->value);
      friction.links = friction_links(f, *joint, friction.index);
      sliding = false;
    } else if (slider) {
      friction.joint = JointFriction::Joint::Slider;
      const int body = body_ref(slider->value);
      for (std::size_t i = 0; i < model_.sliders.size(); ++i)
        if (model_.sliders[i].body == body) friction.index = static_cast<int>(i);
      if (friction.index < 0)
        fail(slider->value, "body '" + model_.bodies[body].name + "' has no slider (`sliders:` lists it first)");
    } else {
      friction.joint = JointFriction::Joint::Slot;
      const int point = point_ref(slot->value);
      for (std::size_t i = 0; i < model_.slots.size(); ++i)
        if (model_.slots[i].point == point) friction.index = static_cast<int>(i);
      if (friction.index < 0)
        fail(slot->value, "point '" + model_.points[point].name + "' has no slot (`slots:` lists it first)");
    }
    const Entry* viscous = f.find("viscous");
    const Entry* coulomb = f.find("coulomb");
    if (!viscous && !coulomb) fail(item, "a joint's friction needs `viscous`, `coulomb` or both");
    if (viscous) friction.viscous = load_coefficient(*viscous, "the viscous friction", sliding ? "N s/m" : "N m s/rad");
    if (coulomb) friction.coulomb = load_coefficient(*coulomb, "the Coulomb friction", sliding ? "N" : "N m");
    if (const Entry* creep = f.find("creep_speed")) {
      if (!coulomb) fail(creep->key_node, "`creep_speed` applies only to Coulomb friction (`coulomb:`)");
      friction.creep_speed = number(*creep, sliding ? "the creep speed (m/s)" : "the creep speed (rad/s)");
      if (!(friction.creep_speed > 0.0)) fail(mark(*creep), "the creep speed must be positive");
    } else {
      friction.creep_speed = sliding ? kDefaultLinearCreep * drawing_diagonal() : kDefaultAngularCreep;
    }
    model_.frictions.push_back(friction);
    source_.frictions.push_back(mark(item));
  }
}

double Parser::drawing_diagonal() const {
  Eigen::Vector2d low = model_.points.front().position, high = low;
  for (const Point& p : model_.points) {
    low = low.cwiseMin(p.position);
    high = high.cwiseMax(p.position);
  }
  const double diagonal = (high - low).norm();
  return diagonal > 0.0 ? diagonal : 1.0;
}

void Parser::parse_simulation(const Entry& e) {
  const Fields f = section_fields(e, kSimulationKeys, "{to: 2, dt: 0.01, stop_when: 'slider.x > 200'}");
  source_.simulation = {mark(e.key_node), mark(e.key_node)};
  SimulationSpec& spec = model_.simulation;
  const auto positive_seconds = [&](const char* key, const char* what) -> std::optional<double> {
    const Entry* entry = f.find(key);
    if (!entry) return std::nullopt;
    const double value = number(*entry, std::string(what) + " (s)");
    if (!(value > 0.0)) fail(mark(*entry), std::string(what) + " must be a positive number of seconds");
    return value;
  };
  spec.end_time = positive_seconds("to", "the simulated time `to`");
  spec.output_step = positive_seconds("dt", "the output step `dt`");
  if (const Entry* rtol = f.find("rtol")) {
    spec.relative_tolerance = number(*rtol, "the relative tolerance `rtol`");
    if (!(*spec.relative_tolerance >= 1e-14 && *spec.relative_tolerance <= 0.01))
      fail(mark(*rtol), "the relative tolerance `rtol` is between 1e-14 and 0.01");
  }
  if (const Entry* stop = f.find("stop_when")) {
    const std::string text = text_value(*stop, "the stop condition");
    if (!parse_stop_condition(text))
      fail(mark(*stop), "`stop_when` is a column, < or > and a number, like 'slider.x > 200', not '" + text + "'");
    spec.stop_when = text;
    source_.simulation[1] = mark(*stop);
  }
  if (const Entry* toggle = f.find("at_toggle")) {
    const std::string text = toggle->value.IsScalar() ? toggle->value.Scalar() : std::string();
    if (text != "stop" && text != "reverse")
      fail(mark(*toggle), "`at_toggle` is stop or reverse, not " + describe(toggle->value));
    spec.reverse_at_toggle = text == "reverse";
  }
}

}  // namespace nbar::io::model_file_detail
