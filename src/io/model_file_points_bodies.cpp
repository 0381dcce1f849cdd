// The model file's points, ground, bodies, lengths, sliders, slots, drivers and sweep
// (model_file_parser.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "model_file_parser.hpp"

namespace nbar::io::model_file_detail {

void Parser::parse_points(const Entry* e) {
  // A model being built may have no point yet: `points: {}`, or no section at all.
  if (draft_ && (!e || e->value.IsNull() || (e->value.IsMap() && e->value.size() == 0))) return;
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

void Parser::parse_ground(const Entry& e) {
  for (const YAML::Node& item : section_list(e, "[O2, O4]")) {
    const int p = point_ref(item);
    if (model_.points[p].ground) fail(item, "point '" + model_.points[p].name + "' is listed twice under `ground`");
    model_.points[p].ground = true;
  }
}

void Parser::parse_bodies(const Entry& e) {
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
      fail(mark(b), "body '" + b.key + "' needs a list of its points, like [A, B], or a mapping with `points:`, not " +
                        describe(b.value));
    }
    model_.bodies.push_back(std::move(body));
    source_.bodies.push_back(mark(b.key_node));
  }
}

// The long form of a body: {points: [...], shape or bar, thickness, material, mass, cg, inertia}.
void Parser::parse_body_details(const Entry& b, Body& body) {
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

// Checked here as well as in validate() so that the error points into `lengths:`
// rather than at the body.
void Parser::parse_lengths(const Entry& e) {
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

void Parser::parse_sliders(const Entry& e) {
  for (const YAML::Node& item : section_list(e, "[{body: piston, point: C, along: [O2, X]}]")) {
    if (!item.IsMap()) {
      fail(item, "a slider is a mapping like {body: piston, point: C, along: [O2, X]}, not " + describe(item));
    }
    const Fields f = fields(item, kSliderKeys);
    Slider s;
    s.body = body_ref(required(f, item, "body", "a slider").value);
    s.point = point_ref(required(f, item, "point", "a slider").value);
    s.along = guide(required(f, item, "along", "a slider"), "[O2, X]", s.body);
    model_.sliders.push_back(s);
    source_.sliders.push_back(mark(item));
  }
}

void Parser::parse_slots(const Entry& e) {
  for (const YAML::Node& item : section_list(e, "[{point: D, along: [E, F]}]")) {
    if (!item.IsMap()) fail(item, "a slot is a mapping like {point: D, along: [E, F]}, not " + describe(item));
    const Fields f = fields(item, kSlotKeys);
    Slot s;
    s.point = point_ref(required(f, item, "point", "a slot").value);
    s.along = guide(required(f, item, "along", "a slot"), "[E, F]", -1);
    model_.slots.push_back(s);
    source_.slots.push_back(mark(item));
  }
}

// A guide's line: two points, or a point and an angle (`{point: C, angle: 30 deg}`, the angle in
// the drawing from +x, a number in the model's angle unit or a quantity in deg or rad), with
// `body:` the body that carries the guide when it is not the ground or the one body of the point.
std::array<int, 2> Parser::guide(const Entry& e, std::string_view example, int slider_body) {
  if (!e.value.IsMap()) return point_pair(e, example);
  const YAML::Node& given = e.value;
  if (!given["point"] && !given["angle"]) {
    fail(mark(e), "`" + e.key + "` needs two point names, like " + std::string(example) +
                      ", or a point and an angle, like {point: O2, angle: 30 deg}, not " + describe(e.value));
  }
  const Fields f = fields(e.value, kGuideKeys);
  const Entry& through_entry = required(f, e.value, "point", "a guide by a point and an angle");
  const int through = point_ref(through_entry.value);
  // A bare number is in the model's angle unit, the first of the list.
  const UnitScale degrees{"deg", std::numbers::pi / 180.0}, radians{"rad", 1.0};
  const std::vector<UnitScale> units =
      model_.units.angle == "rad" ? std::vector<UnitScale>{radians, degrees} : std::vector<UnitScale>{degrees, radians};
  const double angle =
      quantity(required(f, e.value, "angle", "a guide by a point and an angle"), "the guide's angle", units, "30 deg");
  const Entry* carrier_entry = f.find("body");
  const int carrier = carrier_entry ? guide_carrier(*carrier_entry, through, slider_body)
                                    : guide_carrier(through_entry.value, through, slider_body);
  const std::string owner = slider_body >= 0 ? model_.bodies[slider_body].name : model_.points[through].name;
  return {through, guide_direction_point(through_entry.value, through, angle, owner + ".guide", carrier)};
}

// The body `body:` names as the guide's: one that holds the guide's point, not the slider's own.
int Parser::guide_carrier(const Entry& e, int through, int slider_body) const {
  const int b = body_ref(e.value);
  const std::vector<int>& points = model_.bodies[b].points;
  if (std::find(points.begin(), points.end(), through) == points.end())
    fail(e.value, "body '" + model_.bodies[b].name + "' does not hold point '" + model_.points[through].name +
                      "', the guide's point");
  if (b == slider_body) fail(e.value, "a slider cannot slide along its own body '" + model_.bodies[b].name + "'");
  if (points.size() < 2)
    fail(e.value, "body '" + model_.bodies[b].name + "' is a one-point slider block: it cannot carry a guide");
  return b;
}

// Without `body:`: the ground (-1) for a ground point, else the one body that holds the point
// (other than the slider's).
int Parser::guide_carrier(const YAML::Node& at, int through, int slider_body) const {
  const Point& c = model_.points[through];
  if (c.ground) return -1;
  int carrier = -1;
  for (std::size_t b = 0; b < model_.bodies.size(); ++b) {
    const std::vector<int>& points = model_.bodies[b].points;
    if (static_cast<int>(b) == slider_body || std::find(points.begin(), points.end(), through) == points.end())
      continue;
    if (carrier >= 0)
      fail(at, "point '" + c.name + "' belongs to bodies '" + model_.bodies[carrier].name + "' and '" +
                   model_.bodies[b].name + "': say which carries the guide with `body:`");
    carrier = static_cast<int>(b);
  }
  if (carrier < 0) fail(at, "point '" + c.name + "' is on no body that could carry the guide");
  if (model_.bodies[carrier].points.size() < 2)
    fail(at, "point '" + c.name + "' is on '" + model_.bodies[carrier].name +
                 "', a one-point slider block, which cannot carry a guide");
  return carrier;
}

// The second point of a guide given by `through` and `angle`, on `carrier` (-1: the ground), a
// drawing's size away so that the guide's rows are as well scaled as a guide drawn with two points.
int Parser::guide_direction_point(const YAML::Node& at, int through, double angle, const std::string& name,
                                  int carrier) {
  const Point& c = model_.points[through];
  Eigen::Vector2d low = c.position, high = c.position;
  for (const Point& p : model_.points) {
    low = low.cwiseMin(p.position);
    high = high.cwiseMax(p.position);
  }
  const double reach = (high - low).norm() > 0.0 ? (high - low).norm() : model_.units.length_scale;
  Point direction{name, c.position + reach * Eigen::Vector2d(std::cos(angle), std::sin(angle)), carrier < 0, true};
  for (int k = 2; model_.find_point(direction.name) >= 0; ++k) direction.name = name + std::to_string(k);
  const int index = static_cast<int>(model_.points.size());
  model_.points.push_back(std::move(direction));
  source_.points.push_back(mark(at));
  if (carrier >= 0) model_.bodies[carrier].points.push_back(index);
  return index;
}

void Parser::parse_drivers(const Entry& e) {
  for (const YAML::Node& item : section_list(e, "[{angle: crank, from: 0, to: 360}]")) parse_driver(item);
}

void Parser::parse_driver(const YAML::Node& item) {
  if (!item.IsMap()) {
    fail(item, "a driver is a mapping like {angle: crank, from: 0, to: 360}, not " + describe(item));
  }
  const Fields f = fields(item, kDriverKeys);
  Driver d = driver_of_kind(item, f);
  std::array<SourceMark, 2> law_marks{};
  parse_driver_motion(f, d, law_marks);
  parse_driver_run(f, d);
  model_.drivers.push_back(std::move(d));
  source_.drivers.push_back(mark(item));
  source_.driver_laws.push_back(law_marks);
}

// What the driver moves (`angle`, `distance` or `slide`) and its name.
Driver Parser::driver_of_kind(const YAML::Node& item, const Fields& f) {
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
  return d;
}

// How it moves: `from`, `to`, `speed` and `accel`, or a `law` that replaces them all.
void Parser::parse_driver_motion(const Fields& f, Driver& d, std::array<SourceMark, 2>& law_marks) {
  const double scale = driver_scale(d);
  const std::string unit = d.is_angular() ? model_.units.angle : model_.units.length;
  if (const Entry* from = f.find("from")) d.from = driver_value(*from, d, scale, unit);
  if (const Entry* to = f.find("to")) d.to = driver_value(*to, d, scale, unit);
  // Without a speed, one driver unit a second towards `to`: time runs forward either way.
  d.speed = d.from && d.to && *d.to < *d.from ? -scale : scale;
  if (const Entry* speed = f.find("speed")) d.speed = rate(*speed, 1, d, scale);
  if (const Entry* accel = f.find("accel")) d.accel = rate(*accel, 2, d, scale);
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
}

// How a run treats it: left `free` to the loads (with its `initial_speed`), and what it does at a
// limit of its motion (`at_limits`, `cycles`).
void Parser::parse_driver_run(const Fields& f, Driver& d) {
  if (const Entry* free = f.find("free")) {
    const std::string text = free->value.IsScalar() ? free->value.Scalar() : std::string();
    if (text != "true" && text != "false") fail(mark(*free), "`free` is true or false, not " + describe(free->value));
    d.free = text == "true";
  }
  if (const Entry* initial = f.find("initial_speed")) {
    if (!d.free) fail(initial->key_node, "`initial_speed` applies only to a driver with `free: true`");
    d.initial_speed = rate(*initial, 1, d, driver_scale(d), true);
  }
  if (const Entry* at_limits = f.find("at_limits")) {
    const std::string text = at_limits->value.IsScalar() ? at_limits->value.Scalar() : std::string();
    if (text != "stop" && text != "reverse")
      fail(mark(*at_limits),
           "`at_limits` is `stop` (the sweep ends at a limit) or `reverse` (it turns back and "
           "rocks between the limits), not " +
               describe(at_limits->value));
    d.at_limits = text == "reverse" ? AtLimits::Reverse : AtLimits::Stop;
  }
  if (const Entry* cycles = f.find("cycles")) {
    if (d.at_limits != AtLimits::Reverse)
      fail(cycles->key_node, "`cycles` counts the cycles of a rocking motion: it needs `at_limits: reverse`");
    const double n = number(*cycles, "`cycles`");
    if (!(n >= 1.0 && n <= kMaxRockingCycles) || n != std::floor(n))
      fail(mark(*cycles), "`cycles` is a whole number from 1 to " + std::to_string(kMaxRockingCycles) + ", not " +
                              cycles->value.Scalar());
    d.cycles = static_cast<int>(n);
  }
}

// A driver's `from` or `to`. An angle is refused past a million radians: there the spacing of
// doubles (1e-10 rad at 1e6, 2 deg at 1e16) eats the motion, and `from: 1e20` gave a time ratio
// of inf with exit 0.
double Parser::driver_value(const Entry& e, const Driver& d, double scale, const std::string& unit) const {
  const double value = scale * number(e, "`" + e.key + "` (" + unit + ")");
  if (d.is_angular() && std::abs(value) > kMaxDriverAngle) {
    fail(mark(e), "`" + e.key + "` is " + e.value.Scalar() + " " + unit +
                      ", too large for a driver angle: the largest is " +
                      fmt::format("{:.9g}", kMaxDriverAngle / scale) + " " + unit +
                      " (a million radians), past which the digits of a double no longer hold the motion" +
                      " (at this value neighbouring doubles are " +
                      fmt::format("{:.3g}", std::nextafter(std::abs(value), INFINITY) - std::abs(value)) +
                      " rad apart); take whole turns off it");
  }
  return value;
}

// A bare number is in driver units (angle or length unit) per second, or per second
// squared; text carries its own unit, which must be of the driver's kind.
double Parser::rate(const Entry& e, int order, const Driver& d, double scale, bool initial) const {
  const std::string what = order == 1 ? (initial ? "the initial speed" : "the speed") : "the acceleration";
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
  } catch (const Error& error) {
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

Law Parser::parse_law(const Entry& e, double scale) const {
  if (!e.value.IsScalar()) {
    fail(mark(e), "a law must be an expression in t like \"30*sin(2*pi*t)\", not " + describe(e.value));
  }
  return law_of(e.value, mark(e), e.value.Scalar(), scale);
}

void Parser::parse_sweep(const Entry& e) {
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

}  // namespace nbar::io::model_file_detail
